// SPDX-License-Identifier: MIT
// The host's one detection type: a detection (or a ground-truth sign read as one) with its
// image, half-open box, class and score; made from the core's sbr_detection_t, read from
// and written to the detection files (GTSDB's inclusive format). No OpenCV.
#pragma once

#include <string>

#include "geometry.hpp"

extern "C" {
#include "sbr/recog.h"
}

namespace sbr_host {

struct Detection {
    int image = 0;       // GTSDB image number
    PixBox box;          // [x0, x1) x [y0, y1), pixels
    int class_id = 0;    // GTSDB class 0..42
    double score = 1.0;  // 0..1 (1 for ground truth and files without scores)
};

// The core's detection d on image `image` (its sbr_rect_t is half-open already).
Detection from_core(const sbr_detection_t &d, int image);

// Back to the core's type (for the core's ECU job, e.g. from a detection file): false
// unless the box is whole pixels in 0 .. 2^24 with x0 <= x1, y0 <= y1, and the class id
// fits; the score is taken as it is (the core checks its range).
bool to_core(const Detection &d, sbr_detection_t &out);

// A detection file's line, "NNNNN.ext;left;top;right;bottom;class[;score]" (inclusive
// pixels; score 1 when absent), as sbr_detect writes it; false unless it has six or seven
// fields, the first starting with the image number and the others numbers (finite; the
// class id a whole number from 0). ./sbr.sh checks a --baseline file by the same rule
// before it runs anything.
bool parse_detection_line(std::string line, Detection &d);

// The line of d for the image file `name` (score to four decimals), newline included.
std::string detection_line(const std::string &name, const Detection &d);

}  // namespace sbr_host
