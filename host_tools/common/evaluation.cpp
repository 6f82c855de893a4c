// SPDX-License-Identifier: MIT
// Scoring detection files against GTSDB ground truth (evaluation.hpp): greedy matching per
// superclass, per class and class-agnostic, AP, the report's text and its JSON form.
#include "evaluation.hpp"

#include "classes.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace sbr_host {

double precision_of(const Prf &p) { return p.tp + p.fp ? double(p.tp) / double(p.tp + p.fp) : 0.0; }
double recall_of(const Prf &p) { return p.tp + p.fn ? double(p.tp) / double(p.tp + p.fn) : 0.0; }
double f1_of(const Prf &p) {
    const double a = precision_of(p), b = recall_of(p);
    return a + b > 0 ? 2 * a * b / (a + b) : 0.0;
}

std::string class_text(int c) { return c < 0 ? "none" : std::to_string(c) + " " + class_name(c); }

namespace {

const char *const *kSuper = kSuperclassNames;
const auto prec = precision_of;
const auto rec = recall_of;
const auto f1 = f1_of;

// printf into a string.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void appendf(std::string &s, const char *fmt, ...) {
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    const int n = std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if (size_t(n) < sizeof buf) {
        s.append(buf, size_t(n));
        return;
    }
    std::string big(size_t(n) + 1, '\0');
    va_start(ap, fmt);
    std::vsnprintf(&big[0], big.size(), fmt, ap);
    va_end(ap);
    s.append(big.c_str(), size_t(n));
}

// A detection or ground-truth box of a file (the ground truth is read as detections).
using Box = Detection;

// The boxes of a file; "" or what is wrong (the file, or its line and line number).
std::string read_boxes(const std::string &path, std::vector<Box> &out) {
    std::ifstream in(path);
    if (!in) return path + ": cannot open it";
    std::string line;
    for (long no = 1; std::getline(in, line); ++no) {
        if (line.empty() || line[0] == '#') continue;
        Detection d;
        if (!parse_detection_line(line, d)) return path + ":" + std::to_string(no) + ": not a detection line: " + line;
        out.push_back(d);
    }
    return "";
}

double iou(const Box &a, const Box &b) {
    return box_iou(a.box, b.box);
}

