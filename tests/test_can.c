/* SPDX-License-Identifier: MIT */
/* Unity tests of the CAN messages, E2E protection, scheduler and the mock (and, on the
   Cortex-M build, the bare-metal) port (include/sbr/can.h, ports/). */
#include "unity.h"
#include "sbr/can.h"
#include "sbr_port_mock.h"
#include "test_status_table.h"
#ifdef SBR_TEST_CORTEX_M_PORT
#include "sbr_port_cortex_m.h"
#endif

#include <math.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

/* ---- CRC ------------------------------------------------------------------------------ */

/* CRC-8/SAE-J1850 check value and the AUTOSAR CRC library's published vectors. */
/* SBR_Restrictions: the layout by hand, round trips at the limits, refusals, E2E. */
static void test_restrictions(void)
{
    sbr_can_restrictions_t r, o;
    sbr_can_frame_t f;
    sbr_can_e2e_tx_t tx;
    sbr_can_e2e_rx_t rx;
    sbr_can_e2e_result_t res;
    memset(&r, 0, sizeof r);
    r.speed_limit_kmh = 120u;
    r.no_overtaking = 1u;
    r.priority_road = 1u;
    r.speed_age_s = 0x1234u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_restrictions(&r, &f));
    TEST_ASSERT_EQUAL_UINT32(0x302u, f.id);
    TEST_ASSERT_EQUAL_UINT8(8u, f.dlc);
    TEST_ASSERT_EQUAL_HEX8(120u, f.data[2]);  /* limit: bits 16..23 */
    TEST_ASSERT_EQUAL_HEX8(0x05u, f.data[3]); /* bans at 24, 25; priority at 26 */
    TEST_ASSERT_EQUAL_HEX8(0x34u, f.data[4]); /* age: bits 32..47, Intel order */
    TEST_ASSERT_EQUAL_HEX8(0x12u, f.data[5]);
    TEST_ASSERT_EQUAL_HEX8(0x00u, f.data[6]);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_restrictions(&f, &o));
    TEST_ASSERT_EQUAL_MEMORY(&r, &o, sizeof r);
    r.speed_limit_kmh = 255u;
    r.no_overtaking_trucks = 1u;
    r.speed_age_s = 65535u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_restrictions(&r, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_restrictions(&f, &o));
    TEST_ASSERT_EQUAL_MEMORY(&r, &o, sizeof r);
    r.speed_age_s = 65536u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_restrictions(&r, &f));
    r.speed_age_s = 0u;
    r.priority_road = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_restrictions(&r, &f));
    r.priority_road = 0u;
    r.speed_limit_kmh = 256u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_restrictions(&r, &f));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_pack_restrictions(NULL, &f));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_restrictions(&f, NULL));
    f.id = SBR_CAN_ID_ECU_STATUS;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_restrictions(&f, &o));
    f.id = SBR_CAN_ID_RESTRICTIONS;
    f.dlc = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_unpack_restrictions(&f, &o));
    /* its own alive counter and Data ID 0x5B02 */
    r.speed_limit_kmh = 50u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_restrictions(&r, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx, SBR_CAN_ID_RESTRICTIONS));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_protect(&tx, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &f, &res));
    TEST_ASSERT_EQUAL_UINT8(1u, tx.counter[4]);
    TEST_ASSERT_EQUAL_UINT8(0u, tx.counter[1]);
    {
        uint8_t buf[9] = {0x02u, 0x5Bu};
        memcpy(&buf[2], &f.data[1], 7u);
        TEST_ASSERT_EQUAL_HEX8(sbr_crc8_j1850(buf, 9u), f.data[0]);
    }
}

static void test_crc8_j1850_vectors(void)
{
    static const uint8_t v1[4] = {0x00, 0x00, 0x00, 0x00};
    static const uint8_t v2[3] = {0xF2, 0x01, 0x83};
    static const uint8_t v3[4] = {0x0F, 0xAA, 0x00, 0x55};
    static const uint8_t v4[4] = {0x00, 0xFF, 0x55, 0x11};
    static const uint8_t v5[9] = {0x33, 0x22, 0x55, 0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF};
    static const uint8_t v6[3] = {0x92, 0x6B, 0x55};
    static const uint8_t v7[4] = {0xFF, 0xFF, 0xFF, 0xFF};
    TEST_ASSERT_EQUAL_HEX8(0x4B, sbr_crc8_j1850((const uint8_t *)"123456789", 9u));
    TEST_ASSERT_EQUAL_HEX8(0x59, sbr_crc8_j1850(v1, 4u));
    TEST_ASSERT_EQUAL_HEX8(0x37, sbr_crc8_j1850(v2, 3u));
    TEST_ASSERT_EQUAL_HEX8(0x79, sbr_crc8_j1850(v3, 4u));
    TEST_ASSERT_EQUAL_HEX8(0xB8, sbr_crc8_j1850(v4, 4u));
    TEST_ASSERT_EQUAL_HEX8(0xCB, sbr_crc8_j1850(v5, 9u));
    TEST_ASSERT_EQUAL_HEX8(0x8C, sbr_crc8_j1850(v6, 3u));
    TEST_ASSERT_EQUAL_HEX8(0x74, sbr_crc8_j1850(v7, 4u));
    TEST_ASSERT_EQUAL_HEX8(0x00, sbr_crc8_j1850(v1, 0u)); /* empty: 0xFF ^ 0xFF */
}

