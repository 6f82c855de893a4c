// SPDX-License-Identifier: MIT
// Annotated pictures of the recogniser's results (sbr_detect --annotated, --overview):
// each detection judged against the ground truth when it is known (found, false, or a
// missed sign), drawn with its class name, labels placed so they neither overlap each
// other nor leave the image, and a contact sheet of the images with the most errors.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gtsdb.hpp"

namespace sbr_host {

// What a box on the picture is.
enum class MarkKind {
    kDetected,  // a detection, no ground truth to judge it by
    kFound,     // a detection that matches a ground-truth sign of its class
    kFalse,     // a detection that matches none (wrong place or wrong class)
    kMissed     // a ground-truth sign no detection of its class matches
};

struct Mark {
    PixBox box;  // [x0, x1) x [y0, y1)
    int class_id = 0;
    double score = 0.0;  // detections only
    MarkKind kind = MarkKind::kDetected;
};

// The colours (BGR): found and plain detections in their superclass's colour, false
// detections magenta, missed signs dashed in white and black.
extern const cv::Scalar kFalseColour;
cv::Scalar superclass_colour(int class_id);

// The marks of one image: its detections judged at class level against its ground truth
// (sbr_eval's rule: greedy by score, IoU >= iou_thr, same class), or all kDetected when
// has_gt is false.
std::vector<Mark> judge(const std::vector<Detection> &dets, const std::vector<GtBox> &gts, bool has_gt,
                        double iou_thr = 0.5);

// Draws the marks on img: boxes first, then one label per mark ("FP" or "missed" before
// the class name of false and missed ones) at the first place next to its box that keeps
// inside the image and clear of the labels already placed (boxes in reading order).
// Returns the label rectangles, in the order of `marks`.
std::vector<cv::Rect> draw_marks(cv::Mat &img, const std::vector<Mark> &marks);

// A legend on a bar at the bottom left (when it fits the width): the superclass of each
// box colour and, when the marks are `judged` against ground truth, what magenta (FP) and
// dashed (missed) mean.
void draw_legend(cv::Mat &img, bool judged);

// The worst images of a run, for the contact sheet: at most `capacity` kept, ranked by
// misses + false detections (then misses, then name).
class WorstImages {
public:
    explicit WorstImages(size_t capacity) : capacity_(capacity) {}
    // An annotated image, its marks and their labels (draw_marks()); kept as a tile (a crop
    // around its errors and their labels, so no label is cut at the tile's edge) when it
    // ranks among the worst so far. Images without errors are not kept.
    void offer(const std::string &name, const cv::Mat &annotated, const std::vector<Mark> &marks,
               const std::vector<cv::Rect> &labels);
    size_t size() const { return tiles_.size(); }
    // The part of its annotated image that tile i shows (worst first).
    cv::Rect crop(size_t i) const { return tiles_.at(i).crop; }
    // The contact sheet: a title and the colours' legend, the tiles, worst first, 3 a row,
    // each captioned with its name and counts. False when there is nothing to show or the file cannot be written.
    bool write(const std::string &path) const;

private:
    struct Tile {
        std::string name;
        size_t missed = 0, false_dets = 0;
        cv::Rect crop;
        cv::Mat image;
    };
    static bool worse(const Tile &a, const Tile &b);
    size_t capacity_;
    std::vector<Tile> tiles_;
};

}  // namespace sbr_host
