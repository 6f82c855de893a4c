// Geometry shared by the host tools: boxes, their overlap, and the assignment problem
// (Hungarian method) behind detection-to-track and ground-truth-to-hypothesis matching.
// No OpenCV: the tracking tools use it too.
#pragma once

#include <cstddef>
#include <vector>

namespace sbr_host {

// A box [x0, x1) x [y0, y1) in pixels. GTSDB's files give inclusive pixel ranges: their
// right and bottom get + 1 (gt_pixbox() in gtsdb.hpp).
struct PixBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

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

}  // namespace sbr_host
