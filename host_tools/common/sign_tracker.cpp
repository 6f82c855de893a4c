// SPDX-License-Identifier: MIT
#include "sign_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace sbr_host {

SignTracker::SignTracker(float width, float height, float period_s)
    : w_(width), h_(height), period_us_(static_cast<uint32_t>(std::lround(period_s * 1.0e6))) {
    const uint32_t vel = 41;
    trans_.resize(SBR_TRACK_MODEL_TRANSITION_LEN(3, 3, vel));
    birth_.resize(SBR_TRACK_MODEL_BIRTH_LEN(3, 3, vel));
    if (sbr_track_model_cv(&model_, width, height, period_s, vel, 4.0f, 4.0f, 20.0f, trans_.data(),
                           trans_.size(), birth_.data(), birth_.size()) != SBR_OK)
        return;
    sbr_track_config_default(&cfg_);
    cfg_.model = &model_;
    cfg_.max_targets = 16;
    cfg_.window = 31;
    cfg_.meas_sigma = 4.0f;
    cfg_.confirm_hits = 2;
    cfg_.max_misses = 5;
    ws_.resize(sbr_track_workspace_size(&cfg_) / sizeof(uint32_t) + 1);
    ok_ = sbr_track_init(&trk_, &cfg_, ws_.data(), ws_.size() * sizeof(uint32_t)) == SBR_OK;
}

std::vector<SignTracker::Track> SignTracker::update(const std::vector<Input> &dets,
                                                    std::vector<uint32_t> &det_track) {
    std::vector<Track> out;
    det_track.assign(dets.size(), 0u);
    if (!ok_) return out;
    std::vector<sbr_track_detection_t> in;
    std::vector<size_t> src;
    for (size_t i = 0; i < dets.size() && in.size() < SBR_TRACK_MAX_DETECTIONS; ++i) {
        const Input &d = dets[i];
        if (!(d.cx >= 0.0f && d.cy >= 0.0f && d.cx < w_ && d.cy < h_)) continue;
        const float c = std::min(1.0f, std::max(0.05f, d.score));
        in.push_back({d.cx, d.cy, c});
        src.push_back(i);
    }
    std::vector<sbr_track_target_t> tg(cfg_.max_targets);
    uint32_t n = 0;
    const sbr_status_t st = sbr_track_step(&trk_, period_us_, in.data(), static_cast<uint32_t>(in.size()),
                                           tg.data(), static_cast<uint32_t>(tg.size()), &n);
    ++frame_;
    if (st != SBR_OK && st != SBR_ERR_CAPACITY) return out;
    std::map<uint32_t, Info> alive;
    for (uint32_t k = 0; k < n; ++k) {
        const sbr_track_target_t &t = tg[k];
        Info info = info_.count(t.id) ? info_[t.id] : Info{};
        if (t.detection >= 0) {
            const Input &d = dets[src[static_cast<size_t>(t.detection)]];
            info.votes[d.class_id] += d.score;
            info.best = std::max(info.best, d.score);
            if (t.flags & SBR_TRACK_CONFIRMED) det_track[src[static_cast<size_t>(t.detection)]] = t.id;
        }
        bool fresh = false;
        if ((t.flags & SBR_TRACK_CONFIRMED) && !info.confirmed) {
            info.confirmed = true;
            info.confirmed_frame = frame_ - 1;
            fresh = true;
        }
        if (info.confirmed) {
            int cls = 0;
            float bestv = -1.0f;
            for (const auto &v : info.votes)
                if (v.second > bestv) {
                    bestv = v.second;
                    cls = v.first;
                }
            out.push_back(Track{t.id, cls, info.best, t.x, t.y, info.confirmed_frame, fresh});
        }
        alive[t.id] = info;
    }
    info_.swap(alive);
    return out;
}

}  // namespace sbr_host
