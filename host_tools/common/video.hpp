// SPDX-License-Identifier: MIT
// Recorded drives as video files (sbr_detect --input drive.mp4): frames in order with the
// file's own times (OpenCV's VideoCapture), a damaged or truncated file named with the
// frame it ends at; and the annotated video out (--annotated-video), with the boxes, the
// confirmed signs and the restrictions in force that the ECU sent on CAN drawn on it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

extern "C" {
#include "sbr/can.h"
}

namespace sbr_host {

// Whether `path` names a video file (by its extension: .mp4 .avi .mkv .mov .m4v .webm
// .mpg .mpeg, any case).
bool is_video_path(const std::string &path);

class VideoInput {
public:
    // False with `err` set when the file cannot be opened or has no frame.
    bool open(const std::string &path, std::string &err);
    // The next frame and its time in microseconds from the file's start (strictly
    // increasing: a frame without a later time than the previous one gets one period
    // more). False at the end of the frames.
    bool next(cv::Mat &frame, uint64_t &t_us);
    int64_t frames_read() const { return read_; }
    // The frame count the file's header gives (-1: unknown).
    int64_t frames_expected() const { return expected_; }
    double fps() const { return fps_; }
    // After the last next(): why the frames ended before the count the file's header
    // gives ("" when they did not, or the count is unknown).
    std::string ended_early() const;

private:
    cv::VideoCapture cap_;
    cv::Mat first_;
    bool have_first_ = false;
    int64_t read_ = 0, expected_ = -1;
    double fps_ = 0.0;
    uint64_t last_us_ = 0;
};

// What one CAN cycle of the ECU says, decoded from its frames (as a consumer reads it).
struct CycleView {
    struct Sign {
        uint32_t class_id, track_id, speed_kmh, age_frames;
        float confidence;
    };
    struct Det {
        uint32_t class_id, track_id;
        float cx, cy, w, h, confidence;
    };
    std::vector<Sign> signs;  // newest first
    std::vector<Det> dets;
    bool have_restrictions = false;
    sbr_can_restrictions_t restrictions{};
};
CycleView decode_cycle(const std::vector<sbr_can_frame_t> &frames);

// Draws a cycle on a frame: each detection's box with its class and sign id, and a panel
// with the limit in force (a roundel), the bans, priority road, and the confirmed signs.
void draw_cycle(cv::Mat &img, const CycleView &c, double t_s);

// The annotated video: written under a temporary name (same extension) and renamed over
// `path` by close(); MJPG for .avi, mp4v otherwise.
class VideoOutput {
public:
    bool open(const std::string &path, double fps, cv::Size size, std::string &err);
    void write(const cv::Mat &frame);
    // "" when the video was written whole and renamed; else why not (the temporary goes).
    std::string close();
    bool is_open() const { return writer_.isOpened(); }

private:
    cv::VideoWriter writer_;
    std::string path_, tmp_;
};

}  // namespace sbr_host
