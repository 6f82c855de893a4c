/* SPDX-License-Identifier: MIT */
/* Channel-based multi-target tracker (paper E), its model and set-up: the motion model's
   tables and checks, the constant-velocity model, the configuration, the workspace and
   sbr_track_init(). See include/sbr/track.h for the method. */
#include "sbr/track.h"

#include <math.h>
#include <string.h>

#include "sbr/channel.h"
#include "../common/sbr_util.h"
#include "track_internal.h"

/* cos² kernel B(d) with support w (|d| < w / 2). */
float sbr_track_priv_kernel(float d, float w)
{
    float r = 0.0f;
    if (fabsf(d) < (0.5f * w)) {
        const float c = cosf((SBR_PI_F * d) / w);
        r = c * c;
    }
    return r;
}

sbr_status_t sbr_track_region_config(const sbr_track_model_t *model, uint32_t axis,
                                     sbr_channel_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if ((model == NULL) || (cfg == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((axis > 1u) || (model->regions[axis] < 3u) ||
               (model->regions[axis] > SBR_TRACK_MAX_REGIONS) ||
               (isfinite(model->extent[axis]) == 0) || (model->extent[axis] < 8.0f)) {
        st = SBR_ERR_RANGE;
    } else {
        const uint32_t nr2 = model->regions[axis] - 2u;
        cfg->spacing = model->extent[axis] / (float)nr2;
        cfg->first_centre = -0.5f * cfg->spacing;
        cfg->count = model->regions[axis];
        cfg->overlap = 3u;
    }
    return st;
}

/* The active region channels (at most 3) of position `pos` on axis `axis`, weights
   normalised to sum 1: the channel encoding of the position, clamped into the image. */
uint32_t sbr_track_priv_region_weights(const sbr_track_model_t *m, uint32_t axis, float pos,
                                       uint32_t *idx, float *w)
{
    float enc[SBR_TRACK_MAX_REGIONS];
    sbr_channel_config_t rc;
    uint32_t n = 0u;
    float x = pos;
    (void)memset(&rc, 0, sizeof(rc));
    (void)sbr_track_region_config(m, axis, &rc);
    /* the encodable range is [0, extent); its top end is excluded */
    if (x < 0.0f) {
        x = 0.0f;
    }
    if (x > (m->extent[axis] - (1e-3f * rc.spacing))) {
        x = m->extent[axis] - (1e-3f * rc.spacing);
    }
    if (sbr_channel_encode(&rc, x, 1.0f, enc, SBR_TRACK_MAX_REGIONS) == SBR_OK) {
        uint32_t r;
        for (r = 0u; r < rc.count; r++) {
            if ((enc[r] > 0.0f) && (n < 3u)) {
                idx[n] = r;
                /* one encoding sums to overlap / 2 = 1.5 */
                w[n] = enc[r] / 1.5f;
                n++;
            }
        }
    }
    return n;
}

const float *sbr_track_priv_table(const sbr_track_model_t *m, uint32_t axis, int birth)
{
    const size_t v = (size_t)m->vel_count;
    size_t off = 0u;
    const float *base = m->transition;
    size_t per = v * v;
    if (birth != 0) {
        base = m->birth;
        per = v;
    }
    if (axis == 1u) {
        off = (size_t)m->regions[0] * per;
    }
    return &base[off];
}

static sbr_status_t trk_rows_ok(const float *t, size_t rows, uint32_t len)
{
    sbr_status_t st = SBR_OK;
    size_t i;
    for (i = 0u; (i < rows) && (st == SBR_OK); i++) {
        float sum = 0.0f;
        uint32_t k;
        for (k = 0u; k < len; k++) {
            const float v = t[(i * len) + k];
            if ((isfinite(v) == 0) || (v < 0.0f)) {
                st = SBR_ERR_CORRUPT;
            } else {
                sum += v;
            }
        }
        if (fabsf(sum - 1.0f) > TRK_ROW_TOL) {
            st = SBR_ERR_CORRUPT;
        }
    }
    return st;
}

/* A model's header (everything but the table contents): used by sbr_track_model_check()
   and, on every step, by the instance check (the tables are checked once, at init). */
sbr_status_t sbr_track_priv_model_header(const sbr_track_model_t *model)
{
    sbr_status_t st = SBR_OK;
    if ((model->transition == NULL) || (model->birth == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((model->regions[0] < 3u) || (model->regions[0] > SBR_TRACK_MAX_REGIONS) ||
               (model->regions[1] < 3u) || (model->regions[1] > SBR_TRACK_MAX_REGIONS) ||
               (model->vel_count < 5u) || (model->vel_count > SBR_TRACK_MAX_VEL) ||
               ((model->vel_count % 2u) == 0u)) {
        st = SBR_ERR_SIZE;
    } else if ((model->order != SBR_TRACK_ORDER) || (isfinite(model->period) == 0) ||
               (model->period <= 0.0f) || (isfinite(model->extent[0]) == 0) ||
               (isfinite(model->extent[1]) == 0) || (model->extent[0] < 8.0f) ||
               (model->extent[1] < 8.0f) || (model->extent[0] > SBR_TRACK_MAX_EXTENT) ||
               (model->extent[1] > SBR_TRACK_MAX_EXTENT) || (isfinite(model->vel_spacing) == 0) ||
               (model->vel_spacing <= 0.0f) ||
               (model->vel_spacing > fmaxf(model->extent[0], model->extent[1]))) {
        st = SBR_ERR_RANGE;
    } else {
        st = SBR_OK;
    }
    return st;
}

sbr_status_t sbr_track_model_check(const sbr_track_model_t *model)
{
    sbr_status_t st = SBR_OK;
    if (model == NULL) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_track_priv_model_header(model);
    }
    if (st == SBR_OK) {
        const uint32_t v = model->vel_count;
        const size_t rows = (size_t)model->regions[0] + (size_t)model->regions[1];
        st = trk_rows_ok(model->transition, rows * (size_t)v, v);
        if (st == SBR_OK) {
            st = trk_rows_ok(model->birth, rows, v);
        }
    }
    return st;
}

static void trk_gauss_row(float *row, uint32_t v, float centre, float sigma)
{
    float sum = 0.0f;
    uint32_t k;
    for (k = 0u; k < v; k++) {
        const float d = ((float)k - centre) / sigma;
        row[k] = expf(-0.5f * d * d);
        sum += row[k];
    }
    for (k = 0u; k < v; k++) {
        row[k] /= sum;
    }
}

sbr_status_t sbr_track_model_cv(sbr_track_model_t *model, float width, float height,
                                float period, uint32_t vel_count, float vel_spacing,
                                float accel_sigma, float birth_sigma, float *transition,
                                size_t transition_len, float *birth, size_t birth_len)
{
    sbr_status_t st = SBR_OK;
    if ((model == NULL) || (transition == NULL) || (birth == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((vel_count < 5u) || (vel_count > SBR_TRACK_MAX_VEL) || ((vel_count % 2u) == 0u) ||
               (transition_len < SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, vel_count)) ||
               (birth_len < SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, vel_count))) {
        st = SBR_ERR_SIZE;
    } else if ((isfinite(width) == 0) || (isfinite(height) == 0) || (width < 8.0f) ||
               (height < 8.0f) || (width > SBR_TRACK_MAX_EXTENT) ||
               (height > SBR_TRACK_MAX_EXTENT) || (isfinite(period) == 0) || (period <= 0.0f) ||
               (isfinite(vel_spacing) == 0) || (vel_spacing <= 0.0f) ||
               (vel_spacing > fmaxf(width, height)) ||
               (isfinite(accel_sigma) == 0) || (accel_sigma <= 0.0f) ||
               (isfinite(birth_sigma) == 0) || (birth_sigma <= 0.0f)) {
        st = SBR_ERR_RANGE;
    } else {
        const uint32_t vm1 = vel_count - 1u;
        const float c0 = (float)vm1 * 0.5f;
        /* at least a third of a channel, so that every row has some spread */
        float as = accel_sigma / vel_spacing;
        float bs = birth_sigma / vel_spacing;
        uint32_t r;
        uint32_t j;
        if (as < 0.34f) {
            as = 0.34f;
        }
        if (bs < 0.34f) {
            bs = 0.34f;
        }
        for (r = 0u; r < 6u; r++) {
            for (j = 0u; j < vel_count; j++) {
                trk_gauss_row(&transition[(((size_t)r * vel_count) + j) * vel_count], vel_count,
                              (float)j, as);
            }
            trk_gauss_row(&birth[(size_t)r * vel_count], vel_count, c0, bs);
        }
        model->order = SBR_TRACK_ORDER;
        model->period = period;
        model->extent[0] = width;
        model->extent[1] = height;
        model->regions[0] = 3u;
        model->regions[1] = 3u;
        model->vel_count = vel_count;
        model->vel_spacing = vel_spacing;
        model->transition = transition;
        model->birth = birth;
    }
    return st;
}

void sbr_track_config_default(sbr_track_config_t *cfg)
{
    if (cfg != NULL) {
        (void)memset(cfg, 0, sizeof(*cfg));
        cfg->model = NULL;
        cfg->max_targets = 32u;
        cfg->window = 21u;
        cfg->meas_sigma = 3.0f;
        cfg->gate = 4.0f;
        cfg->confirm_hits = 2u;
        cfg->max_misses = 5u;
    }
}

sbr_status_t sbr_track_priv_config_scalars(const sbr_track_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if ((cfg->max_targets < 1u) || (cfg->max_targets > SBR_TRACK_MAX_TARGETS) ||
        (cfg->window < 7u) || (cfg->window > SBR_TRACK_MAX_WINDOW) ||
        ((cfg->window % 2u) == 0u)) {
        st = SBR_ERR_SIZE;
    } else if ((isfinite(cfg->meas_sigma) == 0) || (cfg->meas_sigma <= 0.0f) ||
               (isfinite(cfg->gate) == 0) || (cfg->gate <= 0.0f) || (cfg->confirm_hits < 1u) ||
               (cfg->confirm_hits > 16u) || (cfg->max_misses > 255u)) {
        st = SBR_ERR_RANGE;
    } else {
        st = SBR_OK;
    }
    return st;
}

sbr_status_t sbr_track_config_check(const sbr_track_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_track_priv_config_scalars(cfg);
        if (st == SBR_OK) {
            st = sbr_track_model_check(cfg->model);
        }
        if (st == SBR_OK) {
            /* a detection's kernel, in channels, must fit in a target's window (the
               decoder's neighbourhood and the channel counts it derives are then bounded) */
            const float kernel = (TRK_KERNEL_PER_SIGMA * cfg->meas_sigma) / cfg->model->vel_spacing;
            if ((isfinite(kernel) == 0) || (kernel > (float)cfg->window)) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

size_t sbr_track_workspace_size(const sbr_track_config_t *cfg)
{
    size_t n = 0u;
    if (sbr_track_config_check(cfg) == SBR_OK) {
        n = SBR_TRACK_WORKSPACE_SIZE(cfg->max_targets, cfg->window, cfg->model->vel_count);
    }
    return n;
}

sbr_status_t sbr_track_init(sbr_track_t *trk, const sbr_track_config_t *cfg, void *workspace,
                            size_t workspace_size)
{
    sbr_status_t st = SBR_OK;
    if ((trk == NULL) || (cfg == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_track_config_check(cfg);
    }
    if (st == SBR_OK) {
        const size_t need = sbr_track_workspace_size(cfg);
        if ((workspace == NULL) || (workspace_size < need) ||
            (sbr_util_aligned(workspace, 4u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        } else {
            const size_t tf = SBR_TRACK_TARGET_FLOATS(cfg->window, cfg->model->vel_count);
            float *f = (float *)workspace;
            (void)memset(trk, 0, sizeof(*trk));
            trk->cfg = *cfg;
            trk->dens = f;
            trk->scratch = &f[(size_t)cfg->max_targets * tf];
            trk->cand_cost =
                &trk->scratch[(size_t)cfg->window * (size_t)cfg->model->vel_count];
            trk->cand_det = (uint32_t *)(void *)&trk->cand_cost[(size_t)cfg->max_targets *
                                                                SBR_TRACK_CANDIDATES];
            trk->next_id = 1u;
            trk->frame = 0u;
            trk->magic = TRK_MAGIC;
        }
    }
    return st;
}
