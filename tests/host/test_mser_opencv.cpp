// SPDX-License-Identifier: MIT
// Host regression test: sbr's MSER agrees with OpenCV's cv::MSER (the oracle) on GTSDB
// scenes. For 20 images spread over the set, on the intensity map and on the red-opponent
// map (both made by sbr and handed to both implementations), with OpenCV's default
// parameters: the share of OpenCV's regions of area >= 64 px that have an sbr region of the
// same polarity at pixel IoU >= 0.8 must be >= 90%, and the reverse share (sbr's regions
// of area >= 64 px with an OpenCV region at IoU >= 0.8) >= 98% (sbr reports fewer regions:
// its diversity filter keeps one of nested near-equal ones). Also prints the share matched
// exactly (IoU = 1), region and node counts and both run times.
// Usage: test_mser_opencv <gtsdb dir> [images=20] [min_percent=90] [min_reverse_percent=98]
// Exit 77 (ctest: skipped) without the data.
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

extern "C" {
#include "sbr/map.h"
#include "sbr/mser.h"

#include "test_help.hpp"
}

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Region {           // one region as a pixel set, for either implementation
    cv::Rect box;
    std::vector<uint8_t> in; // box-sized mask
    int area = 0;
    bool bright = false;
};

static double iou(const Region &a, const Region &b) {
    const cv::Rect r = a.box & b.box;
    if (r.area() == 0) return 0.0;
    int inter = 0;
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x)
            inter += a.in[(y - a.box.y) * a.box.width + (x - a.box.x)] &&
                     b.in[(y - b.box.y) * b.box.width + (x - b.box.x)];
    return static_cast<double>(inter) / (a.area + b.area - inter);
}

// best IoU of `r` against any region of `set` with the same polarity
static double best_iou(const Region &r, const std::vector<Region> &set) {
    double best = 0.0;
    for (const Region &s : set) {
        if (s.bright != r.bright) continue;
        const double ratio = static_cast<double>(std::min(s.area, r.area)) / std::max(s.area, r.area);
        if (ratio < best || ratio < 0.5) continue;  // IoU <= area ratio
        if ((s.box & r.box).area() == 0) continue;
        best = std::max(best, iou(r, s));
        if (best >= 1.0) break;
    }
    return best;
}

