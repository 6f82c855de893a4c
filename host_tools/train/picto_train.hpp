// SPDX-License-Identifier: MIT
// sbr_train_picto's shared parts: the training sample, the options, the features and
// candidate boxes every step of the class stage's training reads (docs/usage/train.md).
#pragma once
#include <opencv2/core.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gtsdb.hpp"
#include "model_io.hpp"

extern "C" {
#include "sbr/picto.h"
#include "sbr/recog.h"
}

namespace sbr_host::picto_train {

constexpr int kF = int(SBR_PICTO_FEATURES);
constexpr int kBackground = int(kGtsdbClasses);  // the background output
constexpr int kK = kBackground + 1;               // outputs
constexpr int kR = int(SBR_PICTO_BOX_OUTPUTS);
constexpr uint32_t kTriangle = uint32_t(SBR_PICTO_OUTLINE_TRIANGLE);
// Box targets are learned in units of kTargetScale (about the spread of the jitter), and
// the output rows scaled back when the weights are written.
constexpr float kTargetScale = 0.1f;
// --rare: at most this many rounds of synthetic copies (jitter copies each) per sign.
constexpr int kRareMax = 4;

using Box = PixBox;

// --bg-swap, --bg-fill: which signs are seen in front of other backgrounds.
enum class BgSwap { off, round, triangle, all };

// Options (the defaults are the shipped class stage's, except the seed: ./sbr.sh train
// passes --seed 2).
struct Options {
    std::string data = std::string(SBR_DATA_ROOT) + "/gtsdb", cand_path, out_c, out_file, model_path;
    int hidden = 128, epochs = 40, jitter = 20, box_jitter = 0;
    ImageRanges range{{{0, 399}}}, eval_range;
    float lr = 0.01f, threshold = 0.7f, bg_fraction = 0.3f, dropout = 0.5f, decay = 1e-4f, balance = 0.0f;
    int rounds = 2, rare = 0;
    std::vector<int> rim_classes{13};  // --rim-check: classes that get a colour check
    std::string from_picto;        // --from-picto: only the colour check, added to this file
    bool gate = true;              // --gate / --no-gate: learn the class stage's gate
    float gate_recall = 0.95f;     // --gate-recall: share of positive candidates it passes
    int gate_hidden = 32;          // --gate-hidden: its rectified units (0: linear)
    bool box = true, exposure = false, mirror = true, rotate = true, tview = true;
    bool degrade = false;  // --degrade: a fifth of the copies under a camera's degradations
    BgSwap bg_swap = BgSwap::round, bg_fill = BgSwap::off;
    unsigned seed = 1;
    std::string gtsrb = std::string(SBR_DATA_ROOT) + "/gtsrb";  // --gtsrb: GTSRB folder whose training tracks add sign samples
    bool gtsrb_given = false;  // --gtsrb on the command line (a missing default folder is only a note)
    int gtsrb_cap = 400;    // --gtsrb-cap: crops a class at most, spread over its tracks
    int gtsrb_copies = 2;   // --gtsrb-copies: jittered copies of each crop besides itself
    int gtsrb_synth = 0;    // --gtsrb-synth: synthetic copies of each crop (synth_copy())
    FrontEnd front_end;     // --map-subsample, --map-min-area: the part stage of the candidates
    LooksCli looks;         // --refine-score, ...: the looks written into the model (default: the table's)
    std::string trainer = "hand";            // --trainer: hand (picto_net.cpp) or sklearn (picto_fit.py)
    std::string python = SBR_PICTO_PYTHON;   // --python: the interpreter of --trainer sklearn
    std::string trainer_args;                // --trainer-args: more options for picto_fit.py
};

// One training box: its features, its class (or -1: box regression only) and, for boxes
// near a sign, where that sign's box is relative to it (the regression target).
struct Sample {
    std::vector<float> f;
    int label;
    bool has_box = false;
    float t[4] = {0, 0, 0, 0};
    bool hard = false;  // a detection of an earlier round: weighted like a sign, always seen
};

// A deterministic order of the samples, whatever order threads collected them in.
void sort_samples(std::vector<Sample> &s);

// Regression target of box b for the sign box g: centre shift in units of b's width and
// height, log size ratios (picto.h, sbr_picto_refine()).
void box_target(const Box &b, const Box &g, float t[4]);

// The core's features of box b of v (sbr_picto_features_outline()) into f; false when the
// core refuses the box.
bool features(const sbr_image_t &v, const Box &b, std::vector<float> &f,
              uint32_t outline = uint32_t(SBR_PICTO_OUTLINE_BOX));

// The boxes of sbr_recog_detect() on one image with configuration rc, best first.
std::vector<Box> recog_boxes(const sbr_image_t &v, const sbr_recog_config_t &rc, const sbr_model_t &m,
                             const sbr_picto_model_t *picto, std::vector<uint64_t> &ws);

// Boxes of one image from the recogniser: without `picto`, its part model's candidates
// (min_parts 1, no score floor); with it, the detections of the whole recogniser with
// that class stage (boxes refined, score >= 0.05).
std::vector<Box> recog_candidates(const sbr_image_t &v, const sbr_model_t &model, const sbr_picto_model_t *picto,
                                  bool triangle_view, const FrontEnd &front_end, std::vector<uint64_t> &ws);

// Boxes of a detection file (sbr_detect's format), keyed by image number.
std::map<int, std::vector<Box>> read_boxes(const std::string &path);

}  // namespace sbr_host::picto_train
