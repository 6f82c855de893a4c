// SPDX-License-Identifier: MIT
// Fuzz harness: CAN pack/unpack of every message, E2E protect/check, the scheduler.
// On SBR_OK: unpacked values in their signals' ranges; pack(unpack(f)) is accepted and
// unpacks to the same values; a packed frame unpacks to its input within resolution and
// packs again to the same bytes; protected frames pass the receiver's check; the
// scheduler's frames fit the budget and pass E2E in order.
#include "fuzz_common.hpp"

extern "C" {
#include "sbr/can.h"
}

namespace {

bool same_bytes(const sbr_can_frame_t &a, const sbr_can_frame_t &b)
{
    return (a.id == b.id) && (a.dlc == b.dlc) && (std::memcmp(a.data, b.data, 8) == 0);
}

sbr_can_frame_t frame_from(FuzzedDataProvider &in)
{
    static const uint32_t ids[] = {SBR_CAN_ID_CONFIRMED_SIGN, SBR_CAN_ID_ECU_STATUS,
                                   SBR_CAN_ID_DETECTION, SBR_CAN_ID_TRACKED_OBJECT};
    sbr_can_frame_t f;
    std::memset(&f, 0, sizeof f);
    f.id = (in.ConsumeIntegral<uint8_t>() < 230u) ? ids[in.ConsumeIntegralInRange<int>(0, 3)]
                                                  : in.ConsumeIntegral<uint32_t>();
    f.dlc = (in.ConsumeIntegral<uint8_t>() < 230u) ? 8u : in.ConsumeIntegral<uint8_t>();
    for (int i = 0; i < 8; i++) {
        f.data[i] = in.ConsumeIntegral<uint8_t>();
    }
    return f;
}

void check_detection(const sbr_can_detection_t &d)
{
    FZ_CHECK(d.class_id <= 42u || d.class_id == SBR_CAN_CLASS_NONE_DET);
    FZ_CHECK(d.confidence >= 0.0f && d.confidence <= 100.0f);
    FZ_CHECK(d.center_x >= 0.0f && d.center_x <= 2046.0f && d.center_y >= 0.0f && d.center_y <= 2046.0f);
    FZ_CHECK(d.width >= 0.0f && d.width <= 508.0f && d.height >= 0.0f && d.height <= 508.0f);
    FZ_CHECK(d.track_id <= 62u || d.track_id == SBR_CAN_TRACK_NONE_DET);
}

void check_sign(const sbr_can_confirmed_sign_t &s)
{
    FZ_CHECK(s.slot <= 3u && s.count <= 4u);
    FZ_CHECK(s.class_id <= 42u || s.class_id == SBR_CAN_CLASS_NONE);
    FZ_CHECK(s.speed_kmh <= 250u || s.speed_kmh == SBR_CAN_SPEED_NONE);
    FZ_CHECK(s.confidence >= 0.0f && s.confidence <= 100.0f && s.age_frames <= 255u);
}

void check_object(const sbr_can_object_t &o)
{
    FZ_CHECK(o.index <= 15u);
    FZ_CHECK(o.x >= 0.0f && o.x <= 2047.0f && o.y >= 0.0f && o.y <= 1023.0f);
    FZ_CHECK(o.vx >= -256.0f && o.vx <= 252.0f && o.vy >= -256.0f && o.vy <= 252.0f);
    FZ_CHECK(o.certainty >= 0.0f && o.certainty <= 100.0f);
}

void check_status(const sbr_can_ecu_status_t &s)
{
    FZ_CHECK(s.frame_counter <= 65535u && s.processing_ms >= 0.0f && s.processing_ms <= 6553.5f);
    FZ_CHECK(s.region_count <= 4095u && s.detection_count <= 15u);
    FZ_CHECK(s.overload <= 1u && s.error <= 1u && s.capacity_hit <= 1u);
}

// unpack -> pack -> unpack: the values survive, the second pack gives the same bytes.
template <typename T>
void unpack_round_trip(const sbr_can_frame_t &f, sbr_status_t (*unpack)(const sbr_can_frame_t *, T *),
                       sbr_status_t (*pack)(const T *, sbr_can_frame_t *), void (*check)(const T &))
{
    T v;
    const sbr_status_t st = unpack(&f, &v);
    FZ_STATUS(st, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE);
    FZ_STATUS(unpack(nullptr, &v), SBR_ERR_NULL);
    FZ_STATUS(unpack(&f, nullptr), SBR_ERR_NULL);
    if (st == SBR_OK) {
        FZ_CHECK(f.dlc == 8u);
        check(v);
        sbr_can_frame_t g;
        sbr_can_frame_t h;
        T w;
        T x;
        FZ_STATUS(pack(&v, &g), SBR_OK);
        FZ_CHECK(g.id == f.id && g.dlc == 8u);
        FZ_STATUS(unpack(&g, &w), SBR_OK);
        FZ_STATUS(pack(&w, &h), SBR_OK);
        FZ_CHECK(same_bytes(g, h));
        FZ_STATUS(unpack(&h, &x), SBR_OK);
        FZ_CHECK(std::memcmp(&w, &x, sizeof w) == 0);
    }
}

// pack(x) -> unpack: on SBR_OK the frame is complete and re-packs to the same bytes.
template <typename T>
void pack_round_trip(const T &v, sbr_status_t (*unpack)(const sbr_can_frame_t *, T *),
                     sbr_status_t (*pack)(const T *, sbr_can_frame_t *), void (*check)(const T &))
{
    sbr_can_frame_t f;
    std::memset(&f, 0x5A, sizeof f);
    const sbr_can_frame_t before = f;
    const sbr_status_t st = pack(&v, &f);
    FZ_STATUS(st, SBR_OK, SBR_ERR_RANGE);
    FZ_STATUS(pack(nullptr, &f), SBR_ERR_NULL);
    if (st == SBR_OK) {
        T u;
        sbr_can_frame_t g;
        FZ_CHECK(f.dlc == 8u);
        FZ_STATUS(unpack(&f, &u), SBR_OK);
        check(u);
        FZ_STATUS(pack(&u, &g), SBR_OK);
        FZ_CHECK(same_bytes(f, g));
    } else {
        FZ_CHECK(same_bytes(f, before)); // the frame is untouched
    }
}

void fuzz_pack(FuzzedDataProvider &in)
{
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: {
        sbr_can_detection_t d;
        d.class_id = fz_u32(in, 0u, 64u);
        d.confidence = fz_float(in, -10.0f, 110.0f);
        d.center_x = fz_float(in, -10.0f, 2100.0f);
        d.center_y = fz_float(in, -10.0f, 2100.0f);
        d.width = fz_float(in, -10.0f, 520.0f);
        d.height = fz_float(in, -10.0f, 520.0f);
        d.track_id = fz_u32(in, 0u, 64u);
        pack_round_trip(d, sbr_can_unpack_detection, sbr_can_pack_detection, check_detection);
        if (sbr_can_pack_detection(&d, nullptr) != SBR_ERR_NULL) {
            FZ_CHECK(false);
        }
        break;
    }
    case 1: {
        sbr_can_confirmed_sign_t s;
        s.slot = fz_u32(in, 0u, 5u);
        s.count = fz_u32(in, 0u, 5u);
        s.class_id = fz_u32(in, 0u, 255u);
        s.track_id = fz_u32(in, 0u, 255u);
        s.speed_kmh = fz_u32(in, 0u, 255u);
        s.confidence = fz_float(in, -10.0f, 110.0f);
        s.age_frames = fz_u32(in, 0u, 300u);
        pack_round_trip(s, sbr_can_unpack_confirmed_sign, sbr_can_pack_confirmed_sign, check_sign);
        break;
    }
    case 2: {
        sbr_can_object_t o;
        o.index = fz_u32(in, 0u, 17u);
        o.track_id = fz_u32(in, 0u, 255u);
        o.x = fz_float(in, -10.0f, 2100.0f);
        o.y = fz_float(in, -10.0f, 1100.0f);
        o.vx = fz_float(in, -300.0f, 300.0f);
        o.vy = fz_float(in, -300.0f, 300.0f);
        o.certainty = fz_float(in, -10.0f, 110.0f);
        pack_round_trip(o, sbr_can_unpack_object, sbr_can_pack_object, check_object);
        break;
    }
    default: {
        sbr_can_ecu_status_t s;
        s.frame_counter = fz_u32(in, 0u, 70000u);
        s.processing_ms = fz_float(in, -1.0f, 7000.0f);
        s.region_count = fz_u32(in, 0u, 5000u);
        s.detection_count = fz_u32(in, 0u, 20u);
        s.overload = fz_u32(in, 0u, 2u);
        s.error = fz_u32(in, 0u, 2u);
        s.capacity_hit = fz_u32(in, 0u, 2u);
        pack_round_trip(s, sbr_can_unpack_ecu_status, sbr_can_pack_ecu_status, check_status);
        break;
    }
    }
}

