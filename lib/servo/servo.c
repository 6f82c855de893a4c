/* SPDX-License-Identifier: MIT */
/* Visual servoing with a learned inverse image Jacobian (servo.h): the configuration, the
   receptive fields and their learning (weighted RLS), the Jacobian they give. The servo
   step is in servo_step.c. */
#include "sbr/servo.h"

#include <math.h>
#include <string.h>

#include "../common/sbr_util.h"
#include "servo_internal.h"


/* Offsets of a field's parts (floats). */
static size_t off_b(const sbr_servo_config_t *c) { return (size_t)c->joints; }
static size_t off_p(const sbr_servo_config_t *c)
{
    return (size_t)c->joints + ((size_t)c->joints * (size_t)c->features);
}
static size_t off_w(const sbr_servo_config_t *c)
{
    return off_p(c) + ((size_t)c->features * (size_t)c->features);
}
static size_t field_floats(const sbr_servo_config_t *c)
{
    return SBR_SERVO_FIELD_FLOATS(c->joints, c->features);
}

void sbr_servo_config_default(sbr_servo_config_t *cfg, uint32_t joints, uint32_t features)
{
    if (cfg != NULL) {
        uint32_t k;
        (void)memset(cfg, 0, sizeof *cfg);
        cfg->joints = joints;
        cfg->features = features;
        cfg->max_fields = 128u;
        cfg->angle_mask = 0u;
        cfg->new_field_activation = 0.3f;
        cfg->forgetting = 0.999f;
        cfg->prior = 1.0e3f;
        cfg->gain = 0.9f;
        cfg->max_iterations = 30u;
        for (k = 0u; k < SBR_SERVO_MAX_JOINTS; k++) {
            cfg->width[k] = 0.5f;
            cfg->max_step[k] = 0.2f;
            cfg->joint_min[k] = -3.2f;
            cfg->joint_max[k] = 3.2f;
        }
        for (k = 0u; k < SBR_SERVO_MAX_FEATURES; k++) {
            cfg->tolerance[k] = 1.0f;
        }
    }
}

static int positive_finite(float v) { return ((isfinite(v) != 0) && (v > 0.0f)) ? 1 : 0; }

static sbr_status_t check_joints(const sbr_servo_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    uint32_t j;
    for (j = 0u; j < cfg->joints; j++) {
        if ((positive_finite(cfg->width[j]) == 0) || (positive_finite(cfg->max_step[j]) == 0) ||
            (isfinite(cfg->joint_min[j]) == 0) || (isfinite(cfg->joint_max[j]) == 0) ||
            (cfg->joint_min[j] >= cfg->joint_max[j]) || (cfg->joint_min[j] < -SERVO_MAX_VALUE) ||
            (cfg->joint_max[j] > SERVO_MAX_VALUE)) {
            st = SBR_ERR_RANGE;
        }
    }
    return st;
}

