/* SPDX-License-Identifier: MIT */
/* Channel-based multi-target tracker with a learned second-order motion model
   (paper E). See include/sbr/track.h for the method. */
#include "sbr/track.h"

#include <math.h>
#include <string.h>

#include "sbr/channel.h"
#include "../common/sbr_util.h"

#define TRK_MAGIC 0x5452434Bu
/* cos² kernel of support W has standard deviation 0.1808 W: W = sigma / 0.1808. */
#define TRK_KERNEL_PER_SIGMA 5.53f
#define TRK_ALIVE 0x100u
#define TRK_TINY 1e-30f
#define TRK_ROW_TOL 1e-3f

/* cos² kernel B(d) with support w (|d| < w / 2). */
static float trk_kernel(float d, float w)
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
static uint32_t trk_region_weights(const sbr_track_model_t *m, uint32_t axis, float pos,
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

static const float *trk_table(const sbr_track_model_t *m, uint32_t axis, int birth)
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
static sbr_status_t trk_model_header(const sbr_track_model_t *model)
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
        st = trk_model_header(model);
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

static sbr_status_t trk_config_scalars(const sbr_track_config_t *cfg)
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
        st = trk_config_scalars(cfg);
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

/* ---- per-target density helpers ---------------------------------------------------- */

typedef struct trk_geo_s {
    uint32_t w;   /* window */
    uint32_t v;   /* velocity channels */
    float s;      /* spacing */
    float c0;     /* velocity centre channel */
    float half;   /* window centre channel */
    float kw;     /* detection kernel support */
} trk_geo_t;

static float *trk_dens(const sbr_track_t *trk, const trk_geo_t *g, uint32_t t, uint32_t axis)
{
    return &trk->dens[(((size_t)t * 2u) + axis) * (size_t)g->w * (size_t)g->v];
}

/* Position marginal of one axis' density into m[w]; returns the total. */
static float trk_marginal(const float *d, const trk_geo_t *g, float *m)
{
    float total = 0.0f;
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        const float *row = &d[(size_t)p * g->v];
        float a = 0.0f;
        uint32_t k;
        for (k = 0u; k < g->v; k++) {
            a += row[k];
        }
        m[p] = a;
        total += a;
    }
    return total;
}

/* Mean and variance (in pixels) of a position marginal. */
static void trk_moments(const float *m, const trk_geo_t *g, float origin, float *mean, float *var)
{
    float sw = 0.0f;
    float s1 = 0.0f;
    float s2 = 0.0f;
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        sw += m[p];
        s1 += m[p] * (float)p;
    }
    if (sw > TRK_TINY) {
        s1 /= sw;
        for (p = 0u; p < g->w; p++) {
            const float d = (float)p - s1;
            s2 += m[p] * d * d;
        }
        s2 /= sw;
    }
    *mean = origin + (s1 * g->s);
    /* a channel's own width: variance of the cos² kernel of support 3 s */
    *var = (s2 + 0.294f) * g->s * g->s;
}

static void trk_normalise(float *d, size_t n)
{
    float sum = 0.0f;
    size_t i;
    for (i = 0u; i < n; i++) {
        sum += d[i];
    }
    if (sum > TRK_TINY) {
        const float inv = 1.0f / sum;
        for (i = 0u; i < n; i++) {
            d[i] *= inv;
        }
    }
}

/* Velocity channel j's mass of every position channel p, times the transition t0 + t1
   to velocity channel k, added to out at positions p + sh (share t0) and p + sh + 1
   (share t1), inside the window. */
static void trk_shift_add(const trk_geo_t *g, const float *d, uint32_t j, uint32_t k, int32_t sh,
                          float t0, float t1, float *out)
{
    uint32_t p;
    for (p = 0u; p < g->w; p++) {
        const float c = d[((size_t)p * g->v) + j];
        if (c > 0.0f) {
            const int32_t q = (int32_t)p + sh;
            if ((q >= 0) && (q < (int32_t)g->w)) {
                out[((size_t)q * g->v) + k] += c * t0;
            }
            if (((q + 1) >= 0) && ((q + 1) < (int32_t)g->w)) {
                const int32_t q1 = q + 1;
                out[((size_t)q1 * g->v) + k] += c * t1;
            }
        }
    }
}

