// SPDX-License-Identifier: MIT
#include "annotate.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sbr_host {

const cv::Scalar kFalseColour(255, 0, 255);

namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;
const double kFontScale = 0.45;
const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0);
const int kDash = 6;  // dash length of a missed sign's box, pixels

cv::Rect to_rect(const PixBox &b) {
    const int x0 = int(std::floor(b.x0)), y0 = int(std::floor(b.y0));
    return {x0, y0, std::max(1, int(std::ceil(b.x1)) - x0), std::max(1, int(std::ceil(b.y1)) - y0)};
}

cv::Scalar mark_colour(const Mark &m) {
    switch (m.kind) {
    case MarkKind::kFalse: return kFalseColour;
    case MarkKind::kMissed: return kBlack;
    default: return superclass_colour(m.class_id);
    }
}

// Black text on light label backgrounds, white on dark ones.
cv::Scalar text_colour(const cv::Scalar &bg) {
    const double luma = 0.114 * bg[0] + 0.587 * bg[1] + 0.299 * bg[2];
    return luma > 140.0 ? kBlack : kWhite;
}

std::string label_of(const Mark &m) {
    char buf[96];
    switch (m.kind) {
    case MarkKind::kMissed:
        std::snprintf(buf, sizeof buf, "missed %s", class_name(m.class_id));
        break;
    case MarkKind::kFalse:
        std::snprintf(buf, sizeof buf, "FP %s %.2f", class_name(m.class_id), m.score);
        break;
    default:
        std::snprintf(buf, sizeof buf, "%s %.2f", class_name(m.class_id), m.score);
        break;
    }
    return buf;
}

// A rectangle drawn as dashes alternating white and black (thickness 2), visible on any
// background and unlike the solid boxes of detections.
void dashed_rect(cv::Mat &img, const cv::Rect &r) {
    const cv::Point c[4] = {{r.x, r.y}, {r.x + r.width - 1, r.y}, {r.x + r.width - 1, r.y + r.height - 1},
                            {r.x, r.y + r.height - 1}};
    int phase = 0;
    for (int e = 0; e < 4; ++e) {
        const cv::Point a = c[e], b = c[(e + 1) % 4];
        const cv::Point step((b.x > a.x) - (b.x < a.x), (b.y > a.y) - (b.y < a.y));  // edges are axis-aligned
        const int len = std::max(std::abs(b.x - a.x), std::abs(b.y - a.y));
        for (int s = 0; s < len; s += kDash) {
            const int t = std::min(len, s + kDash);
            cv::line(img, a + step * s, a + step * t, (phase++ % 2) == 0 ? kWhite : kBlack, 2);
        }
    }
}

int overlap(const cv::Rect &a, const cv::Rect &b) { return (a & b).area(); }

// Where the label of box r goes: the first candidate (above, below, at either end, beside,
// then stacked further above and below) that, kept inside the image, overlaps no label
// placed so far; else the candidate with the least overlap (labels count fully, other
// boxes a quarter).
cv::Rect place_label(const cv::Rect &r, cv::Size ls, cv::Size img, const std::vector<cv::Rect> &placed,
                     const std::vector<cv::Rect> &boxes, size_t self) {
    std::vector<cv::Point> cand = {{r.x, r.y - ls.height - 1},
                                   {r.x, r.y + r.height + 1},
                                   {r.x + r.width - ls.width, r.y - ls.height - 1},
                                   {r.x + r.width - ls.width, r.y + r.height + 1},
                                   {r.x + r.width + 2, r.y},
                                   {r.x - ls.width - 2, r.y}};
    for (int k = 1; k <= 6; ++k) {
        cand.push_back({r.x, r.y - ls.height - 1 - k * (ls.height + 1)});
        cand.push_back({r.x, r.y + r.height + 1 + k * (ls.height + 1)});
    }
    cv::Rect best;
    long best_cost = -1;
    for (const cv::Point &p : cand) {
        const cv::Rect q(std::clamp(p.x, 0, std::max(0, img.width - ls.width)),
                         std::clamp(p.y, 0, std::max(0, img.height - ls.height)), ls.width, ls.height);
        long cost = 0;
        for (const cv::Rect &o : placed) cost += 4L * overlap(q, o);
        for (size_t b = 0; b < boxes.size(); ++b)
            if (b != self) cost += overlap(q, boxes[b]);
        if (best_cost < 0 || cost < best_cost) { best = q; best_cost = cost; }
        if (cost == 0) break;
    }
    return best;
}

