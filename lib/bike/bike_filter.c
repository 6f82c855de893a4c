/* SPDX-License-Identifier: MIT */
/* Bicycle tracking from wheel ellipses (paper B), its particle filter: random numbers,
   the filter's configuration, workspace and instance, association, weights, resampling.
   The geometry it uses (motion, projection, wheel pairs) is in bicycle.c. See
   include/sbr/bike.h. */
#include "sbr/bike.h"

#include <math.h>
#include <string.h>

#include "../common/sbr_util.h"
#include "bike_internal.h"

/* ---------------------------------------------------------------- random numbers */

static uint32_t rng_next(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

/* uniform in (0, 1) */
static float rng_uniform(uint32_t *s)
{
    return ((float)(rng_next(s) >> 8) + 0.5f) * (1.0f / 16777216.0f);
}

/* standard normal (Box-Muller, one of the pair) */
static float rng_gauss(uint32_t *s)
{
    const float u1 = rng_uniform(s);
    const float u2 = rng_uniform(s);
    return sqrtf(-2.0f * logf(u1)) * cosf(2.0f * SBR_PI_F * u2);
}

/* ---------------------------------------------------------------- particle filter */

void sbr_bike_pf_config_default(sbr_bike_pf_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->camera.focal = 1000.0f;
        cfg->camera.cx = 639.5f;
        cfg->camera.cy = 359.5f;
        cfg->camera.height = 1.2f;
        sbr_bike_model_default(&cfg->model);
        cfg->particles = 1000u;
        cfg->seed = 1u;
        cfg->speed_noise = 1.5f;
        cfg->steer_noise = 0.3f;
        cfg->heading_noise = 0.05f;
        cfg->position_noise = 0.1f;
        cfg->roll_noise = 0.05f;
        cfg->meas_px = 0.5f;
        cfg->meas_rel = 0.015f;
        cfg->gate = 200.0f;
        cfg->max_speed = 12.0f;
        cfg->resample_fraction = 0.5f;
        cfg->max_missed = 12u;
    }
}

static int nonneg_finite(float v, float hi)
{
    return (isfinite(v) != 0) && (v >= 0.0f) && (v <= hi);
}

sbr_status_t sbr_bike_pf_config_check(const sbr_bike_pf_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if ((cfg->particles < SBR_BIKE_PF_MIN_PARTICLES) || (cfg->particles > SBR_BIKE_PF_MAX_PARTICLES)) {
        st = SBR_ERR_SIZE;
    } else if ((sbr_bike_priv_camera_ok(&cfg->camera) == 0) || (sbr_bike_priv_model_ok(&cfg->model) == 0) ||
               (nonneg_finite(cfg->speed_noise, 100.0f) == 0) || (nonneg_finite(cfg->steer_noise, 10.0f) == 0) ||
               (nonneg_finite(cfg->heading_noise, 10.0f) == 0) ||
               (nonneg_finite(cfg->position_noise, 100.0f) == 0) || (nonneg_finite(cfg->roll_noise, 10.0f) == 0) ||
               (nonneg_finite(cfg->meas_rel, 1.0f) == 0) || (nonneg_finite(cfg->meas_px, 1000.0f) == 0) ||
               (cfg->meas_px <= 0.0f) || (nonneg_finite(cfg->gate, 1e6f) == 0) || (cfg->gate <= 0.0f) ||
               (nonneg_finite(cfg->max_speed, BIKE_MAX_SPEED) == 0) || (cfg->max_speed <= 0.0f) ||
               (nonneg_finite(cfg->resample_fraction, 1.0f) == 0) || (cfg->resample_fraction <= 0.0f) ||
               (cfg->max_missed < 1u)) {
        st = SBR_ERR_RANGE;
    } else {
        /* valid */
    }
    return st;
}

size_t sbr_bike_pf_workspace_size(const sbr_bike_pf_config_t *cfg)
{
    size_t n = 0u;
    if (sbr_bike_pf_config_check(cfg) == SBR_OK) {
        n = SBR_BIKE_PF_WORKSPACE_SIZE(cfg->particles);
    }
    return n;
}

