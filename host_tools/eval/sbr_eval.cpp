// SPDX-License-Identifier: MIT
// sbr_eval: scores a detections file against GTSDB ground truth.
//
//   sbr_eval --detections FILE --gt gt.txt [--range A-B] [--images DIR] [--iou 0.5]
//            [--threshold T] [--plot pr.png] [--confusion N]
//            [--baseline FILE [--max-drop D] [--list N]] [--json FILE]
//
// Files: NNNNN.ext;left;top;right;bottom;class_id[;score] (GTSDB's format; gt has no
// score, a detection without one counts as 1). The images evaluated: --range A-B (image
// numbers, inclusive), else the image files in --images DIR, else every image named in
// either file. Boxes match at IoU >= --iou (default 0.5), greedily by decreasing score,
// each ground-truth box at most once.
//
// Prints, at the operating point (detections with score >= --threshold, default 0):
//  - per superclass (prohibitory, mandatory, danger, other; GTSDB's ReadMe): TP, FP, FN,
//    precision, recall, F1 and AP (area under the interpolated precision-recall curve,
//    all points); a detection counts for a superclass when its class is in it and it
//    matches a ground-truth box of that superclass (the class inside may differ);
//  - class level: a match needs the same class id; P/R/F1 per class that occurs, and the
//    totals (micro average);
//  - a confusion table of the most frequent errors: wrong class on a matched box
//    (gt -> detected), missed boxes (gt -> none) and false detections (none -> detected);
//  - a precision-recall plot per superclass as PNG (--plot, default pr_curve.png).
// Last line: superclass_ap prohibitory=<x> mandatory=<x> danger=<x> other=<x> mean=<x>
//
// Regression between versions (--baseline FILE: another version's detections of the same
// images, scored the same way, same images, --iou and --threshold), printed before that
// last line:
//  - per superclass: recall, precision and AP, baseline -> this file, and the change;
//    class level: TP, FP, FN and F1, baseline -> this file;
//  - the ground-truth signs that changed at class level: found now and missed by the
//    baseline ("gained"), found by the baseline and missed now ("lost"), each with the
//    best-scoring detection of either file on its box (IoU >= --iou, any score: "class
//    30 score 0.29" shows a sign below the threshold or of the wrong class);
//  - false detections at class level that are new (no false detection of the baseline
//    in the same image with the same class at IoU >= --iou) and those that are gone;
//  - up to --list N lines of each list (default 20; the counts are always complete).
// --json FILE: the same figures as one JSON object (superclasses, class level, per class,
// and with --baseline the baseline's figures and the signs gained and lost), for scripts
// such as the cross-validation (host_tools/crossval).
// --max-drop D: the exit status is 4 when class-level F1, or any superclass's recall,
// precision or AP with ground truth in the images, is more than D below the baseline's
// (a regression gate for scripts; without --max-drop the status does not depend on it).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "cli.hpp"
#include "evaluation.hpp"
#include "gtsdb.hpp"

namespace fs = std::filesystem;