/* ---- layout --------------------------------------------------------------------------- */

/* Bytes worked out by hand from the DBC's start bits (Intel order). */
static void test_detection_layout_by_hand(void)
{
    sbr_can_detection_t d;
    sbr_can_frame_t f;
    d.class_id = 14u;     /* bits 12..17: 0b001110 */
    d.confidence = 100.f; /* raw 50 at bits 18..23 */
    d.center_x = 100.0f;  /* raw 50 at bits 24..33 */
    d.center_y = 2046.0f; /* raw 1023 at bits 34..43 */
    d.width = 508.0f;     /* raw 127 at bits 44..50 */
    d.height = 0.0f;      /* raw 0 at 51..57 */
    d.track_id = 63u;     /* bits 58..63 all ones */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_detection(&d, &f));
    TEST_ASSERT_EQUAL_HEX32(0x310u, f.id);
    TEST_ASSERT_EQUAL_UINT8(8u, f.dlc);
    TEST_ASSERT_EQUAL_HEX8(0x00, f.data[0]);            /* CRC: not yet protected */
    TEST_ASSERT_EQUAL_HEX8(0xE0, f.data[1]);            /* class low nibble, counter 0 */
    TEST_ASSERT_EQUAL_HEX8((50u << 2) | 0x0u, f.data[2]); /* class bits 4,5 = 0 */
    TEST_ASSERT_EQUAL_HEX8(50u, f.data[3]);
    TEST_ASSERT_EQUAL_HEX8(0xFC, f.data[4]);            /* cy bits 0..5 at 34..39 */
    TEST_ASSERT_EQUAL_HEX8(0xFF, f.data[5]);            /* cy bits 6..9, width bits 0..3 */
    TEST_ASSERT_EQUAL_HEX8(0x07, f.data[6]);            /* width bits 4..6, height 0 */
    TEST_ASSERT_EQUAL_HEX8(0xFC, f.data[7]);            /* height bits 5,6 = 0, track */
}

/* ---- round trips ---------------------------------------------------------------------- */

static void test_detection_round_trip_limits(void)
{
    sbr_can_detection_t d;
    sbr_can_detection_t o;
    sbr_can_frame_t f;
    sbr_can_frame_t keep;
    const float lo[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    const float hi[5] = {100.0f, 2046.0f, 2046.0f, 508.0f, 508.0f};
    const float res[5] = {2.0f, 2.0f, 2.0f, 4.0f, 4.0f};
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        d.class_id = (k == 0u) ? 0u : ((k == 1u) ? 42u : SBR_CAN_CLASS_NONE_DET);
        d.track_id = (k == 0u) ? 0u : ((k == 1u) ? 62u : SBR_CAN_TRACK_NONE_DET);
        d.confidence = (k == 0u) ? lo[0] : ((k == 1u) ? hi[0] : 37.3f);
        d.center_x = (k == 0u) ? lo[1] : ((k == 1u) ? hi[1] : 681.2f);
        d.center_y = (k == 0u) ? lo[2] : ((k == 1u) ? hi[2] : 400.9f);
        d.width = (k == 0u) ? lo[3] : ((k == 1u) ? hi[3] : 33.0f);
        d.height = (k == 0u) ? lo[4] : ((k == 1u) ? hi[4] : 35.1f);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_detection(&d, &f));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_detection(&f, &o));
        TEST_ASSERT_EQUAL_UINT32(d.class_id, o.class_id);
        TEST_ASSERT_EQUAL_UINT32(d.track_id, o.track_id);
        TEST_ASSERT_FLOAT_WITHIN(res[0] / 2.0f, d.confidence, o.confidence);
        TEST_ASSERT_FLOAT_WITHIN(res[1] / 2.0f, d.center_x, o.center_x);
        TEST_ASSERT_FLOAT_WITHIN(res[2] / 2.0f, d.center_y, o.center_y);
        TEST_ASSERT_FLOAT_WITHIN(res[3] / 2.0f, d.width, o.width);
        TEST_ASSERT_FLOAT_WITHIN(res[4] / 2.0f, d.height, o.height);
    }
    /* out of range (one resolution step beyond either end, NaN): rejected, frame kept */
    memset(&keep, 0x5A, sizeof keep);
    for (k = 0u; k < 5u; k++) {
        uint32_t side;
        for (side = 0u; side < 3u; side++) {
            float bad = (side == 0u) ? (lo[k] - res[k]) : ((side == 1u) ? (hi[k] + res[k]) : NAN);
            sbr_can_detection_t b = o;
            float *fields[5];
            fields[0] = &b.confidence;
            fields[1] = &b.center_x;
            fields[2] = &b.center_y;
            fields[3] = &b.width;
            fields[4] = &b.height;
            *fields[k] = bad;
            f = keep;
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_detection(&b, &f));
            TEST_ASSERT_EQUAL_MEMORY(&keep, &f, sizeof f);
        }
    }
    d = o;
    d.class_id = 43u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_detection(&d, &f));
    d = o;
    d.track_id = 64u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_detection(&d, &f));
    /* unpack of the wrong message or length */
    f.id = SBR_CAN_ID_ECU_STATUS;
    f.dlc = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_detection(&f, &o));
    f.id = SBR_CAN_ID_DETECTION;
    f.dlc = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_unpack_detection(&f, &o));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_pack_detection(NULL, &f));
}

