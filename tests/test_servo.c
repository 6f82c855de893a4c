/* SPDX-License-Identifier: MIT */
/* Unity tests of the servo module (include/sbr/servo.h): the learned inverse Jacobian of
   known linear plants, servoing a planar two-link arm learned from its own random
   motions, angle features, the trust bound and the stopping rule, and every documented
   status. */
#include "unity.h"
#include "sbr/servo.h"
#include "test_status_table.h"
#include "test_support.h"

#include <math.h>
#include <string.h>

#define PI_F 3.14159265f

void setUp(void) {}
void tearDown(void) {}

static uint32_t g_ws[SBR_SERVO_WORKSPACE_SIZE(256u, 5u, 3u) / 4u + 1u];

static void init_or_fail(sbr_servo_t *s, const sbr_servo_config_t *cfg)
{
    TEST_ASSERT_TRUE(sbr_servo_workspace_size(cfg) <= sizeof g_ws);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_init(s, cfg, g_ws, sizeof g_ws));
}

/* `samples` random motions dy (m values, uniform in +-0.1) at y = 0 of the linear plant
   dx = A dy (A: n x m, row-major), each learned. */
static void learn_linear(sbr_servo_t *s, const float *a, uint32_t m, uint32_t n, int samples, uint32_t seed)
{
    tsup_rng_t r;
    const float y[SBR_SERVO_MAX_JOINTS] = {0.0f};
    int i;
    uint32_t k;
    uint32_t c;
    r.s = seed;
    for (i = 0; i < samples; i++) {
        float dy[SBR_SERVO_MAX_JOINTS];
        float dx[SBR_SERVO_MAX_FEATURES];
        for (k = 0u; k < m; k++) {
            dy[k] = tsup_uniform(&r, -0.1f, 0.1f);
        }
        for (k = 0u; k < n; k++) {
            dx[k] = 0.0f;
            for (c = 0u; c < m; c++) {
                dx[k] += a[k * m + c] * dy[c];
            }
        }
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(s, y, dy, dx));
    }
}

/* A J = I (n x n) within tol, for A n x m and J m x n. */
static void assert_right_inverse(const float *a, const float *jac, uint32_t m, uint32_t n, float tol)
{
    uint32_t k;
    uint32_t c;
    uint32_t i;
    for (k = 0u; k < n; k++) {
        for (c = 0u; c < n; c++) {
            float v = 0.0f;
            for (i = 0u; i < m; i++) {
                v += a[k * m + i] * jac[i * n + c];
            }
            TEST_ASSERT_FLOAT_WITHIN(tol, (k == c) ? 1.0f : 0.0f, v);
        }
    }
}

/* A linear plant dx = A dy (3 x 3, invertible): with one field (wide), the learned J is
   A^-1 (A J = I). */
void test_linear_plant_gives_the_inverse(void)
{
    const float a[9] = {40.0f, 5.0f, 0.0f, -3.0f, 30.0f, 2.0f, 0.0f, 1.0f, 2.0f};
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    float y[3] = {0.0f, 0.0f, 0.0f};
    float jac[9];
    float act = 0.0f;
    uint32_t fields = 0u;
    uint32_t n = 0u;
    sbr_servo_config_default(&cfg, 3u, 3u);
    cfg.width[0] = cfg.width[1] = cfg.width[2] = 100.0f;
    cfg.forgetting = 1.0f;
    cfg.prior = 1.0e5f; /* little shrinkage towards 0 after 60 samples */
    init_or_fail(&s, &cfg);
    TEST_ASSERT_EQUAL(SBR_ERR_DEGENERATE, sbr_servo_jacobian(&s, y, jac, NULL));
    learn_linear(&s, a, 3u, 3u, 60, 7u);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_jacobian(&s, y, jac, &act));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, act);
    assert_right_inverse(a, jac, 3u, 3u, 1e-3f);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_stats(&s, &fields, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, fields);
    TEST_ASSERT_EQUAL_UINT32(60u, n);
}

/* A redundant plant (5 joints, 3 features) learned from isotropic motions: the learned J
   tends to the minimum-norm inverse, so J_img J = I. */
void test_redundant_plant_gives_a_right_inverse(void)
{
    const float a[15] = {30.0f, 10.0f, 0.0f, 5.0f, 0.0f, 0.0f, 25.0f, -8.0f, 0.0f, 3.0f,
                         0.0f, 0.0f, 1.0f, 1.0f, 1.0f};
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    float y[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    float jac[15];
    int k;
    sbr_servo_config_default(&cfg, 5u, 3u);
    for (k = 0; k < 5; k++) {
        cfg.width[k] = 100.0f;
    }
    cfg.forgetting = 1.0f;
    init_or_fail(&s, &cfg);
    learn_linear(&s, a, 5u, 3u, 3000, 11u);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_jacobian(&s, y, jac, NULL));
    assert_right_inverse(a, jac, 5u, 3u, 0.05f);
}

