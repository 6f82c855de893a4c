// SPDX-License-Identifier: MIT
// sbr_train_picto's synthetic copies of a sign: jittered, shrunk, re-exposed, in front of
// another background, turned by its symmetry or mirrored (make_copy()), and the harder
// copies of the rare classes (synth_copy()).
#pragma once
#include <opencv2/core.hpp>

#include <random>
#include <vector>

#include "picto_train.hpp"

namespace sbr_host::picto_train {

// The class a GTSDB sign of class c shows in a mirror, -1 when no class does (digits,
// text, vehicles and other pictograms that are not left-right symmetric).
int mirror_class(int c);

// The order of a GTSDB class's rotational symmetry (its sign looks the same turned by
// 360 / order degrees about its centre), 1 when it has none.
int symmetry_order(int c);

// One annotated sign of an image: its box, size and class, and its neighbourhood (one
// sign size around it, clipped to the image) that the transformed copies are taken from.
struct Site {
    const cv::Mat *img;
    const sbr_image_t *view;
    const std::vector<Box> *gts;  // every annotated box of the image
    Box b;
    float w, h;
    int mx0, my0, mx1, my1;
    cv::Mat near;
    int cls;
};

// Sign g of the annotated boxes gts of img (its view v), of class cls.
Site make_site(const cv::Mat &img, const sbr_image_t &v, const std::vector<Box> &gts, size_t g, int cls);

// A training copy of a sign: the jittered box q; the box qs of image `seen` (empty: the
// frame itself) with class `label`; mirrored copies flip the target's horizontal shift.
struct Copy {
    Box q;
    cv::Mat seen;
    Box qs;
    int label;
    bool mirrored;
};

// Copy j of a sign (j = 0: the annotated box itself), drawn from rng in a fixed order.
Copy make_copy(const Options &o, const Site &site, int j, std::mt19937 &rng);

// One synthetic copy of the sign b for --rare: its neighbourhood `near` (at mx0, my0 in
// img) in perspective, under another exposure, blurred, sometimes partly occluded and
// often smaller. Returns the image and the sign's box in it (qs); empty if nothing fit.
cv::Mat synth_copy(const cv::Mat &img, const cv::Mat &near, const Box &b, const std::vector<Box> &gts, int mx0,
                   int my0, std::mt19937 &rng, Box &qs);

}  // namespace sbr_host::picto_train
