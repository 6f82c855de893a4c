// SPDX-License-Identifier: MIT
// test_builtin_models_gtsdb: a regression guard of the built-in models: the recogniser
// (built-in part model and class stage, default options) on every real GTSDB frame of a
// fixed range (default the development split 00400-00599), against the annotations; no
// hand-picked scene list.
//
//   test_builtin_models_gtsdb --data DIR [--range A-B] --min-recall R --min-crop-recall R
//                             [--max-fp-rate F]
//
// 1. Frames with signs: an annotated sign counts as found when a detection at the
//    operating point has its class and IoU >= 0.5; recall over all signs of the range
//    must be >= --min-recall.
// 2. Crops: each annotated sign in a crop of its frame (4 x the sign's size, the sign off
//    centre): found again (class equal, IoU >= 0.5 with the annotation moved into the
//    crop); recall over the crops >= --min-crop-recall.
// 3. Sign-free frames of the range: detections at the operating point per frame
//    <= --max-fp-rate (default 0.25).
// A recogniser error on any frame is a failure (never an empty detection list).
// Exit 0 when all hold, 1 otherwise, 2 for bad options, 77 (skip) without the data.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "recog_run.hpp"

extern "C" {
#include "sbr/recog.h"
#include "sbr/models.h"
}

using namespace sbr_host;

namespace {

struct Run {
    sbr_model_t model{};
    sbr_picto_model_t picto{};
    sbr_recog_config_t cfg{};
    std::vector<uint64_t> ws;
    std::vector<sbr_detection_t> dets = std::vector<sbr_detection_t>(256);
    int errors = 0;