/* One prediction sub-step of one axis: ratio = sub-step / period. */
static void trk_predict_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis,
                             float *d, float *origin, float ratio)
{
    const sbr_track_model_t *m = trk->cfg.model;
    const float *tab = trk_table(m, axis, 0);
    const size_t vv = (size_t)g->v * (size_t)g->v;
    float *out = trk->scratch;
    uint32_t ridx[3];
    float rw[3];
    uint32_t nr;
    float mp = 0.0f;
    float mv = 0.0f;
    float tot = 0.0f;
    float shift_f;
    int32_t recentre;
    uint32_t p;
    uint32_t j;
    uint32_t k;
    uint32_t r;
    for (p = 0u; p < g->w; p++) {
        for (k = 0u; k < g->v; k++) {
            const float c = d[((size_t)p * g->v) + k];
            tot += c;
            mp += c * (float)p;
            mv += c * ((float)k - g->c0);
        }
    }
    if (tot > TRK_TINY) {
        mp /= tot;
        mv /= tot;
    }
    shift_f = (mp + (mv * ratio)) - g->half;
    recentre = (int32_t)floorf(shift_f + 0.5f);
    nr = trk_region_weights(m, axis, *origin + (g->half * g->s), ridx, rw);
    (void)memset(out, 0, (size_t)g->w * (size_t)g->v * sizeof(float));
    for (k = 0u; k < g->v; k++) {
        const float sk = (((float)k - g->c0) * ratio) - (float)recentre;
        const float fl = floorf(sk);
        const float f = sk - fl;
        const int32_t sh = (int32_t)fl;
        for (j = 0u; j < g->v; j++) {
            float t = 0.0f;
            for (r = 0u; r < nr; r++) {
                t += rw[r] * tab[((size_t)ridx[r] * vv) + ((size_t)j * g->v) + k];
            }
            if (t > 0.0f) {
                trk_shift_add(g, d, j, k, sh, t * (1.0f - f), t * f, out);
            }
        }
    }
    trk_normalise(out, (size_t)g->w * (size_t)g->v);
    (void)memcpy(d, out, (size_t)g->w * (size_t)g->v * sizeof(float));
    *origin += (float)recentre * g->s;
}

/* Detection likelihood of one axis at position channel p. */
static float trk_lik(const trk_geo_t *g, float origin, uint32_t p, float z, float w)
{
    const float x = origin + ((float)p * g->s);
    return (1.0f - w) + (w * trk_kernel(x - z, g->kw));
}

/* Update one axis with a detection. If the prediction gave the detection (next to) no
   probability, the position is taken from the detection alone and the velocity marginal
   is kept (the density would otherwise collapse to rounding noise). */
static void trk_update_axis(const trk_geo_t *g, float *d, float origin, float z, float w,
                            float *vel_marg)
{
    float total = 0.0f;
    float before = 0.0f;
    uint32_t p;
    uint32_t k;
    for (k = 0u; k < g->v; k++) {
        vel_marg[k] = 0.0f;
    }
    for (p = 0u; p < g->w; p++) {
        const float l = trk_lik(g, origin, p, z, w);
        for (k = 0u; k < g->v; k++) {
            const size_t i = ((size_t)p * g->v) + k;
            before += d[i];
            vel_marg[k] += d[i];
            d[i] *= l;
            total += d[i];
        }
    }
    if (total <= (1e-6f * before)) {
        for (p = 0u; p < g->w; p++) {
            const float l = trk_lik(g, origin, p, z, 1.0f);
            for (k = 0u; k < g->v; k++) {
                d[((size_t)p * g->v) + k] = l * vel_marg[k];
            }
        }
    }
    trk_normalise(d, (size_t)g->w * (size_t)g->v);
}

/* A new density on one axis: the detection's kernel times the region's velocity prior. */
static void trk_birth_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis, float *d,
                           float *origin, float z)
{
    const sbr_track_model_t *m = trk->cfg.model;
    const float *tab = trk_table(m, axis, 1);
    uint32_t ridx[3];
    float rw[3];
    uint32_t nr;
    float prior[SBR_TRACK_MAX_VEL];
    uint32_t p;
    uint32_t k;
    uint32_t r;
    (void)memset(prior, 0, sizeof(prior));
    nr = trk_region_weights(m, axis, z, ridx, rw);
    for (k = 0u; k < g->v; k++) {
        for (r = 0u; r < nr; r++) {
            prior[k] += rw[r] * tab[((size_t)ridx[r] * g->v) + k];
        }
    }
    *origin = z - (g->half * g->s);
    for (p = 0u; p < g->w; p++) {
        const float l = trk_lik(g, *origin, p, z, 1.0f);
        for (k = 0u; k < g->v; k++) {
            d[((size_t)p * g->v) + k] = l * prior[k];
        }
    }
    trk_normalise(d, (size_t)g->w * (size_t)g->v);
}

/* Mean of channels [c - r, c + r] of a vector, as a channel index (the decoded mode's
   neighbourhood: unbiased for a symmetric blob, unlike a 3-channel window on a density
   that is not a single cos² encoding). */
