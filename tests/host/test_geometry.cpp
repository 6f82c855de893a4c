// SPDX-License-Identifier: MIT
// The host tools' shared geometry and fan-out (host_tools/common/geometry.hpp,
// parallel.hpp): the Hungarian method's assignment cost equals brute force's optimum on
// random rectangular problems, unassigned rows only when rows outnumber columns; IoU on
// boxes whose overlap is known by construction; parallel_for runs every item once.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "geometry.hpp"
#include "parallel.hpp"

#include "test_help.hpp"

namespace {

int failures = 0;

void check(bool ok, const char *what, int i = -1)
{
    if (!ok) {
        std::printf("FAIL %s (case %d)\n", what, i);
        ++failures;
    }
}

// The optimum over every injective assignment of min(rows, cols) pairs, by permutation.
double brute_force(const std::vector<std::vector<double>> &c, size_t rows, size_t cols)
{
    const bool by_row = rows <= cols;
    const size_t small = by_row ? rows : cols, large = by_row ? cols : rows;
    std::vector<size_t> perm(large);
    std::iota(perm.begin(), perm.end(), size_t{0});
    double best = 1e300;
    do {
        double s = 0;
        for (size_t k = 0; k < small; ++k) s += by_row ? c[k][perm[k]] : c[perm[k]][k];
        best = std::min(best, s);
    } while (std::next_permutation(perm.begin(), perm.end()));
    return best;
}

void test_hungarian()
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    for (int t = 0; t < 300; ++t) {
        const size_t rows = 1 + rng() % 6, cols = 1 + rng() % 6;
        std::vector<std::vector<double>> c(rows, std::vector<double>(cols));
        for (auto &r : c)
            for (double &v : r) v = t % 3 == 0 ? std::floor(u(rng)) : u(rng);  // ties too
        const std::vector<int> a = sbr_host::hungarian(c, rows, cols);
        check(a.size() == rows, "one entry per row", t);
        std::vector<char> used(cols, 0);
        double s = 0;
        size_t assigned = 0;
        for (size_t i = 0; i < rows; ++i) {
            if (a[i] < 0) continue;
            check(size_t(a[i]) < cols && !used[size_t(a[i])], "columns in range, used once", t);
            used[size_t(a[i])] = 1;
            s += c[i][size_t(a[i])];
            ++assigned;
        }
        check(assigned == std::min(rows, cols), "min(rows, cols) pairs assigned", t);
        check(std::fabs(s - brute_force(c, rows, cols)) < 1e-9, "cost equals brute force's optimum", t);
    }
    // a known case: the diagonal is not optimal
    const std::vector<std::vector<double>> c{{4, 1, 3}, {2, 0, 5}, {3, 2, 2}};
    const std::vector<int> a = sbr_host::hungarian(c, 3, 3);
    check(a[0] == 1 && a[1] == 0 && a[2] == 2, "3x3 textbook case: 1, 0, 2 (cost 5)");
}

void test_iou()
{
    using sbr_host::box_iou;
    check(box_iou({0, 0, 10, 10}, {0, 0, 10, 10}) == 1.0, "identical boxes: 1");
    check(box_iou({0, 0, 10, 10}, {10, 0, 20, 10}) == 0.0, "touching boxes: 0");
    check(box_iou({0, 0, 10, 10}, {20, 20, 30, 30}) == 0.0, "disjoint boxes: 0");
    check(std::fabs(box_iou({0, 0, 10, 10}, {5, 0, 15, 10}) - 50.0 / 150.0) < 1e-12, "half overlap: 1/3");
    check(std::fabs(box_iou({0, 0, 10, 10}, {2, 2, 8, 8}) - 0.36) < 1e-12, "nested: area ratio 0.36");
    check(box_iou({0, 0, 0, 10}, {0, 0, 10, 10}) == 0.0, "empty box: 0");
}

void test_parallel_for()
{
    struct Worker {
        int items = 0;
    };
    const size_t n = 1000;
    std::vector<std::atomic<int>> hits(n);
    std::atomic<int> total{0};
    sbr_host::parallel_for<Worker>(n, 4, [&](size_t i, Worker &w) {
        hits[i]++;
        w.items++;
        total++;
    });
    bool once = true;
    for (auto &h : hits) once = once && h.load() == 1;
    check(once && total.load() == int(n), "parallel_for: every item exactly once");
    check(sbr_host::worker_count(0) == 1u && sbr_host::worker_count(1) == 1u, "worker_count: at least 1, at most the bound");
}

}  // namespace

int main(int argc, char **argv)
{
    const int h = test_help(argc, argv, "test_geometry: the host tools' box geometry and Hungarian assignment",
                            "test_geometry");
    if (h >= 0) return h;
    test_hungarian();
    test_iou();
    test_parallel_for();
    if (failures == 0) std::printf("geometry: hungarian (300 random problems), iou, parallel_for: all passed\n");
    return failures == 0 ? 0 : 1;
}