sbr_status_t sbr_bike_pf_init(sbr_bike_pf_t *pf, const sbr_bike_pf_config_t *cfg, void *workspace,
                              size_t workspace_size)
{
    sbr_status_t st = SBR_OK;
    if ((pf == NULL) || (cfg == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_bike_pf_config_check(cfg);
        if ((st == SBR_OK) && ((workspace == NULL) || (workspace_size < SBR_BIKE_PF_WORKSPACE_SIZE(cfg->particles)) ||
                               (sbr_util_aligned(workspace, 4u) == 0))) {
            st = SBR_ERR_WORKSPACE;
        }
        if (st == SBR_OK) {
            sbr_bike_particle_t *p = (sbr_bike_particle_t *)workspace;
            pf->cfg = *cfg;
            pf->cur = p;
            pf->next = &p[cfg->particles];
            pf->pred = (float *)(void *)&p[2u * cfg->particles];
            pf->rng = (cfg->seed != 0u) ? cfg->seed : 0x9e3779b9u;
            pf->started = 0u;
            pf->missed = 0u;
            pf->age = 0u;
            pf->magic = BIKE_MAGIC;
        }
    }
    return st;
}

sbr_status_t sbr_bike_pf_reset(sbr_bike_pf_t *pf)
{
    sbr_status_t st = SBR_OK;
    if (pf == NULL) {
        st = SBR_ERR_NULL;
    } else if ((pf->magic != BIKE_MAGIC) || (pf->cur == NULL) || (pf->next == NULL) ||
               (pf->pred == NULL) || (sbr_bike_pf_config_check(&pf->cfg) != SBR_OK)) {
        st = SBR_ERR_STATE;
    } else {
        pf->rng = (pf->cfg.seed != 0u) ? pf->cfg.seed : 0x9e3779b9u;
        pf->started = 0u;
        pf->missed = 0u;
        pf->age = 0u;
    }
    return st;
}

/* A measured wheel: its six features (centre, semi-axes, elongation vector
   (a - b)(cos 2t, sin 2t)) and 1 / sigma^2. */
typedef struct {
    float f[BIKE_NFEAT];
    float inv;
} bike_feat_t;

static void features(const sbr_ellipse_t *e, float f[BIKE_NFEAT])
{
    const float el = e->semi_major - e->semi_minor;
    f[0] = e->cx;
    f[1] = e->cy;
    f[2] = e->semi_major;
    f[3] = e->semi_minor;
    f[4] = el * cosf(2.0f * e->angle);
    f[5] = el * sinf(2.0f * e->angle);
}

static bike_feat_t measured(const sbr_bike_pf_t *pf, const sbr_ellipse_t *e)
{
    bike_feat_t m;
    /* a young track's particles are sparse in speed and heading: its first updates use
       a wider likelihood (BIKE_WARMUP times the noise at the start, 1 after as many
       frames) so that the cloud narrows over several frames instead of collapsing */
    const uint32_t left = (pf->age < BIKE_WARMUP) ? (BIKE_WARMUP - pf->age) : 1u;
    const float warm = (float)left;
    const float sigma = (pf->cfg.meas_px + (pf->cfg.meas_rel * e->semi_major)) * warm;
    features(e, m.f);
    m.inv = 1.0f / (sigma * sigma);
    return m;
}

/* Normalised squared distance between a measured and a predicted wheel. */
static float wheel_d2(const bike_feat_t *m, const float p[BIKE_NFEAT])
{
    float d2 = 0.0f;
    uint32_t k;
    for (k = 0u; k < BIKE_NFEAT; ++k) {
        const float d = m->f[k] - p[k];
        d2 += d * d;
    }
    return d2 * m->inv;
}

/* A candidate measurement: one wheel (either end) or two (either order). */
typedef struct {
    uint32_t kind; /* 0 none, 1 single, 2 pair */
    bike_feat_t w[2];
} bike_cand_t;

/* The measurement a step uses, with its ellipses. */
typedef struct {
    bike_cand_t c;
    sbr_ellipse_t e[2];
} bike_meas_t;

/* Cost of a measurement for predicted wheels (features r, f), under its better
   assignment: the sum of the wheels' squared distances, each capped at BIKE_LL_CAP
   (returned), and uncapped (*raw). *swapped: 1 when w[0] is better the front wheel. */
static float meas_cost(const bike_cand_t *m, const float r[BIKE_NFEAT], const float f[BIKE_NFEAT],
                       float *raw, uint32_t *swapped)
{
    float c0;
    float c1;
    float u0;
    float u1;
    if (m->kind == 1u) {
        u0 = wheel_d2(&m->w[0], r);
        u1 = wheel_d2(&m->w[0], f);
        c0 = fminf(u0, BIKE_LL_CAP);
        c1 = fminf(u1, BIKE_LL_CAP);
    } else {
        const float r0 = wheel_d2(&m->w[0], r);
        const float f1 = wheel_d2(&m->w[1], f);
        const float r1 = wheel_d2(&m->w[1], r);
        const float f0 = wheel_d2(&m->w[0], f);
        u0 = r0 + f1;
        u1 = r1 + f0;
        c0 = fminf(r0, BIKE_LL_CAP) + fminf(f1, BIKE_LL_CAP);
        c1 = fminf(r1, BIKE_LL_CAP) + fminf(f0, BIKE_LL_CAP);
    }
    *raw = fminf(u0, u1);
    *swapped = 0u;
    if (c1 < c0) {
        *swapped = 1u;
    }
    return fminf(c0, c1);
}

/* Features of a particle's predicted wheels; 0 when they are not both in view. */
static int predicted(const sbr_bike_pf_t *pf, const sbr_bike_state_t *s, float r[BIKE_NFEAT],
                     float f[BIKE_NFEAT])
{
    sbr_ellipse_t er;
    sbr_ellipse_t ef;
    const int ok = sbr_bike_priv_project_both(&pf->cfg.camera, &pf->cfg.model, s, &er, &ef);
    if (ok != 0) {
        features(&er, r);
        features(&ef, f);
    }
    return ok;
}

/* Project every particle's wheels once per step into the workspace's prediction cache
   (rear then front features; a semi-major axis of -1 marks a particle out of view), so
   that association and weighting do not project again. */
static void cache_predictions(sbr_bike_pf_t *pf)
{
    uint32_t i;
    for (i = 0u; i < pf->cfg.particles; ++i) {
        float *r = &pf->pred[i * (2u * BIKE_NFEAT)];
        if (predicted(pf, &pf->cur[i].s, r, &r[BIKE_NFEAT]) == 0) {
            r[2] = -1.0f;
        }
    }
}

/* Particle i's cached features (rear, then front), or NULL when it is out of view. */
static const float *cached(const sbr_bike_pf_t *pf, uint32_t i)
{
    const float *r = &pf->pred[i * (2u * BIKE_NFEAT)];
    if (r[2] < 0.0f) {
        r = NULL;
    }
    return r;
}

/* The candidate with the largest predictive likelihood (the weighted sum over the
   particles of each one's likelihood) among those some particle explains within the
   gate (limit: the gate times the number of wheels). Returns nc when none qualifies. */
static uint32_t choose(const sbr_bike_pf_t *pf, const bike_cand_t *cand, uint32_t nc)
{
    float score[SBR_BIKE_MAX_ELLIPSES];
    float best_raw[SBR_BIKE_MAX_ELLIPSES];
    float top = BIKE_DEAD_LOGW;
    uint32_t best = nc;
    uint32_t c;
    uint32_t i;
    for (c = 0u; c < nc; ++c) {
        score[c] = 0.0f;
        best_raw[c] = 3.0e38f;
    }
    for (i = 0u; i < pf->cfg.particles; ++i) {
        top = fmaxf(top, pf->cur[i].logw);
    }
    for (i = 0u; i < pf->cfg.particles; ++i) {
        const float *r = cached(pf, i);
        if (r != NULL) {
            const float *f = &r[BIKE_NFEAT];
            const float w = expf(pf->cur[i].logw - top);
            for (c = 0u; c < nc; ++c) {
                float raw;
                uint32_t sw;
                const float cost = meas_cost(&cand[c], r, f, &raw, &sw);
                score[c] += w * expf(-0.5f * cost);
                best_raw[c] = fminf(best_raw[c], raw);
            }
        }
    }
    for (c = 0u; c < nc; ++c) {
        if ((best_raw[c] <= (pf->cfg.gate * (float)cand[c].kind)) && ((best == nc) || (score[c] > score[best]))) {
            best = c;
        }
    }
    return best;
}

/* Choose this frame's measurement: the best wheel pair, otherwise the best single wheel
   (one hidden), otherwise none. */
static void associate(const sbr_bike_pf_t *pf, const sbr_ellipse_t *el, uint32_t n, bike_meas_t *m)
{
    wheel_group_t g[SBR_BIKE_MAX_ELLIPSES];
    sbr_wheel_pair_t pairs[BIKE_PAIR_CAP];
    bike_cand_t cand[SBR_BIKE_MAX_ELLIPSES];
    const uint32_t ng = sbr_bike_priv_group_ellipses(el, n, g);
    uint32_t np = sbr_bike_priv_pair_groups(g, ng, &pf->cfg.model, pairs, BIKE_PAIR_CAP);
    uint32_t k;
    uint32_t pick;
    (void)memset(cand, 0, sizeof cand);
    if (np > BIKE_PAIR_CAP) {
        np = BIKE_PAIR_CAP;
    }
    m->c.kind = 0u;
    for (k = 0u; k < np; ++k) {
        cand[k].kind = 2u;
        cand[k].w[0] = measured(pf, &pairs[k].wheel[0]);
        cand[k].w[1] = measured(pf, &pairs[k].wheel[1]);
    }
    pick = choose(pf, cand, np);
    if (pick < np) {
        m->c = cand[pick];
        m->e[0] = pairs[pick].wheel[0];
        m->e[1] = pairs[pick].wheel[1];
    } else {
        for (k = 0u; k < ng; ++k) {
            const sbr_ellipse_t e = sbr_bike_priv_group_ellipse(&g[k]);
            cand[k].kind = 1u;
            cand[k].w[0] = measured(pf, &e);
            cand[k].w[1] = cand[k].w[0];
        }
        pick = choose(pf, cand, ng);
        if (pick < ng) {
            m->c = cand[pick];
            m->e[0] = sbr_bike_priv_group_ellipse(&g[pick]);
            m->e[1] = m->e[0];
        }
    }
}

/* Weight the particles by a measurement (kind 0: only renormalise); returns the
   effective sample size. */
static float weigh(sbr_bike_pf_t *pf, const bike_meas_t *m)
{
    const uint32_t n = pf->cfg.particles;
    float top = BIKE_DEAD_LOGW;
    float sum = 0.0f;
    float sum2 = 0.0f;
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        sbr_bike_particle_t *p = &pf->cur[i];
        if (m->c.kind != 0u) {
            const float *r = cached(pf, i);
            if (r != NULL) {
                float raw;
                uint32_t sw;
                p->logw += -0.5f * meas_cost(&m->c, r, &r[BIKE_NFEAT], &raw, &sw);
            } else {
                p->logw = BIKE_DEAD_LOGW;
            }
        }
        top = fmaxf(top, p->logw);
    }
    for (i = 0u; i < n; ++i) {
        sbr_bike_particle_t *p = &pf->cur[i];
        float w;
        p->logw = fmaxf(p->logw - top, BIKE_DEAD_LOGW);
        w = expf(p->logw);
        sum += w;
        sum2 += w * w;
    }
    return (sum2 > 0.0f) ? ((sum * sum) / sum2) : 0.0f;
}

