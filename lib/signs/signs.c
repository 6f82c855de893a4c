/* SPDX-License-Identifier: MIT */
/*
 * Sign tracking: the channel tracker over recognised signs, with class evidence summed
 * per track (include/sbr/signs.h).
 */
#include "sbr/signs.h"

#include <stddef.h>
#include <string.h>

#include "../common/sbr_util.h"

/* "SIGN": an initialised instance. */
#define SIGNS_MAGIC 0x5349474Eu

void sbr_signs_config_default(sbr_signs_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->width = 1360.0f;
        cfg->height = 800.0f;
        cfg->period_us = 100000u;
        cfg->class_count = 43u;
        cfg->max_tracks = 16u;
        cfg->confirm_hits = 2u;
        cfg->confirm_share = 0.6f;
        cfg->max_misses = 5u;
        cfg->meas_sigma = 4.0f;
        cfg->min_certainty = 0.05f;
    }
}

/* Whether lo <= v <= hi (false for NaN). */
static int within(float v, float lo, float hi)
{
    return ((v >= lo) && (v <= hi)) ? 1 : 0;
}

sbr_status_t sbr_signs_config_check(const sbr_signs_config_t *cfg)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (cfg != NULL) {
        st = SBR_OK;
        if ((cfg->class_count == 0u) || (cfg->class_count > SBR_SIGNS_MAX_CLASSES) || (cfg->max_tracks == 0u) ||
            (cfg->max_tracks > SBR_SIGNS_MAX_TRACKS)) {
            st = SBR_ERR_SIZE;
        } else if ((within(cfg->width, 8.0f, SBR_TRACK_MAX_EXTENT) == 0) ||
                   (within(cfg->height, 8.0f, SBR_TRACK_MAX_EXTENT) == 0) || (cfg->period_us < 1000u) ||
                   (cfg->period_us > 1000000u) || (cfg->confirm_hits == 0u) || (cfg->confirm_hits > 16u) ||
                   (within(cfg->confirm_share, 0.0f, 1.0f) == 0) || (cfg->max_misses > 255u) ||
                   (within(cfg->meas_sigma, 1.0f, 20.0f) == 0) || (cfg->min_certainty <= 0.0f) ||
                   (within(cfg->min_certainty, 0.0f, 1.0f) == 0)) {
            st = SBR_ERR_RANGE;
        } else {
            /* in range */
        }
    }
    return st;
}

/* The tracker's configuration for the signs' (its model still to be set). */
static void tracker_config(const sbr_signs_config_t *cfg, sbr_track_config_t *tc)
{
    sbr_track_config_default(tc);
    tc->max_targets = cfg->max_tracks;
    tc->window = SBR_SIGNS_WINDOW;
    tc->meas_sigma = cfg->meas_sigma;
    tc->confirm_hits = cfg->confirm_hits;
    tc->max_misses = cfg->max_misses;
}

/* The tracker's workspace bytes (4-byte multiple). */
static size_t tracker_bytes(uint32_t tracks)
{
    return SBR_TRACK_WORKSPACE_SIZE(tracks, SBR_SIGNS_WINDOW, SBR_SIGNS_VEL);
}

size_t sbr_signs_workspace_size(const sbr_signs_config_t *cfg)
{
    size_t n = 0u;
    if (sbr_signs_config_check(cfg) == SBR_OK) {
        n = SBR_SIGNS_WORKSPACE_SIZE(cfg->max_tracks, cfg->class_count);
    }
    return n;
}

/* Every slot free. */
static void clear_slots(sbr_signs_t *s)
{
    (void)memset(s->slot, 0, sizeof s->slot);
}