void fuzz_e2e(FuzzedDataProvider &in)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_e2e_rx_t rx;
    FZ_STATUS(sbr_can_e2e_tx_init(&tx), SBR_OK);
    FZ_STATUS(sbr_can_e2e_tx_init(nullptr), SBR_ERR_NULL);
    if (in.ConsumeBool()) { // a corrupted sender state
        for (auto &c : tx.counter) {
            c = in.ConsumeIntegral<uint8_t>();
        }
    }
    sbr_can_frame_t f = frame_from(in);
    const sbr_status_t rs = sbr_can_e2e_rx_init(&rx, f.id);
    FZ_STATUS(rs, SBR_OK, SBR_ERR_RANGE);
    const sbr_status_t ps = sbr_can_e2e_protect(&tx, &f);
    FZ_STATUS(ps, SBR_OK, SBR_ERR_RANGE, SBR_ERR_SIZE, SBR_ERR_STATE);
    FZ_STATUS(sbr_can_e2e_protect(nullptr, &f), SBR_ERR_NULL);
    FZ_STATUS(sbr_can_e2e_protect(&tx, nullptr), SBR_ERR_NULL);
    if (ps == SBR_OK) {
        sbr_can_e2e_result_t r;
        FZ_CHECK(rs == SBR_OK);
        FZ_STATUS(sbr_can_e2e_check(&rx, &f, &r), SBR_OK);
        FZ_CHECK(r == SBR_E2E_FIRST);
        // the same frame again is a repeat
        FZ_STATUS(sbr_can_e2e_check(&rx, &f, &r), SBR_ERR_CORRUPT);
        FZ_CHECK(r == SBR_E2E_REPEATED);
        // the next one is in order
        FZ_STATUS(sbr_can_e2e_protect(&tx, &f), SBR_OK);
        FZ_STATUS(sbr_can_e2e_check(&rx, &f, &r), SBR_OK);
        FZ_CHECK(r == SBR_E2E_OK);
    }
    // arbitrary frames against a receiver: a result always, OK only for valid ones
    if (rs == SBR_OK) {
        const uint32_t n = in.ConsumeIntegralInRange<uint32_t>(0u, 8u);
        for (uint32_t i = 0u; i < n; i++) {
            sbr_can_frame_t g = frame_from(in);
            sbr_can_e2e_result_t r = SBR_E2E_SKIPPED;
            const sbr_status_t cs = sbr_can_e2e_check(&rx, &g, &r);
            FZ_STATUS(cs, SBR_OK, SBR_ERR_CORRUPT);
            FZ_CHECK((int)r >= 0 && (int)r <= (int)SBR_E2E_SKIPPED);
            FZ_CHECK((cs == SBR_OK) == ((r == SBR_E2E_OK) || (r == SBR_E2E_FIRST)));
            if (cs == SBR_OK) {
                FZ_CHECK(g.id == rx.id && g.dlc == 8u);
            }
        }
    }
    sbr_can_e2e_result_t r;
    FZ_STATUS(sbr_can_e2e_check(nullptr, &f, &r), SBR_ERR_NULL);
    FZ_STATUS(sbr_can_e2e_rx_init(nullptr, SBR_CAN_ID_DETECTION), SBR_ERR_NULL);
}

