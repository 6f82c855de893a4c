// SPDX-License-Identifier: MIT
#include "clear_mot.hpp"

#include <cmath>

#include "geometry.hpp"

namespace sbr_track_host {

double Mot::mota() const
{
    return gt ? 1.0 - static_cast<double>(fn + fp + idsw) / static_cast<double>(gt) : 0.0;
}

double Mot::rmse() const
{
    return matches ? std::sqrt(sq / static_cast<double>(matches)) : 0.0;
}

void Mot::add(const Mot &o)
{
    gt += o.gt;
    fn += o.fn;
    fp += o.fp;
    idsw += o.idsw;
    matches += o.matches;
    sq += o.sq;
}

void MotScorer::frame(const std::vector<Obj> &gt, const std::vector<Hyp> &hyp)
{
    m.gt += static_cast<long>(gt.size());
    std::vector<int> g2h(gt.size(), -1);
    std::vector<char> hused(hyp.size(), 0);
    auto dist = [&](size_t g, size_t h) {
        return std::hypot(gt[g].cx - hyp[h].x, gt[g].cy - hyp[h].y);
    };
    // keep last frame's correspondences while they are valid
    for (size_t g = 0; g < gt.size(); ++g) {
        auto it = prev_match.find(gt[g].id);
        if (it == prev_match.end()) continue;
        for (size_t h = 0; h < hyp.size(); ++h) {
            if (!hused[h] && hyp[h].id == it->second && dist(g, h) <= kMatchPx) {
                g2h[g] = static_cast<int>(h);
                hused[h] = 1;
            }
        }
    }
    std::vector<size_t> rows, cols;
    for (size_t g = 0; g < gt.size(); ++g)
        if (g2h[g] < 0) rows.push_back(g);
    for (size_t h = 0; h < hyp.size(); ++h)
        if (!hused[h]) cols.push_back(h);
    if (!rows.empty() && !cols.empty()) {
        std::vector<std::vector<double>> cost(rows.size(), std::vector<double>(cols.size(), sbr_host::kAssignForbidden));
        for (size_t a = 0; a < rows.size(); ++a)
            for (size_t c = 0; c < cols.size(); ++c) {
                const double d = dist(rows[a], cols[c]);
                if (d <= kMatchPx) cost[a][c] = d;
            }
        const auto asg = sbr_host::hungarian(cost, rows.size(), cols.size());
        for (size_t a = 0; a < rows.size(); ++a) {
            if (asg[a] >= 0 && cost[a][static_cast<size_t>(asg[a])] <= kMatchPx) {
                g2h[rows[a]] = static_cast<int>(cols[static_cast<size_t>(asg[a])]);
                hused[cols[static_cast<size_t>(asg[a])]] = 1;
            }
        }
    }
    prev_match.clear();
    for (size_t g = 0; g < gt.size(); ++g) {
        if (g2h[g] < 0) {
            m.fn++;
            continue;
        }
        const Hyp &h = hyp[static_cast<size_t>(g2h[g])];
        auto it = last_hyp.find(gt[g].id);
        if (it != last_hyp.end() && it->second != h.id) m.idsw++;
        last_hyp[gt[g].id] = h.id;
        prev_match[gt[g].id] = h.id;
        const double d = dist(g, static_cast<size_t>(g2h[g]));
        m.sq += d * d;
        m.matches++;
    }
    for (size_t h = 0; h < hyp.size(); ++h)
        if (!hused[h]) m.fp++;
}

}  // namespace sbr_track_host