sbr_status_t sbr_signs_init(sbr_signs_t *signs, const sbr_signs_config_t *cfg, void *workspace,
                            size_t workspace_size)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (signs != NULL) {
        (void)memset(signs, 0, sizeof *signs);
        st = sbr_signs_config_check(cfg);
    }
    if (st == SBR_OK) {
        const size_t need = SBR_SIGNS_WORKSPACE_SIZE(cfg->max_tracks, cfg->class_count);
        if ((workspace == NULL) || (workspace_size < need) || (sbr_util_aligned(workspace, 4u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        }
    }
    if (st == SBR_OK) {
        /* layout: transition, birth, evidence (floats), tracker, detections, indices,
           targets; every part a multiple of 4 bytes */
        const size_t trans_len = SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, SBR_SIGNS_VEL);
        const size_t birth_len = SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, SBR_SIGNS_VEL);
        const size_t ev_len = (size_t)cfg->max_tracks * (size_t)cfg->class_count;
        float *trans = (float *)workspace;
        float *birth = &trans[trans_len];
        unsigned char *trk_ws;
        sbr_track_config_t tc;
        signs->cfg = *cfg;
        signs->evidence = &birth[birth_len];
        trk_ws = (unsigned char *)(void *)&signs->evidence[ev_len];
        signs->dets = (sbr_track_detection_t *)(void *)&trk_ws[tracker_bytes(cfg->max_tracks)];
        signs->src = (uint32_t *)(void *)&signs->dets[SBR_TRACK_MAX_DETECTIONS];
        signs->targets = (sbr_track_target_t *)(void *)&signs->src[SBR_TRACK_MAX_DETECTIONS];
        st = sbr_track_model_cv(&signs->model, cfg->width, cfg->height, (float)cfg->period_us * 1.0e-6f,
                                SBR_SIGNS_VEL, SBR_SIGNS_VEL_SPACING, SBR_SIGNS_ACCEL, SBR_SIGNS_BIRTH, trans,
                                trans_len, birth, birth_len);
        if (st == SBR_OK) {
            tracker_config(cfg, &tc);
            tc.model = &signs->model;
            st = sbr_track_init(&signs->trk, &tc, trk_ws, tracker_bytes(cfg->max_tracks));
        }
        if (st == SBR_OK) {
            signs->magic = SIGNS_MAGIC;
        }
    }
    return st;
}

/* Whether an instance looks initialised. */
static int signs_usable(const sbr_signs_t *s)
{
    return ((s->magic == SIGNS_MAGIC) && (s->evidence != NULL) && (s->dets != NULL) && (s->src != NULL) &&
            (s->targets != NULL) && (s->trk.cfg.model == &s->model))
               ? 1
               : 0;
}

/* Drop the tracks; the next ids follow the largest handed out. */
static sbr_status_t drop_tracks(sbr_signs_t *s)
{
    const sbr_status_t st = sbr_track_reset(&s->trk);
    if (st == SBR_OK) {
        clear_slots(s);
        s->id_base = s->id_top;
    }
    return st;
}

sbr_status_t sbr_signs_reset(sbr_signs_t *signs)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (signs != NULL) {
        st = SBR_ERR_STATE;
        if (signs_usable(signs) != 0) {
            st = drop_tracks(signs);
        }
    }
    return st;
}

/* Whether a detection is well formed for a table of `classes`. */
static int detection_ok(const sbr_detection_t *d, uint32_t classes)
{
    return ((within(d->score, 0.0f, 1.0f) != 0) && ((uint32_t)d->class_id < classes)) ? 1 : 0;
}

/* The frame's detections as the tracker takes them (centres inside the image, at most
   SBR_TRACK_MAX_DETECTIONS); 1 when some did not fit. */
static int tracker_input(sbr_signs_t *s, const sbr_detection_t *dets, uint32_t n, uint32_t *m)
{
    int full = 0;
    uint32_t i;
    *m = 0u;
    for (i = 0u; i < n; i++) {
        const sbr_detection_t *d = &dets[i];
        const float cx = (float)d->box.x + (0.5f * (float)d->box.width);
        const float cy = (float)d->box.y + (0.5f * (float)d->box.height);
        if ((cx >= 0.0f) && (cy >= 0.0f) && (cx < s->cfg.width) && (cy < s->cfg.height)) {
            if (*m < SBR_TRACK_MAX_DETECTIONS) {
                sbr_track_detection_t *t = &s->dets[*m];
                t->x = cx;
                t->y = cy;
                t->certainty = (d->score > s->cfg.min_certainty) ? d->score : s->cfg.min_certainty;
                s->src[*m] = i;
                *m += 1u;
            } else {
                full = 1;
            }
        }
    }
    return full;
}

