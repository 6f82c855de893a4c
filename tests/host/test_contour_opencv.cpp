// SPDX-License-Identifier: MIT
// Host regression test: sbr's contour tracing equals OpenCV's findContours(RETR_EXTERNAL,
// CHAIN_APPROX_NONE) on the MPEG-7 CE-Shape-1 silhouettes: the same contours, each the
// same point sequence up to the start point. Exit 77 (ctest: skipped) without the data.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

extern "C" {
#include "sbr/contour.h"

#include "test_help.hpp"
}

namespace fs = std::filesystem;

static bool same_cyclic(const std::vector<cv::Point> &a, const sbr_point_t *b, size_t n) {
    if (a.size() != n) return false;
    for (size_t s = 0; s < n; ++s) {
        if (a[0].x != b[s].x || a[0].y != b[s].y) continue;
        bool ok = true;
        for (size_t i = 0; i < n && ok; ++i) {
            const sbr_point_t &q = b[(s + i) % n];
            ok = a[i].x == q.x && a[i].y == q.y;
        }
        if (ok) return true;
    }
    return false;
}

struct Tally { size_t images = 0, contours_cv = 0, equal = 0, bad_images = 0; };

static void compare(const cv::Mat &mask, const std::string &name, Tally &t) {
    static std::vector<uint8_t> ws;
    static std::vector<sbr_point_t> pts;
    static std::vector<sbr_contour_t> cts(65536);
    std::vector<std::vector<cv::Point>> cv_contours;
    cv::findContours(mask.clone(), cv_contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    sbr_image_t view{static_cast<uint32_t>(mask.cols), static_cast<uint32_t>(mask.rows),
                     static_cast<uint32_t>(mask.step), SBR_PIXEL_GRAY8, mask.data};
    ws.resize(sbr_contour_workspace_size(view.width, view.height));
    pts.resize(static_cast<size_t>(8) * (mask.cols + 2) * (mask.rows + 2));
    uint32_t n = 0;
    const sbr_status_t st = sbr_contour_find_external(&view, ws.data(), ws.size(), pts.data(),
                                                      static_cast<uint32_t>(pts.size()), cts.data(),
                                                      static_cast<uint32_t>(cts.size()), &n);
    ++t.images;
    t.contours_cv += cv_contours.size();
    size_t matched = 0;
    if (st == SBR_OK && n == cv_contours.size()) {
        std::vector<bool> used(n, false);
        for (const auto &c : cv_contours) {
            for (uint32_t k = 0; k < n; ++k) {
                if (!used[k] && same_cyclic(c, &pts[cts[k].first], cts[k].length)) {
                    used[k] = true;
                    ++matched;
                    break;
                }
            }
        }
    }
    t.equal += matched;
    if (matched != cv_contours.size() || n != cv_contours.size()) {
        ++t.bad_images;
        if (t.bad_images <= 5)
            std::printf("MISMATCH %s: status %s, sbr %u contours, OpenCV %zu, %zu equal\n",
                        name.c_str(), sbr_status_str(st), n, cv_contours.size(), matched);
    }
}

int main(int argc, char **argv) {
    const int h = test_help(argc, argv, "test_contour_opencv: sbr's outer contours against OpenCV's findContours on MPEG-7 shapes",
                            "test_contour_opencv MPEG7_PBM_DIR [MAX_IMAGES]");
    if (h >= 0) return h;
    if (argc < 2) {
        std::fprintf(stderr, "usage: test_contour_opencv MPEG7_PBM_DIR [MAX_IMAGES]\n");
        return 2;
    }
    const fs::path dir = argv[1];
    const size_t max_images = argc > 2 ? std::stoul(argv[2]) : 100000;
    std::vector<fs::path> files;
    if (!fs::is_directory(dir)) {
        std::printf("SKIP (MPEG-7 part): %s not found; the random masks still run\n", dir.c_str());
    } else {
        for (const auto &e : fs::directory_iterator(dir))
            if (e.path().extension() == ".pbm") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.size() > max_images) files.resize(max_images);

    Tally mp, rnd;
    for (const auto &f : files) {
        cv::Mat img = cv::imread(f.string(), cv::IMREAD_GRAYSCALE);
        if (img.empty()) {
            std::printf("FAIL: cannot read %s\n", f.c_str());
            return 1;
        }
        // PBM bit 1 = object; OpenCV decodes it as black (0).
        compare(img == 0, f.filename().string(), mp);
        if (mp.images % 100 == 0) std::fprintf(stderr, "\r%zu/%zu images", mp.images, files.size());
    }
    // Random masks: blurred noise, thresholded: many blobs, holes, blobs inside holes,
    // one-pixel bridges and blobs touching the border.
    cv::RNG rng(20261121);
    for (int i = 0; i < 300; ++i) {
        cv::Mat noise(48 + i % 37, 64 + i % 53, CV_32F);
        rng.fill(noise, cv::RNG::UNIFORM, 0.0f, 1.0f);
        cv::GaussianBlur(noise, noise, cv::Size(0, 0), 0.6 + 0.01 * (i % 150));
        compare(noise > 0.5f, "random-" + std::to_string(i), rnd);
    }
    std::fprintf(stderr, "\n");
    std::printf("MPEG-7: %zu images, %zu OpenCV contours, %zu equal to sbr's up to the start point, "
                "%zu images differ\n", mp.images, mp.contours_cv, mp.equal, mp.bad_images);
    std::printf("random masks: %zu images, %zu OpenCV contours, %zu equal, %zu images differ\n",
                rnd.images, rnd.contours_cv, rnd.equal, rnd.bad_images);
    const size_t bad = mp.bad_images + rnd.bad_images;
    std::printf("%zu passed, %zu failed\n", mp.images + rnd.images - bad, bad);
    return bad == 0 ? 0 : 1;
}
