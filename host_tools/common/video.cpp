// SPDX-License-Identifier: MIT
#include "video.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "annotate.hpp"
#include "classes.hpp"
#include "output_file.hpp"

namespace sbr_host {

namespace fs = std::filesystem;

bool is_video_path(const std::string &path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const char *v : {".mp4", ".avi", ".mkv", ".mov", ".m4v", ".webm", ".mpg", ".mpeg"})
        if (ext == v) return true;
    return false;
}

bool VideoInput::open(const std::string &path, std::string &err) {
    bool opened = false;
    try {
        opened = cap_.open(path, cv::CAP_FFMPEG);
    } catch (const cv::Exception &) {
        opened = false;
    }
    if (!opened) {
        err = "not a video this build of OpenCV can read";
        return false;
    }
    fps_ = cap_.get(cv::CAP_PROP_FPS);
    if (!(fps_ > 0.0 && fps_ < 1000.0)) fps_ = 10.0;
    const double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
    expected_ = n >= 1.0 && n < 1e9 ? int64_t(n) : -1;
    try {
        have_first_ = cap_.read(first_) && !first_.empty();
    } catch (const cv::Exception &) {
        have_first_ = false;
    }
    if (!have_first_) {
        err = "a video without a readable frame (damaged, or not a video)";
        return false;
    }
    return true;
}

bool VideoInput::next(cv::Mat &frame, uint64_t &t_us) {
    const double period_us = 1e6 / fps_;
    double ms = 0.0;
    if (have_first_) {
        frame = first_;
        first_ = cv::Mat();
        have_first_ = false;
    } else {
        bool ok = false;
        try {
            ok = cap_.read(frame) && !frame.empty();
        } catch (const cv::Exception &) {
            ok = false;
        }
        if (!ok) return false;
    }
    ms = cap_.get(cv::CAP_PROP_POS_MSEC);
    uint64_t t = std::isfinite(ms) && ms >= 0.0 ? uint64_t(std::llround(ms * 1000.0)) : 0;
    // the first frame's time is the file's start (some containers report the next
    // frame's time after a read); later frames one period on when the file gives no later one
    if (read_ == 0) t = 0;
    else if (t <= last_us_) t = last_us_ + uint64_t(std::llround(period_us));
    last_us_ = t;
    t_us = t;
    ++read_;
    return true;
}

std::string VideoInput::ended_early() const {
    if (expected_ < 0 || read_ >= expected_) return "";
    return "the video ends at frame " + std::to_string(read_) + " of the " + std::to_string(expected_) +
           " its header gives (truncated or damaged); the frames before are processed";
}

CycleView decode_cycle(const std::vector<sbr_can_frame_t> &frames) {
    CycleView c;
    for (const sbr_can_frame_t &f : frames) {
        if (f.id == SBR_CAN_ID_CONFIRMED_SIGN) {
            sbr_can_confirmed_sign_t s;
            if (sbr_can_unpack_confirmed_sign(&f, &s) == SBR_OK && s.class_id != SBR_CAN_CLASS_NONE)
                c.signs.push_back({s.class_id, s.track_id, s.speed_kmh, s.age_frames, s.confidence});
        } else if (f.id == SBR_CAN_ID_DETECTION) {
            sbr_can_detection_t d;
            if (sbr_can_unpack_detection(&f, &d) == SBR_OK && d.class_id != SBR_CAN_CLASS_NONE_DET)
                c.dets.push_back({d.class_id, d.track_id, d.center_x, d.center_y, d.width, d.height, d.confidence});
        } else if (f.id == SBR_CAN_ID_RESTRICTIONS) {
            c.have_restrictions = sbr_can_unpack_restrictions(&f, &c.restrictions) == SBR_OK;
        }
    }
    return c;
}

namespace {

void label(cv::Mat &img, const std::string &text, cv::Point at, double scale, const cv::Scalar &colour) {
    int base = 0;
    const cv::Size sz = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 2, &base);
    cv::rectangle(img, at + cv::Point(-2, -sz.height - 4), at + cv::Point(sz.width + 2, base), cv::Scalar(0, 0, 0),
                  cv::FILLED);
    cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 2, cv::LINE_AA);
}