static void test_sign_object_status_round_trips(void)
{
    sbr_can_confirmed_sign_t s = {3u, 4u, 42u, 254u, 250u, 100.0f, 255u};
    sbr_can_confirmed_sign_t so;
    sbr_can_object_t ob = {15u, 254u, 2047.0f, 1023.0f, -256.0f, 252.0f, 100.0f};
    sbr_can_object_t oo;
    sbr_can_ecu_status_t st = {65535u, 6553.4f, 4095u, 15u, 1u, 1u, 1u};
    sbr_can_ecu_status_t sto;
    sbr_can_frame_t f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_confirmed_sign(&s, &f));
    TEST_ASSERT_EQUAL_HEX32(0x300u, f.id);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_confirmed_sign(&f, &so));
    TEST_ASSERT_EQUAL_UINT32(3u, so.slot);
    TEST_ASSERT_EQUAL_UINT32(4u, so.count);
    TEST_ASSERT_EQUAL_UINT32(42u, so.class_id);
    TEST_ASSERT_EQUAL_UINT32(254u, so.track_id);
    TEST_ASSERT_EQUAL_UINT32(250u, so.speed_kmh);
    TEST_ASSERT_EQUAL_FLOAT(100.0f, so.confidence);
    TEST_ASSERT_EQUAL_UINT32(255u, so.age_frames);
    s.speed_kmh = 251u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_confirmed_sign(&s, &f));
    s.speed_kmh = SBR_CAN_SPEED_NONE;
    s.class_id = SBR_CAN_CLASS_NONE;
    s.confidence = 100.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_confirmed_sign(&s, &f));
    s.confidence = 0.0f;
    s.slot = 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_confirmed_sign(&s, &f));

    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_object(&ob, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_object(&f, &oo));
    TEST_ASSERT_EQUAL_UINT32(15u, oo.index);
    TEST_ASSERT_EQUAL_FLOAT(2047.0f, oo.x);
    TEST_ASSERT_EQUAL_FLOAT(1023.0f, oo.y);
    TEST_ASSERT_EQUAL_FLOAT(-256.0f, oo.vx);
    TEST_ASSERT_EQUAL_FLOAT(252.0f, oo.vy);
    TEST_ASSERT_EQUAL_FLOAT(100.0f, oo.certainty);
    ob.vx = -13.0f; /* rounds to -12 (raw -3), signed field */
    ob.vy = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_object(&ob, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_object(&f, &oo));
    TEST_ASSERT_EQUAL_FLOAT(-12.0f, oo.vx);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, oo.vy);
    ob.vx = -260.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_object(&ob, &f));
    ob.vx = 0.0f;
    ob.y = 1024.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_object(&ob, &f));

    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_ecu_status(&st, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&f, &sto));
    TEST_ASSERT_EQUAL_UINT32(65535u, sto.frame_counter);
    TEST_ASSERT_FLOAT_WITHIN(0.05f, 6553.4f, sto.processing_ms);
    TEST_ASSERT_EQUAL_UINT32(4095u, sto.region_count);
    TEST_ASSERT_EQUAL_UINT32(15u, sto.detection_count);
    TEST_ASSERT_EQUAL_UINT32(1u, sto.overload + sto.error + sto.capacity_hit - 2u);
    /* counts saturate (documented), time does not */
    st.region_count = 100000u;
    st.detection_count = 99u;
    st.frame_counter = 65536u + 7u; /* modulo 2^16 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_ecu_status(&st, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&f, &sto));
    TEST_ASSERT_EQUAL_UINT32(4095u, sto.region_count);
    TEST_ASSERT_EQUAL_UINT32(15u, sto.detection_count);
    TEST_ASSERT_EQUAL_UINT32(7u, sto.frame_counter);
    st.processing_ms = 6553.6f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_ecu_status(&st, &f));
    st.processing_ms = -0.1f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_pack_ecu_status(&st, &f));
}

/* ---- E2E ------------------------------------------------------------------------------ */