static uint32_t best_particle(const sbr_bike_pf_t *pf)
{
    uint32_t best = 0u;
    uint32_t i;
    for (i = 1u; i < pf->cfg.particles; ++i) {
        if (pf->cur[i].logw > pf->cur[best].logw) {
            best = i;
        }
    }
    return best;
}

/* Start particles from a wheel pair. */
static void start_track(sbr_bike_pf_t *pf, const sbr_wheel_pair_t *pair)
{
    const sbr_camera_t *cam = &pf->cfg.camera;
    const float r = pf->cfg.model.wheel_radius;
    float ray[2][3];
    float dist[2];
    float srel[2];
    uint32_t w;
    uint32_t i;
    for (w = 0u; w < 2u; ++w) {
        const sbr_ellipse_t *e = &pair->wheel[w];
        const float x = (e->cx - cam->cx) / cam->focal;
        const float y = (e->cy - cam->cy) / cam->focal;
        const float norm = sqrtf((x * x) + (y * y) + 1.0f);
        ray[w][0] = x / norm;
        ray[w][1] = y / norm;
        ray[w][2] = 1.0f / norm;
        dist[w] = (cam->focal * r) / e->semi_major;
        srel[w] = (pf->cfg.meas_px + (pf->cfg.meas_rel * e->semi_major)) / e->semi_major;
    }
    for (i = 0u; i < pf->cfg.particles; ++i) {
        sbr_bike_particle_t *p = &pf->cur[i];
        const uint32_t rear = i & 1u;
        const uint32_t front = 1u - rear;
        const float sr = dist[rear] * (1.0f + (srel[rear] * rng_gauss(&pf->rng)));
        const float sf = dist[front] * (1.0f + (srel[front] * rng_gauss(&pf->rng)));
        const float rx = ray[rear][0] * sr;
        const float rz = ray[rear][2] * sr;
        const float fx = ray[front][0] * sf;
        const float fz = ray[front][2] * sf;
        p->s.x = rx;
        p->s.z = rz;
        p->s.heading = atan2f(fz - rz, fx - rx);
        p->s.speed = pf->cfg.max_speed * rng_uniform(&pf->rng);
        p->s.steer = 0.05f * rng_gauss(&pf->rng);
        p->s.roll = 0.03f * rng_gauss(&pf->rng);
        p->logw = 0.0f;
    }
    pf->started = 1u;
    pf->missed = 0u;
    pf->age = 0u;
}

