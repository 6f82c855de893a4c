// SPDX-License-Identifier: MIT
#include "geometry.hpp"

#include <algorithm>
#include <limits>

namespace sbr_host {

PixBox from_inclusive(double left, double top, double right, double bottom) {
    return {left, top, right + 1.0, bottom + 1.0};
}

InclusiveBox to_inclusive(const PixBox &b) { return {b.x0, b.y0, b.x1 - 1.0, b.y1 - 1.0}; }

double box_iou(const PixBox &a, const PixBox &b) {
    const double iw = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
    const double ih = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
    if (iw <= 0 || ih <= 0) return 0.0;
    const double in = iw * ih;
    return in / ((a.x1 - a.x0) * (a.y1 - a.y0) + (b.x1 - b.x0) * (b.y1 - b.y0) - in);
}

namespace {

// The square (n + 1) x (n + 1) problem, 1-based: missing rows cost 0 (a padded row takes
// any column for free), missing columns cost `big` (a real row avoids them).
std::vector<std::vector<double>> square_costs(const std::vector<std::vector<double>> &cost, size_t rows,
                                              size_t cols, size_t n) {
    const double big = 1e9;
    std::vector<std::vector<double>> a(n + 1, std::vector<double>(n + 1, big));
    for (size_t i = 0; i < rows; ++i)
        for (size_t j = 0; j < cols; ++j) a[i + 1][j + 1] = cost[i][j];
    for (size_t i = rows; i < n; ++i)
        for (size_t j = 0; j < n; ++j) a[i + 1][j + 1] = 0.0;
    return a;
}

}  // namespace

std::vector<int> hungarian(const std::vector<std::vector<double>> &cost, size_t rows, size_t cols) {
    const size_t n = std::max(rows, cols);
    const std::vector<std::vector<double>> a = square_costs(cost, rows, cols, n);
    // potentials u (rows), v (columns); p[j]: the row assigned to column j; way[j]: the
    // column before j on the augmenting path
    std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
    std::vector<size_t> p(n + 1, 0), way(n + 1, 0);
    for (size_t i = 1; i <= n; ++i) {
        p[0] = i;
        size_t j0 = 0;
        std::vector<double> minv(n + 1, std::numeric_limits<double>::infinity());
        std::vector<char> used(n + 1, 0);
        do {
            used[j0] = 1;
            const size_t i0 = p[j0];
            double delta = std::numeric_limits<double>::infinity();
            size_t j1 = 0;
            for (size_t j = 1; j <= n; ++j) {
                if (used[j]) continue;
                const double cur = a[i0][j] - u[i0] - v[j];
                if (cur < minv[j]) {
                    minv[j] = cur;
                    way[j] = j0;
                }
                if (minv[j] < delta) {
                    delta = minv[j];
                    j1 = j;
                }
            }
            for (size_t j = 0; j <= n; ++j) {
                if (used[j]) {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            const size_t j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    std::vector<int> assign(rows, -1);
    for (size_t j = 1; j <= n; ++j) {
        if (p[j] >= 1 && p[j] <= rows && j <= cols) assign[p[j] - 1] = static_cast<int>(j - 1);
    }
    return assign;
}

}  // namespace sbr_host
