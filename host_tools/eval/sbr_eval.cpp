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
// --max-drop D: the exit status is 3 when class-level F1, or any superclass's recall,
// precision or AP with ground truth in the images, is more than D below the baseline's
// (a regression gate for scripts; without --max-drop the status does not depend on it).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"

namespace fs = std::filesystem;

namespace {

using sbr_host::superclass_of;  // GTSDB's ReadMe superclasses (host_tools/common/gtsdb.hpp)
const char *const *kSuper = sbr_host::kSuperclassNames;

struct Box {
    int image = 0;
    double l = 0, t = 0, r = 0, b = 0;
    int cls = 0;
    double score = 1.0;
};

bool read_boxes(const std::string &path, std::vector<Box> &out) {
    std::ifstream in(path);
    if (!in) return false;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        sbr_host::DetLine d;
        if (!sbr_host::parse_detection_line(line, d)) {
            std::fprintf(stderr, "sbr_eval: bad line in %s: %s\n", path.c_str(), line.c_str());
            return false;
        }
        Box b;
        b.image = d.image;
        b.l = d.left; b.t = d.top; b.r = d.right; b.b = d.bottom;
        b.cls = d.class_id;
        b.score = d.score;
        out.push_back(b);
    }
    return true;
}

// GTSDB boxes are inclusive pixel ranges.
double iou(const Box &a, const Box &b) {
    return sbr_host::box_iou({a.l, a.t, a.r + 1.0, a.b + 1.0}, {b.l, b.t, b.r + 1.0, b.b + 1.0});
}

struct Prf { long tp = 0, fp = 0, fn = 0; };
double prec(const Prf &p) { return p.tp + p.fp ? double(p.tp) / double(p.tp + p.fp) : 0.0; }
double rec(const Prf &p) { return p.tp + p.fn ? double(p.tp) / double(p.tp + p.fn) : 0.0; }
double f1(const Prf &p) { const double a = prec(p), b = rec(p); return a + b > 0 ? 2 * a * b / (a + b) : 0.0; }

// Greedy matching of detections to ground truth (sbr_host::greedy_match) within each image.
// `key` decides which gt a detection may match (same superclass or same class). Returns
// per detection: matched gt index or -1; `gt_hit` marks matched gt.
template <class Key>
std::vector<int> match(const std::vector<Box> &dets, const std::vector<Box> &gts, double thr, Key key,
                       std::vector<char> &gt_hit) {
    std::vector<double> scores(dets.size());
    for (size_t i = 0; i < dets.size(); ++i) scores[i] = dets[i].score;
    return sbr_host::greedy_match(scores, gts.size(), thr, [&](size_t d, size_t g) {
        return dets[d].image == gts[g].image && key(dets[d], gts[g]) ? iou(dets[d], gts[g]) : -1.0;
    }, gt_hit);
}

// AP: precision made monotone from the right, integrated over recall (all points).
double average_precision(std::vector<std::pair<double, bool>> scored, long n_gt,
                         std::vector<std::pair<double, double>> &curve) {
    std::stable_sort(scored.begin(), scored.end(), [](auto &a, auto &b) { return a.first > b.first; });
    curve.clear();
    long tp = 0, fp = 0;
    for (auto &s : scored) {
        (s.second ? tp : fp)++;
        curve.emplace_back(n_gt ? double(tp) / n_gt : 0.0, double(tp) / double(tp + fp));
    }
    if (n_gt == 0) return 0.0;
    std::vector<double> p(curve.size());
    for (size_t i = curve.size(); i-- > 0;) p[i] = std::max(curve[i].second, i + 1 < curve.size() ? p[i + 1] : 0.0);
    double ap = 0.0, prev_r = 0.0;
    for (size_t i = 0; i < curve.size(); ++i) {
        ap += (curve[i].first - prev_r) * p[i];
        prev_r = curve[i].first;
    }
    return ap;
}

