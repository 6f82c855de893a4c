/* SPDX-License-Identifier: MIT */
/* Visual servoing with a learned inverse image Jacobian (servo.h): the servo step (a run,
   joint limits, the small solves of the limit re-solve, the stopping rule). */
#include "sbr/servo.h"

#include <math.h>
#include <string.h>

#include "../common/sbr_util.h"
#include "servo_internal.h"

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
    sbr_servo_priv_wrap_features(c, d);
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
            (void)sbr_servo_priv_predict(servo, y, jac);
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
    } else if ((sbr_servo_priv_valid(servo) == 0) || (run->magic != RUN_MAGIC)) {
        st = SBR_ERR_STATE;
    } else if ((sbr_servo_priv_values_ok(y, servo->cfg.joints) == 0) || (sbr_servo_priv_values_ok(x, servo->cfg.features) == 0) ||
               (sbr_servo_priv_values_ok(x_wanted, servo->cfg.features) == 0) ||
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
                   ((sbr_servo_priv_values_ok(jacobian, cfg->joints * cfg->features) == 0) ||
                    (sbr_servo_priv_values_ok(y, cfg->joints) == 0) || (sbr_servo_priv_values_ok(x, cfg->features) == 0) ||
                    (sbr_servo_priv_values_ok(x_wanted, cfg->features) == 0) || (within_limits(cfg, y) == 0))) {
            st = SBR_ERR_RANGE;
        } else if (st == SBR_OK) {
            st = step_decide(cfg, NULL, jacobian, run, y, x, x_wanted, y_new, result);
        } else {
            /* the configuration's status */
        }
    }
    return st;
}