sbr_status_t sbr_servo_config_check(const sbr_servo_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    uint32_t i;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if ((cfg->joints < 1u) || (cfg->joints > SBR_SERVO_MAX_JOINTS) || (cfg->features < 1u) ||
               (cfg->features > SBR_SERVO_MAX_FEATURES) || (cfg->max_fields < 1u) ||
               (cfg->max_fields > SBR_SERVO_MAX_FIELDS)) {
        st = SBR_ERR_SIZE;
    } else if (((cfg->angle_mask >> cfg->features) != 0u) ||
               (isfinite(cfg->new_field_activation) == 0) ||
               (cfg->new_field_activation <= SBR_SERVO_MIN_ACTIVATION) ||
               (cfg->new_field_activation >= 1.0f) || (isfinite(cfg->forgetting) == 0) ||
               (cfg->forgetting < 0.9f) || (cfg->forgetting > 1.0f) ||
               (positive_finite(cfg->prior) == 0) || (cfg->prior > SERVO_MAX_VALUE) ||
               (positive_finite(cfg->gain) == 0) || (cfg->gain > 1.0f) ||
               (cfg->max_iterations < 1u) || (cfg->max_iterations > 100000u)) {
        st = SBR_ERR_RANGE;
    } else {
        st = check_joints(cfg);
        for (i = 0u; i < cfg->features; i++) {
            if ((isfinite(cfg->tolerance[i]) == 0) || (cfg->tolerance[i] < 0.0f)) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

size_t sbr_servo_workspace_size(const sbr_servo_config_t *cfg)
{
    size_t n = 0u;
    if (sbr_servo_config_check(cfg) == SBR_OK) {
        n = SBR_SERVO_WORKSPACE_SIZE(cfg->max_fields, cfg->joints, cfg->features);
    }
    return n;
}

sbr_status_t sbr_servo_init(sbr_servo_t *servo, const sbr_servo_config_t *cfg, void *workspace,
                            size_t workspace_size)
{
    sbr_status_t st;
    if ((servo == NULL) || (cfg == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_servo_config_check(cfg);
        if (st == SBR_OK) {
            if ((workspace == NULL) || (sbr_util_aligned(workspace, 4u) == 0) ||
                (workspace_size < sbr_servo_workspace_size(cfg))) {
                st = SBR_ERR_WORKSPACE;
            } else {
                (void)memset(servo, 0, sizeof *servo);
                servo->cfg = *cfg;
                servo->fields = (float *)workspace;
                servo->count = 0u;
                servo->samples = 0u;
                servo->magic = SERVO_MAGIC ^ sbr_util_addr32(servo);
            }
        }
    }
    return st;
}

int sbr_servo_priv_valid(const sbr_servo_t *s)
{
    return ((s->magic == (SERVO_MAGIC ^ sbr_util_addr32(s))) && (s->fields != NULL) &&
            (sbr_servo_config_check(&s->cfg) == SBR_OK) && (s->count <= s->cfg.max_fields))
               ? 1
               : 0;
}

/* Every value finite and within +-1e6. */
int sbr_servo_priv_values_ok(const float *v, uint32_t n)
{
    int ok = 1;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        if ((isfinite(v[k]) == 0) || (fabsf(v[k]) > SERVO_MAX_VALUE)) {
            ok = 0;
        }
    }
    return ok;
}

/* v wrapped to (-pi, pi] (|v| <= 1e6: a bounded number of turns, done by division). */
static float servo_wrap(float v)
{
    const float two_pi = 2.0f * SBR_PI_F;
    float r = v - (two_pi * floorf((v + SBR_PI_F) / two_pi));
    if (r <= -SBR_PI_F) {
        r += two_pi;
    } else if (r > SBR_PI_F) {
        r -= two_pi;
    } else {
        /* in range */
    }
    return r;
}

void sbr_servo_priv_wrap_features(const sbr_servo_config_t *c, float *d)
{
    uint32_t i;
    for (i = 0u; i < c->features; i++) {
        if (((c->angle_mask >> i) & 1u) != 0u) {
            d[i] = servo_wrap(d[i]);
        }
    }
}

/* Squared normalised distance of y to a field's centre. */
static float distance2(const sbr_servo_config_t *c, const float *centre, const float *y)
{
    float q = 0.0f;
    uint32_t j;
    for (j = 0u; j < c->joints; j++) {
        const float t = (y[j] - centre[j]) / c->width[j];
        q += t * t;
    }
    return q;
}

/* J(y) into jac (m x n) from the fields reaching y, or from the nearest field when none
   does; returns the summed activation of the fields used (0 with no field at all). */
float sbr_servo_priv_predict(const sbr_servo_t *s, const float *y, float *jac)
{
    const sbr_servo_config_t *c = &s->cfg;
    const size_t mn = (size_t)c->joints * (size_t)c->features;
    float wsum = 0.0f;
    float nearest_q = 0.0f;
    uint32_t nearest = 0u;
    uint32_t k;
    size_t e;
    for (e = 0u; e < mn; e++) {
        jac[e] = 0.0f;
    }
    for (k = 0u; k < s->count; k++) {
        const float *f = &s->fields[(size_t)k * field_floats(c)];
        const float q = distance2(c, f, y);
        const float w = (q > 80.0f) ? 0.0f : expf(-0.5f * q);
        if ((k == 0u) || (q < nearest_q)) {
            nearest_q = q;
            nearest = k;
        }
        if (w >= SBR_SERVO_MIN_ACTIVATION) {
            const float *b = &f[off_b(c)];
            for (e = 0u; e < mn; e++) {
                jac[e] += w * b[e];
            }
            wsum += w;
        }
    }
    if (wsum >= SBR_SERVO_MIN_ACTIVATION) {
        for (e = 0u; e < mn; e++) {
            jac[e] /= wsum;
        }
    } else if (s->count > 0u) {
        const float *b = &s->fields[((size_t)nearest * field_floats(c)) + off_b(c)];
        for (e = 0u; e < mn; e++) {
            jac[e] = b[e];
        }
        wsum = (nearest_q > 80.0f) ? 0.0f : expf(-0.5f * nearest_q);
    } else {
        wsum = 0.0f;
    }
    return wsum;
}

static float act_of(const sbr_servo_config_t *c, const float *centre, const float *y)
{
    const float q = distance2(c, centre, y);
    return (q > 80.0f) ? 0.0f : expf(-0.5f * q);
}

static void reset_p(const sbr_servo_config_t *c, float *p)
{
    uint32_t a;
    uint32_t b;
    for (a = 0u; a < c->features; a++) {
        for (b = 0u; b < c->features; b++) {
            p[(a * c->features) + b] = (a == b) ? c->prior : 0.0f;
        }
    }
}

/* Weighted RLS update of one field with the pair (dx -> dy), weight w in (0, 1]. */
static void rls_update(const sbr_servo_config_t *c, float *f, float w, const float *dx,
                       const float *dy)
{
    const uint32_t m = c->joints;
    const uint32_t n = c->features;
    float *b = &f[off_b(c)];
    float *p = &f[off_p(c)];
    float px[SBR_SERVO_MAX_FEATURES];
    float g[SBR_SERVO_MAX_FEATURES];
    float denom = c->forgetting / w;
    float trace = 0.0f;
    int ok = 1;
    uint32_t a;
    uint32_t k;
    for (a = 0u; a < n; a++) {
        px[a] = 0.0f;
        for (k = 0u; k < n; k++) {
            px[a] += p[(a * n) + k] * dx[k];
        }
        denom += dx[a] * px[a];
    }
    for (a = 0u; a < n; a++) {
        g[a] = px[a] / denom;
        if (isfinite(g[a]) == 0) {
            ok = 0;
        }
    }
    if (ok != 0) {
        for (k = 0u; k < m; k++) {
            float e = dy[k];
            for (a = 0u; a < n; a++) {
                e -= b[(k * n) + a] * dx[a];
            }
            for (a = 0u; a < n; a++) {
                b[(k * n) + a] += e * g[a];
            }
        }
        for (a = 0u; a < n; a++) {
            for (k = a; k < n; k++) { /* symmetric: computed once, mirrored */
                const float v = (p[(a * n) + k] - (g[a] * px[k])) / c->forgetting;
                p[(a * n) + k] = v;
                p[(k * n) + a] = v;
            }
            trace += p[(a * n) + a];
        }
    }
    /* anti-windup: directions the motions do not excite would grow by 1 / forgetting per
       update; the trace is kept at most n * prior (and a broken P is started again) */
    if ((ok == 0) || (isfinite(trace) == 0) || (trace <= 0.0f)) {
        reset_p(c, p);
    } else if (trace > ((float)n * c->prior)) {
        const float scale = ((float)n * c->prior) / trace;
        for (a = 0u; a < (n * n); a++) {
            p[a] *= scale;
        }
    } else {
        /* within the bound */
    }
    f[off_w(c)] += w;
}

/* A new field at y, its model started from the prediction there (or 0). */
static void new_field(sbr_servo_t *s, const float *y)
{
    const sbr_servo_config_t *c = &s->cfg;
    float *f = &s->fields[(size_t)s->count * field_floats(c)];
    float jac[SBR_SERVO_MAX_JOINTS * SBR_SERVO_MAX_FEATURES];
    const size_t mn = (size_t)c->joints * (size_t)c->features;
    size_t e;
    uint32_t j;
    (void)sbr_servo_priv_predict(s, y, jac);
    for (j = 0u; j < c->joints; j++) {
        f[j] = y[j];
    }
    for (e = 0u; e < mn; e++) {
        f[off_b(c) + e] = jac[e];
    }
    reset_p(c, &f[off_p(c)]);
    f[off_w(c)] = 0.0f;
    s->count++;
}

sbr_status_t sbr_servo_learn(sbr_servo_t *servo, const float *y, const float *dy,
                             const float *dx)
{
    sbr_status_t st = SBR_OK;
    if ((servo == NULL) || (y == NULL) || (dy == NULL) || (dx == NULL)) {
        st = SBR_ERR_NULL;
    } else if (sbr_servo_priv_valid(servo) == 0) {
        st = SBR_ERR_STATE;
    } else if ((sbr_servo_priv_values_ok(y, servo->cfg.joints) == 0) || (sbr_servo_priv_values_ok(dy, servo->cfg.joints) == 0) ||
               (sbr_servo_priv_values_ok(dx, servo->cfg.features) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        const sbr_servo_config_t *c = &servo->cfg;
        float d[SBR_SERVO_MAX_FEATURES];
        float best = 0.0f;
        uint32_t k;
        (void)memcpy(d, dx, (size_t)c->features * sizeof(float));
        sbr_servo_priv_wrap_features(c, d);
        for (k = 0u; k < servo->count; k++) { /* one pass: activation, best, update */
            float *f = &servo->fields[(size_t)k * field_floats(c)];
            const float w = act_of(c, f, y);
            best = (w > best) ? w : best;
            if (w >= SBR_SERVO_MIN_ACTIVATION) {
                rls_update(c, f, w, d, dy);
            }
        }
        if (best < c->new_field_activation) {
            if (servo->count < c->max_fields) {
                new_field(servo, y); /* from the prediction the updates above give */
                rls_update(c, &servo->fields[(size_t)(servo->count - 1u) * field_floats(c)], 1.0f,
                           d, dy); /* activation 1 at its own centre */
            } else {
                st = SBR_ERR_CAPACITY;
            }
        }
        servo->samples++;
    }
    return st;
}

sbr_status_t sbr_servo_jacobian(const sbr_servo_t *servo, const float *y, float *jacobian,
                                float *activation_out)
{
    sbr_status_t st = SBR_OK;
    if ((servo == NULL) || (y == NULL) || (jacobian == NULL)) {
        st = SBR_ERR_NULL;
    } else if (sbr_servo_priv_valid(servo) == 0) {
        st = SBR_ERR_STATE;
    } else if (sbr_servo_priv_values_ok(y, servo->cfg.joints) == 0) {
        st = SBR_ERR_RANGE;
    } else {
        float jac[SBR_SERVO_MAX_JOINTS * SBR_SERVO_MAX_FEATURES];
        const float wsum = sbr_servo_priv_predict(servo, y, jac);
        if (servo->count == 0u) {
            st = SBR_ERR_DEGENERATE;
        } else {
            (void)memcpy(jacobian, jac,
                         (size_t)servo->cfg.joints * (size_t)servo->cfg.features * sizeof(float));
            if (activation_out != NULL) {
                *activation_out = wsum;
            }
        }
    }
    return st;
}

sbr_status_t sbr_servo_stats(const sbr_servo_t *servo, uint32_t *fields, uint32_t *samples)
{
    sbr_status_t st = SBR_OK;
    if (servo == NULL) {
        st = SBR_ERR_NULL;
    } else if (sbr_servo_priv_valid(servo) == 0) {
        st = SBR_ERR_STATE;
    } else {
        if (fields != NULL) {
            *fields = servo->count;
        }
        if (samples != NULL) {
            *samples = servo->samples;
        }
    }
    return st;
}
