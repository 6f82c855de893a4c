// SPDX-License-Identifier: MIT
#include "can_output.hpp"

#include "sign_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace sbr_host {

CanLogWriter::CanLogWriter(const std::string &path, uint64_t base_time_us, uint64_t period_us,
                           const char *ifname)
    : base_(base_time_us), period_(period_us) {
    file_ = std::fopen(path.c_str(), "w");
    port_ctx_.file = file_;
    port_ctx_.ifname = ifname;
    port_ctx_.written = 0;
    sbr_can_e2e_tx_init(&tx_);
    sbr_can_sched_config_default(&cfg_);
}

CanLogWriter::~CanLogWriter() {
    if (file_) std::fclose(file_);
}

bool CanLogWriter::close() {
    if (!file_) return false;
    const bool good = std::fflush(file_) == 0 && std::ferror(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    port_ctx_.file = nullptr;
    return good && closed;
}

bool CanLogWriter::enable_tracking(float width, float height) {
    tracker_ = std::make_shared<SignTracker>(width, height, static_cast<float>(period_) * 1e-6f);
    return tracker_->ok();
}

static float clampf(float v, float lo, float hi) { return std::min(hi, std::max(lo, v)); }

// km/h of GTSDB's speed-limit classes (0-5, 7, 8); SBR_CAN_SPEED_NONE for the others.
static uint32_t speed_of_class(uint32_t class_id) {
    static const uint32_t kmh[9] = {20, 30, 50, 60, 70, 80, SBR_CAN_SPEED_NONE, 100, 120};
    return class_id < 9 ? kmh[class_id] : SBR_CAN_SPEED_NONE;
}

int CanLogWriter::write_image(const std::vector<Detection> &dets, float processing_ms,
                              uint32_t regions, bool error_flag) {
    if (!file_) return -1;
    std::vector<sbr_can_detection_t> cd;
    for (const Detection &d : dets) {
        sbr_can_detection_t c{};
        c.class_id = static_cast<uint32_t>(d.class_id);
        // the score's range is 0..1 by contract; a tool-side clamp keeps a rounding
        // excess (1.0000001) from costing the frame
        c.confidence = clampf(100.0f * static_cast<float>(d.score), 0.0f, 100.0f);
        c.center_x = static_cast<float>(0.5 * (d.box.x0 + d.box.x1));
        c.center_y = static_cast<float>(0.5 * (d.box.y0 + d.box.y1));
        c.width = static_cast<float>(d.box.x1 - d.box.x0);
        c.height = static_cast<float>(d.box.y1 - d.box.y0);
        c.track_id = SBR_CAN_TRACK_NONE_DET;
        cd.push_back(c);
    }
    std::vector<Confirmed> fresh;
    if (tracker_) {
        // consecutive frames: a sign is listed once, when its track is confirmed
        std::vector<SignTracker::Input> in;
        for (const Detection &d : dets)
            in.push_back({static_cast<float>(0.5 * (d.box.x0 + d.box.x1)), static_cast<float>(0.5 * (d.box.y0 + d.box.y1)),
                          d.class_id, clampf(static_cast<float>(d.score), 0.0f, 1.0f)});
        std::vector<uint32_t> det_track;
        std::vector<SignTracker::Track> tracks = tracker_->update(in, det_track);
        for (size_t i = 0; i < cd.size(); ++i)
            if (det_track[i] != 0u) cd[i].track_id = det_track[i] % 255u;
        std::stable_sort(tracks.begin(), tracks.end(),
                         [](const SignTracker::Track &a, const SignTracker::Track &b) { return a.score > b.score; });
        for (const SignTracker::Track &t : tracks) {
            if (!t.new_confirmation) continue;
            Confirmed c;
            c.class_id = static_cast<uint32_t>(t.class_id);
            c.score = clampf(t.score, 0.0f, 1.0f);
            c.track_id = t.id % 255u;
            c.image = image_;
            fresh.push_back(c);
        }
    } else {
        // stills: this image's detections are confirmed and listed first, by decreasing
        // score (ties in the order given, as the detection frames)
        std::vector<Detection> by_score(dets);
        std::stable_sort(by_score.begin(), by_score.end(),
                         [](const Detection &a, const Detection &b) { return a.score > b.score; });
        for (const Detection &d : by_score) {
            Confirmed c;
            c.class_id = static_cast<uint32_t>(d.class_id);
            c.score = clampf(static_cast<float>(d.score), 0.0f, 1.0f);
            c.track_id = next_track_;
            c.image = image_;
            next_track_ = (next_track_ + 1u) % 255u;
            fresh.push_back(c);
        }
    }
    confirmed_.insert(confirmed_.begin(), fresh.begin(), fresh.end());
    while (!confirmed_.empty() && (confirmed_.size() > 4u || image_ - confirmed_.back().image >= 255u))
        confirmed_.pop_back();
    std::vector<sbr_can_confirmed_sign_t> cs;
    for (const Confirmed &c : confirmed_) {
        sbr_can_confirmed_sign_t s{};
        s.class_id = c.class_id;
        s.track_id = c.track_id;
        s.speed_kmh = speed_of_class(c.class_id);
        s.confidence = std::round(100.0f * c.score);
        s.age_frames = image_ - c.image;
        cs.push_back(s);
    }
    sbr_can_cycle_t cyc{};
    cyc.signs = cs.empty() ? nullptr : cs.data();
    cyc.sign_count = static_cast<uint32_t>(cs.size());
    cyc.detections = cd.empty() ? nullptr : cd.data();
    cyc.detection_count = static_cast<uint32_t>(cd.size());
    cyc.status.frame_counter = image_;
    cyc.status.processing_ms = clampf(processing_ms, 0.0f, 6553.4f);
    cyc.status.region_count = regions;
    cyc.status.detection_count = static_cast<uint32_t>(dets.size());
    cyc.status.error = error_flag ? 1u : 0u;
    std::vector<sbr_can_frame_t> frames(cfg_.frame_budget);
    uint32_t n = 0, dropped = 0;
    const sbr_status_t st = sbr_can_schedule(&tx_, &cfg_, &cyc, frames.data(),
                                             static_cast<uint32_t>(frames.size()), &n, &dropped);
    if (st != SBR_OK && st != SBR_ERR_RANGE) return -1;
    dropped_ += dropped;
    port_ctx_.time_us = base_ + static_cast<uint64_t>(image_) * period_;
    uint32_t sent = 0;
    if (sbr_can_send(&sbr_port_candump, &port_ctx_, frames.data(), n, &sent) != SBR_OK) return -1;
    ++image_;
    return static_cast<int>(sent);
}

}  // namespace sbr_host