namespace {

const char *const *kSuper = sbr_host::kSuperclassNames;

// Markers that tell the superclasses apart where their curves coincide (e.g. all at
// precision 1): circle, square, triangle, diamond.
void draw_marker(cv::Mat &img, cv::Point p, int kind, const cv::Scalar &c, int r, bool filled) {
    const int t = filled ? cv::FILLED : 2;
    if (kind == 0) {
        cv::circle(img, p, r, c, t, cv::LINE_AA);
    } else if (kind == 1) {
        cv::rectangle(img, {p.x - r, p.y - r}, {p.x + r, p.y + r}, c, t, cv::LINE_AA);
    } else {
        const std::vector<cv::Point> tri = {{p.x, p.y - r - 1}, {p.x + r + 1, p.y + r}, {p.x - r - 1, p.y + r}};
        const std::vector<cv::Point> dia = {{p.x, p.y - r - 1}, {p.x + r + 1, p.y}, {p.x, p.y + r + 1}, {p.x - r - 1, p.y}};
        const std::vector<cv::Point> &poly = kind == 2 ? tri : dia;
        if (filled) cv::fillConvexPoly(img, poly, c, cv::LINE_AA);
        else cv::polylines(img, poly, true, c, 2, cv::LINE_AA);
    }
}

// The precision-recall plot: per superclass the curve down to the operating point (thick),
// its continuation down to the lowest score in the file (thin: what a lower threshold
// would give), markers staggered along each curve so coinciding curves stay visible, and
// the operating point as a large filled marker. Precision runs to 1.04 so a curve at 1.0
// lies inside the frame.
// The axes zoom to the data: each starts at the lowest recall or precision of any curve
// (rounded down to 0.05, at most 0.95) and ends just above 1, so curves near the top are
// not squeezed against the frame; the range is stated on the plot. The title names the
// images scored.
void plot_pr(const std::string &path, const sbr_host::EvalReport &r, const std::string &title) {
    const int W = 760, H = 660, x0 = 60, y0 = 50, pw = 660, ph = 440;
    double plo = 1.0, rlo = 1.0;
    for (int s = 0; s < 4; ++s) {
        if (r.n_gt[s] == 0) continue;
        for (const auto &pt : r.curve_all[s]) {
            rlo = std::min(rlo, pt.first);
            plo = std::min(plo, pt.second);
        }
        rlo = std::min(rlo, r.op_recall[s]);
        plo = std::min(plo, r.op_precision[s]);
    }
    plo = std::min(0.95, std::floor(std::max(0.0, plo - 0.02) * 20.0) / 20.0);
    rlo = std::min(0.95, std::floor(std::max(0.0, rlo - 0.02) * 20.0) / 20.0);
    const double pmax = 1.0 + 0.04 * (1.0 - plo), rmax = 1.0 + 0.02 * (1.0 - rlo);
    const double step_p = (1.0 - plo) > 0.5 ? 0.1 : 0.05, step_r = (1.0 - rlo) > 0.5 ? 0.1 : 0.05;
    auto to_px = [&](double rc, double p) {
        return cv::Point(x0 + int(std::lround((rc - rlo) / (rmax - rlo) * pw)),
                         y0 + ph - int(std::lround((p - plo) / (pmax - plo) * ph)));
    };
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int k = 0; rlo + k * step_r <= 1.0 + 1e-9; ++k) {
        const double v = rlo + k * step_r;
        const cv::Point px = to_px(v, plo);
        cv::line(img, {px.x, y0}, {px.x, y0 + ph}, cv::Scalar(225, 225, 225));
        char t[8];
        std::snprintf(t, sizeof t, "%.2f", v);
        cv::putText(img, t, {px.x - 12, y0 + ph + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    }
    for (int k = 0; plo + k * step_p <= 1.0 + 1e-9; ++k) {
        const double v = plo + k * step_p;
        const cv::Point py = to_px(rlo, v);
        cv::line(img, {x0, py.y}, {x0 + pw, py.y}, cv::Scalar(225, 225, 225));
        char t[8];
        std::snprintf(t, sizeof t, "%.2f", v);
        cv::putText(img, t, {x0 - 40, py.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    }
    cv::rectangle(img, {x0, y0}, {x0 + pw, y0 + ph}, cv::Scalar(0, 0, 0));
    cv::putText(img, title, {5, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    char axes[128];
    std::snprintf(axes, sizeof axes, "precision (axis %.2f-1)", plo);
    cv::putText(img, axes, {5, y0 - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    std::snprintf(axes, sizeof axes, "recall (axis %.2f-1)", rlo);
    cv::putText(img, axes, {x0 + pw / 2 - 60, y0 + ph + 38}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    const cv::Scalar col[4] = {cv::Scalar(40, 40, 220), cv::Scalar(220, 90, 20), cv::Scalar(20, 160, 230),
                               cv::Scalar(60, 160, 60)};
    for (int s = 0; s < 4; ++s) {
        for (int part = 0; part < 2; ++part) {  // the continuation thin, then the curve to the operating point
            const auto &curve = part == 0 ? r.curve_all[s] : r.curve_op[s];
            for (size_t i = 1; i < curve.size(); ++i)
                cv::line(img, to_px(curve[i - 1].first, curve[i - 1].second), to_px(curve[i].first, curve[i].second),
                         col[s], part == 0 ? 1 : 2, cv::LINE_AA);
        }
        // a marker every 0.1 of recall, shifted by a quarter step per superclass
        const auto &curve = r.curve_op[s];
        size_t i = 0;
        for (double r = rlo + (1.0 - rlo) * 0.025 * (s + 1); r < 1.0 && !curve.empty(); r += (1.0 - rlo) * 0.1) {
            while (i + 1 < curve.size() && curve[i].first < r) ++i;
            if (curve[i].first + 1e-9 < r) break;
            draw_marker(img, to_px(curve[i].first, curve[i].second), s, col[s], 4, false);
        }
        if (r.n_gt[s] > 0) draw_marker(img, to_px(r.op_recall[s], r.op_precision[s]), s, col[s], 7, true);
        char t[96];
        std::snprintf(t, sizeof t, "%s: AP %.3f, operating point precision %.3f recall %.3f", kSuper[s], r.ap[s],
                      r.op_precision[s], r.op_recall[s]);
        const cv::Point at(x0 + 10, y0 + ph + 64 + 20 * s);
        draw_marker(img, {at.x, at.y - 5}, s, col[s], 5, true);
        cv::putText(img, t, {at.x + 12, at.y}, cv::FONT_HERSHEY_SIMPLEX, 0.4, col[s], 1, cv::LINE_AA);
    }
    cv::putText(img, "thick: down to the operating point (large filled marker); thin: lower scores",
                {x0 + 10, H - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
    cv::imwrite(path, img);
}

struct Options {
    std::string det_path, gt_path, images_dir, plot_path = "pr_curve.png", base_path, json_path;
    double max_drop = -1.0;
    size_t list_n = 20;
    sbr_host::ImageRanges range;
    double iou_thr = 0.5, score_thr = 0.0;
    size_t confusion_n = 10;
};

// -1: go on; otherwise the exit status.
int parse_options(int argc, char **argv, Options &o) {
    CLI::App app{"sbr_eval: scores a detections file against GTSDB ground truth (docs/usage/detect.md)"};
    app.add_option("--detections", o.det_path, "detections, NNNNN.ext;left;top;right;bottom;class_id[;score]")
        ->required();
    app.add_option("--gt", o.gt_path, "ground truth in the same format (GTSDB's gt.txt)")->required();
    sbr_host::add_range_option(app, o.range, "evaluate images numbered A..B (default: --images, or every image named)");
    app.add_option("--images", o.images_dir, "evaluate the images of this folder")->check(CLI::ExistingDirectory);
    app.add_option("--iou", o.iou_thr, "a detection matches a box at IoU >= this")
        ->check(sbr_host::finite_range(1e-6, 1.0))
        ->capture_default_str();
    app.add_option("--threshold", o.score_thr, "operating point: detections with score >= this")
        ->check(sbr_host::finite_range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--plot", o.plot_path, "precision-recall plot (PNG)")->capture_default_str();
    app.add_option("--confusion", o.confusion_n, "lines of the most frequent errors")
        ->check(CLI::Range(size_t(0), size_t(100000)))
        ->capture_default_str();
    auto *base = app.add_option("--baseline", o.base_path, "another version's detections of the same images");
    app.add_option("--max-drop", o.max_drop, "exit 3 when F1 or a superclass's recall or AP drops by more")
        ->check(sbr_host::finite_range(0.0, 1.0))
        ->needs(base);
    app.add_option("--list", o.list_n, "lines of each list of changed signs (the counts are complete)")
        ->check(CLI::Range(size_t(0), size_t(100000)))
        ->capture_default_str();
    app.add_option("--json", o.json_path, "the same figures as one JSON object");
    return sbr_host::parse_cli(app, argc, argv);
}

// The images evaluated: --range, else the image files in --images, else every image named.
std::vector<int> images_of(const Options &o) {
    std::set<int> image_set;
    if (!o.range.empty()) {
        for (const auto &sp : o.range.spans)
            for (int k = sp.first; k <= sp.second; ++k) image_set.insert(k);
    } else if (!o.images_dir.empty()) {
        std::error_code ec;
        for (const auto &e : fs::directory_iterator(o.images_dir, ec)) {
            const std::string ext = e.path().extension().string();
            if (ext == ".jpg" || ext == ".png" || ext == ".ppm") image_set.insert(std::atoi(e.path().stem().c_str()));
        }
    }
    return std::vector<int>(image_set.begin(), image_set.end());  // empty: every image named
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int rc = parse_options(argc, argv, o);
    if (rc >= 0) return rc;
    sbr_host::EvalRequest q;
    q.detections = o.det_path;
    q.gt = o.gt_path;
    q.baseline = o.base_path;
    q.images = images_of(o);
    q.iou = o.iou_thr;
    q.threshold = o.score_thr;
    q.confusion = o.confusion_n;
    q.list = o.list_n;
    q.max_drop = o.max_drop;
    q.plot_path = o.plot_path;
    sbr_host::EvalReport r;
    std::string error;
    if (!sbr_host::evaluate_files(q, r, error)) {
        std::fprintf(stderr, "sbr_eval: %s\n", error.c_str());
        return 2;
    }
    std::string title = "precision-recall, images ";
    if (!o.range.empty()) title += o.range.str() + " (" + std::to_string(q.images.size()) + " images)";
    else if (!o.images_dir.empty()) title += "of " + o.images_dir + " (" + std::to_string(q.images.size()) + ")";
    else title += ": every image named in the files";
    plot_pr(o.plot_path, r, title);
    std::fputs(r.text.c_str(), stdout);
    if (!o.json_path.empty()) {
        std::ofstream j(o.json_path);
        j << r.json;
        if (!j) {
            std::fprintf(stderr, "sbr_eval: cannot write %s\n", o.json_path.c_str());
            return 1;
        }
    }
    return r.regression ? 4 : 0;
}