static sbr_can_frame_t protected_status(sbr_can_e2e_tx_t *tx, uint32_t counter_value)
{
    sbr_can_ecu_status_t st = {counter_value, 12.3f, 100u, 2u, 0u, 0u, 0u};
    sbr_can_frame_t f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_ecu_status(&st, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_protect(tx, &f));
    return f;
}

static void test_e2e_counter_sequence(void)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_e2e_rx_t rx;
    sbr_can_e2e_result_t r;
    sbr_can_frame_t f[40];
    uint32_t i;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx, SBR_CAN_ID_ECU_STATUS));
    for (i = 0u; i < 40u; i++) {
        f[i] = protected_status(&tx, i);
        TEST_ASSERT_EQUAL_UINT8(i % 15u, f[i].data[1] & 0x0Fu); /* 0..14, wraps, never 15 */
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &f[0], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_FIRST, r);
    for (i = 1u; i < 20u; i++) {
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &f[i], &r));
        TEST_ASSERT_EQUAL_INT(SBR_E2E_OK, r);
    }
    /* repeated: rejected, state kept */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &f[19], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_REPEATED, r);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &f[20], &r));
    /* skipped (21 lost): reported, then in sync again */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &f[22], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_SKIPPED, r);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &f[23], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_OK, r);
    /* an old frame (counter went backwards by 3) counts as a jump */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &f[20], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_SKIPPED, r);
    /* wrong length, wrong id */
    f[30].dlc = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &f[30], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_WRONG_LENGTH, r);
    f[31].id = SBR_CAN_ID_DETECTION;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &f[31], &r));
    TEST_ASSERT_EQUAL_INT(SBR_E2E_WRONG_ID, r);
    /* a frame sent with another message's Data ID fails the CRC */
    f[32].id = SBR_CAN_ID_DETECTION;
    {
        sbr_can_e2e_rx_t rx2;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx2, SBR_CAN_ID_DETECTION));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx2, &f[32], &r));
        TEST_ASSERT_EQUAL_INT(SBR_E2E_WRONG_CRC, r);
    }
    /* bad input */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_e2e_rx_init(&rx, 0x123u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_e2e_check(&rx, NULL, &r));
    tx.counter[1] = 15u; /* corrupted sender state */
    f[0].id = SBR_CAN_ID_ECU_STATUS;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_can_e2e_protect(&tx, &f[0]));
}

/* Every single-bit flip of a protected frame of every message is rejected. */
static void test_e2e_every_single_bit_flip_is_caught(void)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_frame_t frames[4];
    sbr_can_detection_t d = {14u, 80.0f, 700.0f, 300.0f, 40.0f, 40.0f, 5u};
    sbr_can_confirmed_sign_t s = {0u, 1u, 1u, 7u, 30u, 90.0f, 3u};
    sbr_can_object_t ob = {0u, 7u, 700.0f, 300.0f, 8.0f, -4.0f, 60.0f};
    sbr_can_ecu_status_t st = {1u, 40.0f, 321u, 1u, 0u, 0u, 0u};
    uint32_t m;
    uint32_t tried = 0u;
    uint32_t caught = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_detection(&d, &frames[0]));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_confirmed_sign(&s, &frames[1]));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_object(&ob, &frames[2]));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_ecu_status(&st, &frames[3]));
    for (m = 0u; m < 4u; m++) {
        uint32_t bit;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_protect(&tx, &frames[m]));
        for (bit = 0u; bit < 64u; bit++) {
            sbr_can_e2e_rx_t rx;
            sbr_can_e2e_result_t r;
            sbr_can_frame_t bad = frames[m];
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx, frames[m].id));
            bad.data[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
            tried++;
            if (sbr_can_e2e_check(&rx, &bad, &r) == SBR_ERR_CORRUPT) {
                caught++;
            }
        }
        /* the unflipped frame passes */
        {
            sbr_can_e2e_rx_t rx;
            sbr_can_e2e_result_t r;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx, frames[m].id));
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &frames[m], &r));
        }
    }
    TEST_ASSERT_EQUAL_UINT32(256u, tried);
    TEST_ASSERT_EQUAL_UINT32(tried, caught);
}

/* ---- scheduler and ports -------------------------------------------------------------- */