/* A planar two-link arm seen from above: x = (u, v) pixels of its tip. */
static void arm2(const float *q, float *x)
{
    x[0] = 320.0f + 150.0f * cosf(q[0]) + 110.0f * cosf(q[0] + q[1]);
    x[1] = 240.0f + 150.0f * sinf(q[0]) + 110.0f * sinf(q[0] + q[1]);
}

/* Learned from 1500 random motions (random walks from random configurations), then 100 servo runs from random
   starts to random targets, learning the executed steps: at least 95 of them within 0.5
   pixel in 30 steps. */
void test_two_link_arm_learned_and_servoed(void)
{
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    tsup_rng_t r = {3u};
    float q[2] = {0.5f, 1.0f};
    float x[2];
    int i;
    int ok = 0;
    uint32_t iters_sum = 0u;
    sbr_servo_config_default(&cfg, 2u, 2u);
    cfg.joint_min[0] = -PI_F;
    cfg.joint_max[0] = PI_F;
    cfg.joint_min[1] = 0.3f;
    cfg.joint_max[1] = 2.8f;
    cfg.tolerance[0] = cfg.tolerance[1] = 0.5f;
    cfg.width[0] = cfg.width[1] = 0.3f; /* 0.5: 95 of 100, but slower near the stretched arm */
    init_or_fail(&s, &cfg);
    for (i = 0; i < 1500; i++) {
        float dy[2];
        float q2[2];
        float x2[2];
        float dx[2];
        if ((i % 25) == 0) { /* a new random configuration now and then: the whole space */
            q[0] = tsup_uniform(&r, -3.0f, 3.0f);
            q[1] = tsup_uniform(&r, 0.4f, 2.7f);
        }
        dy[0] = tsup_uniform(&r, -0.08f, 0.08f);
        dy[1] = tsup_uniform(&r, -0.08f, 0.08f);
        q2[0] = q[0] + dy[0];
        q2[1] = q[1] + dy[1];
        if ((q2[0] < -PI_F) || (q2[0] > PI_F) || (q2[1] < 0.3f) || (q2[1] > 2.8f)) {
            continue;
        }
        arm2(q, x);
        arm2(q2, x2);
        dx[0] = x2[0] - x[0];
        dx[1] = x2[1] - x[1];
        (void)sbr_servo_learn(&s, q, dy, dx); /* may report CAPACITY when the bound is hit */
        q[0] = q2[0];
        q[1] = q2[1];
    }
    for (i = 0; i < 100; i++) {
        float qt[2];
        float xt[2];
        float qc[2];
        sbr_servo_run_t run;
        sbr_servo_result_t res = SBR_SERVO_STEP;
        qt[0] = tsup_uniform(&r, -2.5f, 2.5f);
        qt[1] = tsup_uniform(&r, 0.5f, 2.6f);
        qc[0] = qt[0] + tsup_uniform(&r, -0.5f, 0.5f);
        qc[1] = qt[1] + tsup_uniform(&r, -0.4f, 0.4f);
        qc[1] = (qc[1] < 0.3f) ? 0.3f : ((qc[1] > 2.8f) ? 2.8f : qc[1]); /* a start within the limits */
        arm2(qt, xt);
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_run_start(&run));
        while (res == SBR_SERVO_STEP) {
            float qn[2];
            float xn[2];
            float dy[2];
            float dx[2];
            arm2(qc, x);
            if (sbr_servo_step(&s, &run, qc, x, xt, qn, &res) != SBR_OK) {
                break;
            }
            if (res == SBR_SERVO_STEP) {
                arm2(qn, xn);
                dy[0] = qn[0] - qc[0];
                dy[1] = qn[1] - qc[1];
                dx[0] = xn[0] - x[0];
                dx[1] = xn[1] - x[1];
                (void)sbr_servo_learn(&s, qc, dy, dx);
                qc[0] = qn[0];
                qc[1] = qn[1];
            }
        }
        if (res == SBR_SERVO_CONVERGED) {
            ok++;
            iters_sum += run.iterations;
        }
    }
    TEST_ASSERT_GREATER_OR_EQUAL_INT(95, ok);
    TEST_ASSERT_TRUE(iters_sum <= 10u * (uint32_t)ok); /* a mean of at most 10 steps */
}

