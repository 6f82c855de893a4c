// SPDX-License-Identifier: MIT
// The recogniser on one image for host tools that change models or configurations between
// calls (trainers, evaluations): the workspace grows as images need, and sbr_recog_init()
// checks the models with the configuration on each call (a host's cost; an ECU sets up
// once and calls sbr_recog_detect() per frame).
#pragma once
#include <cstdint>
#include <vector>
extern "C" {
#include "sbr/recog.h"
}

namespace sbr_host {

// sbr_recog_init() then sbr_recog_detect() on `v` (its `roi`, or all of it). `picto`
// nullptr: no class stage. Returns the first status that is not SBR_OK (n = 0 when init
// refused).
inline sbr_status_t recog_once(const sbr_recog_config_t &cfg, const sbr_model_t &model,
                               const sbr_picto_model_t *picto, std::vector<uint64_t> &ws,
                               const sbr_image_t &v, const sbr_rect_t *roi, sbr_detection_t *dets,
                               uint32_t capacity, uint32_t *n, sbr_recog_stats_t *stats) {
    const size_t need = sbr_recog_workspace_size(&cfg, roi != nullptr ? roi->width : v.width,
                                                 roi != nullptr ? roi->height : v.height);
    if (ws.empty() || ws.size() * 8 < need) ws.assign(need / 8 + 1, 0);
    sbr_recog_t rec;
    const sbr_status_t st = sbr_recog_init(&rec, &cfg, &model, picto, ws.data(), ws.size() * 8);
    if (st != SBR_OK) {
        *n = 0;
        return st;
    }
    return sbr_recog_detect(&rec, &v, roi, dets, capacity, n, stats);
}

}  // namespace sbr_host
