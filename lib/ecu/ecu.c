/* SPDX-License-Identifier: MIT */
/*
 * The ECU's per-frame job: sign tracking, restrictions, the CAN cycle (include/sbr/ecu.h).
 */
#include "sbr/ecu.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "../common/sbr_util.h"

/* "ECU!": an initialised instance. */
#define ECU_MAGIC 0x45435521u

/* SBR_Detection's track ids: 0..62 (63: none). */
#define DET_TRACK_IDS 63u
/* SBR_ConfirmedSign's track ids: 0..254 (255: none). */
#define SIGN_TRACK_IDS 255u

void sbr_ecu_config_default(sbr_ecu_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_signs_config_default(&cfg->signs);
        sbr_rules_config_default(&cfg->rules);
        sbr_can_sched_config_default(&cfg->sched);
        cfg->min_score = 0.0f;
        cfg->stills = 0u;
    }
}

sbr_status_t sbr_ecu_config_check(const sbr_ecu_config_t *cfg)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (cfg != NULL) {
        st = sbr_signs_config_check(&cfg->signs);
        if (st == SBR_OK) {
            st = sbr_rules_config_check(&cfg->rules);
        }
        if (st == SBR_OK) {
            st = sbr_can_sched_config_check(&cfg->sched);
        }
        if ((st == SBR_OK) &&
            ((cfg->sched.frame_budget > SBR_ECU_MAX_FRAMES) || (cfg->rules.class_count != cfg->signs.class_count) ||
             (cfg->stills > 1u) || (cfg->min_score < 0.0f) || (cfg->min_score > 1.0f) ||
             (cfg->min_score != cfg->min_score))) {
            st = SBR_ERR_RANGE;
        }
    }
    return st;
}

size_t sbr_ecu_workspace_size(const sbr_ecu_config_t *cfg)
{
    size_t n = 0u;
    if (sbr_ecu_config_check(cfg) == SBR_OK) {
        n = SBR_ECU_WORKSPACE_SIZE(cfg->signs.max_tracks, cfg->signs.class_count, cfg->sched.frame_budget);
    }
    return n;
}

