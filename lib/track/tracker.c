/* SPDX-License-Identifier: MIT */
/* Channel-based multi-target tracker (paper E), the step: candidates, assignment, update,
   birth and the targets reported. The model is in track_model.c, each target's density in
   track_density.c. See include/sbr/track.h for the method. */
#include "sbr/track.h"

#include <math.h>
#include <string.h>

#include "sbr/channel.h"
#include "../common/sbr_util.h"
#include "track_internal.h"

/* ---- the step --------------------------------------------------------------------- */

static sbr_status_t trk_check_instance(const sbr_track_t *trk)
{
    sbr_status_t st = SBR_OK;
    if ((trk->magic != TRK_MAGIC) || (trk->dens == NULL) || (trk->scratch == NULL) ||
        (trk->cand_cost == NULL) || (trk->cand_det == NULL) || (trk->cfg.model == NULL) ||
        (trk->next_id == 0u)) {
        st = SBR_ERR_STATE;
    } else if ((sbr_track_priv_config_scalars(&trk->cfg) != SBR_OK) ||
               (sbr_track_priv_model_header(trk->cfg.model) != SBR_OK)) {
        st = SBR_ERR_STATE;
    } else {
        st = SBR_OK;
    }
    return st;
}

static sbr_status_t trk_check_inputs(const sbr_track_t *trk, uint32_t dt_us,
                                     const sbr_track_detection_t *dets, uint32_t n)
{
    sbr_status_t st = SBR_OK;
    const sbr_track_model_t *m = trk->cfg.model;
    uint32_t i;
    if (n > SBR_TRACK_MAX_DETECTIONS) {
        st = SBR_ERR_SIZE;
    } else if ((n > 0u) && (dets == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((dt_us == 0u) || (sbr_util_seconds(dt_us) > (8.0f * m->period))) {
        st = SBR_ERR_RANGE;
    } else {
        for (i = 0u; (i < n) && (st == SBR_OK); i++) {
            const sbr_track_detection_t *q = &dets[i];
            if ((isfinite(q->x) == 0) || (isfinite(q->y) == 0) ||
                (isfinite(q->certainty) == 0) || (q->x < 0.0f) || (q->y < 0.0f) ||
                (q->x >= m->extent[0]) || (q->y >= m->extent[1]) || (q->certainty <= 0.0f) ||
                (q->certainty > 1.0f)) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

/* Candidates of target t: the cheapest SBR_TRACK_CANDIDATES detections within the gate. */
static void trk_candidates(sbr_track_t *trk, const trk_geo_t *g, uint32_t t,
                           const sbr_track_detection_t *dets, uint32_t n)
{
    float m[2][SBR_TRACK_MAX_WINDOW];
    float mean[2];
    float var[2];
    float *cost = &trk->cand_cost[(size_t)t * SBR_TRACK_CANDIDATES];
    uint32_t *det = &trk->cand_det[(size_t)t * SBR_TRACK_CANDIDATES];
    const float sig2 = trk->cfg.meas_sigma * trk->cfg.meas_sigma;
    const float gate2 = trk->cfg.gate * trk->cfg.gate;
    uint32_t a;
    uint32_t i;
    uint32_t nc = 0u;
    for (a = 0u; a < 2u; a++) {
        (void)sbr_track_priv_marginal(sbr_track_priv_dens(trk, g, t, a), g, m[a]);
        sbr_track_priv_moments(m[a], g, trk->slot[t].origin[a], &mean[a], &var[a]);
    }
    for (i = 0u; i < n; i++) {
        const float z[2] = {dets[i].x, dets[i].y};
        float d2 = 0.0f;
        for (a = 0u; a < 2u; a++) {
            const float e = z[a] - mean[a];
            d2 += (e * e) / (var[a] + sig2);
        }
        if (d2 <= gate2) {
            float c = 0.0f;
            uint32_t pos;
            for (a = 0u; a < 2u; a++) {
                float l = 0.0f;
                uint32_t p;
                for (p = 0u; p < g->w; p++) {
                    const float x = trk->slot[t].origin[a] + ((float)p * g->s);
                    l += m[a][p] * sbr_track_priv_kernel(x - z[a], g->kw);
                }
                if (l > TRK_TINY) {
                    c -= logf(l);
                } else {
                    c += 100.0f + d2;
                }
            }
            /* insertion into the sorted list of at most SBR_TRACK_CANDIDATES */
            pos = nc;
            while ((pos > 0u) && (cost[pos - 1u] > c)) {
                if (pos < SBR_TRACK_CANDIDATES) {
                    cost[pos] = cost[pos - 1u];
                    det[pos] = det[pos - 1u];
                }
                pos--;
            }
            if (pos < SBR_TRACK_CANDIDATES) {
                cost[pos] = c;
                det[pos] = i;
                if (nc < SBR_TRACK_CANDIDATES) {
                    nc++;
                }
            }
        }
    }
    trk->ncand[t] = nc;
}

/* Target t's free candidates against the best pair so far (*bt = SBR_TRACK_MAX_TARGETS:
   none yet): a cheaper one becomes the best (cost *best, target *bt, detection *bd). */
static void trk_best_candidate(const sbr_track_t *trk, uint32_t t, const uint8_t *used, float *best,
                               uint32_t *bt, uint32_t *bd)
{
    uint32_t c;
    for (c = 0u; c < trk->ncand[t]; c++) {
        const size_t idx = ((size_t)t * SBR_TRACK_CANDIDATES) + c;
        const uint32_t d = trk->cand_det[idx];
        if ((used[d] == 0u) && ((*bt == SBR_TRACK_MAX_TARGETS) || (trk->cand_cost[idx] < *best))) {
            *best = trk->cand_cost[idx];
            *bt = t;
            *bd = d;
        }
    }
}

/* Greedy global assignment within one group (confirmed or tentative targets). */
static void trk_assign(sbr_track_t *trk, uint32_t confirmed, uint8_t *used)
{
    int done = 0;
    while (done == 0) {
        float best = 0.0f;
        uint32_t bt = SBR_TRACK_MAX_TARGETS;
        uint32_t bd = 0u;
        uint32_t t;
        for (t = 0u; t < trk->cfg.max_targets; t++) {
            const sbr_track_slot_t *s = &trk->slot[t];
            if (((s->flags & TRK_ALIVE) != 0u) && (s->det < 0) &&
                ((s->flags & SBR_TRACK_CONFIRMED) == confirmed)) {
                trk_best_candidate(trk, t, used, &best, &bt, &bd);
            }
        }
        if (bt == SBR_TRACK_MAX_TARGETS) {
            done = 1;
        } else {
            trk->slot[bt].det = (int32_t)bd;
            used[bd] = 1u;
        }
    }
}

static void trk_emit(const sbr_track_t *trk, sbr_track_target_t *targets, uint32_t capacity,
                     uint32_t *count, int *overflow)
{
    uint32_t written = 0u;
    uint32_t group;
    for (group = 0u; group < 2u; group++) {
        uint32_t want = 0u;
        if (group == 0u) {
            want = SBR_TRACK_CONFIRMED;
        }
        uint32_t last = 0u;
        int more = 1;
        while (more != 0) {
            uint32_t bt = SBR_TRACK_MAX_TARGETS;
            uint32_t t;
            for (t = 0u; t < trk->cfg.max_targets; t++) {
                const sbr_track_slot_t *s = &trk->slot[t];
                if (((s->flags & TRK_ALIVE) != 0u) &&
                    ((s->flags & SBR_TRACK_CONFIRMED) == want) && (s->id > last) &&
                    ((bt == SBR_TRACK_MAX_TARGETS) || (s->id < trk->slot[bt].id))) {
                    bt = t;
                }
            }
            if (bt == SBR_TRACK_MAX_TARGETS) {
                more = 0;
            } else {
                const sbr_track_slot_t *s = &trk->slot[bt];
                last = s->id;
                if (written < capacity) {
                    sbr_track_target_t *o = &targets[written];
                    o->id = s->id;
                    o->x = s->est[0];
                    o->y = s->est[1];
                    o->vx = s->est[2];
                    o->vy = s->est[3];
                    o->certainty = s->certainty;
                    o->hits = s->hits;
                    o->misses = s->misses;
                    o->age = s->age;
                    o->detection = s->det;
                    o->flags = s->flags & (SBR_TRACK_CONFIRMED | SBR_TRACK_UPDATED | SBR_TRACK_BORN);
                    written++;
                } else {
                    *overflow = 1;
                }
            }
        }
    }
    *count = written;
}

sbr_status_t sbr_track_reset(sbr_track_t *trk)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (trk != NULL) {
        st = trk_check_instance(trk);
    }
    if (st == SBR_OK) {
        (void)memset(trk->ncand, 0, sizeof(trk->ncand));
        (void)memset(trk->slot, 0, sizeof(trk->slot));
        trk->next_id = 1u;
        trk->frame = 0u;
    }
    return st;
}

/* The geometry of this step: channel layout, kernel width, and the sub-steps that split a
   dt longer than 1.5 model periods (*sub of *ratio periods each). */
static void trk_step_geo(const sbr_track_t *trk, uint32_t dt_us, trk_geo_t *g, uint32_t *sub,
                         float *ratio)
{
    const sbr_track_model_t *m = trk->cfg.model;
    const uint32_t vm1 = m->vel_count - 1u;
    const uint32_t wm1 = trk->cfg.window - 1u;
    g->w = trk->cfg.window;
    g->v = m->vel_count;
    g->s = m->vel_spacing;
    g->c0 = (float)vm1 * 0.5f;
    g->half = (float)wm1 * 0.5f;
    /* a whole number (>= 3) of channels: then a detection's kernel is an exact cos²
       channel encoding (its centroid is the detection, whatever its sub-channel
       position) */
    g->kw = floorf(((TRK_KERNEL_PER_SIGMA * trk->cfg.meas_sigma) / g->s) + 0.5f);
    if (g->kw < 3.0f) {
        g->kw = 3.0f;
    }
    g->kw *= g->s;
    *sub = 1u;
    *ratio = sbr_util_seconds(dt_us) / m->period;
    if (*ratio > 1.5f) {
        *sub = (uint32_t)ceilf(*ratio);
        *ratio /= (float)*sub;
    }
}

/* 1-2. Every live target predicted over `sub` sub-steps of `ratio` periods, aged, and its
   candidate detections gathered. */
static void trk_predict_all(sbr_track_t *trk, const trk_geo_t *g, uint32_t sub, float ratio,
                            const sbr_track_detection_t *dets, uint32_t n)
{
    uint32_t t;
    for (t = 0u; t < trk->cfg.max_targets; t++) {
        sbr_track_slot_t *sl = &trk->slot[t];
        sl->det = -1;
        sl->flags &= ~(SBR_TRACK_UPDATED | SBR_TRACK_BORN);
        trk->ncand[t] = 0u;
        if ((sl->flags & TRK_ALIVE) != 0u) {
            uint32_t a;
            uint32_t s;
            for (a = 0u; a < 2u; a++) {
                for (s = 0u; s < sub; s++) {
                    sbr_track_priv_predict_axis(trk, g, a, sbr_track_priv_dens(trk, g, t, a), &sl->origin[a], ratio);
                }
            }
            sl->age++;
            trk_candidates(trk, g, t, dets, n);
        }
    }
}

/* 4. One live target updated by its detection or counted as missed, its estimate decoded;
   it dies when a tentative target misses, a confirmed one misses more than max_misses
   times, or its estimate leaves the model's extent. */
static void trk_update_slot(sbr_track_t *trk, const trk_geo_t *g, uint32_t t,
                            const sbr_track_detection_t *dets, float *vel_marg)
{
    const sbr_track_model_t *m = trk->cfg.model;
    sbr_track_slot_t *sl = &trk->slot[t];
    uint32_t a;
    int dead = 0;
    if (sl->det >= 0) {
        const sbr_track_detection_t *q = &dets[sl->det];
        sbr_track_priv_update_axis(g, sbr_track_priv_dens(trk, g, t, 0u), sl->origin[0], q->x, q->certainty, vel_marg);
        sbr_track_priv_update_axis(g, sbr_track_priv_dens(trk, g, t, 1u), sl->origin[1], q->y, q->certainty, vel_marg);
        sl->hits++;
        sl->misses = 0u;
        sl->flags |= SBR_TRACK_UPDATED;
        if (sl->hits >= trk->cfg.confirm_hits) {
            sl->flags |= SBR_TRACK_CONFIRMED;
        }
    } else {
        sl->misses++;
        if (((sl->flags & SBR_TRACK_CONFIRMED) == 0u) || (sl->misses > trk->cfg.max_misses)) {
            dead = 1;
        }
    }
    sl->certainty = 1.0f;
    for (a = 0u; a < 2u; a++) {
        float c = 0.0f;
        sbr_track_priv_decode_axis(g, sbr_track_priv_dens(trk, g, t, a), sl->origin[a], &sl->est[a], &sl->est[a + 2u],
                        &c);
        sl->certainty *= c;
        if ((sl->est[a] < 0.0f) || (sl->est[a] >= m->extent[a])) {
            dead = 1;
        }
    }
    if (dead != 0) {
        sl->flags = 0u;
    }
}

/* 5. A new target in a free slot for detection i; returns 0 when every slot is taken. */
static int trk_birth(sbr_track_t *trk, const trk_geo_t *g, const sbr_track_detection_t *dets,
                     uint32_t i)
{
    uint32_t free_slot = SBR_TRACK_MAX_TARGETS;
    uint32_t t;
    for (t = 0u; (t < trk->cfg.max_targets) && (free_slot == SBR_TRACK_MAX_TARGETS); t++) {
        if ((trk->slot[t].flags & TRK_ALIVE) == 0u) {
            free_slot = t;
        }
    }
    if (free_slot == SBR_TRACK_MAX_TARGETS) {
        return 0;
    }
    {
        sbr_track_slot_t *sl = &trk->slot[free_slot];
        const float z[2] = {dets[i].x, dets[i].y};
        uint32_t a;
        (void)memset(sl, 0, sizeof(*sl));
        sl->certainty = 1.0f;
        for (a = 0u; a < 2u; a++) {
            float c = 0.0f;
            sbr_track_priv_birth_axis(trk, g, a, sbr_track_priv_dens(trk, g, free_slot, a), &sl->origin[a], z[a]);
            sbr_track_priv_decode_axis(g, sbr_track_priv_dens(trk, g, free_slot, a), sl->origin[a], &sl->est[a],
                            &sl->est[a + 2u], &c);
            sl->certainty *= c;
        }
        sl->id = trk->next_id;
        trk->next_id++;
        if (trk->next_id == 0u) {
            trk->next_id = 1u;
        }
        sl->hits = 1u;
        sl->det = (int32_t)i;
        sl->flags = TRK_ALIVE | SBR_TRACK_BORN | SBR_TRACK_UPDATED;
        if (sl->hits >= trk->cfg.confirm_hits) {
            sl->flags |= SBR_TRACK_CONFIRMED;
        }
    }
    return 1;
}

sbr_status_t sbr_track_step(sbr_track_t *trk, uint32_t dt_us, const sbr_track_detection_t *dets,
                            uint32_t n, sbr_track_target_t *targets, uint32_t capacity,
                            uint32_t *count)
{
    sbr_status_t st;
    uint8_t used[SBR_TRACK_MAX_DETECTIONS];
    float vel_marg[SBR_TRACK_MAX_VEL];
    trk_geo_t g;
    uint32_t sub;
    float ratio;
    uint32_t t;
    uint32_t i;
    int full = 0;
    int overflow = 0;
    if ((trk == NULL) || (count == NULL) || ((targets == NULL) && (capacity > 0u))) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = trk_check_instance(trk);
    if (st == SBR_OK) {
        st = trk_check_inputs(trk, dt_us, dets, n);
    }
    if (st != SBR_OK) {
        return st;
    }
    trk_step_geo(trk, dt_us, &g, &sub, &ratio);
    (void)memset(used, 0, sizeof(used));
    trk_predict_all(trk, &g, sub, ratio, dets, n);
    /* 3. associate: confirmed targets first */
    trk_assign(trk, SBR_TRACK_CONFIRMED, used);
    trk_assign(trk, 0u, used);
    for (t = 0u; t < trk->cfg.max_targets; t++) {
        if ((trk->slot[t].flags & TRK_ALIVE) != 0u) {
            trk_update_slot(trk, &g, t, dets, vel_marg);
        }
    }
    for (i = 0u; i < n; i++) {
        if (used[i] == 0u) {
            if (trk_birth(trk, &g, dets, i) == 0) {
                full = 1;
            } else {
                used[i] = 1u;
            }
        }
    }
    trk->frame++;
    trk_emit(trk, targets, capacity, count, &overflow);
    if ((full != 0) || (overflow != 0)) {
        st = SBR_ERR_CAPACITY;
    }
    return st;
}