// The distance between two rectangles (0 when they touch or overlap).
int gap(const cv::Rect &a, const cv::Rect &b) {
    const int dx = std::max({0, a.x - (b.x + b.width), b.x - (a.x + a.width)});
    const int dy = std::max({0, a.y - (b.y + b.height), b.y - (a.y + a.height)});
    return std::max(dx, dy);
}

// The legend's entries: a swatch (filled, or dashed for a missed sign) and its words.
struct LegendItem {
    cv::Scalar colour;
    bool dashed;
    const char *text;
};

// One line of legend on a black bar from (x, y) (its top), at most `width` pixels wide:
// the box colour is the superclass's; with `judged` also magenta FP (a false detection)
// and dashed (a missed sign). Returns the bar's height, 0 when it does not fit.
int draw_legend_at(cv::Mat &img, int x, int y, int width, bool judged) {
    const LegendItem all[] = {{superclass_colour(1), false, "box colour = superclass: prohibitory"},
                                {superclass_colour(33), false, "mandatory"},
                                {superclass_colour(18), false, "danger"},
                                {superclass_colour(12), false, "other"},
                                {kFalseColour, false, "FP: false detection"},
                                {kWhite, true, "missed sign"}};
    // without ground truth, nothing is judged: the superclass colours only
    const std::vector<LegendItem> items(all, all + (judged ? 6 : 4));
    int base = 0;
    const int h = cv::getTextSize("Ag", kFont, kFontScale, 1, &base).height + base + 6;
    int w = 4;
    for (const LegendItem &it : items) w += 14 + cv::getTextSize(it.text, kFont, kFontScale, 1, &base).width + 10;
    if (y < 0 || y + h > img.rows || w > width || x + w > img.cols) return 0;
    cv::rectangle(img, cv::Rect(x, y, w, h), kBlack, cv::FILLED);
    int at = x + 4;
    for (const LegendItem &it : items) {
        const cv::Rect sw(at, y + 3, 10, h - 6);
        if (it.dashed) dashed_rect(img, sw);
        else cv::rectangle(img, sw, it.colour, cv::FILLED);
        at += 14;
        cv::putText(img, it.text, {at, y + h - base - 3}, kFont, kFontScale, kWhite, 1, cv::LINE_AA);
        at += cv::getTextSize(it.text, kFont, kFontScale, 1, &base).width + 10;
    }
    return h;
}


}  // namespace

cv::Scalar superclass_colour(int class_id) {
    static const cv::Scalar colour[4] = {{0, 0, 255}, {255, 128, 0}, {0, 200, 255}, {0, 200, 0}};
    return colour[superclass_of(class_id)];
}

std::vector<Mark> judge(const std::vector<Detection> &dets, const std::vector<GtBox> &gts, bool has_gt,
                        double iou_thr) {
    std::vector<Mark> marks;
    std::vector<double> scores;
    for (const Detection &d : dets) {
        marks.push_back({d.box, d.class_id, d.score, has_gt ? MarkKind::kFound : MarkKind::kDetected});
        scores.push_back(d.score);
    }
    if (!has_gt) return marks;
    std::vector<char> hit;
    const std::vector<int> m = greedy_match(scores, gts.size(), iou_thr, [&](size_t d, size_t g) {
        return dets[d].class_id == gts[g].class_id ? box_iou(dets[d].box, gt_pixbox(gts[g])) : -1.0;
    }, hit);
    for (size_t i = 0; i < dets.size(); ++i)
        if (m[i] < 0) marks[i].kind = MarkKind::kFalse;
    for (size_t g = 0; g < gts.size(); ++g)
        if (!hit[g]) marks.push_back({gt_pixbox(gts[g]), gts[g].class_id, 0.0, MarkKind::kMissed});
    return marks;
}

std::vector<cv::Rect> draw_marks(cv::Mat &img, const std::vector<Mark> &marks) {
    std::vector<cv::Rect> boxes;
    for (const Mark &m : marks) {
        const cv::Rect r = to_rect(m.box);
        boxes.push_back(r);
        if (m.kind == MarkKind::kMissed) dashed_rect(img, r);
        else cv::rectangle(img, r, mark_colour(m), m.kind == MarkKind::kFalse ? 3 : 2);
    }
    // labels in reading order of their boxes (top to bottom, left to right)
    std::vector<size_t> order(marks.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return boxes[a].y != boxes[b].y ? boxes[a].y < boxes[b].y : boxes[a].x < boxes[b].x;
    });
    std::vector<cv::Rect> labels(marks.size()), placed;
    for (size_t i : order) {
        const std::string text = label_of(marks[i]);
        int base = 0;
        const cv::Size ts = cv::getTextSize(text, kFont, kFontScale, 1, &base);
        const cv::Size ls(ts.width + 4, ts.height + base + 4);
        const cv::Rect q = place_label(boxes[i], ls, img.size(), placed, boxes, i);
        const cv::Scalar bg = mark_colour(marks[i]);
        if (gap(q, boxes[i]) > 2)  // a leader from the label to its box
            cv::line(img, {q.x + q.width / 2, q.y + q.height / 2},
                     {boxes[i].x + boxes[i].width / 2, boxes[i].y + boxes[i].height / 2}, bg, 1, cv::LINE_AA);
        cv::rectangle(img, q, bg, cv::FILLED);
        cv::putText(img, text, {q.x + 2, q.y + ts.height + 2}, kFont, kFontScale, text_colour(bg), 1, cv::LINE_AA);
        labels[i] = q;
        placed.push_back(q);
    }
    return labels;
}

