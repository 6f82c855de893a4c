// SPDX-License-Identifier: MIT
#include "can_output.hpp"

#include <cerrno>
#include <cstring>

namespace sbr_host {

CanLogWriter::CanLogWriter(const std::string &path, uint64_t base_time_us, uint64_t period_us,
                           const char *ifname)
    : base_(base_time_us), period_(period_us) {
    logging_ = !path.empty();
    if (logging_) {
        file_ = std::fopen(path.c_str(), "w");
        if (!file_) open_error_ = std::strerror(errno);
    }
    port_ctx_.file = file_;
    port_ctx_.ifname = ifname;
    port_ctx_.written = 0;
    setup(1u, 1360.0f, 800.0f);
}

CanLogWriter::~CanLogWriter() {
    if (file_) std::fclose(file_);
}

bool CanLogWriter::setup(uint32_t stills, float width, float height) {
    sbr_ecu_config_t cfg;
    sbr_ecu_config_default(&cfg);
    cfg.stills = stills;
    cfg.signs.width = width;
    cfg.signs.height = height;
    cfg.signs.period_us = static_cast<uint32_t>(period_);
    ready_ = false;
    const size_t bytes = sbr_ecu_workspace_size(&cfg);
    if (bytes == 0u) return false;
    ws_.assign(bytes / sizeof(uint64_t) + 1u, 0u);
    ready_ = sbr_ecu_init(&ecu_, &cfg, ws_.data(), ws_.size() * sizeof(uint64_t)) == SBR_OK;
    return ready_;
}

bool CanLogWriter::close() {
    if (!logging_) return true;
    if (!file_) return false;
    const bool good = std::fflush(file_) == 0 && std::ferror(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    port_ctx_.file = nullptr;
    return good && closed;
}

bool CanLogWriter::enable_tracking(float width, float height) {
    return image_ == 0u && setup(0u, width, height);
}

// The port: the frames of the cycle kept, and written to the log when there is one.
sbr_status_t CanLogWriter::tee_send(void *ctx, const sbr_can_frame_t *frame) {
    CanLogWriter *w = static_cast<CanLogWriter *>(ctx);
    w->cycle_.push_back(*frame);
    return w->file_ ? sbr_port_candump.send(&w->port_ctx_, frame) : SBR_OK;
}

int CanLogWriter::write_image(const std::vector<sbr_detection_t> &dets, float processing_ms, uint32_t regions,
                              bool error_flag, bool capacity_hit, int64_t time_us) {
    if ((logging_ && !file_) || !ready_) return -1;
    sbr_ecu_frame_info_t info{};
    info.processing_ms = processing_ms;
    info.regions = regions;
    info.error = error_flag ? 1u : 0u;
    info.capacity_hit = capacity_hit ? 1u : 0u;
    const uint64_t now = base_ + (time_us >= 0 ? static_cast<uint64_t>(time_us) : static_cast<uint64_t>(image_) * period_);
    port_ctx_.time_us = now;
    sbr_ecu_result_t r{};
    static const sbr_can_port_t tee = {"tee", &CanLogWriter::tee_send};
    cycle_.clear();
    const sbr_status_t st = sbr_ecu_output(&ecu_, now, dets.empty() ? nullptr : dets.data(),
                                           static_cast<uint32_t>(dets.size()), &info, &tee, this, &r);
    if (st != SBR_OK && st != SBR_ERR_CAPACITY) return -1;
    dropped_ += r.dropped;
    state_ = r.restrictions;
    ++image_;
    return static_cast<int>(r.frames_sent);
}

}  // namespace sbr_host