/* Move every particle by dt with process noise. */
static void predict_particles(sbr_bike_pf_t *pf, float dt)
{
    const float sq = sqrtf(dt);
    uint32_t i;
    for (i = 0u; i < pf->cfg.particles; ++i) {
        sbr_bike_state_t *s = &pf->cur[i].s;
        sbr_bike_priv_advance(&pf->cfg.model, s, dt);
        s->x += pf->cfg.position_noise * sq * rng_gauss(&pf->rng);
        s->z += pf->cfg.position_noise * sq * rng_gauss(&pf->rng);
        s->heading = sbr_bike_priv_wrap_angle(s->heading + (pf->cfg.heading_noise * sq * rng_gauss(&pf->rng)));
        s->speed = sbr_util_clampf(s->speed + (pf->cfg.speed_noise * sq * rng_gauss(&pf->rng)), 0.0f, BIKE_MAX_SPEED);
        s->steer = sbr_util_clampf(s->steer + (pf->cfg.steer_noise * sq * rng_gauss(&pf->rng)), -BIKE_MAX_STEER, BIKE_MAX_STEER);
        s->roll = sbr_util_clampf(s->roll + (pf->cfg.roll_noise * sq * rng_gauss(&pf->rng)), -BIKE_MAX_ROLL, BIKE_MAX_ROLL);
    }
}

