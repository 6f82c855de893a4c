// SPDX-License-Identifier: MIT
// Sign tracking over consecutive frames with the core's channel tracker (sbr_track_*):
// recogniser detections become tracks, so that a sign is reported once per pass with a
// stable id. Positions are the box centres; the motion model is constant velocity
// (sbr_track_model_cv: velocity channels of 4 px, +-80 px per frame; 4 px of velocity
// change per frame; a new sign's velocity prior 20 px), detection noise 4 px, a track is
// confirmed by its second detection and dropped after 5 frames without one. A track's
// class is the one with the highest summed score among its detections.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

extern "C" {
#include "sbr/track.h"
}

namespace sbr_host {

class SignTracker {
public:
    struct Input {
        float cx, cy;    // box centre, pixels
        int class_id;
        float score;     // 0..1
    };
    struct Track {
        uint32_t id;        // stable for the sign's pass, never reused
        int class_id;       // by summed score
        float score;        // best score seen
        float x, y;
        uint32_t confirmed_frame;  // frame of confirmation
        bool new_confirmation;     // confirmed in this frame: report it once
    };
    // width, height: image size; period_s: time between frames.
    SignTracker(float width, float height, float period_s);
    bool ok() const { return ok_; }
    // One frame. det_track[i] gets the track id of detection i (0 if it started no
    // confirmed track yet). Returns the confirmed tracks alive after the frame.
    std::vector<Track> update(const std::vector<Input> &dets, std::vector<uint32_t> &det_track);
    uint32_t frame() const { return frame_; }

private:
    bool ok_ = false;
    float w_, h_;
    uint32_t period_us_;  // microseconds between frames (what sbr_track_step() takes)
    std::vector<float> trans_, birth_;
    sbr_track_model_t model_{};
    sbr_track_config_t cfg_{};
    std::vector<uint32_t> ws_;
    sbr_track_t trk_{};
    uint32_t frame_ = 0;
    struct Info {
        std::map<int, float> votes;
        float best = 0.0f;
        bool confirmed = false;
        uint32_t confirmed_frame = 0;
    };
    std::map<uint32_t, Info> info_;
};

}  // namespace sbr_host
