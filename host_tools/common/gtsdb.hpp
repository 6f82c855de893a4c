// GTSDB helpers for the host tools: ground truth, image lists, BGR views for the core.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

extern "C" {
#include "sbr/image.h"
}

namespace sbr_host {

struct GtBox {
    int left = 0, top = 0, right = 0, bottom = 0;  // inclusive pixels, as in gt.txt
    int class_id = 0;
};

// gt.txt lines "NNNNN.ppm;l;t;r;b;class", keyed by image number. Empty map if unreadable.
std::map<int, std::vector<GtBox>> read_gt(const std::string &path);

// The folder that holds the images and gt.txt: DIR itself, or DIR/FullIJCNN2013.
std::string gtsdb_image_dir(const std::string &dir);

// Image files (.jpg, .jpeg, .png, .ppm) of a folder, sorted by name.
std::vector<std::string> list_images(const std::string &dir);

// Image number of a file name like "00123.jpg" (-1 if it has none).
int image_number(const std::string &path);

// A BGR888 view of an 8-bit, 3-channel OpenCV image.
sbr_image_t bgr_view(const cv::Mat &m);

// Superclass of a GTSDB class (0 prohibitory, 1 mandatory, 2 danger, 3 other; GTSDB's
// ReadMe), the superclass names, and short class names.
int superclass_of(int class_id);
extern const char *const kSuperclassNames[4];
const char *class_name(int class_id);

}  // namespace sbr_host