static float trk_local_mean(const float *m, uint32_t len, float c, uint32_t r)
{
    const int32_t ci = (int32_t)floorf(c + 0.5f);
    int32_t lo = ci - (int32_t)r;
    int32_t hi = ci + (int32_t)r;
    int32_t i;
    float sw = 0.0f;
    float s1 = 0.0f;
    float res = c;
    if (lo < 0) {
        lo = 0;
    }
    if (hi > ((int32_t)len - 1)) {
        hi = (int32_t)len - 1;
    }
    for (i = lo; i <= hi; i++) {
        sw += m[i];
        s1 += m[i] * (float)i;
    }
    if (sw > TRK_TINY) {
        res = s1 / sw;
    }
    return res;
}

/* Decode one channel vector, in channel units: the strongest valid 3-channel window
   (sbr_channel_decode()) locates the mode, the mean of its neighbourhood (`radius`
   channels each side) refines it; without a valid window, the mean of the whole vector.
   `cert` gets the window's sum (clamped to 1; 0 without a window). */
static float trk_decode_vec(const float *vec, uint32_t len, uint32_t radius, float *cert)
{
    sbr_channel_config_t cc;
    sbr_channel_mode_t mode;
    uint32_t cnt = 0u;
    float res;
    cc.first_centre = 0.0f;
    cc.spacing = 1.0f;
    cc.count = len;
    cc.overlap = 3u;
    *cert = 0.0f;
    (void)sbr_channel_decode(&cc, vec, len, 0.0f, &mode, 1u, &cnt);
    if (cnt == 1u) {
        res = trk_local_mean(vec, len, mode.value, radius);
        *cert = mode.certainty;
        if (*cert > 1.0f) {
            *cert = 1.0f;
        }
    } else {
        const uint32_t mid = len / 2u;
        res = trk_local_mean(vec, len, (float)mid, len);
    }
    return res;
}

/* Decode position and velocity of one axis from its position and velocity marginals;
   the position's neighbourhood is the detection kernel's half width plus one channel. */
static void trk_decode_axis(const trk_geo_t *g, const float *d, float origin, float *pos,
                            float *vel, float *cert)
{
    float m[SBR_TRACK_MAX_WINDOW];
    float mv[SBR_TRACK_MAX_VEL];
    const uint32_t r = (uint32_t)ceilf((0.5f * g->kw) / g->s) + 1u;
    float vcert = 0.0f;
    uint32_t p;
    uint32_t k;
    (void)trk_marginal(d, g, m);
    for (k = 0u; k < g->v; k++) {
        mv[k] = 0.0f;
    }
    for (p = 0u; p < g->w; p++) {
        for (k = 0u; k < g->v; k++) {
            mv[k] += d[((size_t)p * g->v) + k];
        }
    }
    *pos = origin + (trk_decode_vec(m, g->w, r, cert) * g->s);
    *vel = (trk_decode_vec(mv, g->v, 3u, &vcert) - g->c0) * g->s;
}

/* ---- the step --------------------------------------------------------------------- */

static sbr_status_t trk_check_instance(const sbr_track_t *trk)
{
    sbr_status_t st = SBR_OK;
    if ((trk->magic != TRK_MAGIC) || (trk->dens == NULL) || (trk->scratch == NULL) ||
        (trk->cand_cost == NULL) || (trk->cand_det == NULL) || (trk->cfg.model == NULL) ||
        (trk->next_id == 0u)) {
        st = SBR_ERR_STATE;
    } else if ((trk_config_scalars(&trk->cfg) != SBR_OK) ||
               (trk_model_header(trk->cfg.model) != SBR_OK)) {
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
        (void)trk_marginal(trk_dens(trk, g, t, a), g, m[a]);
        trk_moments(m[a], g, trk->slot[t].origin[a], &mean[a], &var[a]);
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
                    l += m[a][p] * trk_kernel(x - z[a], g->kw);
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
                    trk_predict_axis(trk, g, a, trk_dens(trk, g, t, a), &sl->origin[a], ratio);
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
        trk_update_axis(g, trk_dens(trk, g, t, 0u), sl->origin[0], q->x, q->certainty, vel_marg);
        trk_update_axis(g, trk_dens(trk, g, t, 1u), sl->origin[1], q->y, q->certainty, vel_marg);
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
        trk_decode_axis(g, trk_dens(trk, g, t, a), sl->origin[a], &sl->est[a], &sl->est[a + 2u],
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
            trk_birth_axis(trk, g, a, trk_dens(trk, g, free_slot, a), &sl->origin[a], z[a]);
            trk_decode_axis(g, trk_dens(trk, g, free_slot, a), sl->origin[a], &sl->est[a],
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
