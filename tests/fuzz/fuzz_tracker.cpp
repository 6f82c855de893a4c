// SPDX-License-Identifier: MIT
// Fuzz harness: the channel tracker. The model (the KITTI one, or a constant-velocity one
// from fuzzed parameters), configuration fields, dt and detections from the input, over
// several steps. On SBR_OK / SBR_ERR_CAPACITY: count <= capacity; targets with finite
// positions and velocities, certainty in [0, 1], ids never reused, a used detection index
// in range; every status documented.
#include "fuzz_common.hpp"

#include <cstddef>
#include <set>

extern "C" {
#include "sbr/track.h"
#include "sbr/models.h"
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    static sbr_track_model_t kitti;
    static bool have = false;
    if (!have) {
        FZ_STATUS(sbr_track_model_kitti(&kitti), SBR_OK);
        have = true;
    }
    static std::vector<float> trans, birth;
    sbr_track_model_t cv;
    const sbr_track_model_t *model = &kitti;
    if (in.ConsumeBool()) {
        const uint32_t vel = fz_u32(in, 5u, 41u);
        const size_t tl = SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, (vel < 200u ? vel : 5u));
        const size_t bl = SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, (vel < 200u ? vel : 5u));
        trans.assign(tl, 0.0f);
        birth.assign(bl, 0.0f);
        const sbr_status_t ms = sbr_track_model_cv(&cv, fz_float(in, 8.0f, 2000.0f), fz_float(in, 8.0f, 2000.0f),
                                                   fz_float(in, 0.01f, 1.0f), vel, fz_float(in, 0.1f, 10.0f),
                                                   fz_float(in, 0.0f, 5.0f), fz_float(in, 0.0f, 20.0f), trans.data(),
                                                   tl, birth.data(), bl);
        FZ_STATUS(ms, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE);
        if (ms != SBR_OK) {
            return 0;
        }
        FZ_STATUS(sbr_track_model_check(&cv), SBR_OK);
        model = &cv;
    }
    sbr_track_config_t cfg;
    sbr_track_config_default(&cfg);
    cfg.model = model;
    cfg.max_targets = in.ConsumeIntegralInRange<uint32_t>(1u, 8u);
    cfg.window = 25u;
    fz_edit_fields(in, reinterpret_cast<unsigned char *>(&cfg) + offsetof(sbr_track_config_t, max_targets),
                   sizeof cfg - offsetof(sbr_track_config_t, max_targets), 2u);
    const sbr_status_t cs = sbr_track_config_check(&cfg);
    FZ_STATUS(cs, SBR_OK, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_NULL, SBR_ERR_CORRUPT);
    const size_t need = sbr_track_workspace_size(&cfg);
    FZ_CHECK((need == 0u) == (cs != SBR_OK));
    sbr_track_t trk;
    const sbr_status_t is = sbr_track_init(&trk, &cfg, fz_workspace(need > 0u ? need : 64u), need);
    FZ_STATUS(is, SBR_OK, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_NULL, SBR_ERR_CORRUPT, SBR_ERR_WORKSPACE);
    FZ_CHECK((is == SBR_OK) == (cs == SBR_OK));
    if (is != SBR_OK) {
        return 0;
    }
    std::set<uint32_t> ended;
    std::set<uint32_t> alive;
    const uint32_t steps = in.ConsumeIntegralInRange<uint32_t>(1u, 12u);
    for (uint32_t s = 0u; s < steps; s++) {
        sbr_track_detection_t det[12];
        const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, 12u);
        for (uint32_t i = 0u; i < n; i++) {
            det[i].x = fz_float(in, 0.0f, model->extent[0]);
            det[i].y = fz_float(in, 0.0f, model->extent[1]);
            det[i].certainty = fz_float(in, 0.0f, 1.0f);
        }
        // the model's period in microseconds, as a dt_us can carry it: a valid model may
        // have any finite period > 0 (1e30 s from the model maker is accepted), so the
        // conversion is clamped here, where the harness makes its steps
        const double period_d = static_cast<double>(model->period) * 1.0e6 + 0.5;
        const uint32_t period_us = (period_d < 4.0e9) ? static_cast<uint32_t>(period_d) : 4000000000u;
        const uint64_t dt_max = 10ull * period_us;
        const uint32_t dt = (in.ConsumeIntegral<uint8_t>() < 200u)
                                ? period_us
                                : in.ConsumeIntegralInRange<uint32_t>(
                                      0u, dt_max < 0xFFFFFFFFull ? static_cast<uint32_t>(dt_max) : 0xFFFFFFFFu);
        sbr_track_target_t out[8];
        uint32_t count = 999u;
        const uint32_t cap = in.ConsumeIntegralInRange<uint32_t>(0u, 8u);
        // now and then more detections than the tracker takes (SBR_ERR_SIZE)
        const uint32_t n_pass = (in.ConsumeIntegral<uint8_t>() < 250u) ? n : SBR_TRACK_MAX_DETECTIONS + 1u;
        const sbr_status_t st = sbr_track_step(&trk, dt, det, n_pass, cap > 0u ? out : nullptr, cap, &count);
        if (n_pass > SBR_TRACK_MAX_DETECTIONS) {
            FZ_STATUS(st, SBR_ERR_SIZE);
        }
        FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_STATE, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
        if (st != SBR_OK && st != SBR_ERR_CAPACITY) {
            continue;
        }
        FZ_CHECK(count <= cap);
        std::set<uint32_t> now;
        for (uint32_t i = 0u; i < count; i++) {
            const sbr_track_target_t &t = out[i];
            FZ_CHECK(t.id >= 1u && ended.count(t.id) == 0u && now.count(t.id) == 0u);
            now.insert(t.id);
            FZ_CHECK(fz_finite(t.x) && fz_finite(t.y) && fz_finite(t.vx) && fz_finite(t.vy));
            FZ_CHECK(fz_finite(t.certainty) && t.certainty >= 0.0f && t.certainty <= 1.0f + 1e-5f);
            FZ_CHECK(t.detection >= -1 && t.detection < (int32_t)n);
            FZ_CHECK(((t.flags & SBR_TRACK_UPDATED) != 0u) == (t.detection >= 0));
        }
        if (st == SBR_OK) {
            for (uint32_t id : alive) {
                if (now.count(id) == 0u) {
                    ended.insert(id); // a target that left is never reported again
                }
            }
            alive = now;
        }
    }
    return 0;
}
