// SPDX-License-Identifier: MIT
// GTSDB helpers for the host tools: ground truth, image lists, BGR views for the core.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "classes.hpp"
#include "evaluation.hpp"
#include "geometry.hpp"

extern "C" {
#include "sbr/image.h"
}

namespace sbr_host {

struct GtBox {
    int left = 0, top = 0, right = 0, bottom = 0;  // inclusive pixels, as in gt.txt
    int class_id = 0;
};

// The box of a ground-truth line (its right and bottom + 1) and of a core rectangle.
PixBox gt_pixbox(const GtBox &g);
PixBox rect_pixbox(const sbr_rect_t &r);

// Detection and parse_detection_line(): detection.hpp.

// gt.txt lines "NNNNN.ppm;l;t;r;b;class", keyed by image number. Empty map if unreadable.
std::map<int, std::vector<GtBox>> read_gt(const std::string &path);

// The folder that holds the images and gt.txt: DIR itself, or DIR/FullIJCNN2013.
std::string gtsdb_image_dir(const std::string &dir);

// Image files (.jpg, .jpeg, .png, .ppm) of a folder, sorted by name (symbolic links to
// files count as files). `problem`, when given, gets the first reason the folder or one of
// its image entries could not be read ("" when none): a caller that finds no image can
// then say why instead of "no images".
std::vector<std::string> list_images(const std::string &dir, std::string *problem = nullptr);

// Why an image file cannot be trusted to decode whole, or "" when it looks complete:
// empty, a JPEG without its end-of-image marker in the last kilobyte, a PNG without its
// IEND chunk at the end, a PPM shorter than its header's size. OpenCV decodes a truncated
// JPEG without an error (the missing rows grey), so readers check this first.
std::string image_file_problem(const std::string &path);
// The image (BGR) read once from its file: "" and img set, or the problem (the file's, as
// image_file_problem() says, or "cannot decode it").
std::string read_image(const std::string &path, cv::Mat &img);

// Image number of a file name like "00123.jpg" (-1 if it has none).
int image_number(const std::string &path);

// A set of image numbers given as inclusive spans "A-B[,C-D...]", e.g. "0-199,400-599"
// (the training folds of a cross-validation). Spans are kept sorted and merged.
struct ImageRanges {
    std::vector<std::pair<int, int>> spans;
    bool empty() const { return spans.empty(); }
    bool contains(int n) const;
    // "0-199,400-599" (as --range takes it), padded: "00000-00199,00400-00599"; "all"
    // when empty
    std::string str(bool padded = false) const;
};
// Largest image number a range may name (GTSDB numbers its images with five digits).
constexpr long kMaxImageNumber = 99999999;
// False (and out untouched) unless s is one or more spans A-B with 0 <= A <= B,
// separated by commas.
bool parse_image_ranges(const std::string &s, ImageRanges &out);
// The images of a folder (list_images()) whose number is in `range`; every image when
// the range is empty.
std::vector<std::string> list_images(const std::string &dir, const ImageRanges &range,
                                     std::string *problem = nullptr);

// FNV-1a (64 bit) of n bytes, continuing from h (start: kFnvStart): checksums with which
// benchmarks show that two builds computed bit-identical results.
constexpr uint64_t kFnvStart = 1469598103934665603ull;
uint64_t fnv1a(uint64_t h, const void *p, size_t n);

// A BGR888 view of an 8-bit, 3-channel OpenCV image (a GRAY8 view of a 1-channel one).
sbr_image_t bgr_view(const cv::Mat &m);

}  // namespace sbr_host