/* An angle feature: a deviation across the +-pi seam is the short way round, and the step
   turns the joint by it (not by almost 2 pi). */
void test_angle_feature_wraps(void)
{
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    sbr_servo_run_t run;
    sbr_servo_result_t res;
    float y[1] = {0.0f};
    float dy[1] = {0.1f};
    float dx[1] = {0.1f - 2.0f * PI_F}; /* the same turn, seen one revolution off */
    float x[1] = {PI_F - 0.05f};
    float xw[1] = {-PI_F + 0.05f}; /* 0.1 rad further counter-clockwise */
    float yn[1];
    float jac[1];
    sbr_servo_config_default(&cfg, 1u, 1u);
    cfg.angle_mask = 1u;
    cfg.gain = 1.0f;
    cfg.prior = 1.0e5f;
    cfg.tolerance[0] = 0.01f;
    init_or_fail(&s, &cfg);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(&s, y, dy, dx));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_jacobian(&s, y, jac, NULL));
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 1.0f, jac[0]);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_run_start(&run));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_SERVO_STEP, res);
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 0.1f, yn[0]);
}

/* The trust bound scales the whole step (its direction is kept); limits clamp; the run
   stops at max_iterations; converged leaves y as it is (also in place). */
void test_trust_bound_limits_and_stopping(void)
{
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    sbr_servo_run_t run;
    sbr_servo_result_t res;
    float y[2] = {0.0f, 0.0f};
    float dy[2] = {0.01f, 0.0f};
    float dx[2] = {1.0f, 0.0f};
    float dy2[2] = {0.0f, 0.02f};
    float dx2[2] = {0.0f, 1.0f};
    float x[2] = {0.0f, 0.0f};
    float xw[2] = {100.0f, 50.0f}; /* wanted: dy = (1.0, 1.0) before the bound */
    float yn[2];
    int i;
    sbr_servo_config_default(&cfg, 2u, 2u);
    cfg.gain = 1.0f;
    cfg.max_step[0] = 0.1f;
    cfg.max_step[1] = 0.5f;
    cfg.joint_max[1] = 0.05f;
    cfg.max_iterations = 3u;
    cfg.forgetting = 1.0f;
    init_or_fail(&s, &cfg);
    for (i = 0; i < 4; i++) {
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(&s, y, dy, dx));
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(&s, y, dy2, dx2));
    }
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_run_start(&run));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_SERVO_STEP, res);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.1f, yn[0]);  /* joint 0 at its bound of 0.1 */
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.05f, yn[1]); /* 0.1 by the scaled step, clamped */
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL_UINT32(3u, run.iterations);
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_SERVO_LIMIT, res);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, yn[0]);
    xw[0] = 0.5f;
    xw[1] = -0.5f; /* within the default tolerance of 1 */
    y[0] = 0.02f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step(&s, &run, y, x, xw, y, &res));
    TEST_ASSERT_EQUAL(SBR_SERVO_CONVERGED, res);
    TEST_ASSERT_EQUAL_FLOAT(0.02f, y[0]);
}

/* A given inverse Jacobian (sbr_servo_step_with): without a limit in the way the step is
   -gain J d; a joint the step would take beyond its limit is held there and the other
   joints make up the wanted change (plant x = A y, A = [[1 0 1] [0 1 1]]). */