static void test_scheduler_priority_and_budget(void)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_sched_config_t cfg;
    sbr_can_cycle_t cyc;
    sbr_can_detection_t dets[10];
    sbr_can_object_t objs[2];
    sbr_can_frame_t frames[16];
    sbr_can_detection_t d;
    sbr_can_ecu_status_t st;
    sbr_can_confirmed_sign_t s;
    uint32_t n = 0u;
    uint32_t dropped = 0u;
    uint32_t i;
    static const float conf[10] = {10.0f, 90.0f, 50.0f, 70.0f, 30.0f, 90.0f, 20.0f, 60.0f, 80.0f, 40.0f};
    memset(&cyc, 0, sizeof cyc);
    for (i = 0u; i < 10u; i++) {
        dets[i].class_id = i;
        dets[i].confidence = conf[i];
        dets[i].center_x = 100.0f;
        dets[i].center_y = 100.0f;
        dets[i].width = 20.0f;
        dets[i].height = 20.0f;
        dets[i].track_id = SBR_CAN_TRACK_NONE_DET;
    }
    memset(objs, 0, sizeof objs);
    objs[0].certainty = 20.0f;
    objs[1].certainty = 60.0f;
    cyc.detections = dets;
    cyc.detection_count = 10u;
    cyc.objects = objs;
    cyc.object_count = 2u;
    cyc.status.processing_ms = 33.0f;
    sbr_can_sched_config_default(&cfg);
    cfg.frame_budget = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_UINT32(8u, n);
    /* 2 beyond max_detections 8, 2 more beyond the budget, both objects */
    TEST_ASSERT_EQUAL_UINT32(6u, dropped);
    TEST_ASSERT_EQUAL_HEX32(SBR_CAN_ID_CONFIRMED_SIGN, frames[0].id);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_confirmed_sign(&frames[0], &s));
    TEST_ASSERT_EQUAL_UINT32(SBR_CAN_CLASS_NONE, s.class_id);
    TEST_ASSERT_EQUAL_UINT32(SBR_CAN_SPEED_NONE, s.speed_kmh);
    TEST_ASSERT_EQUAL_HEX32(SBR_CAN_ID_ECU_STATUS, frames[1].id);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&frames[1], &st));
    TEST_ASSERT_EQUAL_UINT32(1u, st.overload);
    /* detections by decreasing confidence, ties by index: 1, 5, 8, 3, 7, 2 */
    {
        static const uint32_t order[6] = {1u, 5u, 8u, 3u, 7u, 2u};
        for (i = 0u; i < 6u; i++) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_detection(&frames[2u + i], &d));
            TEST_ASSERT_EQUAL_UINT32(order[i], d.class_id);
        }
    }
    /* every frame is protected: a receiver accepts them in order */
    {
        sbr_can_e2e_rx_t rx;
        sbr_can_e2e_result_t r;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_rx_init(&rx, SBR_CAN_ID_DETECTION));
        for (i = 2u; i < 8u; i++) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_check(&rx, &frames[i], &r));
        }
    }
    /* enough budget: everything fits, objects by certainty, no overload */
    cfg.frame_budget = 16u;
    cfg.max_detections = 10u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_UINT32(14u, n);
    TEST_ASSERT_EQUAL_UINT32(0u, dropped);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&frames[1], &st));
    TEST_ASSERT_EQUAL_UINT32(0u, st.overload);
    {
        sbr_can_object_t o;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_object(&frames[12], &o));
        TEST_ASSERT_EQUAL_FLOAT(60.0f, o.certainty);
        TEST_ASSERT_EQUAL_UINT32(0u, o.index);
    }
    /* an invalid detection is left out and reported */
    dets[3].center_x = 5000.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_UINT32(13u, n);
    TEST_ASSERT_EQUAL_UINT32(1u, dropped);
    dets[3].center_x = NAN;
    dets[3].confidence = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_UINT32(13u, n);
    /* capacity and config */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_can_schedule(&tx, &cfg, &cyc, frames, 15u, &n, &dropped));
    cfg.frame_budget = 3u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_schedule(NULL, &cfg, &cyc, frames, 16u, &n, &dropped));
}

/* Regression (fuzzer finding): confirmed signs beyond max_signs raised overload but were
   not counted in `dropped`. */
static void test_scheduler_counts_signs_beyond_the_limit(void)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_sched_config_t cfg;
    sbr_can_cycle_t cyc;
    sbr_can_confirmed_sign_t signs[6];
    sbr_can_frame_t frames[16];
    sbr_can_ecu_status_t st;
    uint32_t n = 0u;
    uint32_t dropped = 0u;
    uint32_t i;
    memset(&cyc, 0, sizeof cyc);
    memset(signs, 0, sizeof signs);
    for (i = 0u; i < 6u; i++) {
        signs[i].class_id = 14u;
        signs[i].track_id = i;
        signs[i].speed_kmh = SBR_CAN_SPEED_NONE;
        signs[i].confidence = 90.0f;
    }
    cyc.signs = signs;
    cyc.sign_count = 6u;
    sbr_can_sched_config_default(&cfg);
    cfg.max_signs = 3u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_schedule(&tx, &cfg, &cyc, frames, 16u, &n, &dropped));
    TEST_ASSERT_EQUAL_UINT32(6u, n); /* 3 signs, status, no detection, no object */
    TEST_ASSERT_EQUAL_UINT32(3u, dropped);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&frames[3], &st));
    TEST_ASSERT_EQUAL_UINT32(1u, st.overload);
}