void roundel(cv::Mat &img, cv::Point c, int r, const std::string &text) {
    cv::circle(img, c, r, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
    cv::circle(img, c, r - r / 8, cv::Scalar(40, 20, 200), std::max(2, r / 5), cv::LINE_AA);
    int base = 0;
    // the number fills about 1.2 radii across
    const cv::Size one = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 1.0, 2, &base);
    const double scale = std::min(r / 28.0, 1.2 * r / std::max(1, one.width));
    const cv::Size sz = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 2, &base);
    cv::putText(img, text, c + cv::Point(-sz.width / 2, sz.height / 2), cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar(0, 0, 0), 2 + r / 20, cv::LINE_AA);
}

}  // namespace

void draw_cycle(cv::Mat &img, const CycleView &c, double t_s) {
    for (const CycleView::Det &d : c.dets) {
        const cv::Rect box(int(std::lround(d.cx - d.w / 2)), int(std::lround(d.cy - d.h / 2)), int(std::lround(d.w)),
                           int(std::lround(d.h)));
        const cv::Scalar col = superclass_colour(int(d.class_id));
        cv::rectangle(img, box, col, 2);
        std::string t = class_name(int(d.class_id));
        if (d.track_id != SBR_CAN_TRACK_NONE_DET) t += " #" + std::to_string(d.track_id);
        label(img, t, cv::Point(box.x, std::max(14, box.y - 4)), 0.5, col);
    }
    // the panel: what the driver is shown
    const int r = std::max(24, img.rows / 14);
    const cv::Point c0(r + 12, r + 12);
    if (c.have_restrictions && c.restrictions.speed_limit_kmh != 0)
        roundel(img, c0, r, std::to_string(c.restrictions.speed_limit_kmh));
    else
        label(img, "no limit known", cv::Point(8, r), 0.6, cv::Scalar(255, 255, 255));
    int y = 2 * r + 40;
    if (c.have_restrictions) {
        const struct {
            uint32_t on;
            const char *text;
        } bans[] = {{c.restrictions.no_overtaking, "no overtaking"},
                    {c.restrictions.no_overtaking_trucks, "no overtaking for trucks"},
                    {c.restrictions.priority_road, "priority road"}};
        for (const auto &b : bans)
            if (b.on) {
                label(img, b.text, cv::Point(8, y), 0.6, cv::Scalar(80, 200, 255));
                y += 26;
            }
    }
    for (const CycleView::Sign &s : c.signs) {
        label(img, std::string("confirmed: ") + class_name(int(s.class_id)) + " #" + std::to_string(s.track_id) +
                       " (" + std::to_string(s.age_frames) + " frames ago)",
              cv::Point(8, y), 0.5, cv::Scalar(255, 255, 255));
        y += 22;
    }
    char t[32];
    std::snprintf(t, sizeof t, "t = %.2f s", t_s);
    label(img, t, cv::Point(8, img.rows - 10), 0.5, cv::Scalar(255, 255, 255));
}

bool VideoOutput::open(const std::string &path, double fps, cv::Size size, std::string &err) {
    path_ = path;
    tmp_ = temp_path_of(path);
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    const int fourcc = ext == ".avi" ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G') : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
    bool ok = false;
    try {
        ok = writer_.open(tmp_, cv::CAP_FFMPEG, fourcc, fps > 0.0 ? fps : 10.0, size);
    } catch (const cv::Exception &) {
        ok = false;
    }
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp_, ec);
        err = "cannot write a video there (an .mp4 or .avi in a writable folder is needed)";
    }
    return ok;
}

void VideoOutput::write(const cv::Mat &frame) {
    if (writer_.isOpened()) writer_.write(frame);
}

std::string VideoOutput::close() {
    if (!writer_.isOpened()) return "not open";
    writer_.release();
    std::error_code ec;
    if (!fs::exists(tmp_, ec) || fs::file_size(tmp_, ec) == 0) {
        fs::remove(tmp_, ec);
        return "the video could not be written";
    }
    return commit_temp(tmp_, path_);
}

}  // namespace sbr_host