void fuzz_schedule(FuzzedDataProvider &in)
{
    sbr_can_confirmed_sign_t signs[6];
    sbr_can_detection_t dets[20];
    sbr_can_object_t objs[20];
    sbr_can_cycle_t cyc;
    sbr_can_sched_config_t cfg;
    sbr_can_e2e_tx_t tx;
    sbr_can_frame_t frames[64];
    uint32_t count = 0u;
    uint32_t dropped = 0u;
    std::memset(&cyc, 0, sizeof cyc);
    sbr_can_sched_config_default(&cfg);
    if (in.ConsumeBool()) {
        cfg.frame_budget = fz_u32(in, 0u, 70u);
        cfg.max_signs = fz_u32(in, 0u, 5u);
        cfg.max_detections = fz_u32(in, 0u, 25u);
        cfg.max_objects = fz_u32(in, 0u, 17u);
    }
    (void)sbr_can_e2e_tx_init(&tx);
    cyc.sign_count = in.ConsumeIntegralInRange<uint32_t>(0u, 6u);
    for (uint32_t i = 0u; i < cyc.sign_count; i++) {
        signs[i].slot = 0u;
        signs[i].count = 0u;
        signs[i].class_id = fz_u32(in, 0u, 44u);
        signs[i].track_id = fz_u32(in, 0u, 255u);
        signs[i].speed_kmh = fz_u32(in, 0u, 255u);
        signs[i].confidence = fz_float(in, 0.0f, 100.0f);
        signs[i].age_frames = fz_u32(in, 0u, 255u);
    }
    cyc.detection_count = in.ConsumeIntegralInRange<uint32_t>(0u, 20u);
    for (uint32_t i = 0u; i < cyc.detection_count; i++) {
        dets[i].class_id = fz_u32(in, 0u, 43u);
        dets[i].confidence = fz_float(in, 0.0f, 100.0f);
        dets[i].center_x = fz_float(in, 0.0f, 2046.0f);
        dets[i].center_y = fz_float(in, 0.0f, 2046.0f);
        dets[i].width = fz_float(in, 0.0f, 508.0f);
        dets[i].height = fz_float(in, 0.0f, 508.0f);
        dets[i].track_id = fz_u32(in, 0u, 63u);
    }
    cyc.object_count = in.ConsumeIntegralInRange<uint32_t>(0u, 20u);
    for (uint32_t i = 0u; i < cyc.object_count; i++) {
        objs[i].index = 0u;
        objs[i].track_id = fz_u32(in, 0u, 255u);
        objs[i].x = fz_float(in, 0.0f, 2047.0f);
        objs[i].y = fz_float(in, 0.0f, 1023.0f);
        objs[i].vx = fz_float(in, -256.0f, 252.0f);
        objs[i].vy = fz_float(in, -256.0f, 252.0f);
        objs[i].certainty = fz_float(in, 0.0f, 100.0f);
    }
    cyc.signs = (cyc.sign_count > 0u || in.ConsumeBool()) ? signs : nullptr;
    cyc.detections = (cyc.detection_count > 0u || in.ConsumeBool()) ? dets : nullptr;
    cyc.objects = (cyc.object_count > 0u || in.ConsumeBool()) ? objs : nullptr;
    cyc.status.frame_counter = fz_u32(in, 0u, 65535u);
    cyc.status.processing_ms = fz_float(in, 0.0f, 6553.0f);
    cyc.status.region_count = fz_u32(in, 0u, 4095u);
    cyc.status.detection_count = fz_u32(in, 0u, 15u);
    cyc.status.error = in.ConsumeIntegralInRange<uint32_t>(0u, 1u);
    cyc.status.capacity_hit = in.ConsumeIntegralInRange<uint32_t>(0u, 1u);
    const uint32_t capacity = in.ConsumeIntegralInRange<uint32_t>(0u, 64u);
    const sbr_status_t st = sbr_can_schedule(&tx, &cfg, &cyc, frames, capacity, &count, &dropped);
    FZ_STATUS(st, SBR_OK, SBR_ERR_NULL, SBR_ERR_RANGE, SBR_ERR_CAPACITY);
    if (st == SBR_OK || (st == SBR_ERR_RANGE && count > 0u)) {
        sbr_can_e2e_rx_t rx[4];
        const uint32_t ids[4] = {SBR_CAN_ID_CONFIRMED_SIGN, SBR_CAN_ID_ECU_STATUS, SBR_CAN_ID_DETECTION,
                                 SBR_CAN_ID_TRACKED_OBJECT};
        // one frame of each message at least, unless a result was refused (then left out)
        FZ_CHECK(count <= capacity && count <= cfg.frame_budget && (count >= 4u || st == SBR_ERR_RANGE));
        for (int k = 0; k < 4; k++) {
            FZ_STATUS(sbr_can_e2e_rx_init(&rx[k], ids[k]), SBR_OK);
        }
        for (uint32_t i = 0u; i < count; i++) {
            int k = 0;
            while (k < 4 && ids[k] != frames[i].id) {
                k++;
            }
            FZ_CHECK(k < 4);
            sbr_can_e2e_result_t r;
            FZ_STATUS(sbr_can_e2e_check(&rx[k], &frames[i], &r), SBR_OK);
            switch (k) {
            case 0: {
                sbr_can_confirmed_sign_t s;
                FZ_STATUS(sbr_can_unpack_confirmed_sign(&frames[i], &s), SBR_OK);
                check_sign(s);
                break;
            }
            case 1: {
                sbr_can_ecu_status_t s;
                FZ_STATUS(sbr_can_unpack_ecu_status(&frames[i], &s), SBR_OK);
                check_status(s);
                FZ_CHECK((dropped > 0u) == (s.overload == 1u) || st == SBR_ERR_RANGE);
                break;
            }
            case 2: {
                sbr_can_detection_t d;
                FZ_STATUS(sbr_can_unpack_detection(&frames[i], &d), SBR_OK);
                check_detection(d);
                break;
            }
            default: {
                sbr_can_object_t o;
                FZ_STATUS(sbr_can_unpack_object(&frames[i], &o), SBR_OK);
                check_object(o);
                break;
            }
            }
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FuzzedDataProvider in(data, size);
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: {
        const sbr_can_frame_t f = frame_from(in);
        unpack_round_trip(f, sbr_can_unpack_detection, sbr_can_pack_detection, check_detection);
        unpack_round_trip(f, sbr_can_unpack_confirmed_sign, sbr_can_pack_confirmed_sign, check_sign);
        unpack_round_trip(f, sbr_can_unpack_object, sbr_can_pack_object, check_object);
        unpack_round_trip(f, sbr_can_unpack_ecu_status, sbr_can_pack_ecu_status, check_status);
        break;
    }
    case 1:
        fuzz_pack(in);
        break;
    case 2:
        fuzz_e2e(in);
        break;
    default:
        fuzz_schedule(in);
        break;
    }
    return 0;
}
