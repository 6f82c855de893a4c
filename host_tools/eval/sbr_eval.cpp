// sbr_eval: scores a detections file against GTSDB ground truth.
//
//   sbr_eval --detections FILE --gt gt.txt [--range A-B] [--images DIR] [--iou 0.5]
//            [--threshold T] [--plot pr.png] [--confusion N]
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
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

// Greedy matching of detections to ground truth in one image set. `key` decides which gt a
// detection may match (same superclass or same class). Returns per detection: matched gt
// index or -1; `gt_hit` marks matched gt.
template <class Key>
std::vector<int> match(const std::vector<Box> &dets, const std::vector<Box> &gts, double thr, Key key,
                       std::vector<char> &gt_hit) {
    std::vector<size_t> order(dets.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return dets[a].score > dets[b].score; });
    std::map<int, std::vector<size_t>> gt_by_image;
    for (size_t g = 0; g < gts.size(); ++g) gt_by_image[gts[g].image].push_back(g);
    gt_hit.assign(gts.size(), 0);
    std::vector<int> m(dets.size(), -1);
    for (size_t i : order) {
        const Box &d = dets[i];
        double best = thr;
        int bg = -1;
        auto it = gt_by_image.find(d.image);
        if (it == gt_by_image.end()) continue;
        for (size_t g : it->second) {
            if (gt_hit[g] || !key(d, gts[g])) continue;
            const double v = iou(d, gts[g]);
            if (v >= best) { best = v; bg = static_cast<int>(g); }
        }
        if (bg >= 0) { m[i] = bg; gt_hit[static_cast<size_t>(bg)] = 1; }
    }
    return m;
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

