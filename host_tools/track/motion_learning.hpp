// SPDX-License-Identifier: MIT
// Learning of the channel tracker's motion model (paper E) from detections without track
// ids, and its generated C form (lib/models/sbr_track_model_kitti.c).
//
// Every detection triple of three consecutive frames whose displacements fit the velocity
// range adds a channel-coded soft count per image region (pairs: the birth prior); each
// middle detection spreads one unit over its candidate triples. Later passes of a soft
// EM weight a middle detection's triples by the previous pass's transition probability.
// A row gets a wide constant-velocity tail (a share `tail` of the row, at least one
// count) so rows with little data stay usable.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "kitti.hpp"
#include "track_model_io.hpp"

namespace sbr_track_host {

struct LearnParams {
    uint32_t vel_count = 41;     // velocity channels (odd)
    float vel_spacing = 3.5f;    // pixels per period between velocity channels
    uint32_t regions[2] = {10, 5};
    double tail = 0.01;          // share of a learned row given to the constant-velocity tail
    double tail_sigma = 2.0;     // its standard deviation, velocity channels
    int em_iters = 3;            // passes of the soft association EM
};

struct LearnStats {
    long triples = 0, pairs = 0;  // detection triples and pairs of the last pass
};

// The model learned from seqs' detections (dets[i] belongs to seqs[i]; the image size is
// seqs.front()'s).
sbr_host::TrackModel learn_motion_model(const std::vector<Seq> &seqs,
                                        const std::vector<std::vector<std::vector<Det>>> &dets,
                                        const LearnParams &p, LearnStats &stats);

// The model as a generated C source defining sbr_track_model_kitti(); `header` goes into
// its opening comment. "" on success, else the reason.
std::string write_model_c(const sbr_host::TrackModel &d, const std::string &path, const std::string &header);

}  // namespace sbr_track_host