/* The slot of tracker id `id`, taken from the free ones when it has none (its evidence
   cleared); SBR_SIGNS_MAX_TRACKS only when every slot is taken (the tracker holds no
   more targets than slots, so not in practice). */
static uint32_t slot_of(sbr_signs_t *s, uint32_t id)
{
    uint32_t k = SBR_SIGNS_MAX_TRACKS;
    uint32_t i;
    for (i = 0u; (i < s->cfg.max_tracks) && (k == SBR_SIGNS_MAX_TRACKS); i++) {
        if (s->slot[i].id == id) {
            k = i;
        }
    }
    for (i = 0u; (i < s->cfg.max_tracks) && (k == SBR_SIGNS_MAX_TRACKS); i++) {
        if (s->slot[i].id == 0u) {
            k = i;
            (void)memset(&s->slot[i], 0, sizeof s->slot[i]);
            (void)memset(&s->evidence[(size_t)i * s->cfg.class_count], 0,
                         (size_t)s->cfg.class_count * sizeof(float));
            s->slot[i].id = id;
        }
    }
    return k;
}

/* A slot's leading class (lowest id on a tie) and its share of the evidence. */
static uint32_t leading_class(const sbr_signs_t *s, uint32_t k, float *share)
{
    const float *ev = &s->evidence[(size_t)k * s->cfg.class_count];
    float total = 0.0f;
    uint32_t best = 0u;
    uint32_t c;
    for (c = 0u; c < s->cfg.class_count; c++) {
        total += ev[c];
        if (ev[c] > ev[best]) {
            best = c;
        }
    }
    *share = (total > 0.0f) ? (ev[best] / total) : 0.0f;
    return best;
}

/* One target of the step: evidence, confirmation, report (into `out` unless NULL).
   Returns 1 for a confirmed sign. */
static uint32_t account(sbr_signs_t *s, const sbr_track_target_t *t, const sbr_detection_t *dets,
                        uint32_t *det_sign, sbr_sign_t *out)
{
    uint32_t written = 0u;
    const uint32_t k = slot_of(s, t->id);
    if (k < SBR_SIGNS_MAX_TRACKS) {
        sbr_signs_slot_t *sl = &s->slot[k];
        const sbr_detection_t *d = NULL;
        uint32_t flags = 0u;
        uint32_t cls;
        float share = 0.0f;
        sl->seen = 1u;
        if (t->detection >= 0) {
            d = &dets[s->src[(uint32_t)t->detection]];
            s->evidence[((size_t)k * s->cfg.class_count) + d->class_id] += d->score;
            sl->hits += 1u;
            sl->best = (d->score > sl->best) ? d->score : sl->best;
            sl->box[0] = (float)d->box.width;
            sl->box[1] = (float)d->box.height;
            flags |= SBR_SIGN_SEEN;
        }
        cls = leading_class(s, k, &share);
        if (sl->confirmed != 0u) {
            sl->frames += (sl->frames < 0xFFFFFFFFu) ? 1u : 0u;
            if (cls != sl->class_id) {
                flags |= SBR_SIGN_RENAMED;
            }
        } else if (((t->flags & SBR_TRACK_CONFIRMED) != 0u) && (share > 0.0f) && (share >= s->cfg.confirm_share)) {
            sl->confirmed = 1u;
            sl->frames = 0u;
            flags |= SBR_SIGN_NEW;
        } else {
            /* not (yet) a confirmed sign */
        }
        if (sl->confirmed != 0u) {
            const uint32_t id = s->id_base + t->id;
            written = 1u;
            s->id_top = (id > s->id_top) ? id : s->id_top;
            sl->class_id = cls;
            if ((d != NULL) && (det_sign != NULL)) {
                det_sign[s->src[(uint32_t)t->detection]] = id;
            }
            if (out != NULL) {
                out->id = id;
                out->class_id = (uint16_t)cls;
                out->flags = (uint16_t)flags;
                out->x = t->x;
                out->y = t->y;
                out->width = sl->box[0];
                out->height = sl->box[1];
                out->score = sl->best;
                out->share = share;
                out->hits = sl->hits;
                out->frames = sl->frames;
            }
        }
    }
    return written;
}