/* Systematic resampling into the second generation, then swap. */
static void resample(sbr_bike_pf_t *pf)
{
    const uint32_t n = pf->cfg.particles;
    const float step = 1.0f / (float)n;
    float total = 0.0f;
    float cum;
    float u;
    uint32_t i;
    uint32_t j = 0u;
    sbr_bike_particle_t *t;
    for (i = 0u; i < n; ++i) {
        total += expf(pf->cur[i].logw);
    }
    u = step * rng_uniform(&pf->rng);
    cum = expf(pf->cur[0].logw) / total;
    for (i = 0u; i < n; ++i) {
        int more = 0;
        if (u > cum) {
            more = 1;
        }
        while ((more != 0) && (j < (n - 1u))) {
            j++;
            cum += expf(pf->cur[j].logw) / total;
            if (u <= cum) {
                more = 0;
            }
        }
        pf->next[i].s = pf->cur[j].s;
        pf->next[i].logw = 0.0f;
        u += step;
    }
    t = pf->cur;
    pf->cur = pf->next;
    pf->next = t;
}

/* Mean and spread of the dominant heading mode. */
static void estimate(const sbr_bike_pf_t *pf, sbr_bike_result_t *res)
{
    const uint32_t n = pf->cfg.particles;
    const float href = pf->cur[best_particle(pf)].s.heading;
    float acc[7] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f}; /* w, x, z, cos, sin, v, steer */
    float roll = 0.0f;
    float var[6] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        const sbr_bike_state_t *s = &pf->cur[i].s;
        if (cosf(s->heading - href) > 0.0f) {
            const float w = expf(pf->cur[i].logw);
            acc[0] += w;
            acc[1] += w * s->x;
            acc[2] += w * s->z;
            acc[3] += w * cosf(s->heading);
            acc[4] += w * sinf(s->heading);
            acc[5] += w * s->speed;
            acc[6] += w * s->steer;
            roll += w * s->roll;
        }
    }
    res->mean.x = acc[1] / acc[0];
    res->mean.z = acc[2] / acc[0];
    res->mean.heading = atan2f(acc[4], acc[3]);
    res->mean.speed = acc[5] / acc[0];
    res->mean.steer = acc[6] / acc[0];
    res->mean.roll = roll / acc[0];
    for (i = 0u; i < n; ++i) {
        const sbr_bike_state_t *s = &pf->cur[i].s;
        if (cosf(s->heading - href) > 0.0f) {
            const float w = expf(pf->cur[i].logw);
            const float d[6] = {s->x - res->mean.x, s->z - res->mean.z, sbr_bike_priv_wrap_angle(s->heading - res->mean.heading),
                                s->speed - res->mean.speed, s->steer - res->mean.steer, s->roll - res->mean.roll};
            uint32_t k;
            for (k = 0u; k < 6u; ++k) {
                var[k] += w * d[k] * d[k];
            }
        }
    }
    res->stddev.x = sqrtf(var[0] / acc[0]);
    res->stddev.z = sqrtf(var[1] / acc[0]);
    res->stddev.heading = sqrtf(var[2] / acc[0]);
    res->stddev.speed = sqrtf(var[3] / acc[0]);
    res->stddev.steer = sqrtf(var[4] / acc[0]);
    res->stddev.roll = sqrtf(var[5] / acc[0]);
}

