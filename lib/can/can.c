/* SPDX-License-Identifier: MIT */
/*
 * CAN messages of dbc/sbr.dbc: Intel-order signals by explicit shifts and masks, and E2E
 * (CRC-8/SAE-J1850 + alive counter, Profile 1 style). The per-cycle scheduler and the
 * send through a port are in can_sched.c.
 */
#include "sbr/can.h"

#include <math.h>
#include <string.h>

#define CAN_DLC 8u
#define MSG_SIGN 0u
#define MSG_STATUS 1u
#define MSG_DET 2u
#define MSG_OBJ 3u
#define MSG_RESTR 4u
#define MSG_FOREIGN 5u

/* ---- bits --------------------------------------------------------------------------- */

static uint64_t frame_bits(const uint8_t data[8])
{
    uint64_t v = 0u;
    uint32_t i;
    for (i = 0u; i < 8u; i++) {
        const uint32_t sh = 8u * i;
        v |= ((uint64_t)data[i]) << sh;
    }
    return v;
}

static void bits_to_frame(uint64_t v, uint8_t data[8])
{
    uint32_t i;
    for (i = 0u; i < 8u; i++) {
        const uint32_t sh = 8u * i;
        data[i] = (uint8_t)((v >> sh) & 0xFFu);
    }
}

/* Intel signal: `len` bits starting at bit `start` (LSB first). */
static uint64_t put_bits(uint64_t v, uint32_t start, uint32_t len, uint32_t raw)
{
    const uint64_t mask = (((uint64_t)1u) << len) - 1u;
    return (v & ~(mask << start)) | ((((uint64_t)raw) & mask) << start);
}

static uint32_t get_bits(uint64_t v, uint32_t start, uint32_t len)
{
    const uint64_t mask = (((uint64_t)1u) << len) - 1u;
    return (uint32_t)((v >> start) & mask);
}

/* Sign-extend a two's complement field of `len` bits. */
static int32_t to_signed(uint32_t raw, uint32_t len)
{
    const uint32_t sign = 1u << (len - 1u);
    int32_t v = (int32_t)raw;
    if ((raw & sign) != 0u) {
        const uint32_t span = sign << 1u;
        v = (int32_t)raw - (int32_t)span;
    }
    return v;
}

/* Physical value to raw integer: phys / factor rounded to nearest; fails outside [lo, hi]
   or NaN. */
static int encode(float phys, float factor, float lo, float hi, int32_t *raw)
{
    int ok = 0;
    if ((phys >= lo) && (phys <= hi)) {
        *raw = (int32_t)floorf((phys / factor) + 0.5f);
        ok = 1;
    }
    return ok;
}

static void frame_init(sbr_can_frame_t *f, uint32_t id, uint64_t bits)
{
    f->id = id;
    f->dlc = (uint8_t)CAN_DLC;
    bits_to_frame(bits, f->data);
}

static sbr_status_t frame_check(const sbr_can_frame_t *f, uint32_t id)
{
    if (f->id != id) {
        return SBR_ERR_RANGE;
    }
    if (f->dlc != CAN_DLC) {
        return SBR_ERR_SIZE;
    }
    return SBR_OK;
}

/* ---- SBR_Detection 0x310 ------------------------------------------------------------ */

