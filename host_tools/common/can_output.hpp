// SPDX-License-Identifier: MIT
// Host-side CAN output: one cycle per processed image, scheduled and E2E-protected by the
// core (sbr_can_schedule) and written through the candump-log port. Used by sbr_canlog
// and by sbr_detect --canlog.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "sbr/can.h"
#include "sbr_port_candump.h"
}

#include "detection.hpp"

namespace sbr_host {


// Confirmed signs (SBR_ConfirmedSign): the images are taken as independent stills, so a
// detection passed to write_image (one at the operating point) is confirmed in its own
// image; each gets a new track id (0..254, wrapping). The four newest stay listed, newest
// first (within an image by decreasing score), with their age in images, until they are
// 255 images old. SpeedLimit carries the km/h of the speed-limit classes 0-5, 7, 8 and
// 255 otherwise.
// With enable_tracking() the images are consecutive frames of one drive instead: the
// detections go through the channel tracker (SignTracker), a sign is confirmed by its
// second detection on the same track and listed once per pass with its track's id
// (id mod 255); detections carry the id of their confirmed track.
class SignTracker;
class CanLogWriter {
public:
    // base_time_us: timestamp of the first image; period_us: time between images.
    CanLogWriter(const std::string &path, uint64_t base_time_us = 1700000000000000ull,
                 uint64_t period_us = 100000ull, const char *ifname = "can0");
    ~CanLogWriter();
    bool ok() const { return file_ != nullptr; }
    // Closes the log: false when a write or the close failed (disk full), or it never opened.
    bool close();
    // Consecutive frames of width x height: track signs (see above). False on failure.
    bool enable_tracking(float width, float height);
    // Writes the frames of one image; returns the number of frames, or -1 on error.
    int write_image(const std::vector<Detection> &dets, float processing_ms, uint32_t regions,
                    bool error_flag);
    uint32_t frames_written() const { return port_ctx_.written; }
    uint32_t results_dropped() const { return dropped_; }

private:
    FILE *file_ = nullptr;
    sbr_port_candump_t port_ctx_{};
    sbr_can_e2e_tx_t tx_{};
    sbr_can_sched_config_t cfg_{};
    uint64_t base_ = 0, period_ = 0;
    uint32_t image_ = 0, dropped_ = 0;
    // Confirmed signs, newest first (at most four are listed, as the DBC allows).
    struct Confirmed {
        uint32_t class_id = 0, track_id = 0, image = 0;
        float score = 0.0f;
    };
    std::vector<Confirmed> confirmed_;
    uint32_t next_track_ = 0;
    std::shared_ptr<SignTracker> tracker_;
};

}  // namespace sbr_host
