/* SPDX-License-Identifier: MIT */
/* The per-cycle CAN scheduler (sbr_can_schedule(): what of an image's results fits the
   frame budget, in the order of dbc/sbr.dbc's messages, E2E-protected) and the send
   through a port (sbr_can_send()). Messages and E2E: can.c. */
#include "sbr/can.h"

#include <math.h>
#include <string.h>

/* ---- scheduler ---------------------------------------------------------------------- */

void sbr_can_sched_config_default(sbr_can_sched_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->frame_budget = 16u;
        cfg->max_signs = 4u;
        cfg->max_detections = 8u;
        cfg->max_objects = 8u;
    }
}

/* Sort key of entry i: detection confidence or object certainty; NaN sorts last (its
   frame is then rejected by the pack function). */
static float sched_key(const sbr_can_cycle_t *c, int objects, uint32_t i)
{
    float k;
    if (objects != 0) {
        k = c->objects[i].certainty;
    } else {
        k = c->detections[i].confidence;
    }
    if (isnan(k) != 0) {
        k = -1.0f;
    }
    return k;
}

/* Index of the best entry after (prev_key, prev_idx) in the order (key descending, index
   ascending); n when there is none. Selection without a workspace: O(n) per call. */
static uint32_t next_best(const sbr_can_cycle_t *c, int objects, uint32_t n, int first,
                          float prev_key, uint32_t prev_idx)
{
    uint32_t i;
    uint32_t best = n;
    float best_key = 0.0f;
    for (i = 0u; i < n; i++) {
        const float k = sched_key(c, objects, i);
        int after = 1;
        if (first == 0) {
            after = 0;
            if ((k < prev_key) || ((k == prev_key) && (i > prev_idx))) {
                after = 1;
            }
        }
        if ((after != 0) && ((best == n) || (k > best_key))) {
            best = i;
            best_key = k;
        }
    }
    return best;
}

typedef struct sched_out_s {
    sbr_can_e2e_tx_t *tx;
    sbr_can_frame_t *frames;
    uint32_t count;
    uint32_t budget;
    uint32_t dropped;
    int invalid;
} sched_out_t;

/* Protect and keep a packed frame if the budget allows. */
static void sched_emit(sched_out_t *o, sbr_status_t pack_status, sbr_can_frame_t *f)
{
    if (pack_status != SBR_OK) {
        o->invalid = 1;
        o->dropped++;
    } else if (o->count >= o->budget) {
        o->dropped++;
    } else {
        if (sbr_can_e2e_protect(o->tx, f) == SBR_OK) {
            o->frames[o->count] = *f;
            o->count++;
        } else {
            o->invalid = 1;
            o->dropped++;
        }
    }
}

sbr_status_t sbr_can_sched_config_check(const sbr_can_sched_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if ((cfg->frame_budget < 4u) || (cfg->max_signs == 0u) || (cfg->max_signs > 4u) ||
               (cfg->max_detections == 0u) || (cfg->max_objects == 0u) ||
               (cfg->max_objects > 16u)) {
        st = SBR_ERR_RANGE;
    } else {
        /* valid */
    }
    return st;
}

/* How many of each message this cycle sends: the counts clamped to the configuration's
   maxima, and the frames they need (at least one of each message, even when empty). */
typedef struct sched_plan_s {
    uint32_t n_sign;
    uint32_t n_det;
    uint32_t n_obj;
    uint32_t need;
} sched_plan_t;

static uint32_t sched_min(uint32_t a, uint32_t b)
{
    return (a < b) ? a : b;
}

static void sched_plan(const sbr_can_sched_config_t *cfg, const sbr_can_cycle_t *cycle,
                       sched_plan_t *p)
{
    p->n_sign = sched_min(cycle->sign_count, cfg->max_signs);
    p->n_det = sched_min(cycle->detection_count, cfg->max_detections);
    p->n_obj = sched_min(cycle->object_count, cfg->max_objects);
    p->need = 4u;
    if (cycle->restrictions != NULL) {
        p->need = 5u;
    }
    if (p->n_sign > 1u) {
        p->need += p->n_sign - 1u;
    }
    if (p->n_det > 1u) {
        p->need += p->n_det - 1u;
    }
    if (p->n_obj > 1u) {
        p->need += p->n_obj - 1u;
    }
}

/* 1. Confirmed signs, newest first (or one empty frame). */
static void sched_signs(sched_out_t *o, const sbr_can_cycle_t *cycle, uint32_t n_sign)
{
    sbr_can_frame_t f;
    if (cycle->sign_count == 0u) {
        sbr_can_confirmed_sign_t none;
        none.slot = 0u;
        none.count = 0u;
        none.class_id = SBR_CAN_CLASS_NONE;
        none.track_id = SBR_CAN_TRACK_NONE;
        none.speed_kmh = SBR_CAN_SPEED_NONE;
        none.confidence = 0.0f;
        none.age_frames = 0u;
        sched_emit(o, sbr_can_pack_confirmed_sign(&none, &f), &f);
    } else {
        uint32_t i;
        for (i = 0u; i < n_sign; i++) {
            sbr_can_confirmed_sign_t sg = cycle->signs[i];
            sg.slot = i;
            sg.count = n_sign;
            sched_emit(o, sbr_can_pack_confirmed_sign(&sg, &f), &f);
        }
        o->dropped += cycle->sign_count - n_sign; /* beyond max_signs */
    }
}