sbr_status_t sbr_can_pack_detection(const sbr_can_detection_t *in, sbr_can_frame_t *frame)
{
    int32_t conf = 0;
    int32_t cx = 0;
    int32_t cy = 0;
    int32_t w = 0;
    int32_t h = 0;
    uint64_t v = 0u;
    int ok;

    if ((in == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    ok = encode(in->confidence, 2.0f, 0.0f, 100.0f, &conf);
    ok &= encode(in->center_x, 2.0f, 0.0f, 2046.0f, &cx);
    ok &= encode(in->center_y, 2.0f, 0.0f, 2046.0f, &cy);
    ok &= encode(in->width, 4.0f, 0.0f, 508.0f, &w);
    ok &= encode(in->height, 4.0f, 0.0f, 508.0f, &h);
    if ((ok == 0) || ((in->class_id > 42u) && (in->class_id != SBR_CAN_CLASS_NONE_DET)) ||
        (in->track_id > SBR_CAN_TRACK_NONE_DET)) {
        return SBR_ERR_RANGE;
    }
    v = put_bits(v, 12u, 6u, in->class_id);
    v = put_bits(v, 18u, 6u, (uint32_t)conf);
    v = put_bits(v, 24u, 10u, (uint32_t)cx);
    v = put_bits(v, 34u, 10u, (uint32_t)cy);
    v = put_bits(v, 44u, 7u, (uint32_t)w);
    v = put_bits(v, 51u, 7u, (uint32_t)h);
    v = put_bits(v, 58u, 6u, in->track_id);
    frame_init(frame, SBR_CAN_ID_DETECTION, v);
    return SBR_OK;
}

sbr_status_t sbr_can_unpack_detection(const sbr_can_frame_t *frame, sbr_can_detection_t *out)
{
    sbr_status_t st;
    uint64_t v;
    sbr_can_detection_t r;
    sbr_can_frame_t scratch;

    if ((frame == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = frame_check(frame, SBR_CAN_ID_DETECTION);
    if (st != SBR_OK) {
        return st;
    }
    v = frame_bits(frame->data);
    r.class_id = get_bits(v, 12u, 6u);
    r.confidence = 2.0f * (float)get_bits(v, 18u, 6u);
    r.center_x = 2.0f * (float)get_bits(v, 24u, 10u);
    r.center_y = 2.0f * (float)get_bits(v, 34u, 10u);
    r.width = 4.0f * (float)get_bits(v, 44u, 7u);
    r.height = 4.0f * (float)get_bits(v, 51u, 7u);
    r.track_id = get_bits(v, 58u, 6u);
    /* a value outside its signal's range (a corrupted or foreign frame) is refused:
       exactly what the packer would refuse */
    if (sbr_can_pack_detection(&r, &scratch) != SBR_OK) {
        return SBR_ERR_RANGE;
    }
    *out = r;
    return SBR_OK;
}

/* ---- SBR_ConfirmedSign 0x300 -------------------------------------------------------- */

sbr_status_t sbr_can_pack_confirmed_sign(const sbr_can_confirmed_sign_t *in,
                                         sbr_can_frame_t *frame)
{
    int32_t conf = 0;
    uint64_t v = 0u;

    if ((in == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((encode(in->confidence, 1.0f, 0.0f, 100.0f, &conf) == 0) || (in->slot > 3u) ||
        (in->count > 4u) || ((in->class_id > 42u) && (in->class_id != SBR_CAN_CLASS_NONE)) ||
        (in->track_id > 255u) ||
        ((in->speed_kmh > 250u) && (in->speed_kmh != SBR_CAN_SPEED_NONE)) ||
        (in->age_frames > 255u)) {
        return SBR_ERR_RANGE;
    }
    v = put_bits(v, 12u, 4u, in->slot);
    v = put_bits(v, 16u, 8u, in->class_id);
    v = put_bits(v, 24u, 8u, in->track_id);
    v = put_bits(v, 32u, 8u, in->speed_kmh);
    v = put_bits(v, 40u, 7u, (uint32_t)conf);
    v = put_bits(v, 48u, 8u, in->age_frames);
    v = put_bits(v, 56u, 4u, in->count);
    frame_init(frame, SBR_CAN_ID_CONFIRMED_SIGN, v);
    return SBR_OK;
}

sbr_status_t sbr_can_unpack_confirmed_sign(const sbr_can_frame_t *frame,
                                           sbr_can_confirmed_sign_t *out)
{
    sbr_status_t st;
    uint64_t v;
    sbr_can_confirmed_sign_t r;
    sbr_can_frame_t scratch;

    if ((frame == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = frame_check(frame, SBR_CAN_ID_CONFIRMED_SIGN);
    if (st != SBR_OK) {
        return st;
    }
    v = frame_bits(frame->data);
    r.slot = get_bits(v, 12u, 4u);
    r.class_id = get_bits(v, 16u, 8u);
    r.track_id = get_bits(v, 24u, 8u);
    r.speed_kmh = get_bits(v, 32u, 8u);
    r.confidence = (float)get_bits(v, 40u, 7u);
    r.age_frames = get_bits(v, 48u, 8u);
    r.count = get_bits(v, 56u, 4u);
    /* a value outside its signal's range (a corrupted or foreign frame) is refused:
       exactly what the packer would refuse */
    if (sbr_can_pack_confirmed_sign(&r, &scratch) != SBR_OK) {
        return SBR_ERR_RANGE;
    }
    *out = r;
    return SBR_OK;
}

/* ---- SBR_TrackedObject 0x320 -------------------------------------------------------- */

sbr_status_t sbr_can_pack_object(const sbr_can_object_t *in, sbr_can_frame_t *frame)
{
    int32_t x = 0;
    int32_t y = 0;
    int32_t vx = 0;
    int32_t vy = 0;
    int32_t c = 0;
    uint64_t v = 0u;
    int ok;

    if ((in == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    ok = encode(in->x, 1.0f, 0.0f, 2047.0f, &x);
    ok &= encode(in->y, 1.0f, 0.0f, 1023.0f, &y);
    ok &= encode(in->vx, 4.0f, -256.0f, 252.0f, &vx);
    ok &= encode(in->vy, 4.0f, -256.0f, 252.0f, &vy);
    ok &= encode(in->certainty, 4.0f, 0.0f, 100.0f, &c);
    if ((ok == 0) || (in->index > 15u) || (in->track_id > 255u)) {
        return SBR_ERR_RANGE;
    }
    v = put_bits(v, 12u, 4u, in->index);
    v = put_bits(v, 16u, 8u, in->track_id);
    v = put_bits(v, 24u, 11u, (uint32_t)x);
    v = put_bits(v, 35u, 10u, (uint32_t)y);
    v = put_bits(v, 45u, 7u, (uint32_t)vx);
    v = put_bits(v, 52u, 7u, (uint32_t)vy);
    v = put_bits(v, 59u, 5u, (uint32_t)c);
    frame_init(frame, SBR_CAN_ID_TRACKED_OBJECT, v);
    return SBR_OK;
}

sbr_status_t sbr_can_unpack_object(const sbr_can_frame_t *frame, sbr_can_object_t *out)
{
    sbr_status_t st;
    uint64_t v;
    sbr_can_object_t r;
    sbr_can_frame_t scratch;

    if ((frame == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = frame_check(frame, SBR_CAN_ID_TRACKED_OBJECT);
    if (st != SBR_OK) {
        return st;
    }
    v = frame_bits(frame->data);
    r.index = get_bits(v, 12u, 4u);
    r.track_id = get_bits(v, 16u, 8u);
    r.x = (float)get_bits(v, 24u, 11u);
    r.y = (float)get_bits(v, 35u, 10u);
    r.vx = 4.0f * (float)to_signed(get_bits(v, 45u, 7u), 7u);
    r.vy = 4.0f * (float)to_signed(get_bits(v, 52u, 7u), 7u);
    r.certainty = 4.0f * (float)get_bits(v, 59u, 5u);
    /* a value outside its signal's range (a corrupted or foreign frame) is refused:
       exactly what the packer would refuse */
    if (sbr_can_pack_object(&r, &scratch) != SBR_OK) {
        return SBR_ERR_RANGE;
    }
    *out = r;
    return SBR_OK;
}

/* ---- SBR_EcuStatus 0x301 ------------------------------------------------------------ */

sbr_status_t sbr_can_pack_ecu_status(const sbr_can_ecu_status_t *in, sbr_can_frame_t *frame)
{
    int32_t t = 0;
    uint32_t regions;
    uint32_t dets;
    uint64_t v = 0u;

    if ((in == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((encode(in->processing_ms, 0.1f, 0.0f, 6553.4f, &t) == 0) || (in->overload > 1u) ||
        (in->error > 1u) || (in->capacity_hit > 1u)) {
        return SBR_ERR_RANGE;
    }
    /* counts saturate by definition (documented in the DBC) */
    regions = in->region_count;
    if (regions > 4095u) {
        regions = 4095u;
    }
    dets = in->detection_count;
    if (dets > 15u) {
        dets = 15u;
    }
    v = put_bits(v, 12u, 1u, in->overload);
    v = put_bits(v, 13u, 1u, in->error);
    v = put_bits(v, 14u, 1u, in->capacity_hit);
    v = put_bits(v, 16u, 16u, in->frame_counter & 0xFFFFu);
    v = put_bits(v, 32u, 16u, (uint32_t)t);
    v = put_bits(v, 48u, 12u, regions);
    v = put_bits(v, 60u, 4u, dets);
    frame_init(frame, SBR_CAN_ID_ECU_STATUS, v);
    return SBR_OK;
}

sbr_status_t sbr_can_unpack_ecu_status(const sbr_can_frame_t *frame, sbr_can_ecu_status_t *out)
{
    sbr_status_t st;
    uint64_t v;
    sbr_can_ecu_status_t r;
    sbr_can_frame_t scratch;

    if ((frame == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = frame_check(frame, SBR_CAN_ID_ECU_STATUS);
    if (st != SBR_OK) {
        return st;
    }
    v = frame_bits(frame->data);
    r.overload = get_bits(v, 12u, 1u);
    r.error = get_bits(v, 13u, 1u);
    r.capacity_hit = get_bits(v, 14u, 1u);
    r.frame_counter = get_bits(v, 16u, 16u);
    r.processing_ms = 0.1f * (float)get_bits(v, 32u, 16u);
    r.region_count = get_bits(v, 48u, 12u);
    r.detection_count = get_bits(v, 60u, 4u);
    /* a value outside its signal's range (a corrupted or foreign frame) is refused:
       exactly what the packer would refuse */
    if (sbr_can_pack_ecu_status(&r, &scratch) != SBR_OK) {
        return SBR_ERR_RANGE;
    }
    *out = r;
    return SBR_OK;
}

/* ---- SBR_Restrictions 0x302 --------------------------------------------------------- */

sbr_status_t sbr_can_pack_restrictions(const sbr_can_restrictions_t *in, sbr_can_frame_t *frame)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((in != NULL) && (frame != NULL)) {
        st = SBR_ERR_RANGE;
        if ((in->speed_limit_kmh <= 255u) && (in->no_overtaking <= 1u) && (in->no_overtaking_trucks <= 1u) &&
            (in->priority_road <= 1u) && (in->speed_age_s <= 65535u)) {
            uint64_t v = 0u;
            v = put_bits(v, 16u, 8u, in->speed_limit_kmh);
            v = put_bits(v, 24u, 1u, in->no_overtaking);
            v = put_bits(v, 25u, 1u, in->no_overtaking_trucks);
            v = put_bits(v, 26u, 1u, in->priority_road);
            v = put_bits(v, 32u, 16u, in->speed_age_s);
            frame_init(frame, SBR_CAN_ID_RESTRICTIONS, v);
            st = SBR_OK;
        }
    }
    return st;
}

sbr_status_t sbr_can_unpack_restrictions(const sbr_can_frame_t *frame, sbr_can_restrictions_t *out)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((frame != NULL) && (out != NULL)) {
        st = frame_check(frame, SBR_CAN_ID_RESTRICTIONS);
    }
    if (st == SBR_OK) {
        const uint64_t v = frame_bits(frame->data);
        /* every raw value of these signals is in range */
        out->speed_limit_kmh = get_bits(v, 16u, 8u);
        out->no_overtaking = get_bits(v, 24u, 1u);
        out->no_overtaking_trucks = get_bits(v, 25u, 1u);
        out->priority_road = get_bits(v, 26u, 1u);
        out->speed_age_s = get_bits(v, 32u, 16u);
    }
    return st;
}

/* ---- E2E ---------------------------------------------------------------------------- */

uint8_t sbr_crc8_j1850(const uint8_t *data, uint32_t len)
{
    uint32_t crc = 0xFFu;
    uint32_t i;
    uint32_t b;

    if (data == NULL) {
        return 0u;
    }
    for (i = 0u; i < len; i++) {
        crc ^= (uint32_t)data[i];
        for (b = 0u; b < 8u; b++) {
            if ((crc & 0x80u) != 0u) {
                crc = ((crc << 1u) ^ 0x1Du) & 0xFFu;
            } else {
                crc = (crc << 1u) & 0xFFu;
            }
        }
    }
    return (uint8_t)(crc ^ 0xFFu);
}

/* Message slot of an identifier, or MSG_FOREIGN for a foreign one. */
static uint32_t msg_slot(uint32_t id)
{
    uint32_t s;
    switch (id) {
    case SBR_CAN_ID_CONFIRMED_SIGN:
        s = MSG_SIGN;
        break;
    case SBR_CAN_ID_ECU_STATUS:
        s = MSG_STATUS;
        break;
    case SBR_CAN_ID_DETECTION:
        s = MSG_DET;
        break;
    case SBR_CAN_ID_TRACKED_OBJECT:
        s = MSG_OBJ;
        break;
    case SBR_CAN_ID_RESTRICTIONS:
        s = MSG_RESTR;
        break;
    default:
        s = MSG_FOREIGN;
        break;
    }
    return s;
}

/* CRC over Data ID (low, high) and payload bytes 1..7. */
static uint8_t frame_crc(const sbr_can_frame_t *f)
{
    uint8_t buf[9];
    const uint32_t data_id = SBR_CAN_DATA_ID(f->id);
    buf[0] = (uint8_t)(data_id & 0xFFu);
    buf[1] = (uint8_t)((data_id >> 8u) & 0xFFu);
    (void)memcpy(&buf[2], &f->data[1], 7u);
    return sbr_crc8_j1850(buf, 9u);
}

sbr_status_t sbr_can_e2e_tx_init(sbr_can_e2e_tx_t *tx)
{
    if (tx == NULL) {
        return SBR_ERR_NULL;
    }
    (void)memset(tx->counter, 0, sizeof tx->counter);
    return SBR_OK;
}

sbr_status_t sbr_can_e2e_protect(sbr_can_e2e_tx_t *tx, sbr_can_frame_t *frame)
{
    uint32_t s;
    uint32_t c;

    if ((tx == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    s = msg_slot(frame->id);
    if (s >= MSG_FOREIGN) {
        return SBR_ERR_RANGE;
    }
    if (frame->dlc != CAN_DLC) {
        return SBR_ERR_SIZE;
    }
    c = (uint32_t)tx->counter[s];
    if (c > SBR_CAN_COUNTER_MAX) {
        return SBR_ERR_STATE;
    }
    frame->data[1] = (uint8_t)((frame->data[1] & 0xF0u) | c);
    frame->data[0] = frame_crc(frame);
    if (c == SBR_CAN_COUNTER_MAX) {
        c = 0u;
    } else {
        c++;
    }
    tx->counter[s] = (uint8_t)c;
    return SBR_OK;
}

sbr_status_t sbr_can_e2e_rx_init(sbr_can_e2e_rx_t *rx, uint32_t id)
{
    if (rx == NULL) {
        return SBR_ERR_NULL;
    }
    if (msg_slot(id) >= MSG_FOREIGN) {
        return SBR_ERR_RANGE;
    }
    rx->id = id;
    rx->last_counter = 0u;
    rx->synced = 0u;
    return SBR_OK;
}

sbr_status_t sbr_can_e2e_check(sbr_can_e2e_rx_t *rx, const sbr_can_frame_t *frame,
                               sbr_can_e2e_result_t *result)
{
    sbr_can_e2e_result_t r;
    uint32_t c;

    if ((rx == NULL) || (frame == NULL) || (result == NULL)) {
        return SBR_ERR_NULL;
    }
    c = (uint32_t)frame->data[1] & 0x0Fu;
    if (frame->id != rx->id) {
        r = SBR_E2E_WRONG_ID;
    } else if (frame->dlc != CAN_DLC) {
        r = SBR_E2E_WRONG_LENGTH;
    } else if (frame_crc(frame) != frame->data[0]) {
        r = SBR_E2E_WRONG_CRC;
    } else if (c > SBR_CAN_COUNTER_MAX) {
        r = SBR_E2E_BAD_COUNTER;
    } else if (rx->synced == 0u) {
        r = SBR_E2E_FIRST;
        rx->synced = 1u;
        rx->last_counter = (uint8_t)c;
    } else {
        const uint32_t last = (uint32_t)rx->last_counter;
        const uint32_t delta = ((c + SBR_CAN_COUNTER_MAX + 1u) - last) % (SBR_CAN_COUNTER_MAX + 1u);
        if (delta == 0u) {
            r = SBR_E2E_REPEATED;
        } else {
            if (delta == 1u) {
                r = SBR_E2E_OK;
            } else {
                r = SBR_E2E_SKIPPED;
            }
            rx->last_counter = (uint8_t)c;
        }
    }
    *result = r;
    if ((r == SBR_E2E_OK) || (r == SBR_E2E_FIRST)) {
        return SBR_OK;
    }
    return SBR_ERR_CORRUPT;
}