void draw_legend(cv::Mat &img, bool judged) {
    int base = 0;
    const int h = cv::getTextSize("Ag", kFont, kFontScale, 1, &base).height + base + 6;
    draw_legend_at(img, 0, img.rows - h, img.cols, judged);
}

bool WorstImages::worse(const Tile &a, const Tile &b) {
    const size_t ea = a.missed + a.false_dets, eb = b.missed + b.false_dets;
    if (ea != eb) return ea > eb;
    if (a.missed != b.missed) return a.missed > b.missed;
    return a.name < b.name;
}

void WorstImages::offer(const std::string &name, const cv::Mat &annotated, const std::vector<Mark> &marks,
                        const std::vector<cv::Rect> &labels) {
    Tile t;
    t.name = name;
    cv::Rect errors;
    for (size_t i = 0; i < marks.size(); ++i) {
        const Mark &m = marks[i];
        if (m.kind != MarkKind::kMissed && m.kind != MarkKind::kFalse) continue;
        (m.kind == MarkKind::kMissed ? t.missed : t.false_dets)++;
        cv::Rect r = to_rect(m.box);
        if (i < labels.size()) r |= labels[i];  // the label stays inside the tile
        errors = errors.area() == 0 ? r : (errors | r);
    }
    if (t.missed + t.false_dets == 0 || annotated.empty() || capacity_ == 0) return;
    if (tiles_.size() == capacity_ && !worse(t, tiles_.back())) return;
    // a 3:2 crop around the errors with context on every side, inside the image
    const int ctx = std::max(80, int(1.5 * std::max(errors.width, errors.height)));
    int w = std::max(360, errors.width + 2 * ctx), h = std::max(240, errors.height + 2 * ctx);
    if (w * 2 < h * 3) w = h * 3 / 2; else h = w * 2 / 3;
    w = std::min(w, annotated.cols);
    h = std::min(h, annotated.rows);
    const int x = std::clamp(errors.x + errors.width / 2 - w / 2, 0, annotated.cols - w);
    const int y = std::clamp(errors.y + errors.height / 2 - h / 2, 0, annotated.rows - h);
    t.crop = cv::Rect(x, y, w, h);
    cv::resize(annotated(t.crop), t.image, cv::Size(420, 280), 0, 0, cv::INTER_AREA);
    tiles_.push_back(std::move(t));
    std::stable_sort(tiles_.begin(), tiles_.end(), worse);
    if (tiles_.size() > capacity_) tiles_.pop_back();
}

bool WorstImages::write(const std::string &path) const {
    if (tiles_.empty()) return false;
    const int cols = 3, tw = 420, th = 280, cap = 24, pad = 6, title = 52;
    const int rows = int((tiles_.size() + cols - 1) / cols);
    cv::Mat sheet(title + rows * (th + cap + pad) + pad, pad + cols * (tw + pad), CV_8UC3, cv::Scalar(40, 40, 40));
    cv::putText(sheet, "worst images first: most missed signs (dashed) and false detections (magenta FP)",
                {pad, 20}, kFont, 0.55, kWhite, 1, cv::LINE_AA);
    draw_legend_at(sheet, pad, 27, sheet.cols - 2 * pad, true);
    for (size_t i = 0; i < tiles_.size(); ++i) {
        const int x = pad + int(i % cols) * (tw + pad), y = title + int(i / cols) * (th + cap + pad);
        tiles_[i].image.copyTo(sheet(cv::Rect(x, y, tw, th)));
        char buf[128];
        std::snprintf(buf, sizeof buf, "%s: %zu missed, %zu false", tiles_[i].name.c_str(), tiles_[i].missed,
                      tiles_[i].false_dets);
        cv::putText(sheet, buf, {x + 2, y + th + 17}, kFont, 0.5, kWhite, 1, cv::LINE_AA);
    }
    return cv::imwrite(path, sheet);
}

}  // namespace sbr_host