void test_step_with_holds_joints_at_limits(void)
{
    /* J = A^T (A A^T)^-1, the minimum-norm inverse of A */
    const float jac[6] = {2.0f / 3.0f, -1.0f / 3.0f, -1.0f / 3.0f, 2.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};
    sbr_servo_config_t cfg;
    sbr_servo_run_t run;
    sbr_servo_result_t res;
    float y[3] = {0.0f, 0.0f, 0.0f};
    const float x[2] = {0.0f, 0.0f};
    const float xw[2] = {0.3f, 0.3f};
    float yn[3];
    sbr_servo_config_default(&cfg, 3u, 2u);
    cfg.gain = 1.0f;
    cfg.tolerance[0] = cfg.tolerance[1] = 1e-3f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_run_start(&run));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_SERVO_STEP, res);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.1f, yn[0]); /* J (0.3, 0.3) = (0.1, 0.1, 0.2) */
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.1f, yn[1]);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.2f, yn[2]);
    cfg.max_step[0] = cfg.max_step[1] = cfg.max_step[2] = 1.0f;
    cfg.joint_max[2] = 0.05f; /* joint 2 may move 0.05 only: joints 0 and 1 do the rest */
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.05f, yn[2]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.3f, yn[0] + yn[2]); /* A yn = the wanted (0.3, 0.3) */
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.3f, yn[1] + yn[2]);
    y[2] = 0.05f; /* already at the limit: held, the others take the whole step */
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL_FLOAT(0.05f, yn[2]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.3f, yn[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.3f, yn[1]);
    cfg.max_step[0] = cfg.max_step[1] = 0.1f; /* the re-solved step keeps the trust bound */
    TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.1f, yn[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.1f, yn[1]);
    TEST_ASSERT_EQUAL_UINT32(4u, run.iterations);
    /* statuses */
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_servo_step_with(&cfg, &run, NULL, y, x, xw, yn, &res));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_servo_step_with(NULL, &run, jac, y, x, xw, yn, &res));
    {
        float bad[6];
        sbr_servo_run_t fresh;
        sbr_servo_config_t c2 = cfg;
        (void)memcpy(bad, jac, sizeof bad);
        bad[3] = NAN;
        TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_servo_step_with(&cfg, &run, bad, y, x, xw, yn, &res));
        y[2] = 0.06f; /* outside its limit */
        TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_servo_step_with(&cfg, &run, jac, y, x, xw, yn, &res));
        y[2] = 0.05f;
        c2.gain = 0.0f;
        TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_servo_step_with(&c2, &run, jac, y, x, xw, yn, &res));
        (void)memset(&fresh, 0, sizeof fresh); /* never started */
        TEST_ASSERT_EQUAL(SBR_ERR_STATE, sbr_servo_step_with(&cfg, &fresh, jac, y, x, xw, yn, &res));
        TEST_ASSERT_EQUAL_UINT32(4u, run.iterations); /* refused calls take no step */
    }
}

/* Fields are created where the samples are, up to max_fields; then CAPACITY. */
void test_fields_and_capacity(void)
{
    sbr_servo_config_t cfg;
    sbr_servo_t s;
    float dy[1] = {0.1f};
    float dx[1] = {1.0f};
    uint32_t fields = 0u;
    int i;
    sbr_servo_config_default(&cfg, 1u, 1u);
    cfg.max_fields = 3u;
    cfg.width[0] = 0.1f;
    init_or_fail(&s, &cfg);
    for (i = 0; i < 3; i++) {
        float y[1];
        y[0] = (float)i; /* 10 widths apart: a field each */
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(&s, y, dy, dx));
    }
    {
        float y[1] = {1.02f}; /* near field 1: learned there, no new field */
        float far[1] = {2.0f + 1.0f};
        float jac[1];
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_learn(&s, y, dy, dx));
        TEST_ASSERT_EQUAL(SBR_ERR_CAPACITY, sbr_servo_learn(&s, far, dy, dx));
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_stats(&s, &fields, NULL));
        TEST_ASSERT_EQUAL_UINT32(3u, fields);
        float act = 1.0f;
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_jacobian(&s, y, jac, &act));
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.1f, jac[0]);
        TEST_ASSERT_TRUE(act > 0.9f);
        TEST_ASSERT_EQUAL(SBR_OK, sbr_servo_jacobian(&s, far, jac, &act)); /* the nearest field's */
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.1f, jac[0]);
        TEST_ASSERT_TRUE(act < SBR_SERVO_MIN_ACTIVATION);
    }
}