/* The scheduler's configuration check: defaults pass, each bound refused with its field. */
static void test_sched_config_check(void)
{
    sbr_can_sched_config_t cfg;
    sbr_can_sched_config_t bad;
    sbr_can_sched_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_sched_config_check(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_sched_config_check(NULL));
    bad = cfg;
    bad.frame_budget = 3u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_sched_config_check(&bad));
    bad = cfg;
    bad.max_signs = 5u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_sched_config_check(&bad));
    bad = cfg;
    bad.max_detections = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_sched_config_check(&bad));
    bad = cfg;
    bad.max_objects = 17u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_sched_config_check(&bad));
}

/* Regression (fuzzer finding): unpack returned SBR_OK with values outside their signals'
   ranges (slot 15, class 50, confidence 126 %); every documented status of the unpackers. */
static void test_unpack_refuses_out_of_range_signals(void)
{
    sbr_can_frame_t f;
    sbr_can_confirmed_sign_t s;
    sbr_can_detection_t d;
    sbr_can_object_t o;
    sbr_can_ecu_status_t e;
    sbr_can_confirmed_sign_t good;
    memset(&good, 0, sizeof good);
    good.class_id = 14u;
    good.speed_kmh = SBR_CAN_SPEED_NONE;
    good.track_id = 7u;
    good.confidence = 80.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_confirmed_sign(&good, &f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_confirmed_sign(&f, &s));
    TEST_ASSERT_EQUAL_UINT32(14u, s.class_id);
    f.data[1] |= 0xF0u; /* slot (bits 12..15) = 15 */
    memset(&s, 0x5A, sizeof s);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_confirmed_sign(&f, &s));
    TEST_ASSERT_EQUAL_HEX8(0x5Au, ((const uint8_t *)&s)[0]); /* untouched */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_confirmed_sign(&good, &f));
    f.data[2] = 50u; /* class 50 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_confirmed_sign(&f, &s));
    f.dlc = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_unpack_confirmed_sign(&f, &s));
    f.dlc = 8u;
    f.id = SBR_CAN_ID_DETECTION;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_confirmed_sign(&f, &s));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_confirmed_sign(NULL, &s));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_confirmed_sign(&f, NULL));
    /* a detection with confidence 126 % (raw 63 at bits 18..23) */
    memset(&f, 0, sizeof f);
    f.id = SBR_CAN_ID_DETECTION;
    f.dlc = 8u;
    f.data[2] = 0xFCu;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_detection(&f, &d));
    f.data[2] = 0x00u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_detection(&f, &d));
    /* objects and status: wrong id, length, NULL */
    f.id = SBR_CAN_ID_TRACKED_OBJECT;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_object(&f, &o));
    f.dlc = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_unpack_object(&f, &o));
    f.dlc = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_ecu_status(&f, &e));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_object(NULL, &o));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_object(&f, NULL));
    f.id = SBR_CAN_ID_ECU_STATUS;
    /* processing time raw 65535 = 6553.5 ms, above the signal's 6553.4 */
    f.data[4] = 0xFFu;
    f.data[5] = 0xFFu;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_unpack_ecu_status(&f, &e));
    f.data[5] = 0x00u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_unpack_ecu_status(&f, &e));
    f.dlc = 9u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_unpack_ecu_status(&f, &e));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_ecu_status(NULL, &e));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_unpack_ecu_status(&f, NULL));
}

/* Every documented status of sbr_can_e2e_protect(). */
static void test_e2e_protect_statuses(void)
{
    sbr_can_e2e_tx_t tx;
    sbr_can_frame_t f;
    sbr_can_detection_t d;
    memset(&d, 0, sizeof d);
    d.class_id = SBR_CAN_CLASS_NONE_DET;
    d.track_id = SBR_CAN_TRACK_NONE_DET;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_tx_init(&tx));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_pack_detection(&d, &f));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_e2e_protect(NULL, &f));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_e2e_protect(&tx, NULL));
    f.id = 0x123u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_can_e2e_protect(&tx, &f));
    f.id = SBR_CAN_ID_DETECTION;
    f.dlc = 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_can_e2e_protect(&tx, &f));
    f.dlc = 8u;
    tx.counter[2] = 15u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_can_e2e_protect(&tx, &f));
    tx.counter[2] = 14u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_e2e_protect(&tx, &f));
    TEST_ASSERT_EQUAL_UINT8(0u, tx.counter[2]); /* 14 wraps to 0 */
}