    std::vector<sbr_detection_t> detect(const cv::Mat &img, float thr, const char *what) {
        const sbr_image_t v = bgr_view(img);
        uint32_t n = 0;
        const sbr_status_t st =
            recog_once(cfg, model, &picto, ws, v, nullptr, dets.data(), uint32_t(dets.size()), &n, nullptr);
        std::vector<sbr_detection_t> out;
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
            std::printf("FAIL %s: sbr_recog_detect: %s\n", what, sbr_status_str(st));
            ++errors;
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

struct Options {
    std::string data;
    sbr_host::ImageRanges range{{{400, 599}}};
    double min_recall = -1, min_crop_recall = -1, max_fp_rate = 0.25;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    CLI::App app{"test_builtin_models_gtsdb: the built-in recogniser on GTSDB scenes against recall and false-detection floors"};
    app.add_option("--data", o.data, "GTSDB folder")->required();
    sbr_host::add_range_option(app, o.range, "images (default 400-599)");
    app.add_option("--min-recall", o.min_recall, "fail below this sign recall")->required()->check(sbr_host::finite_range(0, 1));
    app.add_option("--min-crop-recall", o.min_crop_recall, "fail below this recall on sign crops")
        ->required()
        ->check(sbr_host::finite_range(0, 1));
    app.add_option("--max-fp-rate", o.max_fp_rate, "fail above this many false detections per sign-free frame")
        ->check(sbr_host::finite_range(0, 1000))
        ->capture_default_str();
    return sbr_host::parse_cli(app, argc, argv);
}

struct Tally {
    int signs = 0, found_n = 0, crops = 0, crops_found = 0, frames = 0, fps = 0, images = 0;
};

// One annotated sign: found in its frame's detections, and in a crop of 4 x its size
// with the sign a quarter off centre.
void check_sign(Run &run, const cv::Mat &img, int num, const GtBox &g, const std::vector<sbr_detection_t> &dets,
                float thr, Tally &t) {
    float o = 0;
    const bool ok = found(dets, g.class_id, g.left, g.top, g.right, g.bottom, &o);
    ++t.signs;
    t.found_n += ok;
    if (!ok)
        std::printf("miss  %05d class %d (%s) at %d,%d: best IoU with that class %.2f\n", num, g.class_id,
                    class_name(g.class_id), g.left, g.top, double(o));
    const int s = std::max(g.right - g.left, g.bottom - g.top) + 1;
    const int x0 = std::clamp(g.left - s - s / 2, 0, img.cols - 1), y0 = std::clamp(g.top - s - s / 4, 0, img.rows - 1);
    const int x1 = std::min(img.cols, x0 + 4 * s), y1 = std::min(img.rows, y0 + 4 * s);
    const cv::Mat crop = img(cv::Rect(x0, y0, x1 - x0, y1 - y0)).clone();
    char what[32];
    std::snprintf(what, sizeof what, "crop of %05d", num);
    const auto cd = run.detect(crop, thr, what);
    const bool cok = found(cd, g.class_id, g.left - x0, g.top - y0, g.right - x0, g.bottom - y0, &o);
    ++t.crops;
    t.crops_found += cok;
    if (!cok)
        std::printf("miss  crop of %05d class %d, %dx%d px: best IoU with that class %.2f\n", num, g.class_id,
                    x1 - x0, y1 - y0, double(o));
}

// The figures against the floors; the number of failures.
int verdict(const Options &o, const Tally &t, int errors) {
    int failures = errors;
    const double recall = t.signs ? double(t.found_n) / t.signs : 0.0;
    const double crop_recall = t.crops ? double(t.crops_found) / t.crops : 0.0;
    const double rate = t.frames ? double(t.fps) / t.frames : 0.0;
    const bool r_ok = t.signs > 0 && recall >= o.min_recall;
    const bool c_ok = t.crops > 0 && crop_recall >= o.min_crop_recall;
    const bool f_ok = t.frames > 0 && rate <= o.max_fp_rate;
    std::printf("%s frames %s: %d images, %d signs, found %d (recall %.3f, floor %.3f)\n", r_ok ? "ok  " : "FAIL",
                o.range.str(true).c_str(), t.images, t.signs, t.found_n, recall, o.min_recall);
    std::printf("%s crops: %d, found %d (recall %.3f, floor %.3f)\n", c_ok ? "ok  " : "FAIL", t.crops, t.crops_found,
                crop_recall, o.min_crop_recall);
    std::printf("%s sign-free frames: %d, detections at the operating point %d (%.3f per frame, limit %.2f)\n",
                f_ok ? "ok  " : "FAIL", t.frames, t.fps, rate, o.max_fp_rate);
    std::printf("%s recogniser errors: %d\n", errors ? "FAIL" : "ok  ", errors);
    failures += !r_ok + !c_ok + !f_ok;
    std::printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
    return failures;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int parsed = parse_options(argc, argv, o);
    if (parsed >= 0) return parsed;
    const std::string dir = gtsdb_image_dir(o.data);
    const auto gt = read_gt(dir + "/gt.txt");
    if (gt.empty()) { std::printf("SKIP: no GTSDB ground truth under %s\n", o.data.c_str()); return 77; }
    Run run;
    if (sbr_model_gtsdb(&run.model) != SBR_OK || sbr_picto_gtsdb(&run.picto) != SBR_OK) {
        std::printf("FAIL: sbr_model_gtsdb, sbr_picto_gtsdb\n");
        return 1;
    }
    sbr_recog_config_default(&run.cfg);
    const float thr = run.picto.threshold;
    Tally t;
    for (const auto &f : list_images(dir, o.range)) {
        const int num = image_number(f);
        cv::Mat img = cv::imread(f, cv::IMREAD_COLOR);
        if (img.empty()) { std::printf("FAIL %05d: cannot read the image\n", num); ++run.errors; continue; }
        ++t.images;
        char what[32];
        std::snprintf(what, sizeof what, "frame %05d", num);
        const auto dets = run.detect(img, thr, what);
        if (!gt.count(num)) {
            ++t.frames;
            t.fps += int(dets.size());
            continue;
        }
        for (const auto &g : gt.at(num)) check_sign(run, img, num, g, dets, thr, t);
    }
    return verdict(o, t, run.errors) ? 1 : 0;
}
