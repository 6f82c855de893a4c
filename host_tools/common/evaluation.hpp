// SPDX-License-Identifier: MIT
// Scoring detection files against GTSDB ground truth, as sbr_eval reports it: no OpenCV,
// so the Python package (sbr.regress) links the same code and prints the same report.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "detection.hpp"

namespace sbr_host {

// Counts of one superclass, class or the class level, and what they give.
struct Prf {
    long tp = 0, fp = 0, fn = 0;
};
double precision_of(const Prf &p);
double recall_of(const Prf &p);
double f1_of(const Prf &p);

// What an evaluation is asked: the files, the images (empty: every image named in the
// detections or the ground truth), the matching and the report's lengths.
struct EvalRequest {
    std::string detections, gt, baseline;  // baseline "": none
    std::vector<int> images;
    double iou = 0.5, threshold = 0.0;
    size_t confusion = 10, list = 20;
    double max_drop = -1.0;  // < 0: no regression gate
    std::string plot_path;   // named in the report when not ""
};

// Its outcome: the report as sbr_eval prints it, the JSON form, and what a plot draws.
struct EvalReport {
    std::string text;  // every line, the last one "superclass_ap ..."
    std::string json;
    // per superclass: the curve (recall, precision) down to the operating point and down to
    // the lowest score, the operating point's precision and recall, AP, ground-truth boxes
    std::array<std::vector<std::pair<double, double>>, 4> curve_op, curve_all;
    std::array<double, 4> op_precision{}, op_recall{}, ap{};
    std::array<long, 4> n_gt{};
    double worst_drop = 0.0;  // with a baseline: the largest drop (sbr_eval --max-drop)
    bool regression = false;  // max_drop >= 0 and worst_drop > max_drop
};

// Reads and scores the files; false with `error` naming the file and the line that could
// not be read. The report's plot line names req.plot_path (the caller draws the plot).
bool evaluate_files(const EvalRequest &req, EvalReport &out, std::string &error);

// "25 road works", or "none" for -1 (a missed sign's detection, a false detection's sign).
std::string class_text(int class_id);

}  // namespace sbr_host
