// SPDX-License-Identifier: MIT
// GTSRB's tracks as sequences: the core's sign tracking (sbr_signs_update) over each
// track's crops in order, fed with the class stage's verdict on each crop, so that a
// track is named by its evidence the way a drive's sign is (sbr_gtsrb_eval --tracks).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "gtsrb.hpp"

extern "C" {
#include "sbr/signs.h"
}

namespace sbr_host {

// One track's outcome.
struct GtsrbTrack {
    int cls = 0, track = 0;
    int crops = 0, crops_right = 0;  // crops, and those whose most probable output is the class
    int confirmed_at = 0;            // crops until confirmation (1-based), 0: never confirmed
    int confirmed_class = -1;        // the class it was confirmed as
    int final_class = -1;            // its class after the last crop (-1: none confirmed)
    int renamed = 0;                 // renamings after confirmation
    int signs = 0;                   // distinct sign ids confirmed (1 unless the track was lost)
};

// Each track of crops[idx[...]] (idx in crop order: class, track, file) through a fresh
// sign tracking of configuration `cfg`: crop j is frame j (one period apart), a detection
// at one place of the frame (a 40-pixel box at its centre) with the class stage's most
// probable class and its probability as the score, or no detection when "no sign" wins
// (or the crop could not be read). `probs` as classify_gtsrb gives them; k classes.
// Empty with `err` set when the configuration is refused.
std::vector<GtsrbTrack> fuse_gtsrb_tracks(const std::vector<GtsrbCrop> &crops, const std::vector<size_t> &idx,
                                          const std::vector<std::vector<float>> &probs, int k,
                                          const sbr_signs_config_t &cfg, std::string &err);

// The table: per superclass and overall, per-crop accuracy, track-level accuracy (the
// class after the last crop; over all tracks, and over the tracks with at least `hits`
// crops, the confirmation's minimum), tracks confirmed as another class, tracks never confirmed,
// crops until confirmation (mean, median, 90th percentile); then each track that ended
// wrong or was confirmed wrong.
void print_gtsrb_tracks(std::FILE *out, const std::vector<GtsrbTrack> &t, int hits, const std::string &title);

// The same figures as JSON.
std::string gtsrb_tracks_json(const std::vector<GtsrbTrack> &t, int hits);

}  // namespace sbr_host