/* can.h: every documented status, in one table. */
static void test_can_h_statuses(void)
{
    status_table_t t;
    sbr_can_detection_t d;
    sbr_can_detection_t dbad;
    sbr_can_confirmed_sign_t cs;
    sbr_can_confirmed_sign_t csbad;
    sbr_can_object_t ob;
    sbr_can_object_t obbad;
    sbr_can_ecu_status_t es;
    sbr_can_ecu_status_t esbad;
    sbr_can_frame_t f;
    sbr_can_frame_t fd;
    sbr_can_frame_t wrong_id;
    sbr_can_frame_t short_f;
    sbr_can_frame_t frames[16];
    sbr_can_e2e_tx_t tx;
    sbr_can_e2e_rx_t rx;
    sbr_can_e2e_result_t res;
    sbr_can_sched_config_t sc;
    sbr_can_sched_config_t scbad;
    sbr_can_cycle_t cyc;
    sbr_can_detection_t cdet[1];
    sbr_port_mock_t m;
    sbr_can_frame_t store[2];
    uint32_t n = 0u;
    uint32_t dropped = 0u;
    uint32_t sent = 0u;
    memset(&d, 0, sizeof d);
    d.class_id = 14u;
    d.track_id = SBR_CAN_TRACK_NONE_DET;
    dbad = d;
    dbad.confidence = 101.0f;
    memset(&cs, 0, sizeof cs);
    cs.class_id = SBR_CAN_CLASS_NONE;
    cs.track_id = SBR_CAN_TRACK_NONE;
    cs.speed_kmh = SBR_CAN_SPEED_NONE;
    csbad = cs;
    csbad.slot = 4u;
    memset(&ob, 0, sizeof ob);
    ob.track_id = SBR_CAN_TRACK_NONE;
    obbad = ob;
    obbad.vx = NAN;
    memset(&es, 0, sizeof es);
    esbad = es;
    esbad.overload = 2u;
    memset(&cyc, 0, sizeof cyc);
    cdet[0] = d;
    cdet[0].confidence = 80.0f;
    cyc.detections = cdet;
    cyc.detection_count = 1u;
    sbr_can_sched_config_default(&sc);
    scbad = sc;
    scbad.frame_budget = 3u;
    sbr_port_mock_init(&m, store, 2u);
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_can_pack_detection(&d, &fd));
    ROW(&t, SBR_ERR_NULL, sbr_can_pack_detection(NULL, &f));
    ROW(&t, SBR_ERR_RANGE, sbr_can_pack_detection(&dbad, &f));
    ROW(&t, SBR_OK, sbr_can_unpack_detection(&fd, &d));
    ROW(&t, SBR_ERR_NULL, sbr_can_unpack_detection(&fd, NULL));
    ROW(&t, SBR_OK, sbr_can_pack_confirmed_sign(&cs, &f));
    ROW(&t, SBR_ERR_NULL, sbr_can_pack_confirmed_sign(&cs, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_can_pack_confirmed_sign(&csbad, &f));
    ROW(&t, SBR_OK, sbr_can_unpack_confirmed_sign(&f, &cs));
    wrong_id = fd;
    short_f = f;
    short_f.dlc = 7u;
    ROW(&t, SBR_ERR_RANGE, sbr_can_unpack_confirmed_sign(&wrong_id, &cs));
    ROW(&t, SBR_ERR_SIZE, sbr_can_unpack_confirmed_sign(&short_f, &cs));
    ROW(&t, SBR_OK, sbr_can_pack_object(&ob, &f));
    ROW(&t, SBR_ERR_RANGE, sbr_can_pack_object(&obbad, &f));
    ROW(&t, SBR_OK, sbr_can_unpack_object(&f, &ob));
    ROW(&t, SBR_ERR_RANGE, sbr_can_unpack_object(&fd, &ob));
    ROW(&t, SBR_OK, sbr_can_pack_ecu_status(&es, &f));
    ROW(&t, SBR_ERR_RANGE, sbr_can_pack_ecu_status(&esbad, &f));
    ROW(&t, SBR_OK, sbr_can_unpack_ecu_status(&f, &es));
    ROW(&t, SBR_ERR_NULL, sbr_can_unpack_ecu_status(NULL, &es));
    ROW(&t, SBR_OK, sbr_can_e2e_tx_init(&tx));
    ROW(&t, SBR_ERR_NULL, sbr_can_e2e_tx_init(NULL));
    ROW(&t, SBR_OK, sbr_can_e2e_protect(&tx, &fd));
    ROW(&t, SBR_OK, sbr_can_e2e_rx_init(&rx, SBR_CAN_ID_DETECTION));
    ROW(&t, SBR_ERR_NULL, sbr_can_e2e_rx_init(NULL, SBR_CAN_ID_DETECTION));
    ROW(&t, SBR_ERR_RANGE, sbr_can_e2e_rx_init(&rx, 0x7FFu));
    ROW(&t, SBR_OK, sbr_can_e2e_rx_init(&rx, SBR_CAN_ID_DETECTION));
    ROW(&t, SBR_OK, sbr_can_e2e_check(&rx, &fd, &res));
    ROW(&t, SBR_ERR_CORRUPT, sbr_can_e2e_check(&rx, &fd, &res)); /* repeated */
    ROW(&t, SBR_ERR_NULL, sbr_can_e2e_check(&rx, NULL, &res));
    ROW(&t, SBR_OK, sbr_can_schedule(&tx, &sc, &cyc, frames, 16u, &n, &dropped));
    ROW(&t, SBR_ERR_NULL, sbr_can_schedule(&tx, &sc, &cyc, frames, 16u, &n, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_can_schedule(&tx, &scbad, &cyc, frames, 16u, &n, &dropped));
    ROW(&t, SBR_ERR_CAPACITY, sbr_can_schedule(&tx, &sc, &cyc, frames, 15u, &n, &dropped));
    cdet[0].center_x = 9999.0f; /* a result out of range: left out, reported */
    ROW(&t, SBR_ERR_RANGE, sbr_can_schedule(&tx, &sc, &cyc, frames, 16u, &n, &dropped));
    ROW(&t, SBR_OK, sbr_can_send(&sbr_port_mock, &m, frames, 2u, &sent));
    ROW(&t, SBR_ERR_NULL, sbr_can_send(NULL, &m, frames, 2u, &sent));
    ROW(&t, SBR_ERR_CAPACITY, sbr_can_send(&sbr_port_mock, &m, frames, 1u, &sent)); /* the port's status */
    status_table_check(&t);
    TEST_ASSERT_EQUAL_INT(SBR_E2E_REPEATED, res);
    TEST_ASSERT_EQUAL_UINT32(0u, sent);
    TEST_ASSERT_EQUAL_UINT8(0u, sbr_crc8_j1850(NULL, 4u));
}

static void test_mock_port_and_send(void)
{
    sbr_can_frame_t store[4];
    sbr_can_frame_t out[6];
    sbr_port_mock_t m;
    uint32_t sent = 99u;
    uint32_t i;
    for (i = 0u; i < 6u; i++) {
        memset(&out[i], 0, sizeof out[i]);
        out[i].id = 0x300u + i;
        out[i].dlc = 8u;
        out[i].data[7] = (uint8_t)i;
    }
    sbr_port_mock_init(&m, store, 4u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_can_send(&sbr_port_mock, &m, out, 3u, &sent));
    TEST_ASSERT_EQUAL_UINT32(3u, sent);
    TEST_ASSERT_EQUAL_MEMORY(out, store, 3u * sizeof out[0]);
    /* the queue runs full: the sender stops at the first refused frame */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_can_send(&sbr_port_mock, &m, out, 3u, &sent));
    TEST_ASSERT_EQUAL_UINT32(1u, sent);
    TEST_ASSERT_EQUAL_UINT32(1u, m.refused);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_can_send(NULL, &m, out, 3u, &sent));
}