void plot_pr(const std::string &path, const std::array<std::vector<std::pair<double, double>>, 4> &curves,
             const std::array<double, 4> &ap) {
    const int W = 640, H = 520, x0 = 60, y0 = 30, pw = 540, ph = 420;
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    for (int k = 0; k <= 10; ++k) {
        const int x = x0 + pw * k / 10, y = y0 + ph - ph * k / 10;
        cv::line(img, {x, y0}, {x, y0 + ph}, cv::Scalar(225, 225, 225));
        cv::line(img, {x0, y}, {x0 + pw, y}, cv::Scalar(225, 225, 225));
        char t[8];
        std::snprintf(t, sizeof t, "%.1f", k / 10.0);
        cv::putText(img, t, {x - 10, y0 + ph + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
        cv::putText(img, t, {x0 - 35, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
    }
    cv::rectangle(img, {x0, y0}, {x0 + pw, y0 + ph}, cv::Scalar(0, 0, 0));
    cv::putText(img, "recall", {x0 + pw / 2 - 20, H - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    cv::putText(img, "precision", {5, y0 - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0));
    const cv::Scalar col[4] = {cv::Scalar(40, 40, 220), cv::Scalar(220, 90, 20), cv::Scalar(20, 160, 230),
                               cv::Scalar(60, 160, 60)};
    for (int s = 0; s < 4; ++s) {
        cv::Point prev(x0, y0);
        bool first = true;
        for (auto &rp : curves[s]) {
            const cv::Point p(x0 + static_cast<int>(rp.first * pw), y0 + ph - static_cast<int>(rp.second * ph));
            if (!first) cv::line(img, prev, p, col[s], 2, cv::LINE_AA);
            prev = p;
            first = false;
        }
        char t[64];
        std::snprintf(t, sizeof t, "%s AP %.3f", kSuper[s], ap[s]);
        cv::putText(img, t, {x0 + 10, y0 + ph - 80 + 18 * s}, cv::FONT_HERSHEY_SIMPLEX, 0.5, col[s], 1, cv::LINE_AA);
    }
    cv::imwrite(path, img);
}

}  // namespace

int main(int argc, char **argv) {
    std::string det_path, gt_path, images_dir, plot_path = "pr_curve.png";
    int range_a = -1, range_b = -1;
    double iou_thr = 0.5, score_thr = 0.0;
    size_t confusion_n = 10;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--detections") det_path = next();
        else if (a == "--gt") gt_path = next();
        else if (a == "--images") images_dir = next();
        else if (a == "--plot") plot_path = next();
        else if (a == "--iou") iou_thr = std::atof(next().c_str());
        else if (a == "--threshold") score_thr = std::atof(next().c_str());
        else if (a == "--confusion") confusion_n = static_cast<size_t>(std::atoi(next().c_str()));
        else if (a == "--range") {
            const std::string r = next();
            if (std::sscanf(r.c_str(), "%d-%d", &range_a, &range_b) != 2 || range_a < 0 || range_b < range_a) {
                std::fprintf(stderr, "sbr_eval: --range wants A-B\n");
                return 2;
            }
        } else {
            std::fprintf(stderr, "usage: %s --detections FILE --gt gt.txt [--range A-B] [--images DIR] "
                                 "[--iou 0.5] [--threshold T] [--plot pr.png] [--confusion N]\n", argv[0]);
            return 2;
        }
    }
    if (det_path.empty() || gt_path.empty()) {
        std::fprintf(stderr, "sbr_eval: --detections and --gt are required\n");
        return 2;
    }
    std::vector<Box> dets_all, gts_all;
    if (!read_boxes(det_path, dets_all) || !read_boxes(gt_path, gts_all)) {
        std::fprintf(stderr, "sbr_eval: cannot read the input files\n");
        return 1;
    }
    std::set<int> image_set;
    if (range_a >= 0) {
        for (int k = range_a; k <= range_b; ++k) image_set.insert(k);
    } else if (!images_dir.empty()) {
        for (const auto &e : fs::directory_iterator(images_dir)) {
            const std::string ext = e.path().extension().string();
            if (ext == ".jpg" || ext == ".png" || ext == ".ppm") image_set.insert(std::atoi(e.path().stem().c_str()));
        }
    } else {
        for (const Box &b : gts_all) image_set.insert(b.image);
        for (const Box &b : dets_all) image_set.insert(b.image);
    }
    std::vector<Box> dets, gts;
    for (const Box &b : dets_all)
        if (image_set.count(b.image) && b.score >= score_thr) dets.push_back(b);
    for (const Box &b : gts_all)
        if (image_set.count(b.image)) gts.push_back(b);

    // superclass level
    std::vector<char> hit;
    const auto msup = match(dets, gts, iou_thr, [](const Box &d, const Box &g) {
        return superclass_of(d.cls) == superclass_of(g.cls); }, hit);
    std::array<Prf, 4> sp{};
    std::array<std::vector<std::pair<double, bool>>, 4> scored;
    std::array<long, 4> n_gt{};
    for (size_t i = 0; i < dets.size(); ++i) {
        const int s = superclass_of(dets[i].cls);
        (msup[i] >= 0 ? sp[s].tp : sp[s].fp)++;
        scored[s].emplace_back(dets[i].score, msup[i] >= 0);
    }
    for (size_t g = 0; g < gts.size(); ++g) {
        const int s = superclass_of(gts[g].cls);
        ++n_gt[s];
        if (!hit[g]) ++sp[s].fn;
    }
    std::array<double, 4> ap{};
    std::array<std::vector<std::pair<double, double>>, 4> curves;
    for (int s = 0; s < 4; ++s) ap[s] = average_precision(scored[s], n_gt[s], curves[s]);

    // class level
    std::vector<char> hit_c;
    const auto mcls = match(dets, gts, iou_thr, [](const Box &d, const Box &g) { return d.cls == g.cls; }, hit_c);
    std::map<int, Prf> cp;
    Prf total;
    for (size_t i = 0; i < dets.size(); ++i) {
        (mcls[i] >= 0 ? cp[dets[i].cls].tp : cp[dets[i].cls].fp)++;
        (mcls[i] >= 0 ? total.tp : total.fp)++;
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!hit_c[g]) { ++cp[gts[g].cls].fn; ++total.fn; }

    // confusion: class-agnostic matching, then the class pairs that differ
    std::vector<char> hit_any;
    const auto many = match(dets, gts, iou_thr, [](const Box &, const Box &) { return true; }, hit_any);
    std::map<std::pair<int, int>, long> conf;  // (gt class or -1, det class or -1)
    for (size_t i = 0; i < dets.size(); ++i) {
        if (many[i] < 0) ++conf[{-1, dets[i].cls}];
        else if (gts[static_cast<size_t>(many[i])].cls != dets[i].cls) ++conf[{gts[static_cast<size_t>(many[i])].cls, dets[i].cls}];
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!hit_any[g]) ++conf[{gts[g].cls, -1}];

    std::printf("images %zu, ground-truth boxes %zu, detections %zu (score >= %.3f), IoU >= %.2f\n",
                image_set.size(), gts.size(), dets.size(), score_thr, iou_thr);
    std::printf("%-12s %6s %6s %6s %10s %8s %8s %8s\n", "superclass", "TP", "FP", "FN", "precision", "recall", "F1", "AP");
    double ap_mean = 0.0;
    for (int s = 0; s < 4; ++s) {
        std::printf("%-12s %6ld %6ld %6ld %10.4f %8.4f %8.4f %8.4f\n", kSuper[s], sp[s].tp, sp[s].fp, sp[s].fn,
                    prec(sp[s]), rec(sp[s]), f1(sp[s]), ap[s]);
        ap_mean += ap[s] / 4.0;
    }
    std::printf("class level (same class id): TP %ld, FP %ld, FN %ld, precision %.4f, recall %.4f, F1 %.4f\n",
                total.tp, total.fp, total.fn, prec(total), rec(total), f1(total));
    {
        size_t found_any = 0;
        for (char h : hit_any) found_any += h != 0;
        std::printf("any class (box only): %zu of %zu ground-truth boxes matched, recall %.4f\n", found_any, gts.size(),
                    gts.empty() ? 0.0 : double(found_any) / double(gts.size()));
    }
    std::printf("%-6s %6s %6s %6s %10s %8s %8s\n", "class", "TP", "FP", "FN", "precision", "recall", "F1");
    for (auto &kv : cp)
        std::printf("%-6d %6ld %6ld %6ld %10.4f %8.4f %8.4f\n", kv.first, kv.second.tp, kv.second.fp, kv.second.fn,
                    prec(kv.second), rec(kv.second), f1(kv.second));
    std::vector<std::pair<long, std::pair<int, int>>> errs;
    for (auto &kv : conf) errs.emplace_back(kv.second, kv.first);
    std::stable_sort(errs.begin(), errs.end(), [](auto &a, auto &b) { return a.first > b.first; });
    std::printf("most frequent errors (gt -> detected; 'none' = missed / false detection):\n");
    for (size_t k = 0; k < std::min(confusion_n, errs.size()); ++k) {
        const auto &e = errs[k];
        const std::string a = e.second.first < 0 ? "none" : std::to_string(e.second.first);
        const std::string b = e.second.second < 0 ? "none" : std::to_string(e.second.second);
        std::printf("  %5ld  %4s -> %s\n", e.first, a.c_str(), b.c_str());
    }
    plot_pr(plot_path, curves, ap);
    std::printf("precision-recall plot: %s\n", plot_path.c_str());
    std::printf("superclass_ap prohibitory=%.4f mandatory=%.4f danger=%.4f other=%.4f mean=%.4f\n", ap[0], ap[1],
                ap[2], ap[3], ap_mean);
    return 0;
}