sbr_status_t sbr_ecu_init(sbr_ecu_t *ecu, const sbr_ecu_config_t *cfg, void *workspace, size_t workspace_size)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (ecu != NULL) {
        (void)memset(ecu, 0, sizeof *ecu);
        st = sbr_ecu_config_check(cfg);
    }
    if (st == SBR_OK) {
        const size_t need = SBR_ECU_WORKSPACE_SIZE(cfg->signs.max_tracks, cfg->signs.class_count,
                                                   cfg->sched.frame_budget);
        if ((workspace == NULL) || (workspace_size < need) || (sbr_util_aligned(workspace, 8u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        }
    }
    if (st == SBR_OK) {
        /* layout: the sign tracking's workspace, then the frame's arrays (each a multiple
           of 4 bytes; the detections first, they hold floats and 32-bit words) */
        const size_t signs_bytes = SBR_SIGNS_WORKSPACE_SIZE(cfg->signs.max_tracks, cfg->signs.class_count);
        unsigned char *base = (unsigned char *)workspace;
        ecu->cfg = *cfg;
        ecu->dets = (sbr_detection_t *)(void *)&base[signs_bytes];
        ecu->records = (sbr_can_detection_t *)(void *)&ecu->dets[SBR_ECU_MAX_DETECTIONS];
        ecu->alive = (sbr_sign_t *)(void *)&ecu->records[SBR_ECU_MAX_DETECTIONS];
        ecu->frames = (sbr_can_frame_t *)(void *)&ecu->alive[cfg->signs.max_tracks];
        ecu->det_sign = (uint32_t *)(void *)&ecu->frames[cfg->sched.frame_budget];
        st = sbr_signs_init(&ecu->signs, &cfg->signs, workspace, signs_bytes);
        if (st == SBR_OK) {
            st = sbr_rules_init(&ecu->rules, &cfg->rules);
        }
        if (st == SBR_OK) {
            st = sbr_can_e2e_tx_init(&ecu->tx);
        }
        if (st == SBR_OK) {
            ecu->magic = ECU_MAGIC;
        }
    }
    return st;
}

static uint32_t sbr_ecu_min_u32(uint32_t a, uint32_t b)
{
    return (a < b) ? a : b;
}

/* Whether an instance looks initialised. */
static int ecu_usable(const sbr_ecu_t *e)
{
    return ((e->magic == ECU_MAGIC) && (e->dets != NULL) && (e->records != NULL) && (e->alive != NULL) &&
            (e->frames != NULL) && (e->det_sign != NULL) && (e->listed_count <= SBR_ECU_LISTED))
               ? 1
               : 0;
}

/* Checks of a frame's arguments (before anything changes). */
static sbr_status_t output_check(const sbr_ecu_t *e, const sbr_detection_t *dets, uint32_t n,
                                 const sbr_ecu_frame_info_t *info)
{
    sbr_status_t st = SBR_ERR_STATE;
    if (ecu_usable(e) != 0) {
        uint32_t i;
        st = SBR_OK;
        if ((info->error > 1u) || (info->capacity_hit > 1u) || (info->processing_ms != info->processing_ms)) {
            st = SBR_ERR_RANGE;
        }
        for (i = 0u; (i < n) && (st == SBR_OK); i++) {
            if (!((dets[i].score >= 0.0f) && (dets[i].score <= 1.0f)) ||
                ((uint32_t)dets[i].class_id >= e->cfg.signs.class_count)) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

/* The detections at or above min_score, in order, into e->dets; 1 when some did not fit. */
static int keep(sbr_ecu_t *e, const sbr_detection_t *dets, uint32_t n, uint32_t *kept)
{
    int full = 0;
    uint32_t i;
    *kept = 0u;
    for (i = 0u; i < n; i++) {
        if (dets[i].score >= e->cfg.min_score) {
            if (*kept < SBR_ECU_MAX_DETECTIONS) {
                e->dets[*kept] = dets[i];
                *kept += 1u;
            } else {
                full = 1;
            }
        }
    }
    return full;
}

/* Sorts a list of new listings by decreasing score, ties in the order given. */
static void sort_by_score(sbr_ecu_listed_t *l, uint32_t n)
{
    uint32_t i;
    for (i = 1u; i < n; i++) {
        const sbr_ecu_listed_t v = l[i];
        uint32_t j = i;
        while ((j > 0u) && (l[j - 1u].score < v.score)) {
            l[j] = l[j - 1u];
            j--;
        }
        l[j] = v;
    }
}

/* The frame's new confirmations (at most SBR_ECU_MAX_DETECTIONS) into `fresh`. */
static uint32_t confirmations(sbr_ecu_t *e, uint32_t kept, uint32_t signs, sbr_ecu_listed_t *fresh)
{
    uint32_t m = 0u;
    uint32_t i;
    if (e->cfg.stills != 0u) {
        for (i = 0u; i < kept; i++) {
            fresh[m].class_id = e->dets[i].class_id;
            fresh[m].score = e->dets[i].score;
            fresh[m].frame = e->frame;
            m++;
        }
    } else {
        for (i = 0u; i < signs; i++) {
            const sbr_sign_t *s = &e->alive[i];
            if ((s->flags & (SBR_SIGN_NEW | SBR_SIGN_RENAMED)) != 0u) {
                fresh[m].class_id = s->class_id;
                fresh[m].score = s->score;
                fresh[m].track_id = s->id % SIGN_TRACK_IDS;
                fresh[m].frame = e->frame;
                m++;
            }
        }
    }
    sort_by_score(fresh, m);
    if (e->cfg.stills != 0u) {
        /* a still's id in turn, by the listing order */
        for (i = 0u; i < m; i++) {
            fresh[i].track_id = e->next_still;
            e->next_still = (e->next_still + 1u) % SIGN_TRACK_IDS;
        }
    }
    return m;
}

/* The listing after the frame: the new ones first, then the earlier ones, at most
   SBR_ECU_LISTED, none older than SBR_ECU_LIST_FRAMES frames. */
static void relist(sbr_ecu_t *e, const sbr_ecu_listed_t *fresh, uint32_t m)
{
    sbr_ecu_listed_t next[SBR_ECU_LISTED];
    uint32_t k = 0u;
    uint32_t i;
    for (i = 0u; (i < m) && (k < SBR_ECU_LISTED); i++) {
        next[k] = fresh[i];
        k++;
    }
    for (i = 0u; (i < e->listed_count) && (k < SBR_ECU_LISTED); i++) {
        if ((e->frame - e->listed[i].frame) < SBR_ECU_LIST_FRAMES) {
            next[k] = e->listed[i];
            k++;
        }
    }
    (void)memcpy(e->listed, next, (size_t)k * sizeof next[0]);
    e->listed_count = k;
}

/* The detections' CAN records. */
static void detection_records(sbr_ecu_t *e, uint32_t kept)
{
    uint32_t i;
    for (i = 0u; i < kept; i++) {
        const sbr_detection_t *d = &e->dets[i];
        sbr_can_detection_t *c = &e->records[i];
        c->class_id = d->class_id;
        c->confidence = sbr_util_clampf(100.0f * d->score, 0.0f, 100.0f);
        c->center_x = (float)d->box.x + (0.5f * (float)d->box.width);
        c->center_y = (float)d->box.y + (0.5f * (float)d->box.height);
        c->width = (float)d->box.width;
        c->height = (float)d->box.height;
        c->track_id = (e->det_sign[i] != 0u) ? (e->det_sign[i] % DET_TRACK_IDS) : SBR_CAN_TRACK_NONE_DET;
    }
}

/* The listed signs' CAN records. */
static void sign_records(const sbr_ecu_t *e, sbr_can_confirmed_sign_t *out)
{
    uint32_t i;
    for (i = 0u; i < e->listed_count; i++) {
        const sbr_ecu_listed_t *l = &e->listed[i];
        const sbr_rules_meaning_t *m = &e->cfg.rules.meanings[l->class_id];
        (void)memset(&out[i], 0, sizeof out[i]);
        out[i].class_id = l->class_id;
        out[i].track_id = l->track_id;
        out[i].speed_kmh = (m->kind == (uint8_t)SBR_RULES_SPEED) ? (uint32_t)m->value : SBR_CAN_SPEED_NONE;
        out[i].confidence = roundf(100.0f * sbr_util_clampf(l->score, 0.0f, 1.0f));
        out[i].age_frames = e->frame - l->frame;
    }
}

/* Tracking, confirmations, restrictions and the listing for a frame's kept detections;
   1 when something ran full. */
static int track_and_list(sbr_ecu_t *e, uint64_t now_us, uint32_t kept, sbr_ecu_result_t *r, sbr_status_t *st)
{
    uint32_t signs = 0u;
    int full = 0;
    *st = SBR_OK;
    if (e->cfg.stills != 0u) {
        /* stills: no detection belongs to a tracked sign (sbr_signs_update() writes them otherwise) */
        (void)memset(e->det_sign, 0, (size_t)kept * sizeof(uint32_t));
    } else {
        *st = sbr_signs_update(&e->signs, now_us, e->dets, kept, e->det_sign, e->alive, e->cfg.signs.max_tracks,
                               &signs);
        if (*st == SBR_ERR_CAPACITY) {
            full = 1;
            *st = SBR_OK;
        }
    }
    if (*st == SBR_OK) {
        sbr_ecu_listed_t fresh[SBR_ECU_MAX_DETECTIONS];
        uint16_t classes[SBR_ECU_MAX_DETECTIONS];
        uint32_t i;
        const uint32_t m = confirmations(e, kept, signs, fresh);
        for (i = 0u; i < m; i++) {
            classes[i] = (uint16_t)fresh[i].class_id;
        }
        *st = sbr_rules_update(&e->rules, now_us, classes, m, &r->restrictions);
        relist(e, fresh, m);
        r->confirmed = m;
        r->signs = (e->cfg.stills != 0u) ? e->listed_count : signs;
    }
    return full;
}

sbr_status_t sbr_ecu_output(sbr_ecu_t *ecu, uint64_t now_us, const sbr_detection_t *dets, uint32_t n,
                            const sbr_ecu_frame_info_t *info, const sbr_can_port_t *port, void *port_ctx,
                            sbr_ecu_result_t *result)
{
    sbr_status_t st = SBR_ERR_NULL;
    sbr_ecu_result_t r;
    (void)memset(&r, 0, sizeof r);
    if ((ecu != NULL) && ((dets != NULL) || (n == 0u)) && (info != NULL) && (port != NULL)) {
        st = output_check(ecu, dets, n, info);
    }
    if ((st == SBR_OK) && (ecu->started != 0u) && (now_us <= ecu->now_us)) {
        st = SBR_ERR_RANGE;
    }
    if (st == SBR_OK) {
        sbr_can_confirmed_sign_t listed[SBR_ECU_LISTED];
        sbr_can_restrictions_t restr;
        sbr_can_cycle_t cyc;
        uint32_t kept = 0u;
        uint32_t nf = 0u;
        int full = keep(ecu, dets, n, &kept);
        full |= track_and_list(ecu, now_us, kept, &r, &st);
        if (st == SBR_OK) {
            detection_records(ecu, kept);
            sign_records(ecu, listed);
            (void)memset(&cyc, 0, sizeof cyc);
            cyc.signs = listed;
            cyc.sign_count = ecu->listed_count;
            cyc.detections = ecu->records;
            cyc.detection_count = kept;
            restr.speed_limit_kmh = r.restrictions.speed_limit_kmh;
            restr.no_overtaking = r.restrictions.no_overtaking;
            restr.no_overtaking_trucks = r.restrictions.no_overtaking_trucks;
            restr.priority_road = r.restrictions.priority_road;
            restr.speed_age_s = sbr_ecu_min_u32(r.restrictions.speed_age_ms / 1000u, 65535u);
            cyc.restrictions = &restr;
            cyc.status.frame_counter = ecu->frame;
            cyc.status.processing_ms = sbr_util_clampf(info->processing_ms, 0.0f, 6553.4f);
            cyc.status.region_count = info->regions;
            cyc.status.detection_count = kept;
            cyc.status.error = info->error;
            cyc.status.capacity_hit = info->capacity_hit;
            if (full != 0) {
                cyc.status.capacity_hit = 1u;
            }
            r.capacity_hit = cyc.status.capacity_hit;
            r.detections = kept;
            st = sbr_can_schedule(&ecu->tx, &ecu->cfg.sched, &cyc, ecu->frames, ecu->cfg.sched.frame_budget, &nf,
                                  &r.dropped);
            /* a result with a value outside its signal is left out (counted in dropped) */
            st = (st == SBR_ERR_RANGE) ? SBR_OK : st;
        }
        if (st == SBR_OK) {
            ecu->frame += 1u;
            ecu->now_us = now_us;
            ecu->started = 1u;
            st = sbr_can_send(port, port_ctx, ecu->frames, nf, &r.frames_sent);
        }
        if ((st == SBR_OK) && (full != 0)) {
            st = SBR_ERR_CAPACITY;
        }
    }
    if (result != NULL) {
        *result = r;
    }
    return st;
}

sbr_status_t sbr_ecu_frame(sbr_ecu_t *ecu, sbr_recog_t *rec, const sbr_image_t *img, uint64_t now_us,
                           uint32_t ticks_per_ms, const sbr_can_port_t *port, void *port_ctx,
                           sbr_ecu_result_t *result)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((ecu != NULL) && (rec != NULL) && (img != NULL) && (port != NULL)) {
        st = (ecu_usable(ecu) != 0) ? SBR_OK : SBR_ERR_STATE;
    }
    if (st == SBR_OK) {
        sbr_recog_stats_t stats;
        sbr_ecu_frame_info_t info;
        sbr_ecu_result_t r;
        uint32_t n = 0u;
        const sbr_status_t rs = sbr_recog_detect(rec, img, NULL, ecu->dets, SBR_ECU_MAX_DETECTIONS, &n, &stats);
        (void)memset(&info, 0, sizeof info);
        if ((rs == SBR_OK) || (rs == SBR_ERR_CAPACITY)) {
            uint32_t ticks = 0u;
            uint32_t k;
            for (k = 0u; k < (uint32_t)SBR_RECOG_STAGES; k++) {
                ticks += stats.stage_ticks[k];
            }
            if (ticks_per_ms > 0u) {
                info.processing_ms = (float)ticks / (float)ticks_per_ms;
            }
            info.regions = stats.parts_stats.regions;
            if ((rs == SBR_ERR_CAPACITY) || ((stats.capacity_hit & SBR_RECOG_HIT_LOSSES) != 0u)) {
                info.capacity_hit = 1u;
            }
        } else {
            n = 0u;
            info.error = 1u;
        }
        /* the recogniser wrote into the instance's own array: hand it on as the input
           (keep() copies in place, front to back) */
        st = sbr_ecu_output(ecu, now_us, ecu->dets, n, &info, port, port_ctx, &r);
        r.recog = rs;
        if ((st == SBR_OK) && (rs != SBR_OK) && (rs != SBR_ERR_CAPACITY)) {
            st = rs;
        }
        if (result != NULL) {
            *result = r;
        }
    }
    return st;
}
