// SPDX-License-Identifier: MIT
// GTSRB training crops for the host tools: the crop list with each crop's sign box, the
// fixed split of its tracks into training and validation, and the class stage's accuracy
// at the annotated boxes of a set of crops (sbr_gtsrb_eval, sbr_train_picto, sbr_crossval).
#pragma once

#include <array>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "geometry.hpp"

extern "C" {
#include "sbr/picto.h"
}

namespace sbr_host {

// One crop: file, class, track (the TTTTT of TTTTT_IIIII.ppm: one physical sign), the
// sign's box in the file's pixels, and whether its track is held out for validation.
struct GtsrbCrop {
    std::string path;
    int cls = 0;
    int track = 0;
    PixBox box;
    bool validation = false;
};

// The fixed validation split: in each class, the tracks sorted by number, the track of
// rank r (0, 1, ...) is held out when r % 5 == 2 (the third, eighth, thirteenth, ...), so
// every class with three or more tracks has validation tracks and about a fifth of them.
constexpr int kGtsrbValidationEvery = 5;
constexpr int kGtsrbValidationRank = 2;

// Every crop listed by DIR/Final_Training/Images/000NN/GT-000NN.csv (DIR may also be the
// Images folder itself), with its box scaled to the file as PROVENANCE.md says (the CSV
// holds the original crop's size and inclusive ROI; the file is resized). Sorted by
// class, track, file. Empty with `err` set when DIR holds no such CSV or a line is
// malformed.
std::vector<GtsrbCrop> read_gtsrb(const std::string &dir, std::string &err);

// The class stage's verdict on crops at their annotated boxes, accumulated.
struct GtsrbScore {
    struct PerClass {
        int n = 0, right = 0, background = 0;
    };
    std::map<int, PerClass> classes;
    std::map<std::pair<int, int>, int> confusions;  // (true, most probable other class) -> count
    int unreadable = 0;                             // files that did not decode
    // `prob`: the classifier's K + 1 outputs (the last: no sign)
    void add(int cls, const float *prob, int k);
};

// The indices of the crops with `validation` == want (every crop when `all`), in order.
std::vector<size_t> gtsrb_selection(const std::vector<GtsrbCrop> &crops, bool want, bool all);

// The class stage's K + 1 outputs (the last: no sign) for crops[idx[j]] at its annotated
// box; empty for a crop that could not be read or classified. threads: workers (>= 1).
std::vector<std::vector<float>> classify_gtsrb(const sbr_picto_model_t &picto, const std::vector<GtsrbCrop> &crops,
                                              const std::vector<size_t> &idx, unsigned threads);

// The class stage on every crop of `crops` with `validation` == want (both when
// `all`): features at the annotated box (sbr_picto_features), sbr_picto_classify.
// threads: worker threads (1 or more).
GtsrbScore score_gtsrb(const sbr_picto_model_t &picto, const std::vector<GtsrbCrop> &crops, bool want, bool all,
                       unsigned threads);

// The table: accuracy (the true class is the most probable output, "no sign" included)
// over all crops and
// per superclass, how often "no sign" is the most probable output, the danger classes'
// confusions, the worst classes. `title` heads it.
void print_gtsrb_score(std::FILE *out, const GtsrbScore &s, const std::string &title);

// The same as JSON: {"crops", "right", "no_sign", "superclasses": {name: {"crops",
// "right"}}, "classes": {id: {"crops", "right", "no_sign", "taken_for": {id: n}}}}.
std::string gtsrb_score_json(const GtsrbScore &s);

// Accuracy over all, per superclass (0..3) and the share where no sign wins.
struct GtsrbSummary {
    int n = 0, right = 0, background = 0;
    std::array<int, 4> sn{}, sright{};
};
GtsrbSummary summarise(const GtsrbScore &s);

}  // namespace sbr_host
