// SPDX-License-Identifier: MIT
// sbr_train_picto's training samples: the annotated signs and their copies, GTSRB crops,
// the recogniser's candidates and (later rounds) its own detections, with their weights
// and standardisation.
#pragma once
#include <map>
#include <random>
#include <string>
#include <vector>

#include "gtsrb.hpp"
#include "picto_train.hpp"

namespace sbr_host::picto_train {

struct Site;

// The training samples of the images: the first round's (annotated boxes, their jittered
// and synthetic copies, the part model's candidates) or, with a class stage `mine`, the
// whole recogniser's detections with it on the training images (its own mistakes).
class SampleCollector {
public:
    SampleCollector(const Options &o, const std::vector<std::string> &files, const std::map<int, std::vector<GtBox>> &gt,
                    const sbr_model_t &pm);
    // --gtsrb: the training tracks' crops, at most --gtsrb-cap a class, evenly spread over
    // the class's crops (its tracks in order); false with the reason printed
    bool add_gtsrb(const std::string &dir);
    // Every image on 4 threads; the samples in a deterministic order.
    std::vector<Sample> collect(const sbr_picto_model_t *mine) const;

private:
    int rare_rounds(int c) const;
    void image(size_t i, const sbr_picto_model_t *mine, std::vector<uint64_t> &ws, std::mt19937 &rng,
               std::vector<Sample> &local) const;
    void sign_copies(const Site &site, int copies, std::mt19937 &rng, std::vector<Sample> &local) const;
    void gtsrb_crop(size_t i, std::mt19937 &rng, std::vector<Sample> &local) const;
    void rare_copies(const Site &site, int num, size_t g, std::vector<Sample> &local) const;
    void synth_copies(const Site &site, int n, std::mt19937 &srng, std::vector<Sample> &local) const;
    void box_jitter_copies(const Site &site, int num, size_t g, std::vector<Sample> &local) const;
    void candidates(const sbr_image_t &v, const std::vector<Box> &cands, const std::vector<Box> &gts,
                    const std::vector<int> &cls, bool mined, std::vector<Sample> &local) const;

    const Options &o_;
    const std::vector<std::string> &files_;
    const std::map<int, std::vector<GtBox>> &gt_;
    const sbr_model_t &pm_;
    std::map<int, std::vector<Box>> cand_file_;
    std::map<int, int> per_class_;
    std::vector<GtsrbCrop> gtsrb_;
};

// Samples by kind: signs, background, boxes for the box regression only.
struct Counts {
    size_t fg = 0, bg = 0, reg = 0;
};

// The samples' counts, printed with the number of images and the seconds so far.
Counts count_samples(const std::vector<Sample> &samples, size_t images, double secs);

// The features' mean and standard deviation over the samples (+ 1e-3), to standardise.
struct Standard {
    std::vector<float> mean = std::vector<float>(kF, 0.0f), sd = std::vector<float>(kF, 0.0f);
    void apply(Sample &s) const {
        for (int k = 0; k < kF; ++k) s.f[k] = (s.f[k] - mean[k]) / sd[k];
    }
};

// The samples' Standard, applied to them.
Standard standardise(std::vector<Sample> &samples);

// Sample weights: background weighted up to the signs; with --balance, rarer classes'
// samples by (n_c / mean)^-balance, scaled so the signs together weigh as before.
std::vector<float> sample_weights(const std::vector<Sample> &samples, const Counts &n, float balance);

}  // namespace sbr_host::picto_train
