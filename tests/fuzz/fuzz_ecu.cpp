// SPDX-License-Identifier: MIT
// Fuzz harness: the ECU's per-frame job (ecu.h) and the sign tracking under it (signs.h)
// with hostile configurations, detections (boxes anywhere, scores and classes out of
// range, NaN), times that stand still, go back or jump past the tracker's gap, stills and
// tracked frames, and a port that refuses. Checks on success: every frame sent passes the
// receiver's E2E check and unpacks; the status frame's counter counts the cycles; at most
// four signs listed; the sign tracking lists signs by id, each confirmed (SBR_SIGN_NEW)
// once, never before confirm_hits detections, its class in the table and its share in
// [0, 1]; a detection's sign is a listed one. A refused call sends nothing and changes
// nothing.
#include "fuzz_common.hpp"

#include <algorithm>
#include <cstring>
#include <set>
#include <vector>

extern "C" {
#include "sbr/ecu.h"
#include "sbr_port_mock.h"
}

namespace {

sbr_detection_t detection(FuzzedDataProvider &in, uint32_t classes)
{
    sbr_detection_t d{};
    const bool wild = in.ConsumeIntegral<uint8_t>() > 240u;
    d.box.x = wild ? in.ConsumeIntegral<uint32_t>() : fz_u32(in, 0u, 1500u);
    d.box.y = wild ? in.ConsumeIntegral<uint32_t>() : fz_u32(in, 0u, 900u);
    d.box.width = wild ? in.ConsumeIntegral<uint32_t>() : fz_u32(in, 0u, 300u);
    d.box.height = wild ? in.ConsumeIntegral<uint32_t>() : fz_u32(in, 0u, 300u);
    const uint8_t s = in.ConsumeIntegral<uint8_t>();
    d.score = s == 255u ? NAN : (s == 254u ? 1.5f : float(s) / 253.0f);
    d.class_id = uint16_t(fz_u32(in, 0u, classes + (in.ConsumeIntegral<uint8_t>() > 250u ? 3u : 0u)));
    d.class_share = 1.0f;
    return d;
}

// The sign tracking alone on the same frames: its promises.
struct SignsCheck {
    sbr_signs_t s{};
    std::vector<uint64_t> ws;
    std::set<uint32_t> confirmed;
    bool ok = false;
    uint64_t now = 0;
    bool started = false;
    void init(const sbr_signs_config_t &cfg)
    {
        const size_t bytes = sbr_signs_workspace_size(&cfg);
        FZ_CHECK((bytes == 0u) == (sbr_signs_config_check(&cfg) != SBR_OK));
        if (bytes == 0u) return;
        ws.assign(bytes / 8u + 1u, 0u);
        ok = sbr_signs_init(&s, &cfg, ws.data(), bytes) == SBR_OK;
        FZ_CHECK(ok);
    }
    void frame(uint64_t t, const std::vector<sbr_detection_t> &d)
    {
        if (!ok) return;
        std::vector<uint32_t> ds(d.size(), 7u);
        std::vector<sbr_sign_t> out(s.cfg.max_tracks);
        uint32_t n = 0;
        const sbr_signs_t before = s;
        const sbr_status_t st = sbr_signs_update(&s, t, d.empty() ? nullptr : d.data(), uint32_t(d.size()),
                                                 ds.empty() ? nullptr : ds.data(), out.data(), uint32_t(out.size()), &n);
        FZ_STATUS(st, SBR_OK, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
        bool valid = !(started && t <= now);
        for (const sbr_detection_t &x : d)
            valid = valid && x.score >= 0.0f && x.score <= 1.0f && x.class_id < s.cfg.class_count;
        FZ_CHECK((st != SBR_ERR_RANGE) == valid);
        if (st == SBR_ERR_RANGE) {
            FZ_CHECK(std::memcmp(&before, &s, sizeof s) == 0);
            return;
        }
        now = t;
        started = true;
        FZ_CHECK(n <= out.size());
        std::set<uint32_t> listed;
        for (uint32_t i = 0; i < n; ++i) {
            const sbr_sign_t &g = out[i];
            FZ_CHECK(g.id != 0u && (i == 0 || g.id > out[i - 1].id));
            FZ_CHECK(g.class_id < s.cfg.class_count && g.share >= 0.0f && g.share <= 1.0001f);
            FZ_CHECK(g.hits >= s.cfg.confirm_hits && g.score >= 0.0f && g.score <= 1.0f);
            if (g.flags & SBR_SIGN_NEW) {
                FZ_CHECK(confirmed.insert(g.id).second);  // once per pass
                FZ_CHECK(g.frames == 0u);
            } else {
                FZ_CHECK(confirmed.count(g.id) == 1u);
            }
            listed.insert(g.id);
        }
        for (uint32_t v : ds) FZ_CHECK(v == 0u || listed.count(v) == 1u);
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    sbr_ecu_config_t cfg;
    sbr_ecu_config_default(&cfg);
    sbr_signs_config_t &sc = cfg.signs;
    if (in.ConsumeBool()) {
        sc.width = in.ConsumeBool() ? float(fz_u32(in, 0u, 3000u)) : NAN;
        sc.height = float(fz_u32(in, 0u, 2000u));
        sc.period_us = fz_u32(in, 0u, 1100000u);
        sc.class_count = fz_u32(in, 0u, SBR_SIGNS_MAX_CLASSES + 1u);
        cfg.rules.class_count = in.ConsumeBool() ? sc.class_count : fz_u32(in, 0u, 64u);
        sc.max_tracks = fz_u32(in, 0u, SBR_SIGNS_MAX_TRACKS + 1u);
        sc.confirm_hits = fz_u32(in, 0u, 17u);
        sc.confirm_share = float(fz_u32(in, 0u, 110u)) / 100.0f;
        sc.max_misses = fz_u32(in, 0u, 256u);
        sc.meas_sigma = float(fz_u32(in, 0u, 22u));
        sc.min_certainty = float(fz_u32(in, 0u, 11u)) / 10.0f;
        cfg.min_score = float(fz_u32(in, 0u, 12u)) / 10.0f;
        cfg.stills = fz_u32(in, 0u, 2u);
        cfg.sched.frame_budget = fz_u32(in, 0u, SBR_ECU_MAX_FRAMES + 2u);
    }
    // the rules' GTSDB table has 43 classes: a smaller count of the same table is fine
    cfg.rules.class_count = std::min(cfg.rules.class_count, 43u);
    std::vector<uint64_t> ws(SBR_ECU_WORKSPACE_SIZE(SBR_SIGNS_MAX_TRACKS, SBR_SIGNS_MAX_CLASSES, SBR_ECU_MAX_FRAMES) /
                                 8u + 1u);
    sbr_ecu_t e;
    const size_t need = sbr_ecu_workspace_size(&cfg);
    FZ_CHECK((need == 0u) == (sbr_ecu_config_check(&cfg) != SBR_OK));
    const sbr_status_t is = sbr_ecu_init(&e, &cfg, ws.data(), in.ConsumeBool() ? need : ws.size() * 8u);
    FZ_STATUS(is, SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE, SBR_ERR_WORKSPACE);
    sbr_can_frame_t frames[SBR_ECU_MAX_FRAMES];
    sbr_port_mock_t port;
    sbr_port_mock_init(&port, frames, SBR_ECU_MAX_FRAMES);
    sbr_ecu_frame_info_t info{};
    if (is != SBR_OK) {
        FZ_CHECK(sbr_ecu_output(&e, 1u, nullptr, 0u, &info, &sbr_port_mock, &port, nullptr) == SBR_ERR_STATE);
        return 0;
    }
    SignsCheck sig;
    if (cfg.stills == 0u) sig.init(cfg.signs);
    sbr_can_e2e_rx_t rx[5];
    const uint32_t ids[5] = {SBR_CAN_ID_CONFIRMED_SIGN, SBR_CAN_ID_ECU_STATUS, SBR_CAN_ID_DETECTION,
                             SBR_CAN_ID_TRACKED_OBJECT, SBR_CAN_ID_RESTRICTIONS};
    for (int k = 0; k < 5; ++k) sbr_can_e2e_rx_init(&rx[k], ids[k]);
    uint64_t now = 1000000u;
    uint32_t cycles = 0;
    bool started = false;
    const uint32_t nframes = in.ConsumeIntegralInRange<uint32_t>(1u, 40u);
    for (uint32_t f = 0; f < nframes && in.remaining_bytes() > 0; ++f) {
        const uint8_t how = in.ConsumeIntegral<uint8_t>();
        uint64_t t = now + (how < 200u ? uint64_t(sc.period_us) + fz_u32(in, 0u, 2000u)
                                       : uint64_t(fz_u32(in, 0u, 20u)) * sc.period_us);
        if (how >= 250u) t = now - (how & 1u);  // stands still or goes back
        std::vector<sbr_detection_t> d(in.ConsumeIntegralInRange<uint32_t>(0u, 12u));
        for (auto &x : d) x = detection(in, sc.class_count);
        info.error = fz_u32(in, 0u, in.ConsumeIntegral<uint8_t>() > 250u ? 2u : 1u);
        info.capacity_hit = 0u;
        info.processing_ms = float(fz_u32(in, 0u, 10000u)) * 0.7f;
        info.regions = in.ConsumeIntegral<uint32_t>();
        sbr_port_mock_init(&port, frames, SBR_ECU_MAX_FRAMES);
        port.accept_limit = in.ConsumeIntegral<uint8_t>() > 240u ? fz_u32(in, 1u, 5u) : 0u;
        const sbr_ecu_t before = e;
        sbr_ecu_result_t r;
        const sbr_status_t st = sbr_ecu_output(&e, t, d.empty() ? nullptr : d.data(), uint32_t(d.size()), &info,
                                               &sbr_port_mock, &port, &r);
        FZ_STATUS(st, SBR_OK, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
        bool valid = !(started && t <= now) && info.error <= 1u;
        for (const sbr_detection_t &x : d)
            valid = valid && x.score >= 0.0f && x.score <= 1.0f && x.class_id < sc.class_count;
        FZ_CHECK((st != SBR_ERR_RANGE) == valid);
        if (st == SBR_ERR_RANGE) {
            FZ_CHECK(port.count == 0u && std::memcmp(&before, &e, sizeof e) == 0);
            continue;
        }
        if (cfg.stills == 0u) {
            std::vector<sbr_detection_t> kept;
            for (const sbr_detection_t &x : d)
                if (x.score >= cfg.min_score && kept.size() < SBR_ECU_MAX_DETECTIONS) kept.push_back(x);
            sig.frame(t, kept);
        }
        now = t;
        started = true;
        FZ_CHECK(r.frames_sent == port.count && port.count <= cfg.sched.frame_budget);
        FZ_CHECK(st == SBR_OK || port.refused > 0u || r.capacity_hit == 1u);
        uint32_t signs = 0;
        for (uint32_t i = 0; i < port.count; ++i) {
            const sbr_can_frame_t &fr = frames[i];
            int k = 0;
            while (k < 5 && ids[k] != fr.id) ++k;
            FZ_CHECK(k < 5);
            sbr_can_e2e_result_t res;
            FZ_CHECK(sbr_can_e2e_check(&rx[k], &fr, &res) == SBR_OK);
            if (k == 0) {
                sbr_can_confirmed_sign_t s;
                FZ_CHECK(sbr_can_unpack_confirmed_sign(&fr, &s) == SBR_OK);
                signs += s.class_id != SBR_CAN_CLASS_NONE;
            } else if (k == 1) {
                sbr_can_ecu_status_t s;
                FZ_CHECK(sbr_can_unpack_ecu_status(&fr, &s) == SBR_OK);
                FZ_CHECK(s.frame_counter == (cycles & 0xFFFFu) && s.error == info.error);
            } else if (k == 2) {
                sbr_can_detection_t s;
                FZ_CHECK(sbr_can_unpack_detection(&fr, &s) == SBR_OK);
            } else if (k == 4) {
                sbr_can_restrictions_t s;
                FZ_CHECK(sbr_can_unpack_restrictions(&fr, &s) == SBR_OK);
                FZ_CHECK(s.speed_limit_kmh == r.restrictions.speed_limit_kmh &&
                         s.no_overtaking == r.restrictions.no_overtaking &&
                         s.priority_road == r.restrictions.priority_road);
            }
        }
        if (port.refused > 0u) {
            // frames after the refused one were not sent: the receivers resynchronise
            for (int k = 0; k < 5; ++k) sbr_can_e2e_rx_init(&rx[k], ids[k]);
        }
        FZ_CHECK(signs <= SBR_ECU_LISTED);
        ++cycles;
    }
    return 0;
}