/* Weigh, estimate (before resampling, while the weights still tell the modes apart),
   report which measured wheel is which for the estimate, resample if needed. */
static void weigh_and_estimate(sbr_bike_pf_t *pf, const bike_meas_t *m, sbr_bike_result_t *res)
{
    res->ess = weigh(pf, m);
    estimate(pf, res);
    if (m->c.kind != 0u) {
        float r[BIKE_NFEAT];
        float f[BIKE_NFEAT];
        float raw;
        uint32_t sw = 0u;
        if (predicted(pf, &res->mean, r, f) != 0) {
            (void)meas_cost(&m->c, r, f, &raw, &sw);
        }
        if (m->c.kind == 2u) {
            res->rear = m->e[sw];
            res->front = m->e[1u - sw];
            res->wheels = 3u;
        } else if (sw == 0u) {
            res->rear = m->e[0];
            res->wheels = 1u;
        } else {
            res->front = m->e[0];
            res->wheels = 2u;
        }
    }
    if (res->ess < (pf->cfg.resample_fraction * (float)pf->cfg.particles)) {
        resample(pf);
        res->flags |= SBR_BIKE_RESAMPLED;
    }
}

sbr_status_t sbr_bike_pf_step(sbr_bike_pf_t *pf, uint32_t dt_us, const sbr_ellipse_t *ellipses, uint32_t n,
                              sbr_bike_result_t *result)
{
    sbr_status_t st = SBR_OK;
    if ((pf == NULL) || (result == NULL) || ((ellipses == NULL) && (n > 0u))) {
        st = SBR_ERR_NULL;
    } else if ((pf->magic != BIKE_MAGIC) || (pf->cur == NULL) || (pf->next == NULL) || (pf->pred == NULL) ||
               (sbr_bike_pf_config_check(&pf->cfg) != SBR_OK)) {
        st = SBR_ERR_STATE;
    } else if (n > SBR_BIKE_MAX_ELLIPSES) {
        st = SBR_ERR_SIZE;
    } else if ((dt_us > BIKE_MAX_DT_STEP_US) || (sbr_bike_priv_ellipses_ok(ellipses, n) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        bike_meas_t m;
        result->flags = 0u;
        result->wheels = 0u;
        result->ess = 0.0f;
        if (pf->started == 0u) {
            wheel_group_t g[SBR_BIKE_MAX_ELLIPSES];
            sbr_wheel_pair_t pair[1];
            const uint32_t ng = sbr_bike_priv_group_ellipses(ellipses, n, g);
            if (sbr_bike_priv_pair_groups(g, ng, &pf->cfg.model, pair, 1u) > 0u) {
                start_track(pf, &pair[0]);
                cache_predictions(pf);
                m.c.kind = 2u;
                m.e[0] = pair[0].wheel[0];
                m.e[1] = pair[0].wheel[1];
                m.c.w[0] = measured(pf, &m.e[0]);
                m.c.w[1] = measured(pf, &m.e[1]);
                result->flags = SBR_BIKE_TRACKING | SBR_BIKE_STARTED | SBR_BIKE_UPDATED;
                weigh_and_estimate(pf, &m, result);
            }
        } else {
            predict_particles(pf, sbr_util_seconds(dt_us));
            cache_predictions(pf);
            associate(pf, ellipses, n, &m);
            result->flags = SBR_BIKE_TRACKING;
            pf->age = (pf->age < BIKE_WARMUP) ? (pf->age + 1u) : pf->age;
            weigh_and_estimate(pf, &m, result);
            if (m.c.kind != 0u) {
                pf->missed = 0u;
                result->flags |= SBR_BIKE_UPDATED;
            } else {
                pf->missed++;
                if (pf->missed >= pf->cfg.max_missed) {
                    pf->started = 0u;
                    result->flags = SBR_BIKE_LOST;
                }
            }
        }
    }
    return st;
}
