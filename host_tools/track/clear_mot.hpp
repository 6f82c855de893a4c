// SPDX-License-Identifier: MIT
// CLEAR-MOT scoring (Bernardin and Stiefelhagen 2008) of reported tracks against KITTI
// ground truth: in every frame, ground-truth objects and hypotheses are matched if their
// centres are at most kMatchPx apart; the previous frame's correspondences are kept while
// valid, the rest by the Hungarian method on the distance. MOTA = 1 - (misses + false
// positives + id switches) / ground-truth objects; RMSE over matched pairs.
#pragma once

#include <map>
#include <vector>

#include "kitti.hpp"

namespace sbr_track_host {

constexpr double kMatchPx = 20.0;

struct Mot {
    long gt = 0, fn = 0, fp = 0, idsw = 0, matches = 0;
    double sq = 0.0;  // sum of squared centre distances of the matches
    double mota() const;
    double rmse() const;
    void add(const Mot &o);
};

// One sequence's scorer: frame() for every frame in order, then m holds the counts.
struct MotScorer {
    std::map<int, unsigned> last_hyp;    // gt id -> hypothesis id of its last match
    std::map<int, unsigned> prev_match;  // gt id -> hypothesis matched in the previous frame
    Mot m;
    void frame(const std::vector<Obj> &gt, const std::vector<Hyp> &hyp);
};

}  // namespace sbr_track_host