#ifdef SBR_TEST_CORTEX_M_PORT
/* The board hook of this test image: a two-slot "mailbox" that the test drains. */
static sbr_can_frame_t g_mailbox[2];
static uint32_t g_mail_count;
int sbr_board_can_tx(uint32_t id, uint8_t dlc, const uint8_t data[8])
{
    if (g_mail_count >= 2u) {
        return 1;
    }
    g_mailbox[g_mail_count].id = id;
    g_mailbox[g_mail_count].dlc = dlc;
    memcpy(g_mailbox[g_mail_count].data, data, 8u);
    g_mail_count++;
    return 0;
}

static void test_cortex_m_port_hook(void)
{
    sbr_port_cortex_m_t p = {0u, 0u};
    sbr_can_frame_t f[3];
    uint32_t sent = 0u;
    memset(f, 0, sizeof f);
    f[0].id = 0x310u;
    f[0].dlc = 8u;
    f[0].data[3] = 0xAB;
    f[1] = f[0];
    f[2] = f[0];
    g_mail_count = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_can_send(&sbr_port_cortex_m, &p, f, 3u, &sent));
    TEST_ASSERT_EQUAL_UINT32(2u, sent);
    TEST_ASSERT_EQUAL_UINT32(2u, p.sent);
    TEST_ASSERT_EQUAL_UINT32(1u, p.dropped);
    TEST_ASSERT_EQUAL_HEX8(0xAB, g_mailbox[1].data[3]);
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_crc8_j1850_vectors);
    RUN_TEST(test_restrictions);
    RUN_TEST(test_detection_layout_by_hand);
    RUN_TEST(test_detection_round_trip_limits);
    RUN_TEST(test_sign_object_status_round_trips);
    RUN_TEST(test_e2e_counter_sequence);
    RUN_TEST(test_e2e_every_single_bit_flip_is_caught);
    RUN_TEST(test_scheduler_priority_and_budget);
    RUN_TEST(test_scheduler_counts_signs_beyond_the_limit);
    RUN_TEST(test_sched_config_check);
    RUN_TEST(test_unpack_refuses_out_of_range_signals);
    RUN_TEST(test_e2e_protect_statuses);
    RUN_TEST(test_mock_port_and_send);
    RUN_TEST(test_can_h_statuses);
#ifdef SBR_TEST_CORTEX_M_PORT
    RUN_TEST(test_cortex_m_port_hook);
#endif
    return UNITY_END();
}