/* 3-4. Detections by decreasing confidence (objects = 0) or tracked objects by decreasing
   certainty (objects = 1), the first n_keep sent, the rest dropped (or one empty frame). */
static void sched_ranked(sched_out_t *o, const sbr_can_cycle_t *cycle, int objects,
                         uint32_t n_keep)
{
    const uint32_t total = (objects != 0) ? cycle->object_count : cycle->detection_count;
    sbr_can_frame_t f;
    float pk = 0.0f;
    uint32_t pi = 0u;
    uint32_t i;
    int first = 1;
    if ((total == 0u) && (objects == 0)) {
        sbr_can_detection_t none;
        (void)memset(&none, 0, sizeof none);
        none.class_id = SBR_CAN_CLASS_NONE_DET;
        none.track_id = SBR_CAN_TRACK_NONE_DET;
        sched_emit(o, sbr_can_pack_detection(&none, &f), &f);
    } else if (total == 0u) {
        sbr_can_object_t none;
        (void)memset(&none, 0, sizeof none);
        none.track_id = SBR_CAN_TRACK_NONE;
        sched_emit(o, sbr_can_pack_object(&none, &f), &f);
    } else {
        /* every entry is ranked once: next_best() finds one after each previous pick */
        for (i = 0u; i < total; i++) {
            const uint32_t k = next_best(cycle, objects, total, first, pk, pi);
            first = 0;
            if (k >= total) {
                break;
            }
            pk = sched_key(cycle, objects, k);
            pi = k;
            if (i >= n_keep) {
                o->dropped++;
            } else if (objects == 0) {
                sched_emit(o, sbr_can_pack_detection(&cycle->detections[k], &f), &f);
            } else {
                sbr_can_object_t ob = cycle->objects[k];
                ob.index = i;
                sched_emit(o, sbr_can_pack_object(&ob, &f), &f);
            }
        }
    }
}

sbr_status_t sbr_can_schedule(sbr_can_e2e_tx_t *tx, const sbr_can_sched_config_t *cfg,
                              const sbr_can_cycle_t *cycle, sbr_can_frame_t *frames,
                              uint32_t capacity, uint32_t *count, uint32_t *dropped)
{
    sched_out_t o;
    sched_plan_t p;
    sbr_can_frame_t f;
    sbr_can_ecu_status_t est;

    if ((tx == NULL) || (cfg == NULL) || (cycle == NULL) || (frames == NULL) ||
        (count == NULL) || (dropped == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    *dropped = 0u;
    if (sbr_can_sched_config_check(cfg) != SBR_OK) {
        return SBR_ERR_RANGE;
    }
    if (capacity < cfg->frame_budget) {
        return SBR_ERR_CAPACITY;
    }
    if (((cycle->sign_count > 0u) && (cycle->signs == NULL)) ||
        ((cycle->detection_count > 0u) && (cycle->detections == NULL)) ||
        ((cycle->object_count > 0u) && (cycle->objects == NULL))) {
        return SBR_ERR_NULL;
    }
    o.tx = tx;
    o.frames = frames;
    o.count = 0u;
    o.budget = cfg->frame_budget;
    o.dropped = 0u;
    o.invalid = 0;
    sched_plan(cfg, cycle, &p);

    sched_signs(&o, cycle, p.n_sign);
    /* 2. status: overload when anything of this cycle will not fit */
    est = cycle->status;
    est.overload = 0u;
    if ((p.need > cfg->frame_budget) || (p.n_sign < cycle->sign_count) ||
        (p.n_det < cycle->detection_count) || (p.n_obj < cycle->object_count)) {
        est.overload = 1u;
    }
    sched_emit(&o, sbr_can_pack_ecu_status(&est, &f), &f);
    if (cycle->restrictions != NULL) {
        sched_emit(&o, sbr_can_pack_restrictions(cycle->restrictions, &f), &f);
    }
    sched_ranked(&o, cycle, 0, p.n_det);
    sched_ranked(&o, cycle, 1, p.n_obj);
    *count = o.count;
    *dropped = o.dropped;
    if (o.invalid != 0) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

sbr_status_t sbr_can_send(const sbr_can_port_t *port, void *ctx, const sbr_can_frame_t *frames,
                          uint32_t count, uint32_t *sent)
{
    uint32_t i;

    if ((port == NULL) || (port->send == NULL) || (sent == NULL) ||
        ((frames == NULL) && (count > 0u))) {
        return SBR_ERR_NULL;
    }
    *sent = 0u;
    for (i = 0u; i < count; i++) {
        const sbr_status_t st = port->send(ctx, &frames[i]);
        if (st != SBR_OK) {
            return st;
        }
        (*sent)++;
    }
    return SBR_OK;
}