void test_servo_h_statuses(void)
{
    status_table_t t;
    sbr_servo_config_t cfg;
    sbr_servo_config_t bad;
    sbr_servo_t s;
    sbr_servo_t blank;
    sbr_servo_run_t run;
    sbr_servo_run_t norun;
    sbr_servo_result_t res;
    float y[2] = {0.0f, 0.0f};
    float dy[2] = {0.1f, 0.0f};
    float dx[2] = {1.0f, 0.0f};
    float nan2[2] = {0.0f, NAN};
    float out[4];
    memset(&t, 0, sizeof t);
    memset(&blank, 0, sizeof blank);
    memset(&norun, 0, sizeof norun);
    sbr_servo_config_default(&cfg, 2u, 2u);
    sbr_servo_config_default(NULL, 2u, 2u); /* no-op */
    ROW(&t, SBR_OK, sbr_servo_config_check(&cfg));
    ROW(&t, SBR_ERR_NULL, sbr_servo_config_check(NULL));
    bad = cfg;
    bad.joints = 9u;
    ROW(&t, SBR_ERR_SIZE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.features = 0u;
    ROW(&t, SBR_ERR_SIZE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.max_fields = SBR_SERVO_MAX_FIELDS + 1u;
    ROW(&t, SBR_ERR_SIZE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.angle_mask = 4u; /* feature 2 of 2 */
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.width[1] = NAN;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.forgetting = 0.5f;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.gain = 1.5f;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.joint_min[0] = 4.0f; /* above its max */
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.tolerance[1] = -1.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.new_field_activation = 1.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    bad = cfg;
    bad.max_iterations = 0u;
    ROW(&t, SBR_ERR_RANGE, sbr_servo_config_check(&bad));
    ROW(&t, SBR_ERR_NULL, sbr_servo_init(NULL, &cfg, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_servo_init(&s, &cfg, NULL, sizeof g_ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_servo_init(&s, &cfg, g_ws, sbr_servo_workspace_size(&cfg) - 1u));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_servo_init(&s, &cfg, (uint8_t *)g_ws + 1, sizeof g_ws - 4u));
    bad = cfg;
    bad.joints = 0u;
    ROW(&t, SBR_ERR_SIZE, sbr_servo_init(&s, &bad, g_ws, sizeof g_ws));
    ROW(&t, SBR_OK, sbr_servo_init(&s, &cfg, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_STATE, sbr_servo_learn(&blank, y, dy, dx));
    ROW(&t, SBR_ERR_NULL, sbr_servo_learn(&s, NULL, dy, dx));
    ROW(&t, SBR_ERR_RANGE, sbr_servo_learn(&s, y, dy, nan2));
    ROW(&t, SBR_ERR_RANGE, sbr_servo_learn(&s, nan2, dy, dx));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_servo_jacobian(&s, y, out, NULL));
    ROW(&t, SBR_OK, sbr_servo_run_start(&run));
    {
        float xw0[2] = {50.0f, 0.0f};
        ROW(&t, SBR_ERR_DEGENERATE, sbr_servo_step(&s, &run, y, dx, xw0, out, &res));
    }
    ROW(&t, SBR_OK, sbr_servo_learn(&s, y, dy, dx));
    ROW(&t, SBR_OK, sbr_servo_jacobian(&s, y, out, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_servo_jacobian(&s, y, NULL, NULL));
    ROW(&t, SBR_ERR_STATE, sbr_servo_jacobian(&blank, y, out, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_servo_jacobian(&s, nan2, out, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_servo_run_start(NULL));
    ROW(&t, SBR_OK, sbr_servo_run_start(&run));
    ROW(&t, SBR_ERR_STATE, sbr_servo_step(&s, &norun, y, dx, y, out, &res));
    ROW(&t, SBR_ERR_STATE, sbr_servo_step(&blank, &run, y, dx, y, out, &res));
    ROW(&t, SBR_ERR_NULL, sbr_servo_step(&s, &run, y, dx, y, out, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_servo_step(&s, &run, y, nan2, y, out, &res));
    {
        float outside[2] = {4.0f, 0.0f};
        float far[2] = {3.0f, -3.0f};
        float xw[2] = {50.0f, 0.0f};
        ROW(&t, SBR_ERR_RANGE, sbr_servo_step(&s, &run, outside, dx, xw, out, &res));
        ROW(&t, SBR_OK, sbr_servo_step(&s, &run, far, dx, xw, out, &res)); /* nearest field */
        ROW(&t, SBR_OK, sbr_servo_step(&s, &run, y, dx, xw, out, &res));
    }
    ROW(&t, SBR_ERR_NULL, sbr_servo_stats(NULL, NULL, NULL));
    ROW(&t, SBR_ERR_STATE, sbr_servo_stats(&blank, NULL, NULL));
    ROW(&t, SBR_OK, sbr_servo_stats(&s, NULL, NULL));
    TEST_ASSERT_EQUAL_size_t(0u, sbr_servo_workspace_size(&bad));
    TEST_ASSERT_EQUAL_size_t(SBR_SERVO_WORKSPACE_SIZE(128u, 2u, 2u), sbr_servo_workspace_size(&cfg));
    status_table_check(&t);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_linear_plant_gives_the_inverse);
    RUN_TEST(test_redundant_plant_gives_a_right_inverse);
    RUN_TEST(test_two_link_arm_learned_and_servoed);
    RUN_TEST(test_angle_feature_wraps);
    RUN_TEST(test_trust_bound_limits_and_stopping);
    RUN_TEST(test_step_with_holds_joints_at_limits);
    RUN_TEST(test_fields_and_capacity);
    RUN_TEST(test_servo_h_statuses);
    return UNITY_END();
}
