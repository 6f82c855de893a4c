// SPDX-License-Identifier: MIT
// KITTI tracking ground truth for the tracking tools (sbr_track, sbr_train_track): the
// label files, the documented corruption that turns ground truth into detections, a
// synthetic sequence for timing, and KITTI's result format.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace sbr_track_host {

// KITTI: 10 frames per second.
constexpr float kPeriod = 0.1f;
constexpr uint32_t kPeriodUs = 100000u;  // the same in microseconds (sbr_track_step())

// A labelled object of one frame: its id, KITTI class and box centre and size, pixels.
struct Obj {
    int id;
    std::string type;
    double cx, cy, w, h;
};

struct Seq {
    std::string name;
    int frames = 0;
    double width = 1242.0, height = 375.0;
    std::vector<std::vector<Obj>> gt;  // per frame
};

// A detection: a box centre and size without identity.
struct Det {
    double x, y, w, h;
    std::string type;
};

// A reported track in one frame.
struct Hyp {
    unsigned id;
    double x, y, w, h;
    std::string type;
};

// The non-empty pieces of s between separators c.
std::vector<std::string> split_list(const std::string &s, char c);

// Sequence names ("0006") of a list of numbers and inclusive ranges: "0006-0010", "1,3,5".
std::vector<std::string> parse_seqs(const std::string &s);

// DIR/NAME.txt, keeping the objects of `classes`. The frame count comes from KITTI's
// sequence map (DIR/../evaluate_tracking.seqmap.training) when it is there, else from the
// labels. False if the file cannot be read.
bool load_seq(const std::string &dir, const std::string &name, const std::set<std::string> &classes, Seq &seq);

// Every sequence of `names` from the label folder `dir` into seqs; "" on success, else the
// reason (a file that cannot be read, or no sequence named).
std::string load_seqs(const std::string &dir, const std::vector<std::string> &names,
                      const std::set<std::string> &classes, std::vector<Seq> &seqs);

// The documented corruption, one generator per (seed, sequence): every object dropped
// with probability `miss`, else its centre moved by Gaussian noise of `noise` px per axis
// (clamped into the image); a Poisson number (mean `clutter`) of uniform clutter
// detections added; each frame's detections shuffled.
std::vector<std::vector<Det>> corrupt(const Seq &seq, double noise, double miss, double clutter, unsigned seed);

// `frames` frames of `n` targets on an 8-column grid over a KITTI-sized image, each at a
// constant velocity of up to 3 px per frame, turning back at its cell's edge (they never
// meet): the time per frame with n targets in view.
Seq synthetic_seq(unsigned n, int frames, unsigned seed);

// DIR/SEQ.txt in KITTI's tracking result format, one line per hypothesis and frame.
void write_kitti(const std::string &dir, const std::string &seq, const std::vector<std::vector<Hyp>> &per_frame);

}  // namespace sbr_track_host