// Greedy matching of detections to ground truth (greedy_match) within each image. `key`
// decides which gt a detection may match (same superclass or same class). Returns per
// detection: matched gt index or -1; `gt_hit` marks matched gt.
template <class Key>
std::vector<int> match(const std::vector<Box> &dets, const std::vector<Box> &gts, double thr, Key key,
                       std::vector<char> &gt_hit) {
    std::vector<double> scores(dets.size());
    for (size_t i = 0; i < dets.size(); ++i) scores[i] = dets[i].score;
    return greedy_match(scores, gts.size(), thr, [&](size_t d, size_t g) {
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
        curve.emplace_back(n_gt ? double(tp) / double(n_gt) : 0.0, double(tp) / double(tp + fp));
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

// Everything the report says about one detections file.
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

Eval evaluate(const std::vector<Box> &dets, const std::vector<Box> &gts, double iou_thr) {
    Eval e;
    // superclass level
    std::vector<char> hit;
    const auto msup = match(dets, gts, iou_thr, [](const Box &d, const Box &g) {
        return superclass_of(d.class_id) == superclass_of(g.class_id); }, hit);
    std::array<std::vector<std::pair<double, bool>>, 4> scored;
    for (size_t i = 0; i < dets.size(); ++i) {
        const int s = superclass_of(dets[i].class_id);
        (msup[i] >= 0 ? e.sp[s].tp : e.sp[s].fp)++;
        scored[s].emplace_back(dets[i].score, msup[i] >= 0);
    }
    for (size_t g = 0; g < gts.size(); ++g) {
        const int s = superclass_of(gts[g].class_id);
        ++e.n_gt[s];
        if (!hit[g]) ++e.sp[s].fn;
    }
    for (int s = 0; s < 4; ++s) e.ap[s] = average_precision(scored[s], e.n_gt[s], e.curves[s]);

    // class level
    e.match_cls = match(dets, gts, iou_thr, [](const Box &d, const Box &g) { return d.class_id == g.class_id; }, e.hit_cls);
    for (size_t i = 0; i < dets.size(); ++i) {
        (e.match_cls[i] >= 0 ? e.cp[dets[i].class_id].tp : e.cp[dets[i].class_id].fp)++;
        (e.match_cls[i] >= 0 ? e.total.tp : e.total.fp)++;
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!e.hit_cls[g]) { ++e.cp[gts[g].class_id].fn; ++e.total.fn; }

    // confusion: class-agnostic matching, then the class pairs that differ
    const auto many = match(dets, gts, iou_thr, [](const Box &, const Box &) { return true; }, e.hit_any);
    for (size_t i = 0; i < dets.size(); ++i) {
        if (many[i] < 0) ++e.conf[{-1, dets[i].class_id}];
        else if (gts[static_cast<size_t>(many[i])].class_id != dets[i].class_id) ++e.conf[{gts[static_cast<size_t>(many[i])].class_id, dets[i].class_id}];
    }
    for (size_t g = 0; g < gts.size(); ++g)
        if (!e.hit_any[g]) ++e.conf[{gts[g].class_id, -1}];
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
    const InclusiveBox r = to_inclusive(b.box);
    std::snprintf(t, sizeof t, "%05d;%.0f;%.0f;%.0f;%.0f;%d", b.image, r.left, r.top, r.right, r.bottom, b.class_id);
    return t;
}

// The best-scoring detection of `all` (any score) on ground-truth box g, as text.
std::string best_on(const std::vector<Box> &all, const Box &g, double iou_thr) {
    const Box *best = nullptr;
    for (const Box &d : all)
        if (d.image == g.image && iou(d, g) >= iou_thr && (best == nullptr || d.score > best->score)) best = &d;
    if (best == nullptr) return "none";
    char t[64];
    std::snprintf(t, sizeof t, "class %d score %.2f", best->class_id, best->score);
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
            seen = eb.match_cls[j] < 0 && b[j].image == a[i].image && b[j].class_id == a[i].class_id && iou(a[i], b[j]) >= iou_thr;
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

std::string json_of(const Eval &e, const Eval *base, const std::vector<Box> &gts, size_t images, size_t dets,
                    double score_thr, double iou_thr) {
    std::ostringstream o;
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
    return o.str();
}

// The detection files of one comparison: at the operating point and at any score.
struct Side {
    std::vector<Box> at_op, any;
    Eval eval;
};

// The comparison with the baseline; returns the largest drop of class-level F1 and of
// each superclass's recall, precision and AP (superclasses with ground truth only).
double report_baseline(std::string &s, const std::string &path, const Side &base, const Side &now,
                       const std::vector<Box> &gts, double iou_thr, size_t list_n) {
    double worst = 0.0;
    auto drop = [&](double b, double n) { worst = std::max(worst, b - n); };
    const Eval &b = base.eval, &n = now.eval;
    appendf(s, "against the baseline %s (same images, IoU and threshold): baseline -> this file\n", path.c_str());
    appendf(s, "%-12s %26s %26s %26s\n", "superclass", "recall", "precision", "AP");
    for (int k = 0; k < 4; ++k) {
        const double r0 = rec(b.sp[k]), r1 = rec(n.sp[k]), p0 = prec(b.sp[k]), p1 = prec(n.sp[k]);
        appendf(s, "%-12s %6.4f -> %6.4f (%+.4f) %6.4f -> %6.4f (%+.4f) %6.4f -> %6.4f (%+.4f)\n", kSuper[k], r0, r1,
                r1 - r0, p0, p1, p1 - p0, b.ap[k], n.ap[k], n.ap[k] - b.ap[k]);
        if (n.n_gt[k] > 0) { drop(r0, r1); drop(p0, p1); drop(b.ap[k], n.ap[k]); }
    }
    appendf(s, "class level: TP %ld -> %ld, FP %ld -> %ld, FN %ld -> %ld, F1 %.4f -> %.4f (%+.4f)\n", b.total.tp,
            n.total.tp, b.total.fp, n.total.fp, b.total.fn, n.total.fn, f1(b.total), f1(n.total),
            f1(n.total) - f1(b.total));
    drop(f1(b.total), f1(n.total));
    std::vector<size_t> gained, lost;
    changed_signs(b, n, gained, lost);
    auto list_signs = [&](const char *what, const std::vector<size_t> &v) {
        appendf(s, "signs %s: %zu (image;left;top;right;bottom;gt class: baseline | this file)\n", what, v.size());
        for (size_t k = 0; k < std::min(list_n, v.size()); ++k) {
            const Box &g = gts[v[k]];
            appendf(s, "  %s: %s | %s\n", box_text(g).c_str(), best_on(base.any, g, iou_thr).c_str(),
                    best_on(now.any, g, iou_thr).c_str());
        }
    };
    list_signs("gained (found now, missed by the baseline)", gained);
    list_signs("lost (found by the baseline, missed now)", lost);
    auto list_fps = [&](const char *what, const std::vector<const Box *> &v) {
        appendf(s, "false detections %s: %zu (image;left;top;right;bottom;class score)\n", what, v.size());
        for (size_t k = 0; k < std::min(list_n, v.size()); ++k)
            appendf(s, "  %s %.2f\n", box_text(*v[k]).c_str(), v[k]->score);
    };
    list_fps("new", unmatched_fps(now.at_op, n, base.at_op, b, iou_thr));
    list_fps("gone", unmatched_fps(base.at_op, b, now.at_op, n, iou_thr));
    return worst;
}

// The figures at the operating point: superclasses, class level, per class (with its
// name), the most frequent errors. Returns the mean superclass AP.
double report_main(std::string &s, const EvalRequest &q, const Eval &e, size_t images, size_t ngts, size_t ndets) {
    appendf(s, "images %zu, ground-truth boxes %zu, detections %zu (score >= %.3f), IoU >= %.2f\n", images, ngts,
            ndets, q.threshold, q.iou);
    appendf(s, "%-12s %6s %6s %6s %10s %8s %8s %8s\n", "superclass", "TP", "FP", "FN", "precision", "recall", "F1", "AP");
    double ap_mean = 0.0;
    for (int k = 0; k < 4; ++k) {
        const Prf &p = e.sp[k];
        appendf(s, "%-12s %6ld %6ld %6ld %10.4f %8.4f %8.4f %8.4f\n", kSuper[k], p.tp, p.fp, p.fn, prec(p), rec(p),
                f1(p), e.ap[k]);
        ap_mean += e.ap[k] / 4.0;
    }
    appendf(s, "class level (same class id): TP %ld, FP %ld, FN %ld, precision %.4f, recall %.4f, F1 %.4f\n",
            e.total.tp, e.total.fp, e.total.fn, prec(e.total), rec(e.total), f1(e.total));
    size_t found_any = 0;
    for (char h : e.hit_any) found_any += h != 0;
    appendf(s, "any class (box only): %zu of %zu ground-truth boxes matched, recall %.4f\n", found_any, ngts,
            ngts == 0 ? 0.0 : double(found_any) / double(ngts));
    appendf(s, "%-6s %6s %6s %6s %10s %8s %8s  %s\n", "class", "TP", "FP", "FN", "precision", "recall", "F1", "name");
    for (auto &kv : e.cp)
        appendf(s, "%-6d %6ld %6ld %6ld %10.4f %8.4f %8.4f  %s\n", kv.first, kv.second.tp, kv.second.fp,
                kv.second.fn, prec(kv.second), rec(kv.second), f1(kv.second), class_name(kv.first));
    std::vector<std::pair<long, std::pair<int, int>>> errs;
    for (auto &kv : e.conf) errs.emplace_back(kv.second, kv.first);
    std::stable_sort(errs.begin(), errs.end(), [](auto &a, auto &b) { return a.first > b.first; });
    appendf(s, "most frequent errors (gt -> detected; 'none' = missed / false detection):\n");
    for (size_t k = 0; k < std::min(q.confusion, errs.size()); ++k) {
        const auto &er = errs[k];
        appendf(s, "  %5ld  %-28s -> %s\n", er.first, class_text(er.second.first).c_str(),
                class_text(er.second.second).c_str());
    }
    if (!q.plot_path.empty()) appendf(s, "precision-recall plot: %s\n", q.plot_path.c_str());
    return ap_mean;
}

}  // namespace

bool evaluate_files(const EvalRequest &q, EvalReport &out, std::string &error) {
    std::vector<Box> dets_all, gts_all, base_all;
    error = read_boxes(q.detections, dets_all);
    if (error.empty()) error = read_boxes(q.gt, gts_all);
    if (error.empty() && !q.baseline.empty()) error = read_boxes(q.baseline, base_all);
    if (!error.empty()) return false;
    std::set<int> images(q.images.begin(), q.images.end());
    if (q.images.empty()) {
        for (const Box &b : gts_all) images.insert(b.image);
        for (const Box &b : dets_all) images.insert(b.image);
    }
    const double any = -std::numeric_limits<double>::infinity();
    const std::vector<Box> gts = select(gts_all, images, 0.0);
    Side now;
    now.at_op = select(dets_all, images, q.threshold);
    now.any = select(dets_all, images, any);
    now.eval = evaluate(now.at_op, gts, q.iou);
    const Eval full = evaluate(now.any, gts, q.iou);  // the plot's tail
    out = EvalReport{};
    const double ap_mean = report_main(out.text, q, now.eval, images.size(), gts.size(), now.at_op.size());
    Side base;
    if (!q.baseline.empty()) {
        base.at_op = select(base_all, images, q.threshold);
        base.any = select(base_all, images, any);
        base.eval = evaluate(base.at_op, gts, q.iou);
        out.worst_drop = report_baseline(out.text, q.baseline, base, now, gts, q.iou, q.list);
        if (q.max_drop >= 0.0) {
            out.regression = out.worst_drop > q.max_drop;
            appendf(out.text, "largest drop against the baseline %.4f (allowed %.4f): %s\n", out.worst_drop,
                    q.max_drop, out.regression ? "REGRESSION" : "ok");
        }
    }
    const Eval &e = now.eval;
    appendf(out.text, "superclass_ap prohibitory=%.4f mandatory=%.4f danger=%.4f other=%.4f mean=%.4f\n", e.ap[0],
            e.ap[1], e.ap[2], e.ap[3], ap_mean);
    out.json = json_of(e, q.baseline.empty() ? nullptr : &base.eval, gts, images.size(), now.at_op.size(),
                       q.threshold, q.iou);
    for (int k = 0; k < 4; ++k) {
        out.curve_op[k] = e.curves[k];
        out.curve_all[k] = full.curves[k];
        out.op_precision[k] = prec(e.sp[k]);
        out.op_recall[k] = rec(e.sp[k]);
        out.ap[k] = e.ap[k];
        out.n_gt[k] = e.n_gt[k];
    }
    return true;
}

}  // namespace sbr_host
