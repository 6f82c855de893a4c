// SPDX-License-Identifier: MIT
// The two baselines the channel tracker is compared with: a constant-velocity Kalman
// filter with Hungarian association and a bootstrap particle filter, both inside the same
// track management as the core's tracker (confirmed by the second hit; a tentative track
// dies at its first miss, a confirmed one after more than kMaxMisses misses or when its
// estimate leaves the image; reported while it has missed at most kReportMisses frames in a
// row; gate kGate standard deviations).
#pragma once

#include <memory>
#include <vector>

#include "kitti.hpp"

namespace sbr_track_host {

constexpr unsigned kConfirmHits = 2;
constexpr unsigned kMaxMisses = 5;
constexpr unsigned kReportMisses = 2;
constexpr double kGate = 4.0;

// Both filters: white-noise acceleration `accel` (px per frame squared), measurement
// noise `r` (px), initial velocity spread `vel0` (px per frame); `particles` per track for
// the particle filter.
struct FilterParams {
    double accel = 3.0, r = 3.0, vel0 = 8.0;
    unsigned particles = 500;
};

// A multi-target tracker fed one frame of detections at a time.
class FrameTracker {
public:
    virtual ~FrameTracker() = default;
    // The tracks reported after this frame.
    virtual std::vector<Hyp> step(const std::vector<Det> &dets) = 0;
};

// Seeded with `seed`; tracks leaving width x height die.
std::unique_ptr<FrameTracker> make_kalman(const FilterParams &p, unsigned seed, double width, double height);
std::unique_ptr<FrameTracker> make_particle(const FilterParams &p, unsigned seed, double width, double height);

}  // namespace sbr_track_host