// Everything sbr_eval reports about one detections file.
struct Eval {
    std::array<Prf, 4> sp{};                                        // per superclass
    std::array<double, 4> ap{};
    std::array<long, 4> n_gt{};
    std::array<std::vector<std::pair<double, double>>, 4> curves;  // recall, precision
    std::map<int, Prf> cp;                                          // per class
    Prf total;                                                      // class level
    std::vector<char> hit_cls;   // per gt: matched at class level
    std::vector<char> hit_any;   // per gt: matched by a box of any class
    std::vector<int> match_cls;  // per detection: gt matched at class level, or -1
    std::map<std::pair<int, int>, long> conf;  // (gt class or -1, det class or -1)
};

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
void plot_pr(const std::string &path, const Eval &at_op, const Eval &full) {
    const int W = 760, H = 640, x0 = 60, y0 = 30, pw = 660, ph = 440;
    const double pmax = 1.04, rmax = 1.02;
    auto to_px = [&](double r, double p) {
        return cv::Point(x0 + int(std::lround(r / rmax * pw)), y0 + ph - int(std::lround(p / pmax * ph)));
    };
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int k = 0; k <= 10; ++k) {
        const cv::Point px = to_px(k / 10.0, 0.0), py = to_px(0.0, k / 10.0);
        cv::line(img, {px.x, y0}, {px.x, y0 + ph}, cv::Scalar(225, 225, 225));
        cv::line(img, {x0, py.y}, {x0 + pw, py.y}, cv::Scalar(225, 225, 225));
        char t[8];
        std::snprintf(t, sizeof t, "%.1f", k / 10.0);
        cv::putText(img, t, {px.x - 10, y0 + ph + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
        cv::putText(img, t, {x0 - 35, py.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    }
    cv::rectangle(img, {x0, y0}, {x0 + pw, y0 + ph}, cv::Scalar(0, 0, 0));
    cv::putText(img, "recall", {x0 + pw / 2 - 20, y0 + ph + 38}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    cv::putText(img, "precision", {5, y0 - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    const cv::Scalar col[4] = {cv::Scalar(40, 40, 220), cv::Scalar(220, 90, 20), cv::Scalar(20, 160, 230),
                               cv::Scalar(60, 160, 60)};
    for (int s = 0; s < 4; ++s) {
        for (int part = 0; part < 2; ++part) {  // the continuation thin, then the curve to the operating point
            const auto &curve = part == 0 ? full.curves[s] : at_op.curves[s];
            for (size_t i = 1; i < curve.size(); ++i)
                cv::line(img, to_px(curve[i - 1].first, curve[i - 1].second), to_px(curve[i].first, curve[i].second),
                         col[s], part == 0 ? 1 : 2, cv::LINE_AA);
        }
        // a marker every 0.1 of recall, shifted by a quarter step per superclass
        const auto &curve = at_op.curves[s];
        size_t i = 0;
        for (double r = 0.025 * (s + 1); r < 1.0 && !curve.empty(); r += 0.1) {
            while (i + 1 < curve.size() && curve[i].first < r) ++i;
            if (curve[i].first + 1e-9 < r) break;
            draw_marker(img, to_px(curve[i].first, curve[i].second), s, col[s], 4, false);
        }
        if (at_op.n_gt[s] > 0) draw_marker(img, to_px(rec(at_op.sp[s]), prec(at_op.sp[s])), s, col[s], 7, true);
        char t[96];
        std::snprintf(t, sizeof t, "%s: AP %.3f, operating point precision %.3f recall %.3f", kSuper[s], at_op.ap[s],
                      prec(at_op.sp[s]), rec(at_op.sp[s]));
        const cv::Point at(x0 + 10, y0 + ph + 64 + 20 * s);
        draw_marker(img, {at.x, at.y - 5}, s, col[s], 5, true);
        cv::putText(img, t, {at.x + 12, at.y}, cv::FONT_HERSHEY_SIMPLEX, 0.4, col[s], 1, cv::LINE_AA);
    }
    cv::putText(img, "thick: down to the operating point (large filled marker); thin: lower scores",
                {x0 + 10, H - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
    cv::imwrite(path, img);
}

Eval evaluate(const std::vector<Box> &dets, const std::vector<Box> &gts, double iou_thr) {
    Eval e;
    // superclass level
    std::vector<char> hit;
    const auto msup = match(dets, gts, iou_thr, [](const Box &d, const Box &g) {
        return superclass_of(d.cls) == superclass_of(g.cls); }, hit);
    std::array<std::vector<std::pair<double, bool>>, 4> scored;
    for (size_t i = 0; i < dets.size(); ++i) {
        const int s = superclass_of(dets[i].cls);
        (msup[i] >= 0 ? e.sp[s].tp : e.sp[s].fp)++;
        scored[s].emplace_back(dets[i].score, msup[i] >= 0);
    }
    for (size_t g = 0; g < gts.size(); ++g) {
        const int s = superclass_of(gts[g].cls);
        ++e.n_gt[s];
        if (!hit[g]) ++e.sp[s].fn;
    }
    for (int s = 0; s < 4; ++s) e.ap[s] = average_precision(scored[s], e.n_gt[s], e.curves[s]);

    // class level
    e.match_cls = match(dets, gts, iou_thr, [](const Box &d, const Box &g) { return d.cls == g.cls; }, e.hit_cls);
    for (size_t i = 0; i < dets.size(); ++i) {
        (e.match_cls[i] >= 0 ? e.cp[dets[i].cls].tp : e.cp[dets[i].cls].fp)++;
        (e.match_cls[i] >= 0 ? e.total.tp : e.total.fp)++;
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!e.hit_cls[g]) { ++e.cp[gts[g].cls].fn; ++e.total.fn; }

    // confusion: class-agnostic matching, then the class pairs that differ
    const auto many = match(dets, gts, iou_thr, [](const Box &, const Box &) { return true; }, e.hit_any);
    for (size_t i = 0; i < dets.size(); ++i) {
        if (many[i] < 0) ++e.conf[{-1, dets[i].cls}];
        else if (gts[static_cast<size_t>(many[i])].cls != dets[i].cls) ++e.conf[{gts[static_cast<size_t>(many[i])].cls, dets[i].cls}];
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!e.hit_any[g]) ++e.conf[{gts[g].cls, -1}];
    return e;
}

// The boxes of `all` in the images evaluated with a score >= min_score.
std::vector<Box> select(const std::vector<Box> &all, const std::set<int> &images, double min_score) {
    std::vector<Box> out;
    for (const Box &b : all)
        if (images.count(b.image) && b.score >= min_score) out.push_back(b);
    return out;
}

std::string box_text(const Box &b) {
    char t[96];
    std::snprintf(t, sizeof t, "%05d;%.0f;%.0f;%.0f;%.0f;%d", b.image, b.l, b.t, b.r, b.b, b.cls);
    return t;
}

// The best-scoring detection of `all` (any score) on ground-truth box g, as text.
std::string best_on(const std::vector<Box> &all, const Box &g, double iou_thr) {
    const Box *best = nullptr;
    for (const Box &d : all)
        if (d.image == g.image && iou(d, g) >= iou_thr && (best == nullptr || d.score > best->score)) best = &d;
    if (best == nullptr) return "none";
    char t[64];
    std::snprintf(t, sizeof t, "class %d score %.2f", best->cls, best->score);
    return t;
}

// False detections (class level) of `a` with no false detection of `b` in the same image,
// of the same class, at IoU >= iou_thr.
std::vector<const Box *> unmatched_fps(const std::vector<Box> &a, const Eval &ea, const std::vector<Box> &b,
                                       const Eval &eb, double iou_thr) {
    std::vector<const Box *> out;
    for (size_t i = 0; i < a.size(); ++i) {
        if (ea.match_cls[i] >= 0) continue;
        bool seen = false;
        for (size_t j = 0; j < b.size() && !seen; ++j)
            seen = eb.match_cls[j] < 0 && b[j].image == a[i].image && b[j].cls == a[i].cls && iou(a[i], b[j]) >= iou_thr;
        if (!seen) out.push_back(&a[i]);
    }
    return out;
}

// Signs found at class level by `now` and not by `base` (gained), and the reverse (lost).
void changed_signs(const Eval &base, const Eval &now, std::vector<size_t> &gained, std::vector<size_t> &lost) {
    gained.clear();
    lost.clear();
    for (size_t g = 0; g < now.hit_cls.size(); ++g) {
        if (now.hit_cls[g] && !base.hit_cls[g]) gained.push_back(g);
        if (!now.hit_cls[g] && base.hit_cls[g]) lost.push_back(g);
    }
}

void json_prf(std::ostream &o, const Prf &p) {
    o << "\"tp\": " << p.tp << ", \"fp\": " << p.fp << ", \"fn\": " << p.fn << ", \"precision\": " << prec(p)
      << ", \"recall\": " << rec(p) << ", \"f1\": " << f1(p);
}

void json_eval(std::ostream &o, const Eval &e) {
    o << "{\"superclasses\": {";
    for (int s = 0; s < 4; ++s) {
        o << (s ? ", " : "") << "\"" << kSuper[s] << "\": {\"gt\": " << e.n_gt[s] << ", ";
        json_prf(o, e.sp[s]);
        o << ", \"ap\": " << e.ap[s] << "}";
    }
    o << "}, \"class_level\": {";
    json_prf(o, e.total);
    size_t found_any = 0;
    for (char h : e.hit_any) found_any += h != 0;
    o << "}, \"any_class_found\": " << found_any << ", \"classes\": {";
    bool first = true;
    for (const auto &kv : e.cp) {
        o << (first ? "" : ", ") << "\"" << kv.first << "\": {";
        json_prf(o, kv.second);
        o << "}";
        first = false;
    }
    o << "}}";
}

bool write_json(const std::string &path, const Eval &e, const Eval *base, const std::vector<Box> &gts, size_t images,
                size_t dets, double score_thr, double iou_thr) {
    std::ofstream o(path);
    o.precision(6);
    o << "{\"images\": " << images << ", \"gt\": " << gts.size() << ", \"detections\": " << dets
      << ", \"threshold\": " << score_thr << ", \"iou\": " << iou_thr << ", \"eval\": ";
    json_eval(o, e);
    if (base != nullptr) {
        o << ", \"baseline\": ";
        json_eval(o, *base);
        std::vector<size_t> gained, lost;
        changed_signs(*base, e, gained, lost);
        auto list = [&](const char *name, const std::vector<size_t> &v) {
            o << ", \"" << name << "\": [";
            for (size_t k = 0; k < v.size(); ++k) o << (k ? ", " : "") << "\"" << box_text(gts[v[k]]) << "\"";
            o << "]";
        };
        list("gained", gained);
        list("lost", lost);
    }
    o << "}\n";
    return bool(o);
}

// Prints the comparison with the baseline; returns the largest drop of class-level F1 and
// of each superclass's recall, precision and AP (superclasses with ground truth only).
double print_baseline(const std::string &path, const Eval &base, const Eval &now, const std::vector<Box> &base_dets,
                      const std::vector<Box> &dets, const std::vector<Box> &base_all, const std::vector<Box> &dets_all,
                      const std::vector<Box> &gts, double iou_thr, size_t list_n) {
    double worst = 0.0;
    auto drop = [&](double b, double n) { worst = std::max(worst, b - n); };
    std::printf("against the baseline %s (same images, IoU and threshold): baseline -> this file\n", path.c_str());
    std::printf("%-12s %26s %26s %26s\n", "superclass", "recall", "precision", "AP");
    for (int s = 0; s < 4; ++s) {
        const double r0 = rec(base.sp[s]), r1 = rec(now.sp[s]), p0 = prec(base.sp[s]), p1 = prec(now.sp[s]);
        std::printf("%-12s %6.4f -> %6.4f (%+.4f) %6.4f -> %6.4f (%+.4f) %6.4f -> %6.4f (%+.4f)\n", kSuper[s], r0, r1,
                    r1 - r0, p0, p1, p1 - p0, base.ap[s], now.ap[s], now.ap[s] - base.ap[s]);
        if (now.n_gt[s] > 0) { drop(r0, r1); drop(p0, p1); drop(base.ap[s], now.ap[s]); }
    }
    std::printf("class level: TP %ld -> %ld, FP %ld -> %ld, FN %ld -> %ld, F1 %.4f -> %.4f (%+.4f)\n", base.total.tp,
                now.total.tp, base.total.fp, now.total.fp, base.total.fn, now.total.fn, f1(base.total), f1(now.total),
                f1(now.total) - f1(base.total));
    drop(f1(base.total), f1(now.total));
    std::vector<size_t> gained, lost;
    changed_signs(base, now, gained, lost);
    auto list_signs = [&](const char *what, const std::vector<size_t> &v) {
        std::printf("signs %s: %zu (image;left;top;right;bottom;gt class: baseline | this file)\n", what, v.size());
        for (size_t k = 0; k < std::min(list_n, v.size()); ++k) {
            const Box &g = gts[v[k]];
            std::printf("  %s: %s | %s\n", box_text(g).c_str(), best_on(base_all, g, iou_thr).c_str(),
                        best_on(dets_all, g, iou_thr).c_str());
        }
    };
    list_signs("gained (found now, missed by the baseline)", gained);
    list_signs("lost (found by the baseline, missed now)", lost);
    auto list_fps = [&](const char *what, const std::vector<const Box *> &v) {
        std::printf("false detections %s: %zu (image;left;top;right;bottom;class score)\n", what, v.size());
        for (size_t k = 0; k < std::min(list_n, v.size()); ++k)
            std::printf("  %s %.2f\n", box_text(*v[k]).c_str(), v[k]->score);
    };
    list_fps("new", unmatched_fps(dets, now, base_dets, base, iou_thr));
    list_fps("gone", unmatched_fps(base_dets, base, dets, now, iou_thr));
    return worst;
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
    app.add_option("--images", o.images_dir, "evaluate the images of this folder");
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
std::set<int> images_of(const Options &o, const std::vector<Box> &gts_all, const std::vector<Box> &dets_all) {
    std::set<int> image_set;
    if (!o.range.empty()) {
        for (const auto &sp : o.range.spans)
            for (int k = sp.first; k <= sp.second; ++k) image_set.insert(k);
    } else if (!o.images_dir.empty()) {
        for (const auto &e : fs::directory_iterator(o.images_dir)) {
            const std::string ext = e.path().extension().string();
            if (ext == ".jpg" || ext == ".png" || ext == ".ppm") image_set.insert(std::atoi(e.path().stem().c_str()));
        }
    } else {
        for (const Box &b : gts_all) image_set.insert(b.image);
        for (const Box &b : dets_all) image_set.insert(b.image);
    }
    return image_set;
}

// "25 road works", or "none" for -1 (a missed sign's detection, a false detection's sign).
std::string class_text(int c) { return c < 0 ? "none" : std::to_string(c) + " " + sbr_host::class_name(c); }

// The figures at the operating point: superclasses, class level, per class, the most
// frequent errors, the plot. Returns the mean superclass AP.
double print_report(const Options &o, const Eval &e, const Eval &full, size_t images, size_t ngts, size_t ndets) {
    const auto &sp = e.sp;
    const auto &ap = e.ap;
    const Prf &total = e.total;
    std::printf("images %zu, ground-truth boxes %zu, detections %zu (score >= %.3f), IoU >= %.2f\n", images, ngts,
                ndets, o.score_thr, o.iou_thr);
    std::printf("%-12s %6s %6s %6s %10s %8s %8s %8s\n", "superclass", "TP", "FP", "FN", "precision", "recall", "F1", "AP");
    double ap_mean = 0.0;
    for (int s = 0; s < 4; ++s) {
        std::printf("%-12s %6ld %6ld %6ld %10.4f %8.4f %8.4f %8.4f\n", kSuper[s], sp[s].tp, sp[s].fp, sp[s].fn,
                    prec(sp[s]), rec(sp[s]), f1(sp[s]), ap[s]);
        ap_mean += ap[s] / 4.0;
    }
    std::printf("class level (same class id): TP %ld, FP %ld, FN %ld, precision %.4f, recall %.4f, F1 %.4f\n",
                total.tp, total.fp, total.fn, prec(total), rec(total), f1(total));
    size_t found_any = 0;
    for (char h : e.hit_any) found_any += h != 0;
    std::printf("any class (box only): %zu of %zu ground-truth boxes matched, recall %.4f\n", found_any, ngts,
                ngts == 0 ? 0.0 : double(found_any) / double(ngts));
    std::printf("%-6s %6s %6s %6s %10s %8s %8s\n", "class", "TP", "FP", "FN", "precision", "recall", "F1");
    for (auto &kv : e.cp)
        std::printf("%-6d %6ld %6ld %6ld %10.4f %8.4f %8.4f\n", kv.first, kv.second.tp, kv.second.fp, kv.second.fn,
                    prec(kv.second), rec(kv.second), f1(kv.second));
    std::vector<std::pair<long, std::pair<int, int>>> errs;
    for (auto &kv : e.conf) errs.emplace_back(kv.second, kv.first);
    std::stable_sort(errs.begin(), errs.end(), [](auto &a, auto &b) { return a.first > b.first; });
    std::printf("most frequent errors (gt -> detected; 'none' = missed / false detection):\n");
    for (size_t k = 0; k < std::min(o.confusion_n, errs.size()); ++k) {
        const auto &er = errs[k];
        std::printf("  %5ld  %-28s -> %s\n", er.first, class_text(er.second.first).c_str(),
                    class_text(er.second.second).c_str());
    }
    plot_pr(o.plot_path, e, full);
    std::printf("precision-recall plot: %s\n", o.plot_path.c_str());
    return ap_mean;
}

}  // namespace

int main(int argc, char **argv) {
    Options o;
    const int rc = parse_options(argc, argv, o);
    if (rc >= 0) return rc;
    std::vector<Box> dets_all, gts_all, base_all;
    if (!read_boxes(o.det_path, dets_all) || !read_boxes(o.gt_path, gts_all) ||
        (!o.base_path.empty() && !read_boxes(o.base_path, base_all))) {
        std::fprintf(stderr, "sbr_eval: cannot read the input files\n");
        return 1;
    }
    const std::set<int> image_set = images_of(o, gts_all, dets_all);
    const std::vector<Box> dets = select(dets_all, image_set, o.score_thr), gts = select(gts_all, image_set, 0.0);
    const Eval e = evaluate(dets, gts, o.iou_thr);
    // any score, for the plot's tail and for what lies on a changed sign
    const double any = -std::numeric_limits<double>::infinity();
    const std::vector<Box> dets_any = select(dets_all, image_set, any);
    const double ap_mean =
        print_report(o, e, evaluate(dets_any, gts, o.iou_thr), image_set.size(), gts.size(), dets.size());
    double worst = 0.0;
    Eval base_eval;
    if (!o.base_path.empty()) {
        const std::vector<Box> base = select(base_all, image_set, o.score_thr);
        base_eval = evaluate(base, gts, o.iou_thr);
        worst = print_baseline(o.base_path, base_eval, e, base, dets, select(base_all, image_set, any),
                               dets_any, gts, o.iou_thr, o.list_n);
        if (o.max_drop >= 0.0)
            std::printf("largest drop against the baseline %.4f (allowed %.4f): %s\n", worst, o.max_drop,
                        worst > o.max_drop ? "REGRESSION" : "ok");
    }
    if (!o.json_path.empty() && !write_json(o.json_path, e, o.base_path.empty() ? nullptr : &base_eval, gts,
                                            image_set.size(), dets.size(), o.score_thr, o.iou_thr)) {
        std::fprintf(stderr, "sbr_eval: cannot write %s\n", o.json_path.c_str());
        return 1;
    }
    std::printf("superclass_ap prohibitory=%.4f mandatory=%.4f danger=%.4f other=%.4f mean=%.4f\n", e.ap[0], e.ap[1],
                e.ap[2], e.ap[3], ap_mean);
    return (o.max_drop >= 0.0 && worst > o.max_drop) ? 3 : 0;
}
