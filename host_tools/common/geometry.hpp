// SPDX-License-Identifier: MIT
// Geometry shared by the host tools: boxes, their overlap, and the assignment problem
// (Hungarian method) behind detection-to-track and ground-truth-to-hypothesis matching.
// No OpenCV: the tracking tools use it too.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace sbr_host {

// A box [x0, x1) x [y0, y1) in pixels: the host's one box convention (the core's
// sbr_rect_t is half-open too).
struct PixBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// GTSDB's files (ground truth, detection files) give inclusive pixel ranges [left, right]
// x [top, bottom]. The one conversion between the two conventions, both ways:
PixBox from_inclusive(double left, double top, double right, double bottom);
struct InclusiveBox {
    double left = 0, top = 0, right = 0, bottom = 0;
};
InclusiveBox to_inclusive(const PixBox &b);

// Intersection over union; 0 for disjoint or empty boxes.
double box_iou(const PixBox &a, const PixBox &b);

// Cost at or above which a pair counts as "not allowed" in hungarian()'s input: pad
// rectangular problems and gate pairs with it, then drop assignments whose cost is this
// high.
constexpr double kAssignForbidden = 1e6;

// Minimum-cost assignment of `rows` rows to `cols` columns (Hungarian method, O(n^3),
// n = max(rows, cols)): cost[i][j] for i < rows, j < cols. Returns, per row, its column or
// -1 when the row had to go unassigned (more rows than columns). Every assignment it
// makes is returned, forbidden ones included: the caller drops pairs whose cost is at or
// above its own gate.
std::vector<int> hungarian(const std::vector<std::vector<double>> &cost, size_t rows, size_t cols);

// Detections matched to ground truth as GTSDB's evaluation does: by decreasing score
// (ties in input order), each detection takes the not yet matched ground-truth box of
// highest IoU >= thr (ties: the later one), each ground-truth box at most once.
// iou(d, g) gives the IoU of detection d and ground-truth box g, or a negative value when
// the pair may not match (another image, another class). Returns, per detection, its
// ground-truth box or -1; gt_hit marks the matched boxes.
template <class Iou>
std::vector<int> greedy_match(const std::vector<double> &scores, size_t n_gt, double thr, Iou iou,
                              std::vector<char> &gt_hit) {
    std::vector<size_t> order(scores.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return scores[a] > scores[b]; });
    gt_hit.assign(n_gt, 0);
    std::vector<int> m(scores.size(), -1);
    for (size_t i : order) {
        double best = thr;
        int bg = -1;
        for (size_t g = 0; g < n_gt; ++g) {
            if (gt_hit[g]) continue;
            const double v = iou(i, g);
            if (v >= 0.0 && v >= best) { best = v; bg = static_cast<int>(g); }
        }
        if (bg >= 0) { m[i] = bg; gt_hit[static_cast<size_t>(bg)] = 1; }
    }
    return m;
}

}  // namespace sbr_host