int main(int argc, char **argv) {
    const int h = test_help(argc, argv, "test_mser_opencv: sbr's MSER against OpenCV's cv::MSER on GTSDB scenes",
                            "test_mser_opencv GTSDB_DIR [IMAGES] [MIN_PERCENT] [MIN_REVERSE_PERCENT]");
    if (h >= 0) return h;
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <gtsdb dir> [images] [min_percent] [min_reverse_percent]\n", argv[0]);
        return 2;
    }
    const fs::path dir = fs::path(argv[1]) / "FullIJCNN2013";
    const size_t want = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 20;
    const double min_percent = argc > 3 ? std::atof(argv[3]) : 90.0;
    const double min_reverse = argc > 4 ? std::atof(argv[4]) : 98.0;
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const auto &e : fs::directory_iterator(dir))
            if (e.path().extension() == ".jpg" || e.path().extension() == ".ppm") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.size() < want) {
        std::printf("SKIP: fewer than %zu GTSDB images in %s\n", want, dir.c_str());
        return 77;
    }

    sbr_mser_config_t cfg;
    sbr_mser_config_default(&cfg);  // delta 5, area 60..14400, variation 0.25, diversity 0.2
    cv::Ptr<cv::MSER> cvm = cv::MSER::create(static_cast<int>(cfg.delta), static_cast<int>(cfg.min_area),
                                             static_cast<int>(cfg.max_area), cfg.max_variation,
                                             cfg.min_diversity);
    if (std::getenv("SBR_MSER_NO_DIVERSITY")) cfg.min_diversity = 0.0f;  // exactness check
    size_t cv_big = 0, cv_hit = 0, cv_exact = 0, sbr_big = 0, sbr_hit = 0;
    size_t sbr_total = 0, cv_total = 0, max_nodes_seen = 0;
    double t_sbr = 0.0, t_cv = 0.0;
    size_t bounded_ok = 0, ws_small = 0, ws_full = 0;
    std::vector<uint8_t> ws, maskws;
    std::vector<sbr_mser_region_t> regs(1 << 16);
    const sbr_map_kind_t kinds[] = {SBR_MAP_INTENSITY, SBR_MAP_RED};
    const char *kind_names[] = {"intensity", "red"};
    for (size_t i = 0; i < want; ++i) {
        const fs::path &f = files[i * files.size() / want];
        const cv::Mat bgr = cv::imread(f.string(), cv::IMREAD_COLOR);
        if (bgr.empty()) { std::fprintf(stderr, "cannot read %s\n", f.c_str()); return 1; }
        const sbr_image_t src{static_cast<uint32_t>(bgr.cols), static_cast<uint32_t>(bgr.rows),
                              static_cast<uint32_t>(bgr.step), SBR_PIXEL_BGR888, bgr.data};
        for (size_t k = 0; k < 2; ++k) {
            cv::Mat map(bgr.rows, bgr.cols, CV_8UC1);
            sbr_image_t mv;
            if (sbr_map_make(&src, kinds[k], 1, map.data, static_cast<uint32_t>(map.step),
                             map.total(), &mv) != SBR_OK) { std::fprintf(stderr, "map failed\n"); return 1; }
            // OpenCV
            std::vector<std::vector<cv::Point>> cv_regs;
            std::vector<cv::Rect> cv_boxes;
            auto t0 = Clock::now();
            cvm->detectRegions(map, cv_regs, cv_boxes);
            t_cv += std::chrono::duration<double>(Clock::now() - t0).count();
            // sbr
            ws.resize(sbr_mser_workspace_size(&cfg, mv.width, mv.height));
            uint32_t n = 0;
            t0 = Clock::now();
            const sbr_status_t st = sbr_mser_detect(&mv, &cfg, ws.data(), ws.size(), regs.data(),
                                                    static_cast<uint32_t>(regs.size()), &n);
            t_sbr += std::chrono::duration<double>(Clock::now() - t0).count();
            if (st != SBR_OK) { std::fprintf(stderr, "sbr_mser_detect: %s\n", sbr_status_str(st)); return 1; }
            {   // an ECU-sized node bound (1/16 of the pixels) gives the same regions
                sbr_mser_config_t small = cfg;
                small.max_nodes = mv.width * mv.height / 16u;
                std::vector<uint8_t> ws2(sbr_mser_workspace_size(&small, mv.width, mv.height));
                std::vector<sbr_mser_region_t> r2(regs.size());
                uint32_t n2 = 0;
                const sbr_status_t st2 = sbr_mser_detect(&mv, &small, ws2.data(), ws2.size(), r2.data(),
                                                         static_cast<uint32_t>(r2.size()), &n2);
                bounded_ok += st2 == SBR_OK && n2 == n &&
                              std::memcmp(r2.data(), regs.data(), n * sizeof(sbr_mser_region_t)) == 0;
                ws_small = ws2.size();
                ws_full = ws.size();
            }
            // region sets
            std::vector<Region> a, b;
            for (size_t r = 0; r < cv_regs.size(); ++r) {
                Region g;
                g.box = cv_boxes[r];
                g.in.assign(static_cast<size_t>(g.box.area()), 0);
                for (const cv::Point &p : cv_regs[r]) g.in[(p.y - g.box.y) * g.box.width + (p.x - g.box.x)] = 1;
                g.area = static_cast<int>(cv_regs[r].size());
                a.push_back(std::move(g));
            }
            // OpenCV does not say which pass found a region; an extremal region tells by
            // itself: dark if every interior 4-neighbour outside is brighter than all of
            // its pixels, bright if every such neighbour is darker.
            for (Region &g : a) {
                int inmax = 0, inmin = 255, outmin = 255, outmax = 0;
                for (int y = g.box.y; y < g.box.y + g.box.height; ++y)
                    for (int x = g.box.x; x < g.box.x + g.box.width; ++x)
                        if (g.in[(y - g.box.y) * g.box.width + (x - g.box.x)]) {
                            const int v = map.at<uint8_t>(y, x);
                            inmax = std::max(inmax, v); inmin = std::min(inmin, v);
                            const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
                            for (int d = 0; d < 4; ++d) {
                                const int xx = x + dx[d], yy = y + dy[d];
                                const bool inside = xx >= g.box.x && yy >= g.box.y && xx < g.box.x + g.box.width &&
                                                    yy < g.box.y + g.box.height &&
                                                    g.in[(yy - g.box.y) * g.box.width + (xx - g.box.x)];
                                // the map's outer ring bounds regions without being part
                                // of the extremal test
                                const bool ring = xx == 0 || yy == 0 || xx == map.cols - 1 || yy == map.rows - 1;
                                if (!inside && !ring) {
                                    const int w = map.at<uint8_t>(yy, xx);
                                    outmin = std::min(outmin, w); outmax = std::max(outmax, w);
                                }
                            }
                        }
                g.bright = !(inmax < outmin) && (inmin > outmax);
            }
            for (uint32_t r = 0; r < n; ++r) {
                Region g;
                const sbr_mser_region_t &s = regs[r];
                g.box = cv::Rect(static_cast<int>(s.bbox.x), static_cast<int>(s.bbox.y),
                                 static_cast<int>(s.bbox.width), static_cast<int>(s.bbox.height));
                g.in.assign(static_cast<size_t>(g.box.area()), 0);
                maskws.resize(SBR_MSER_MASK_WORKSPACE_SIZE(s.bbox.width, s.bbox.height) + 4);
                const sbr_status_t ms = sbr_mser_region_mask(&mv, &s, maskws.data(), maskws.size(), g.in.data(),
                                                             s.bbox.width, g.in.size());
                if (ms != SBR_OK) { std::fprintf(stderr, "sbr_mser_region_mask: %s\n", sbr_status_str(ms)); return 1; }
                for (uint8_t &v : g.in) v = v ? 1 : 0;
                g.area = static_cast<int>(s.area);
                g.bright = s.polarity == SBR_MSER_BRIGHT;
                b.push_back(std::move(g));
            }
            size_t big = 0, hit = 0, exact = 0, sbig = 0, shit = 0;
            for (const Region &g : a) {
                if (g.area < 64) continue;
                ++big;
                const double v = best_iou(g, b);
                hit += v >= 0.8;
                exact += v >= 1.0;
            }
            for (const Region &g : b) {
                if (g.area < 64) continue;
                ++sbig;
                shit += best_iou(g, a) >= 0.8;
            }
            std::printf("%s %-9s OpenCV %4zu regions (%4zu >= 64 px), sbr %4u: %5.1f%% of OpenCV's "
                        "matched at IoU >= 0.8 (%5.1f%% exactly), %5.1f%% of sbr's\n",
                        f.filename().c_str(), kind_names[k], a.size(), big, n,
                        big ? 100.0 * hit / big : 100.0, big ? 100.0 * exact / big : 100.0,
                        sbig ? 100.0 * shit / sbig : 100.0);
            cv_big += big; cv_hit += hit; cv_exact += exact; sbr_big += sbig; sbr_hit += shit;
            cv_total += a.size(); sbr_total += n;
            (void)max_nodes_seen;
        }
    }
    const double pct = cv_big ? 100.0 * cv_hit / cv_big : 0.0;
    const double rpct = sbr_big ? 100.0 * sbr_hit / sbr_big : 0.0;
    std::printf("images %zu, maps %zu: OpenCV %zu regions (%zu >= 64 px), sbr %zu regions\n", want,
                want * 2, cv_total, cv_big, sbr_total);
    std::printf("OpenCV regions >= 64 px with an sbr region at IoU >= 0.8: %zu / %zu = %.2f%% "
                "(exactly equal: %.2f%%); sbr regions >= 64 px with an OpenCV one: %.2f%%\n",
                cv_hit, cv_big, pct, cv_big ? 100.0 * cv_exact / cv_big : 0.0,
                sbr_big ? 100.0 * sbr_hit / sbr_big : 0.0);
    std::printf("time: sbr %.3f s, OpenCV %.3f s (%zu maps of about 1360x800)\n", t_sbr, t_cv, want * 2);
    std::printf("workspace per map: %zu bytes with the worst-case node bound, %zu bytes with "
                "max_nodes = pixels / 16, which gave identical regions on %zu of %zu maps\n",
                ws_full, ws_small, bounded_ok, want * 2);
    std::printf("mser_agreement_percent=%.2f\n", pct);
    if (bounded_ok != want * 2) {
        std::printf("FAIL: the bounded node pool changed the result\n");
        return 1;
    }
    std::printf("mser_reverse_agreement_percent=%.2f\n", rpct);
    int fail = 0;
    if (pct < min_percent) {
        std::printf("FAIL: OpenCV's regions found by sbr %.2f%% < %.1f%%\n", pct, min_percent);
        fail = 1;
    }
    if (rpct < min_reverse) {
        std::printf("FAIL: sbr's regions found by OpenCV %.2f%% < %.1f%%\n", rpct, min_reverse);
        fail = 1;
    }
    return fail;
}
