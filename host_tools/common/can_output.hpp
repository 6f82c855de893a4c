// SPDX-License-Identifier: MIT
// Host-side CAN output: the core's ECU job (sbr_ecu_output: sign tracking, restrictions,
// the CAN cycle, scheduled and E2E-protected) for each processed image, written through
// the candump-log port. Used by sbr_canlog and by sbr_detect --canlog.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

extern "C" {
#include "sbr/ecu.h"
#include "sbr_port_candump.h"
}

namespace sbr_host {

// By default the images are independent stills (sbr_ecu_config_t::stills): every
// detection passed to write_image (one at the operating point) is a confirmed sign in its
// own image, with ids 0..254 in turn. With enable_tracking() they are consecutive frames
// of one drive: the core's sign tracking confirms each sign once per pass (signs.h).
// Either way the four newest confirmed signs stay listed with their age (ecu.h).
class CanLogWriter {
public:
    // base_time_us: timestamp of the first image; period_us: time between images. An
    // empty path: no log, only the job (its last cycle's frames, last_cycle()).
    CanLogWriter(const std::string &path, uint64_t base_time_us = 1700000000000000ull,
                 uint64_t period_us = 100000ull, const char *ifname = "can0");
    ~CanLogWriter();
    CanLogWriter(const CanLogWriter &) = delete;
    CanLogWriter &operator=(const CanLogWriter &) = delete;
    bool ok() const { return (file_ != nullptr || !logging_) && ready_; }
    // Why the log did not open ("" when it did).
    const std::string &open_error() const { return open_error_; }
    // Closes the log: false when a write or the close failed (disk full), or it never opened.
    bool close();
    // Consecutive frames of width x height: track signs (see above). False on failure;
    // call it before the first image.
    bool enable_tracking(float width, float height);
    // Sends the frames of one image; returns the number of frames, or -1 on error.
    // capacity_hit: a bound of the recogniser ran full on it. time_us: the image's time
    // from the first image's (a video's own frame times); default one period per image.
    int write_image(const std::vector<sbr_detection_t> &dets, float processing_ms, uint32_t regions,
                    bool error_flag, bool capacity_hit = false, int64_t time_us = -1);
    // The frames the last image sent, in order.
    const std::vector<sbr_can_frame_t> &last_cycle() const { return cycle_; }
    uint32_t frames_written() const { return port_ctx_.written; }
    uint32_t results_dropped() const { return dropped_; }
    // The restrictions in force after the last image.
    const sbr_rules_state_t &restrictions() const { return state_; }

private:
    bool setup(uint32_t stills, float width, float height);
    static sbr_status_t tee_send(void *ctx, const sbr_can_frame_t *frame);
    FILE *file_ = nullptr;
    bool logging_ = true;
    std::string open_error_;
    std::vector<sbr_can_frame_t> cycle_;
    sbr_port_candump_t port_ctx_{};
    uint64_t base_ = 0, period_ = 0;
    uint32_t image_ = 0, dropped_ = 0;
    bool ready_ = false;
    std::vector<uint64_t> ws_;
    sbr_ecu_t ecu_{};
    sbr_rules_state_t state_{};
};

}  // namespace sbr_host
