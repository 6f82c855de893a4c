// test_recog_scenes: the recogniser (built-in library and class stage, default options)
// on real GTSDB frames of the development split, against the annotations.
//
//   test_recog_scenes --data DIR --scenes N,N,... [--max-fp-rate R]
//
// 1. Scenes: in each listed image every annotated sign is found: a detection at the
//    operating point with the annotated class and IoU >= 0.5.
// 2. Crops: the same signs in crops of the frame (4 x the sign's size, the sign off
//    centre): found again, class equal, box within IoU 0.5 of the annotation moved into
//    the crop.
// 3. Sign-free frames: every image of 00400-00599 without annotations; detections at the
//    operating point per such frame must stay <= --max-fp-rate (default 0.25).
// Exit 0 when all hold, 1 otherwise, 77 (skip) without the data.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "gtsdb.hpp"

extern "C" {
#include "sbr/recognizer.h"
}

using namespace sbr_host;

namespace {

struct Run {
    sbr_model_t model{};
    sbr_recog_config_t cfg{};
    std::vector<uint64_t> ws;
    std::vector<sbr_detection_t> dets = std::vector<sbr_detection_t>(256);

    std::vector<sbr_detection_t> detect(const cv::Mat &img, float thr) {
        const sbr_image_t v = bgr_view(img);
        const size_t need = sbr_recog_workspace_size(v.width, v.height, &cfg);
        if (ws.size() * 8 < need) ws.assign(need / 8 + 1, 0);
        uint32_t n = 0;
        const sbr_status_t st = sbr_recog_detect(&v, nullptr, &cfg, &model, ws.data(), ws.size() * 8, dets.data(),
                                                 uint32_t(dets.size()), &n, nullptr);
        std::vector<sbr_detection_t> out;
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
            std::printf("  sbr_recog_detect: %s\n", sbr_status_str(st));
            return out;
        }
        for (uint32_t i = 0; i < n; ++i)
            if (dets[i].score >= thr) out.push_back(dets[i]);
        return out;
    }
};

bool found(const std::vector<sbr_detection_t> &dets, int cls, int l, int t, int r, int b, float *best_iou) {
    *best_iou = 0;
    bool ok = false;
    for (const auto &d : dets) {
        const float o = float(box_iou(rect_pixbox(d.box), {double(l), double(t), r + 1.0, b + 1.0}));
        if (int(d.class_id) == cls) *best_iou = std::max(*best_iou, o);
        ok = ok || (int(d.class_id) == cls && o >= 0.5f);
    }
    return ok;
}

}  // namespace

int main(int argc, char **argv) {
    std::string data, scenes;
    float max_fp_rate = 0.25f;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--data") data = next();
        else if (a == "--scenes") scenes = next();
        else if (a == "--max-fp-rate") max_fp_rate = std::strtof(next().c_str(), nullptr);
        else { std::fprintf(stderr, "test_recog_scenes: unknown option %s\n", a.c_str()); return 2; }
    }
    const std::string dir = gtsdb_image_dir(data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) { std::printf("SKIP: no GTSDB ground truth under %s\n", data.c_str()); return 77; }
    Run run;
    sbr_model_gtsdb(&run.model);
    sbr_recog_config_default(&run.cfg);
    const float thr = run.model.picto.threshold;
    int failures = 0;

    std::vector<int> nums;
    {
        std::stringstream ss(scenes);
        for (std::string t; std::getline(ss, t, ',');) nums.push_back(std::atoi(t.c_str()));
    }
    for (int num : nums) {
        char file[16];
        std::snprintf(file, sizeof file, "%05d.jpg", num);
        cv::Mat img = cv::imread(dir + "/" + file, cv::IMREAD_COLOR);
        if (img.empty() || !gt.count(num)) { std::printf("FAIL %05d: no image or no annotation\n", num); ++failures; continue; }
        const auto dets = run.detect(img, thr);
        for (const auto &g : gt.at(num)) {
            float o = 0;
            const bool ok = found(dets, g.class_id, g.left, g.top, g.right, g.bottom, &o);
            std::printf("%s scene %05d class %d (%s) at %d,%d: best IoU with that class %.2f\n", ok ? "ok  " : "FAIL", num,
                        g.class_id, class_name(g.class_id), g.left, g.top, double(o));
            failures += !ok;
            // the crop: 4 x the sign's size, the sign a quarter off centre
            const int s = std::max(g.right - g.left, g.bottom - g.top) + 1;
            const int x0 = std::clamp(g.left - s - s / 2, 0, img.cols - 1), y0 = std::clamp(g.top - s - s / 4, 0, img.rows - 1);
            const int x1 = std::min(img.cols, x0 + 4 * s), y1 = std::min(img.rows, y0 + 4 * s);
            const cv::Mat crop = img(cv::Rect(x0, y0, x1 - x0, y1 - y0)).clone();
            const auto cd = run.detect(crop, thr);
            const bool cok = found(cd, g.class_id, g.left - x0, g.top - y0, g.right - x0, g.bottom - y0, &o);
            std::printf("%s crop  %05d class %d, %dx%d px: best IoU with that class %.2f\n", cok ? "ok  " : "FAIL", num,
                        g.class_id, x1 - x0, y1 - y0, double(o));
            failures += !cok;
        }
    }

    int frames = 0, fps = 0;
    for (const auto &f : list_images(dir)) {
        const int num = image_number(f);
        if (num < 400 || num > 599 || gt.count(num)) continue;
        cv::Mat img = cv::imread(f, cv::IMREAD_COLOR);
        if (img.empty()) continue;
        ++frames;
        fps += int(run.detect(img, thr).size());
    }
    const double rate = frames ? double(fps) / frames : 0.0;
    const bool rok = frames > 0 && rate <= double(max_fp_rate);
    std::printf("%s sign-free frames: %d, detections at the operating point %d (%.3f per frame, limit %.2f)\n",
                rok ? "ok  " : "FAIL", frames, fps, rate, double(max_fp_rate));
    failures += !rok;
    std::printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
    return failures ? 1 : 0;
}