/* The time since the previous frame for the tracker, or 0 after a gap that ends the
   tracks (then a nominal period). */
static uint32_t step_time(const sbr_signs_t *s, uint64_t now_us)
{
    uint32_t dt = s->cfg.period_us;
    if (s->started != 0u) {
        const uint64_t gap = now_us - s->now_us;
        dt = (gap > ((uint64_t)SBR_SIGNS_MAX_GAP * s->cfg.period_us)) ? 0u : (uint32_t)gap;
    }
    return dt;
}

/* Checks of an update's arguments. */
static sbr_status_t update_check(const sbr_signs_t *s, uint64_t now_us, const sbr_detection_t *dets, uint32_t n)
{
    sbr_status_t st = SBR_ERR_STATE;
    if (signs_usable(s) != 0) {
        uint32_t i;
        st = SBR_OK;
        if ((s->started != 0u) && (now_us <= s->now_us)) {
            st = SBR_ERR_RANGE;
        }
        for (i = 0u; (i < n) && (st == SBR_OK); i++) {
            if (detection_ok(&dets[i], s->cfg.class_count) == 0) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

sbr_status_t sbr_signs_update(sbr_signs_t *signs, uint64_t now_us, const sbr_detection_t *dets,
                              uint32_t n, uint32_t *det_sign, sbr_sign_t *out, uint32_t capacity,
                              uint32_t *count)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((signs != NULL) && (count != NULL) && ((dets != NULL) || (n == 0u)) && ((out != NULL) || (capacity == 0u))) {
        st = update_check(signs, now_us, dets, n);
    }
    if (st == SBR_OK) {
        uint32_t dt = step_time(signs, now_us);
        uint32_t m = 0u;
        uint32_t nt = 0u;
        uint32_t i;
        int full = 0;
        *count = 0u;
        if (dt == 0u) {
            st = drop_tracks(signs);
            dt = signs->cfg.period_us;
        }
        if (det_sign != NULL) {
            for (i = 0u; i < n; i++) {
                det_sign[i] = 0u;
            }
        }
        full = tracker_input(signs, dets, n, &m);
        if (st == SBR_OK) {
            st = sbr_track_step(&signs->trk, dt, signs->dets, m, signs->targets, signs->cfg.max_tracks, &nt);
        }
        if ((st == SBR_OK) || (st == SBR_ERR_CAPACITY)) {
            full = (st == SBR_ERR_CAPACITY) ? 1 : full;
            st = SBR_OK;
            for (i = 0u; i < signs->cfg.max_tracks; i++) {
                signs->slot[i].seen = 0u;
            }
            for (i = 0u; i < nt; i++) {
                sbr_sign_t *o = (*count < capacity) ? &out[*count] : NULL;
                if (account(signs, &signs->targets[i], dets, det_sign, o) != 0u) {
                    if (o != NULL) {
                        *count += 1u;
                    } else {
                        full = 1;
                    }
                }
            }
            for (i = 0u; i < signs->cfg.max_tracks; i++) {
                if (signs->slot[i].seen == 0u) {
                    signs->slot[i].id = 0u;
                }
            }
            signs->now_us = now_us;
            signs->started = 1u;
        }
        if ((st == SBR_OK) && (full != 0)) {
            st = SBR_ERR_CAPACITY;
        }
    }
    return st;
}
