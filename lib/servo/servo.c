/* SPDX-License-Identifier: MIT */
/* Visual servoing with a learned inverse image Jacobian (servo.h). */
#include "sbr/servo.h"

#include <math.h>
#include <string.h>

#include "../common/sbr_util.h"

#define SERVO_MAGIC 0x5345524Fu
#define RUN_MAGIC 0x52554E53u
#define SERVO_MAX_VALUE 1.0e6f

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

static int servo_valid(const sbr_servo_t *s)
{
    return ((s->magic == (SERVO_MAGIC ^ sbr_util_addr32(s))) && (s->fields != NULL) &&
            (sbr_servo_config_check(&s->cfg) == SBR_OK) && (s->count <= s->cfg.max_fields))
               ? 1
               : 0;
}

/* Every value finite and within +-1e6. */
static int values_ok(const float *v, uint32_t n)
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

static void wrap_features(const sbr_servo_config_t *c, float *d)
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
static float predict(const sbr_servo_t *s, const float *y, float *jac)
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
    (void)predict(s, y, jac);
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
    } else if (servo_valid(servo) == 0) {
        st = SBR_ERR_STATE;
    } else if ((values_ok(y, servo->cfg.joints) == 0) || (values_ok(dy, servo->cfg.joints) == 0) ||
               (values_ok(dx, servo->cfg.features) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        const sbr_servo_config_t *c = &servo->cfg;
        float d[SBR_SERVO_MAX_FEATURES];
        float best = 0.0f;
        uint32_t k;
        (void)memcpy(d, dx, (size_t)c->features * sizeof(float));
        wrap_features(c, d);
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
    } else if (servo_valid(servo) == 0) {
        st = SBR_ERR_STATE;
    } else if (values_ok(y, servo->cfg.joints) == 0) {
        st = SBR_ERR_RANGE;
    } else {
        float jac[SBR_SERVO_MAX_JOINTS * SBR_SERVO_MAX_FEATURES];
        const float wsum = predict(servo, y, jac);
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

sbr_status_t sbr_servo_run_start(sbr_servo_run_t *run)
{
    sbr_status_t st = SBR_OK;
    if (run == NULL) {
        st = SBR_ERR_NULL;
    } else {
        run->iterations = 0u;
        run->magic = RUN_MAGIC;
    }
    return st;
}

static int within_limits(const sbr_servo_config_t *c, const float *y)
{
    int ok = 1;
    uint32_t j;
    for (j = 0u; j < c->joints; j++) {
        if ((y[j] < c->joint_min[j]) || (y[j] > c->joint_max[j])) {
            ok = 0;
        }
    }
    return ok;
}

/* Solves the n x n system m Z = R in place for `cols` right-hand sides (R n x cols,
   row-major, becomes Z; Gauss-Jordan with partial pivoting, n <= SBR_SERVO_MAX_FEATURES);
   0 when a pivot is not above `tiny`. */
static int solve_small(float *m, float *r, uint32_t n, uint32_t cols, float tiny)
{
    int ok = 1;
    uint32_t col;
    uint32_t k;
    for (col = 0u; (col < n) && (ok != 0); col++) {
        uint32_t piv = col;
        uint32_t row;
        for (row = col + 1u; row < n; row++) {
            if (fabsf(m[(row * n) + col]) > fabsf(m[(piv * n) + col])) {
                piv = row;
            }
        }
        if (!(fabsf(m[(piv * n) + col]) > tiny)) {
            ok = 0;
        } else {
            for (k = 0u; k < n; k++) {
                const float u = m[(piv * n) + k];
                m[(piv * n) + k] = m[(col * n) + k];
                m[(col * n) + k] = u;
            }
            for (k = 0u; k < cols; k++) {
                const float t = r[(piv * cols) + k];
                r[(piv * cols) + k] = r[(col * cols) + k];
                r[(col * cols) + k] = t;
            }
            for (row = 0u; row < n; row++) {
                if (row != col) {
                    const float f = m[(row * n) + col] / m[(col * n) + col];
                    for (k = col; k < n; k++) {
                        m[(row * n) + k] -= f * m[(col * n) + k];
                    }
                    for (k = 0u; k < cols; k++) {
                        r[(row * cols) + k] -= f * r[(col * cols) + k];
                    }
                }
            }
        }
    }
    for (col = 0u; (col < n) && (ok != 0); col++) {
        for (k = 0u; k < cols; k++) {
            r[(col * cols) + k] /= m[(col * n) + col];
        }
    }
    return ok;
}

/* g = X X^T (n x n) over the joints not in `skip`, for the n x m matrix X(i, j) =
   x[i * si + j * sj] (J^T with si 1, sj n; A with si m, sj 1); then each entry scaled by
   s_i s_k for the given row scales s. */
static void scaled_gram(const float *x, uint32_t n, uint32_t m, uint32_t si, uint32_t sj,
                        uint32_t skip, const float *s, float *g)
{
    uint32_t i;
    uint32_t k;
    uint32_t j;
    for (i = 0u; i < n; i++) {
        for (k = 0u; k < n; k++) {
            float v = 0.0f;
            for (j = 0u; j < m; j++) {
                const float p = x[(i * si) + (j * sj)] * x[(k * si) + (j * sj)];
                v += (((skip >> j) & 1u) == 0u) ? p : 0.0f;
            }
            g[(i * n) + k] = s[i] * v * s[k];
        }
    }
}

/* 1 / the length of each of the n rows of X(i, j) = x[i * si + j * sj] over all m
   joints (0 for a zero row). */
static void row_scales(const float *x, uint32_t n, uint32_t m, uint32_t si, uint32_t sj, float *s)
{
    uint32_t i;
    uint32_t j;
    for (i = 0u; i < n; i++) {
        float q = 0.0f;
        for (j = 0u; j < m; j++) {
            q += x[(i * si) + (j * sj)] * x[(i * si) + (j * sj)];
        }
        s[i] = (q > 0.0f) ? (1.0f / sqrtf(q)) : 0.0f;
    }
}

/* The image Jacobian that J is a right inverse of, A = (J^T J)^-1 J^T (n x m, row-major),
   from the normal equations scaled to a unit diagonal, solved once for the m joints' right-
   hand sides; 0 when J^T J is singular. */
static int forward_of(const sbr_servo_config_t *c, const float *jac, float *a)
{
    const uint32_t n = c->features;
    const uint32_t m = c->joints;
    float sc[SBR_SERVO_MAX_FEATURES];
    int ok = 1;
    uint32_t i;
    row_scales(jac, n, m, 1u, n, sc);
    for (i = 0u; i < n; i++) {
        ok = (sc[i] > 0.0f) ? ok : 0;
    }
    if (ok != 0) {
        float g[SBR_SERVO_MAX_FEATURES * SBR_SERVO_MAX_FEATURES];
        uint32_t j;
        scaled_gram(jac, n, m, 1u, n, 0u, sc, g);
        for (i = 0u; i < n; i++) {
            for (j = 0u; j < m; j++) {
                a[(i * m) + j] = sc[i] * jac[(j * n) + i];
            }
        }
        ok = solve_small(g, a, n, m, 1.0e-6f);
        for (i = 0u; (i < n) && (ok != 0); i++) {
            for (j = 0u; j < m; j++) {
                a[(i * m) + j] *= sc[i];
            }
        }
    }
    return ok;
}

/* The free joints' minimum-norm step for the feature change r (n values) under the
   image Jacobian a (n x m): dy_F = A_F^T (A_F A_F^T + 1e-4 I)^-1 r with A's rows scaled to
   unit length (a small damping: fewer free joints than features still give a step);
   locked joints keep dy. 0 when it cannot be solved. */
static int free_step(const sbr_servo_config_t *c, const float *a, const float *r, uint32_t locked,
                     float *dy)
{
    const uint32_t n = c->features;
    const uint32_t m = c->joints;
    float g[SBR_SERVO_MAX_FEATURES * SBR_SERVO_MAX_FEATURES];
    float z[SBR_SERVO_MAX_FEATURES];
    float rs[SBR_SERVO_MAX_FEATURES];
    int ok;
    uint32_t i;
    uint32_t j;
    row_scales(a, n, m, m, 1u, rs);
    scaled_gram(a, n, m, m, 1u, locked, rs, g);
    for (i = 0u; i < n; i++) {
        g[(i * n) + i] += 1.0e-4f;
        z[i] = rs[i] * r[i];
    }
    ok = solve_small(g, z, n, 1u, 1.0e-9f);
    for (j = 0u; (j < m) && (ok != 0); j++) {
        if (((locked >> j) & 1u) == 0u) {
            float v = 0.0f;
            for (i = 0u; i < n; i++) {
                v += rs[i] * a[(i * m) + j] * z[i];
            }
            dy[j] = v;
        }
    }
    return ok;
}

/* Joints whose step dy takes them beyond a limit, as a mask; each set to reach it. */
static uint32_t lock_at_limits(const sbr_servo_config_t *c, const float *y, float *dy)
{
    uint32_t mask = 0u;
    uint32_t j;
    for (j = 0u; j < c->joints; j++) {
        const float v = y[j] + dy[j];
        if ((v < c->joint_min[j]) || (v > c->joint_max[j])) {
            dy[j] = ((v < c->joint_min[j]) ? c->joint_min[j] : c->joint_max[j]) - y[j];
            mask |= 1u << j;
        }
    }
    return mask;
}

/* The rest of the wanted change w that the locked joints leave, solved over the free
   joints (free_step()) and scaled to their trust bound; 0 when it cannot be solved. */
static int resolve_free(const sbr_servo_config_t *c, const float *a, const float *w,
                        uint32_t locked, float *dy)
{
    float r[SBR_SERVO_MAX_FEATURES];
    float s2 = 1.0f;
    int ok;
    uint32_t i;
    uint32_t j;
    for (i = 0u; i < c->features; i++) {
        r[i] = w[i];
        for (j = 0u; j < c->joints; j++) {
            r[i] -= (((locked >> j) & 1u) != 0u) ? (a[(i * c->joints) + j] * dy[j]) : 0.0f;
        }
    }
    ok = free_step(c, a, r, locked, dy);
    for (j = 0u; (j < c->joints) && (ok != 0); j++) {
        if ((((locked >> j) & 1u) == 0u) && ((fabsf(dy[j]) * s2) > c->max_step[j])) {
            s2 = c->max_step[j] / fabsf(dy[j]);
        }
    }
    for (j = 0u; (j < c->joints) && (ok != 0); j++) {
        dy[j] *= (((locked >> j) & 1u) == 0u) ? s2 : 1.0f;
    }
    return ok;
}

/* The step's command from J and the deviation d (the header's "Servo step"): dy = -gain J
   d scaled to the trust bound; joints it takes beyond a limit are held there and the free
   joints' step re-solved for the rest of the wanted change, at most m times; then the
   limits. */
static void take_step(const sbr_servo_config_t *c, const float *jac, const float *d, const float *y,
                      float *y_new)
{
    float dy[SBR_SERVO_MAX_JOINTS];
    float w[SBR_SERVO_MAX_FEATURES];
    float a[SBR_SERVO_MAX_FEATURES * SBR_SERVO_MAX_JOINTS];
    float scale = 1.0f;
    uint32_t locked = 0u;
    uint32_t pass;
    int go = 1;
    uint32_t j;
    uint32_t i;
    (void)memset(dy, 0, sizeof dy);
    for (j = 0u; j < c->joints; j++) {
        float v = 0.0f;
        for (i = 0u; i < c->features; i++) {
            v += jac[(j * c->features) + i] * d[i];
        }
        dy[j] = -c->gain * v;
        if ((fabsf(dy[j]) * scale) > c->max_step[j]) {
            scale = c->max_step[j] / fabsf(dy[j]);
        }
    }
    for (j = 0u; j < c->joints; j++) {
        dy[j] *= scale;
    }
    for (i = 0u; i < c->features; i++) {
        w[i] = -c->gain * scale * d[i];
    }
    (void)memset(a, 0, sizeof a);
    for (pass = 0u; (pass < c->joints) && (go != 0); pass++) {
        const uint32_t more = lock_at_limits(c, y, dy) & ~locked;
        locked |= more;
        if (more == 0u) {
            go = 0;
        } else if ((pass == 0u) && (forward_of(c, jac, a) == 0)) {
            go = 0; /* no image Jacobian behind J: the clamped step */
        } else {
            go = resolve_free(c, a, w, locked, dy);
        }
    }
    for (j = 0u; j < c->joints; j++) {
        float v = y[j] + dy[j];
        v = (v < c->joint_min[j]) ? c->joint_min[j] : v;
        v = (v > c->joint_max[j]) ? c->joint_max[j] : v;
        y_new[j] = v;
    }
}

/* The stopping rule, then a step with J from `servo` (or `given` when servo is NULL);
   arguments already checked. */
static sbr_status_t step_decide(const sbr_servo_config_t *c, const sbr_servo_t *servo,
                                const float *given, sbr_servo_run_t *run, const float *y,
                                const float *x, const float *x_wanted, float *y_new,
                                sbr_servo_result_t *result)
{
    sbr_status_t st = SBR_OK;
    float d[SBR_SERVO_MAX_FEATURES];
    float jac[SBR_SERVO_MAX_JOINTS * SBR_SERVO_MAX_FEATURES];
    int converged = 1;
    uint32_t i;
    for (i = 0u; i < c->features; i++) {
        d[i] = x[i] - x_wanted[i];
    }
    wrap_features(c, d);
    for (i = 0u; i < c->features; i++) {
        if (fabsf(d[i]) > c->tolerance[i]) {
            converged = 0;
        }
    }
    if (converged != 0) {
        (void)memmove(y_new, y, (size_t)c->joints * sizeof(float));
        *result = SBR_SERVO_CONVERGED;
    } else if (run->iterations >= c->max_iterations) {
        (void)memmove(y_new, y, (size_t)c->joints * sizeof(float));
        *result = SBR_SERVO_LIMIT;
    } else if ((servo != NULL) && (servo->count == 0u)) {
        st = SBR_ERR_DEGENERATE;
    } else {
        if (servo != NULL) {
            (void)predict(servo, y, jac);
        } else {
            (void)memcpy(jac, given, (size_t)c->joints * (size_t)c->features * sizeof(float));
        }
        take_step(c, jac, d, y, y_new);
        run->iterations++;
        *result = SBR_SERVO_STEP;
    }
    return st;
}

sbr_status_t sbr_servo_step(const sbr_servo_t *servo, sbr_servo_run_t *run, const float *y,
                            const float *x, const float *x_wanted, float *y_new,
                            sbr_servo_result_t *result)
{
    sbr_status_t st = SBR_OK;
    if ((servo == NULL) || (run == NULL) || (y == NULL) || (x == NULL) || (x_wanted == NULL) ||
        (y_new == NULL) || (result == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((servo_valid(servo) == 0) || (run->magic != RUN_MAGIC)) {
        st = SBR_ERR_STATE;
    } else if ((values_ok(y, servo->cfg.joints) == 0) || (values_ok(x, servo->cfg.features) == 0) ||
               (values_ok(x_wanted, servo->cfg.features) == 0) ||
               (within_limits(&servo->cfg, y) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        st = step_decide(&servo->cfg, servo, NULL, run, y, x, x_wanted, y_new, result);
    }
    return st;
}

sbr_status_t sbr_servo_step_with(const sbr_servo_config_t *cfg, sbr_servo_run_t *run,
                                 const float *jacobian, const float *y, const float *x,
                                 const float *x_wanted, float *y_new,
                                 sbr_servo_result_t *result)
{
    sbr_status_t st = SBR_OK;
    if ((cfg == NULL) || (run == NULL) || (jacobian == NULL) || (y == NULL) || (x == NULL) ||
        (x_wanted == NULL) || (y_new == NULL) || (result == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_servo_config_check(cfg);
        if ((st == SBR_OK) && (run->magic != RUN_MAGIC)) {
            st = SBR_ERR_STATE;
        } else if ((st == SBR_OK) &&
                   ((values_ok(jacobian, cfg->joints * cfg->features) == 0) ||
                    (values_ok(y, cfg->joints) == 0) || (values_ok(x, cfg->features) == 0) ||
                    (values_ok(x_wanted, cfg->features) == 0) || (within_limits(cfg, y) == 0))) {
            st = SBR_ERR_RANGE;
        } else if (st == SBR_OK) {
            st = step_decide(cfg, NULL, jacobian, run, y, x, x_wanted, y_new, result);
        } else {
            /* the configuration's status */
        }
    }
    return st;
}

sbr_status_t sbr_servo_stats(const sbr_servo_t *servo, uint32_t *fields, uint32_t *samples)
{
    sbr_status_t st = SBR_OK;
    if (servo == NULL) {
        st = SBR_ERR_NULL;
    } else if (servo_valid(servo) == 0) {
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
