/* SPDX-License-Identifier: MIT */
/* Unity tests of conics (include/sbr/conic.h): classification, ellipse geometry, the
   direct fit, residual and coverage, torchlight pose and ellipse detection. */
#include "unity.h"
#include "sbr/conic.h"
#include "test_support.h"

#include <math.h>
#include <string.h>

#define PI_F 3.14159265f

void setUp(void) {}
void tearDown(void) {}

static sbr_conic_t mk(float a, float b, float c, float d, float e, float f)
{
    sbr_conic_t q;
    q.a = a;
    q.b = b;
    q.c = c;
    q.d = d;
    q.e = e;
    q.f = f;
    return q;
}

/* C' = H^T C H for H = rotation by t, translation (tx, ty), scale s: the same class. */
static sbr_conic_t moved(sbr_conic_t q, float t, float tx, float ty, float s)
{
    const float h[9] = {cosf(t), -sinf(t), tx, sinf(t), cosf(t), ty, 0.0f, 0.0f, 1.0f};
    const float c[9] = {q.a, q.b, q.d, q.b, q.c, q.e, q.d, q.e, q.f};
    float ch[9];
    float r[9];
    int i;
    int j;
    int k;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            ch[i * 3 + j] = 0.0f;
            for (k = 0; k < 3; k++) {
                ch[i * 3 + j] += c[i * 3 + k] * h[k * 3 + j];
            }
        }
    }
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            r[i * 3 + j] = 0.0f;
            for (k = 0; k < 3; k++) {
                r[i * 3 + j] += h[k * 3 + i] * ch[k * 3 + j];
            }
        }
    }
    return mk(s * r[0], s * r[1], s * r[4], s * r[2], s * r[5], s * r[8]);
}

static void expect_class(sbr_conic_t q, sbr_conic_class_t want)
{
    sbr_conic_class_t got = (sbr_conic_class_t)0;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&q, 0.0f, &got));
    TEST_ASSERT_EQUAL_INT(want, got);
    /* the same conic moved (inverse of a translation by (3, -2) after a rotation),
       scaled by -2.5, at the float tolerance */
    q = moved(q, 0.6f, 3.0f, -2.0f, -2.5f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&q, SBR_CONIC_ZERO_TOL, &got));
    TEST_ASSERT_EQUAL_INT(want, got);
}

static void test_classify_every_case(void)
{
    sbr_conic_class_t cls;
    sbr_conic_t q;
    expect_class(mk(0.25f, 0.0f, 1.0f, 0.0f, 0.0f, -1.0f), SBR_CONIC_REAL_ELLIPSE);
    expect_class(mk(1.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f), SBR_CONIC_IMAGINARY_ELLIPSE);
    expect_class(mk(1.0f, 0.0f, 2.0f, 0.0f, 0.0f, 0.0f), SBR_CONIC_POINT_ELLIPSE);
    expect_class(mk(1.0f, 0.0f, 0.0f, 0.0f, -0.5f, 0.0f), SBR_CONIC_PARABOLA);
    expect_class(mk(1.0f, 0.0f, 0.0f, 0.0f, 0.0f, -1.0f), SBR_CONIC_PARALLEL_LINES);
    expect_class(mk(1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f), SBR_CONIC_IMAGINARY_PARALLEL_LINES);
    expect_class(mk(1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f), SBR_CONIC_DOUBLE_LINE);
    expect_class(mk(1.0f, 0.0f, -1.0f, 0.0f, 0.0f, -1.0f), SBR_CONIC_HYPERBOLA);
    expect_class(mk(1.0f, 0.0f, -1.0f, 0.0f, 0.0f, 0.0f), SBR_CONIC_INTERSECTING_LINES);
    /* the thesis's sign rule with det(C) < 0 and a + c > 0: a real ellipse */
    q = mk(2.0f, 0.5f, 1.0f, 0.3f, -0.2f, -4.0f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&q, 0.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
    /* bad input */
    q = mk(0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_conic_classify(&q, 0.0f, &cls));
    q = mk(NAN, 0.0f, 1.0f, 0.0f, 0.0f, -1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_classify(&q, 0.0f, &cls));
    q = mk(1.0f, 0.0f, 1.0f, 0.0f, 0.0f, -1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_classify(&q, -1.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_classify(&q, 1.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_conic_classify(NULL, 0.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_conic_classify(&q, 0.0f, NULL));
}

static void test_ellipse_conic_round_trip(void)
{
    const sbr_ellipse_t el = {320.5f, 240.25f, 120.0f, 45.0f, 0.3f};
    sbr_conic_t q;
    sbr_ellipse_t back;
    sbr_ellipse_t bad = el;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&el, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &back));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, el.cx, back.cx);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, el.cy, back.cy);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, el.semi_major, back.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, el.semi_minor, back.semi_minor);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, el.angle, back.angle);
    /* the angle is folded into (-pi/2, pi/2] */
    bad.angle = 0.3f + PI_F;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&bad, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &back));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.3f, back.angle);
    bad = el;
    bad.semi_minor = 130.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_to_conic(&bad, &q));
    bad.semi_minor = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_to_conic(&bad, &q));
    q = mk(1.0f, 0.0f, -1.0f, 0.0f, 0.0f, -1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_conic_to_ellipse(&q, &back));
    q = mk(1.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_conic_to_ellipse(&q, &back));
}

static uint32_t sample(const sbr_ellipse_t *el, float t0, float t1, uint32_t n, sbr_pointf_t *p)
{
    uint32_t i;
    const float cs = cosf(el->angle);
    const float sn = sinf(el->angle);
    for (i = 0u; i < n; i++) {
        const float t = t0 + (t1 - t0) * (float)i / (float)n;
        const float u = el->semi_major * cosf(t);
        const float v = el->semi_minor * sinf(t);
        p[i].x = el->cx + u * cs - v * sn;
        p[i].y = el->cy + u * sn + v * cs;
    }
    return n;
}

static void expect_fit(const sbr_ellipse_t *el, float t0, float t1, uint32_t n, int check_angle)
{
    sbr_pointf_t p[200];
    sbr_conic_t q;
    sbr_ellipse_t got;
    float rms = -1.0f;
    const float tol = 1e-4f * el->semi_major; /* 1e-4 relative to the ellipse's size */
    sample(el, t0, t1, n, p);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_fit(p, n, &q, &got));
    TEST_ASSERT_FLOAT_WITHIN(tol, el->cx, got.cx);
    TEST_ASSERT_FLOAT_WITHIN(tol, el->cy, got.cy);
    TEST_ASSERT_FLOAT_WITHIN(tol, el->semi_major, got.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(tol, el->semi_minor, got.semi_minor);
    if (check_angle) {
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, el->angle, got.angle);
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_residual(&q, p, n, &rms, NULL));
    TEST_ASSERT_TRUE(rms < 1e-3f);
}

static void test_fit_exact_points(void)
{
    const sbr_ellipse_t a = {320.5f, 240.25f, 120.0f, 45.0f, 0.3f};
    const sbr_ellipse_t b = {1000.0f, -700.0f, 9.0f, 3.0f, -1.2f};
    const sbr_ellipse_t c = {50.0f, 60.0f, 25.0f, 25.0f, 0.0f};
    const sbr_ellipse_t d = {5000.0f, 4000.0f, 800.0f, 700.0f, 1.5f};
    expect_fit(&a, 0.0f, 2.0f * PI_F, 60u, 1);
    expect_fit(&b, 0.0f, 2.0f * PI_F, 40u, 1);
    expect_fit(&c, 0.0f, 2.0f * PI_F, 36u, 0);
    expect_fit(&d, 0.0f, 2.0f * PI_F, 200u, 1);
    expect_fit(&a, 0.2f, 0.2f + PI_F, 50u, 1); /* half an arc */
    expect_fit(&a, 0.0f, 2.0f * PI_F, 5u, 1);  /* the minimum: five points */
}

static void test_fit_degenerate_sets(void)
{
    sbr_pointf_t p[40];
    sbr_conic_t q;
    sbr_ellipse_t el;
    uint32_t i;
    /* collinear */
    for (i = 0u; i < 20u; i++) {
        p[i].x = 3.0f + 2.0f * (float)i;
        p[i].y = -1.0f + 0.5f * (float)i;
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_ellipse_fit(p, 20u, &q, &el));
    /* fewer than 5 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_ellipse_fit(p, 4u, &q, &el));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_ellipse_fit(p, 0u, &q, &el));
    /* 12 points but only 3 distinct */
    for (i = 0u; i < 12u; i++) {
        p[i].x = (float)(i % 3u) * 10.0f;
        p[i].y = (float)((i % 3u) * (i % 3u));
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_ellipse_fit(p, 12u, &q, &el));
    /* all equal */
    for (i = 0u; i < 12u; i++) {
        p[i].x = 7.0f;
        p[i].y = 7.0f;
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_ellipse_fit(p, 12u, &q, &el));
    /* both branches of the hyperbola x^2 - y^2 = 1 */
    for (i = 0u; i < 40u; i++) {
        const float t = -1.5f + 3.0f * (float)(i % 20u) / 19.0f;
        p[i].x = (i < 20u ? 1.0f : -1.0f) * coshf(t) * 30.0f;
        p[i].y = sinhf(t) * 30.0f;
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_ellipse_fit(p, 40u, &q, &el));
    /* hostile values */
    p[3].x = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_fit(p, 40u, &q, &el));
    p[3].x = 2e7f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_fit(p, 40u, &q, &el));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ellipse_fit(NULL, 40u, &q, &el));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ellipse_fit(p, 40u, NULL, &el));
}

/* Regression (fuzzer findings): finite, valid-looking ellipses whose conic overflows or
   underflows float32 returned SBR_OK with NaN/Inf or a conic of another class. */
static void test_ellipse_conic_refuses_what_float_cannot_hold(void)
{
    static const sbr_ellipse_t refused[] = {
        {0.0f, 0.0f, 1e-30f, 1e-30f, 0.0f},  /* 1 / axis^2 overflows: all NaN before */
        {1e30f, 0.0f, 10.0f, 5.0f, 0.0f},    /* f = inf before */
        {0.0f, 0.0f, 1e-20f, 1e-20f, 0.3f},  /* a = inf, b = nan before */
        {0.0f, 0.0f, 1e30f, 1e30f, 0.0f},    /* classified as a double line before */
        {0.0f, 0.0f, 2e6f, 1e3f, 0.0f},      /* semi-major beyond SBR_CONIC_MAX_COORD */
        {0.0f, 0.0f, 1.0f, 5e-4f, 0.0f},     /* semi-minor below SBR_CONIC_MIN_AXIS */
    };
    const sbr_ellipse_t far = {3e3f, -2e3f, 50.0f, 20.0f, 0.2f};
    sbr_conic_t q = mk(7.0f, 7.0f, 7.0f, 7.0f, 7.0f, 7.0f);
    sbr_conic_t untouched = q;
    sbr_ellipse_t back;
    sbr_conic_class_t cls;
    uint32_t i;
    for (i = 0u; i < sizeof(refused) / sizeof(refused[0]); i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(SBR_ERR_RANGE, sbr_ellipse_to_conic(&refused[i], &q),
                                      "refused ellipse");
        TEST_ASSERT_EQUAL_MEMORY(&untouched, &q, sizeof(q)); /* nothing written */
    }
    /* in range, far from the origin: a finite real ellipse that round-trips */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&far, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&q, SBR_CONIC_ZERO_TOL, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &back));
    TEST_ASSERT_FLOAT_WITHIN(1.0f, far.cx, back.cx);
    TEST_ASSERT_FLOAT_WITHIN(1.0f, far.cy, back.cy);
    TEST_ASSERT_FLOAT_WITHIN(0.5f, far.semi_major, back.semi_major);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&back, &q));
    /* over the domain, thin to round and near to far: either refused, or a finite conic
       whose geometry comes back */
    {
        static const float centre[3] = {0.0f, 3e3f, 9.9e5f};
        static const float minor[4] = {1e-3f, 1e-2f, 1.0f, 1e3f};
        uint32_t ci;
        uint32_t mi;
        uint32_t refused_n = 0u;
        for (ci = 0u; ci < 3u; ci++) {
            for (mi = 0u; mi < 4u; mi++) {
                const sbr_ellipse_t e = {centre[ci], -centre[ci], 1e3f, minor[mi], 0.7f};
                const sbr_status_t st = sbr_ellipse_to_conic(&e, &q);
                if (st == SBR_OK) {
                    TEST_ASSERT_TRUE(isfinite(q.a) && isfinite(q.b) && isfinite(q.c) &&
                                     isfinite(q.d) && isfinite(q.e) && isfinite(q.f));
                    TEST_ASSERT_TRUE((q.a * q.c) - (q.b * q.b) > 0.0f);
                } else {
                    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, st);
                    refused_n++;
                }
            }
        }
        TEST_ASSERT_TRUE(refused_n < 12u); /* the near, round ones are taken */
    }
    /* a real ellipse centred beyond the domain: its geometry is refused, not returned */
    q = mk(1.0f, 0.0f, 1.0f, -4e6f, 0.0f, 1.5e13f); /* centre (4e6, 0), radius 1e6 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_to_ellipse(&q, &back));
}

/* Regression (fuzzer finding): one point at (-1e30, 0) against the unit circle gave
   SBR_OK with rms NaN and max 0 (the max comparison skipped the NaN). */
static void test_residual_refuses_overflow(void)
{
    const sbr_conic_t circle = mk(1.0f, 0.0f, 1.0f, 0.0f, 0.0f, -1.0f);
    const sbr_pointf_t far[1] = {{-1e30f, 0.0f}};
    const sbr_pointf_t edge[2] = {{-1e6f, 0.0f}, {0.0f, 1e6f}};
    const sbr_conic_t huge = mk(3e38f, 0.0f, 3e38f, 0.0f, 0.0f, -1.0f);
    const sbr_pointf_t two[2] = {{0.0f, 0.0f}, {1e3f, 1e3f}};
    float rms = -1.0f;
    float mx = -1.0f;
    float cov = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_residual(&circle, far, 1u, &rms, &mx));
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, rms);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_coverage(&circle, far, 1u, 1.0f, &cov));
    /* at the domain's edge the distance is finite: Sampson's (r^2 - 1) / 2r, about 5e5 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_residual(&circle, edge, 2u, &rms, &mx));
    TEST_ASSERT_TRUE(isfinite(rms) && isfinite(mx));
    TEST_ASSERT_FLOAT_WITHIN(1e2f, 5e5f, mx);
    /* a conic whose values overflow at the points */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_conic_residual(&huge, two, 2u, &rms, &mx));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_conic_residual(NULL, two, 2u, &rms, &mx));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_conic_residual(&circle, NULL, 2u, &rms, &mx));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_conic_residual(&circle, two, 2u, NULL, &mx));
}

static void test_residual_and_coverage(void)
{
    const sbr_ellipse_t el = {100.0f, 80.0f, 60.0f, 30.0f, 0.5f};
    sbr_ellipse_t bigger = el;
    sbr_pointf_t p[128];
    sbr_conic_t q;
    float rms = 0.0f;
    float mx = 0.0f;
    float cov = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&el, &q));
    /* points on a confocal-like ellipse 0.5 px outside: distance 0.5 px near the axes */
    bigger.semi_major += 0.5f;
    bigger.semi_minor += 0.5f;
    sample(&bigger, 0.0f, 2.0f * PI_F, 128u, p);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_residual(&q, p, 128u, &rms, &mx));
    TEST_ASSERT_FLOAT_WITHIN(0.03f, 0.5f, rms);
    TEST_ASSERT_FLOAT_WITHIN(0.03f, 0.5f, mx);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_coverage(&q, p, 128u, 1.0f, &cov));
    TEST_ASSERT_EQUAL_FLOAT(1.0f, cov);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_coverage(&q, p, 128u, 0.25f, &cov));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, cov); /* every point is farther than 0.25 px */
    sample(&el, 0.0f, PI_F, 128u, p);      /* half the ellipse */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_coverage(&q, p, 128u, 1.0f, &cov));
    TEST_ASSERT_FLOAT_WITHIN(1.5f / 64.0f, 0.5f, cov);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_conic_residual(&q, p, 0u, &rms, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_coverage(&q, p, 10u, 0.0f, &cov));
    q = mk(1.0f, 0.0f, -1.0f, 0.0f, 0.0f, -1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_ellipse_coverage(&q, p, 10u, 1.0f, &cov));
}

/* The torchlight conic of the thesis for a pose, times `scale`, pixel coordinates. */
static sbr_conic_t torch_conic(float n1, float n2, float z0r, float f, float scale)
{
    const float k = z0r * z0r;
    return mk(scale * (k - n1 * n1), -scale * n1 * n2, scale * (k - n2 * n2), scale * f * n1,
              scale * f * n2, -scale * f * f);
}

static void test_torch_pose_exact_and_from_fitted_points(void)
{
    static const float poses[4][3] = {{0.0f, 0.0f, 5.0f}, {0.3f, -0.2f, 4.0f},
                                      {-0.6f, 0.4f, 8.0f}, {0.8f, 0.7f, 3.0f}};
    const float f = 500.0f;
    uint32_t i;
    for (i = 0u; i < 4u; i++) {
        const float n1 = poses[i][0];
        const float n2 = poses[i][1];
        const float z0r = poses[i][2];
        sbr_conic_t q = torch_conic(n1, n2, z0r, f, -3.7f);
        sbr_torch_pose_t pose;
        sbr_ellipse_t el;
        sbr_pointf_t p[100];
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_torch_pose(&q, f, SBR_TORCH_MAX_RESIDUAL, &pose));
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, n1, pose.n1);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, n2, pose.n2);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f * z0r, z0r, pose.z0_over_r);
        TEST_ASSERT_TRUE(pose.residual < 1e-4f);
        /* through the image: points of that ellipse, fitted, then the pose */
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &el));
        sample(&el, 0.0f, 2.0f * PI_F, 100u, p);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_fit(p, 100u, &q, NULL));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_torch_pose(&q, f, SBR_TORCH_MAX_RESIDUAL, &pose));
        TEST_ASSERT_FLOAT_WITHIN(0.01f, n1, pose.n1);
        TEST_ASSERT_FLOAT_WITHIN(0.01f, n2, pose.n2);
        TEST_ASSERT_FLOAT_WITHIN(0.01f * z0r, z0r, pose.z0_over_r);
    }
}

static void test_torch_pose_rejects_what_the_model_cannot_produce(void)
{
    /* a centred, elongated, rotated ellipse: the model needs n1 = n2 = 0, i.e. a circle */
    const sbr_ellipse_t el = {0.0f, 0.0f, 100.0f, 50.0f, 0.7f};
    sbr_conic_t q;
    sbr_torch_pose_t pose;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&el, &q));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_torch_pose(&q, 500.0f, SBR_TORCH_MAX_RESIDUAL, &pose));
    TEST_ASSERT_TRUE(pose.residual > SBR_TORCH_MAX_RESIDUAL);
    q = mk(1.0f, 0.0f, -1.0f, 0.0f, 0.0f, -1.0f); /* a hyperbola */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_torch_pose(&q, 500.0f, SBR_TORCH_MAX_RESIDUAL, &pose));
    q = torch_conic(0.1f, 0.1f, 5.0f, 500.0f, 1.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_torch_pose(&q, 0.0f, SBR_TORCH_MAX_RESIDUAL, &pose));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_torch_pose(&q, NAN, SBR_TORCH_MAX_RESIDUAL, &pose));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_torch_pose(&q, 500.0f, 0.0f, &pose));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_torch_pose(&q, 500.0f, SBR_TORCH_MAX_RESIDUAL, NULL));
}

#define IW 128u
#define IH 96u
static uint8_t g_img[IH][IW];
static uint64_t g_ws[1200000u / 8u];

/* Anti-aliased filled ellipse (4 x 4 supersampling) of grey `v` over the image. */
static void draw_ellipse(const sbr_ellipse_t *el, uint8_t v)
{
    uint32_t x;
    uint32_t y;
    const float cs = cosf(el->angle);
    const float sn = sinf(el->angle);
    for (y = 0u; y < IH; y++) {
        for (x = 0u; x < IW; x++) {
            uint32_t in = 0u;
            uint32_t s;
            for (s = 0u; s < 16u; s++) {
                const float px = (float)x - 0.375f + 0.25f * (float)(s % 4u) - el->cx;
                const float py = (float)y - 0.375f + 0.25f * (float)(s / 4u) - el->cy;
                const float u = (px * cs + py * sn) / el->semi_major;
                const float w = (py * cs - px * sn) / el->semi_minor;
                in += (u * u + w * w <= 1.0f) ? 1u : 0u;
            }
            g_img[y][x] = (uint8_t)(((float)g_img[y][x] * (16.0f - (float)in) + (float)v * (float)in) / 16.0f + 0.5f);
        }
    }
}

static void test_detect_ellipse_in_an_image(void)
{
    const sbr_ellipse_t want = {52.3f, 47.6f, 30.0f, 18.0f, 0.4f};
    sbr_ellipse_detect_config_t cfg;
    sbr_ellipse_det_t det[8];
    uint32_t n = 99u;
    uint32_t i;
    uint32_t x;
    uint32_t y;
    size_t need;
    const sbr_image_t img = {IW, IH, IW, SBR_PIXEL_GRAY8, &g_img[0][0]};
    memset(g_img, 200, sizeof g_img);
    draw_ellipse(&want, 40u);
    for (y = 30u; y < 60u; y++) { /* a dark square: a region, not an ellipse */
        for (x = 92u; x < 122u; x++) {
            g_img[y][x] = 60u;
        }
    }
    sbr_ellipse_detect_config_default(&cfg);
    cfg.mser.max_nodes = 6000u;
    need = sbr_ellipse_detect_workspace_size(&cfg, IW, IH);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_ELLIPSE_DETECT_WORKSPACE_SIZE(IW, IH, 5u, 6000u, 0u, 1024u, 4096u),
                             (uint32_t)need);
    TEST_ASSERT_TRUE(need <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_detect(&img, &cfg, g_ws, need, det, 8u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_FLOAT_WITHIN(0.2f, want.cx, det[0].ellipse.cx);
    TEST_ASSERT_FLOAT_WITHIN(0.2f, want.cy, det[0].ellipse.cy);
    TEST_ASSERT_FLOAT_WITHIN(0.4f, want.semi_major, det[0].ellipse.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(0.4f, want.semi_minor, det[0].ellipse.semi_minor);
    TEST_ASSERT_FLOAT_WITHIN(0.02f, want.angle, det[0].ellipse.angle);
    TEST_ASSERT_EQUAL_UINT8(SBR_MSER_DARK, det[0].polarity);
    TEST_ASSERT_TRUE(det[0].coverage >= 0.9f && det[0].residual <= 1.0f);
    /* bad input */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_ellipse_detect(&img, &cfg, g_ws, need - 8u, det, 8u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_ellipse_detect(&img, &cfg, (uint8_t *)g_ws + 4, need, det, 8u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_ellipse_detect(&img, &cfg, g_ws, need, det, 0u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_ellipse_detect(NULL, &cfg, g_ws, need, det, 8u, &n));
    cfg.min_coverage = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_detect(&img, &cfg, g_ws, need, det, 8u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_ellipse_detect_workspace_size(&cfg, IW, IH));
    sbr_ellipse_detect_config_default(&cfg);
    cfg.mser.max_nodes = 6000u;
    {
        const sbr_image_t tiny = {2u, 2u, 2u, SBR_PIXEL_GRAY8, &g_img[0][0]};
        const sbr_image_t rgb = {IW / 3u, IH, IW, SBR_PIXEL_RGB888, &g_img[0][0]};
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_ellipse_detect(&tiny, &cfg, g_ws, need, det, 8u, &n));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_detect(&rgb, &cfg, g_ws, need, det, 8u, &n));
    }
    /* a flat image and noise: no ellipse, no crash */
    memset(g_img, 0, sizeof g_img);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_detect(&img, &cfg, g_ws, need, det, 8u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    {
        tsup_rng_t rng = {12345u};
        for (i = 0u; i < IW * IH; i++) {
            (&g_img[0][0])[i] = (uint8_t)tsup_uniform(&rng, 0.0f, 255.0f);
        }
    }
    n = 99u;
    TEST_ASSERT_TRUE(sbr_ellipse_detect(&img, &cfg, g_ws, need, det, 8u, &n) >= SBR_ERR_CAPACITY);
    TEST_ASSERT_TRUE(n <= 8u);
}

/* Issue 55, items 3-6: inputs on which float32 arithmetic decided below its own rounding
   error, each with the header's promise (exact figures from a rational computation). */
static void test_classify_scaled_and_thin_conics(void)
{
    sbr_conic_class_t cls = SBR_CONIC_HYPERBOLA;
    /* the unit circle at (1, 1) scaled by 1e20: det(C22) overflowed float32 */
    const sbr_conic_t big = mk(1e20f, 0.0f, 1e20f, -1e20f, -1e20f, 1e20f);
    /* a real ellipse of semi-axes 127.0 and 0.694 at (92.5, 26.3): (a + c) det(C) =
       -8.5e-21 exactly, f0 = 3.4e-5 of its terms (above the default tolerance) */
    const sbr_conic_t thin = mk(0.000141399403f, -4.52365712e-05f, 1.44772312e-05f, -0.0118915727f,
                                0.00380422338f, 1.0f);
    /* det(C22) = -0.104 of the quadratic part's scale: a hyperbola-like conic whose f0 is
       5.6e-9 of its terms, zero at tol 3.14e-4 by the rule conic.h states */
    const sbr_conic_t lines = mk(-0.930203319f, -0.692327857f, -0.418600738f, -28.5931358f,
                                 -14.5052252f, -404.020691f);
    sbr_ellipse_t el = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&big, SBR_CONIC_ZERO_TOL, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&big, &el));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, el.cx);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, el.cy);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, el.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, el.semi_minor);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&thin, SBR_CONIC_ZERO_TOL, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&thin, 0.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&thin, &el));
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 92.5162f, el.cx);
    TEST_ASSERT_FLOAT_WITHIN(0.01f, 26.3099f, el.cy);
    TEST_ASSERT_FLOAT_WITHIN(0.01f * 127.0018f, 127.0018f, el.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(0.01f * 0.69351f, 0.69351f, el.semi_minor);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&lines, 3.14137e-4f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_INTERSECTING_LINES, cls);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&lines, 0.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_HYPERBOLA, cls);
}

/* Issue 70, item 14: conics without a centre that the float32 path got wrong at tol = 0
   (scaled by 1/max and multiplied in plain float32: rounded or underflowed); each also
   scaled by powers of two far apart (the class of a conic does not change with its scale). */
static void expect_no_centre(sbr_conic_t q, float tol, sbr_conic_class_t want)
{
    static const int scales[5] = {0, -120, 100, -60, 37};
    uint32_t i;
    for (i = 0u; i < 5u; ++i) {
        const int k = scales[i];
        sbr_conic_t s = mk(ldexpf(q.a, k), ldexpf(q.b, k), ldexpf(q.c, k), ldexpf(q.d, k), ldexpf(q.e, k),
                           ldexpf(q.f, k));
        sbr_conic_class_t got = (sbr_conic_class_t)0;
        if ((isfinite(s.a) == 0) || (isfinite(s.d) == 0) || (isfinite(s.e) == 0) || (isfinite(s.f) == 0) ||
            ((q.f != 0.0f) && (s.f == 0.0f)) || ((q.e != 0.0f) && (s.e == 0.0f)) ||
            ((q.a != 0.0f) && (s.a == 0.0f))) {
            continue; /* that scale leaves float32's range for this conic */
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&s, tol, &got));
        TEST_ASSERT_EQUAL_INT_MESSAGE(want, got, "scaled by a power of two");
    }
}

static void test_classify_no_centre_exactly(void)
{
    /* (2x + 3y)^2 - 20x - 30y + 6: u^2 - 10u + 6 in u = 2x + 3y, two real roots */
    expect_no_centre(mk(4.0f, 6.0f, 9.0f, -10.0f, -15.0f, 6.0f), 0.0f, SBR_CONIC_PARALLEL_LINES);
    /* (5x - 2y - 55)^2 + 36^2: no real point */
    expect_no_centre(mk(25.0f, -10.0f, 4.0f, -275.0f, 110.0f, 4321.0f), 0.0f,
                     SBR_CONIC_IMAGINARY_PARALLEL_LINES);
    /* (x + y + 28)^2: one line counted twice */
    expect_no_centre(mk(1.0f, 1.0f, 1.0f, 28.0f, 28.0f, 784.0f), 0.0f, SBR_CONIC_DOUBLE_LINE);
    /* 2e-30 y - 1e4 = 0: a line (and the line at infinity), rank 2, real */
    expect_no_centre(mk(0.0f, 0.0f, 0.0f, 0.0f, 1e-30f, -1e4f), 0.0f, SBR_CONIC_PARALLEL_LINES);
    /* 1e-30 (x + y)^2 - 2e30 y: det(C) = -a e^2 != 0, a parabola, also at the default tol */
    expect_no_centre(mk(1e-30f, 1e-30f, 1e-30f, 0.0f, -1e30f, 0.0f), 0.0f, SBR_CONIC_PARABOLA);
    expect_no_centre(mk(1e-30f, 1e-30f, 1e-30f, 0.0f, -1e30f, 0.0f), SBR_CONIC_ZERO_TOL, SBR_CONIC_PARABOLA);
    /* the first three at the default tolerance too */
    expect_no_centre(mk(4.0f, 6.0f, 9.0f, -10.0f, -15.0f, 6.0f), SBR_CONIC_ZERO_TOL, SBR_CONIC_PARALLEL_LINES);
    expect_no_centre(mk(25.0f, -10.0f, 4.0f, -275.0f, 110.0f, 4321.0f), SBR_CONIC_ZERO_TOL,
                     SBR_CONIC_IMAGINARY_PARALLEL_LINES);
    expect_no_centre(mk(1.0f, 1.0f, 1.0f, 28.0f, 28.0f, 784.0f), SBR_CONIC_ZERO_TOL, SBR_CONIC_DOUBLE_LINE);
    /* and intersecting lines exactly built: (x + 2y - 3)(3x - y + 5) at tol 0 */
    expect_no_centre(mk(3.0f, 2.5f, -2.0f, -2.0f, 6.5f, -15.0f), 0.0f, SBR_CONIC_INTERSECTING_LINES);
}

/* sbr_ellipse_to_conic() refuses (SBR_ERR_RANGE) an ellipse whose float32 conic is not
   that ellipse; sbr_conic_to_ellipse() never returns geometry other than the conic's. */
static void test_ellipse_conic_far_and_thin(void)
{
    const sbr_ellipse_t far = {0.0f, -195300.234f, 35.6862755f, 12.8247557f, -0.572548985f};
    const sbr_ellipse_t thin = {1000.0f, 1000.0f, 89.3431015f, 0.279240102f, -2.0f};
    const sbr_ellipse_t fine = {1000.0f, 1000.0f, 89.3431015f, 12.0f, -1.0f};
    /* exact: centre (-0.0087, -195.31), semi-axes 17.17 and 0.280, f0 2.7e-6 of its
       terms: a point ellipse at the default tolerance */
    const sbr_conic_t cancel = mk(8.02870846f, -6.20392179f, 4.79931164f, -1211.62732f, 937.306702f,
                                  183055.219f);
    const sbr_conic_t guard = mk(7.0f, 7.0f, 7.0f, 7.0f, 7.0f, 7.0f);
    sbr_conic_t q = guard;
    sbr_ellipse_t el = {7.0f, 7.0f, 7.0f, 7.0f, 7.0f};
    sbr_conic_class_t cls = SBR_CONIC_HYPERBOLA;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_to_conic(&far, &q));
    TEST_ASSERT_EQUAL_MEMORY(&guard, &q, sizeof q);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_ellipse_to_conic(&thin, &q));
    TEST_ASSERT_EQUAL_MEMORY(&guard, &q, sizeof q);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&fine, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &el));
    TEST_ASSERT_FLOAT_WITHIN(0.1f, 1000.0f, el.cx);
    TEST_ASSERT_FLOAT_WITHIN(0.1f, 1000.0f, el.cy);
    TEST_ASSERT_FLOAT_WITHIN(0.09f, 89.3431015f, el.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(0.012f, 12.0f, el.semi_minor);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&cancel, SBR_CONIC_ZERO_TOL, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_POINT_ELLIPSE, cls);
    el.cx = 7.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_conic_to_ellipse(&cancel, &el));
    TEST_ASSERT_EQUAL_FLOAT(7.0f, el.cx);
    /* in exact arithmetic (tol 0) it is the real ellipse it is */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&cancel, 0.0f, &cls));
    TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
}

/* sbr_ellipse_fit() of nearly coincident points far from the origin: the conic it returns
   must be a real ellipse (or SBR_ERR_DEGENERATE). */
static void test_fit_returns_a_real_ellipse(void)
{
    sbr_pointf_t p[244];
    sbr_conic_t q = mk(7.0f, 7.0f, 7.0f, 7.0f, 7.0f, 7.0f);
    sbr_ellipse_t el = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    sbr_ellipse_t back = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    sbr_conic_class_t cls = SBR_CONIC_HYPERBOLA;
    sbr_status_t st;
    uint32_t i;
    p[0].x = 129.048584f;
    p[0].y = 60.824955f;
    p[1].x = 129.126495f;
    p[1].y = 60.8251991f;
    p[2].x = 129.078201f;
    p[2].y = 60.8445282f;
    p[3].x = 128.88533f;
    p[3].y = 60.8647957f;
    for (i = 4u; i < 244u; ++i) {
        p[i].x = 129.048676f;
        p[i].y = 60.8246994f;
    }
    st = sbr_ellipse_fit(p, 244u, &q, &el);
    if (st == SBR_OK) {
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_classify(&q, 0.0f, &cls));
        TEST_ASSERT_EQUAL_INT(SBR_CONIC_REAL_ELLIPSE, cls);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_to_ellipse(&q, &back));
    } else {
        TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, st);
        TEST_ASSERT_EQUAL_FLOAT(7.0f, q.a);
    }
}

/* Issue 55, item 9: the workspace macro equals the function also when max_nodes is above
   the image's worst case (a 7 x 7 image, max_nodes 191) or 0. */
static void test_detect_workspace_macro_equals_function(void)
{
    sbr_ellipse_detect_config_t cfg;
    const uint32_t nodes[3] = {191u, 0u, 20u};
    uint32_t i;
    sbr_ellipse_detect_config_default(&cfg);
    cfg.max_regions = 1u; /* small bounds, so the MSER part decides the size */
    cfg.max_contour_points = 5u;
    for (i = 0u; i < 3u; i++) {
        cfg.mser.max_nodes = nodes[i];
        TEST_ASSERT_EQUAL_UINT32((uint32_t)sbr_ellipse_detect_workspace_size(&cfg, 7u, 7u),
                                 (uint32_t)SBR_ELLIPSE_DETECT_WORKSPACE_SIZE(7u, 7u, cfg.mser.delta, nodes[i], 0u,
                                                                             cfg.max_regions,
                                                                             cfg.max_contour_points));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_classify_every_case);
    RUN_TEST(test_detect_workspace_macro_equals_function);
    RUN_TEST(test_classify_scaled_and_thin_conics);
    RUN_TEST(test_classify_no_centre_exactly);
    RUN_TEST(test_ellipse_conic_far_and_thin);
    RUN_TEST(test_fit_returns_a_real_ellipse);
    RUN_TEST(test_ellipse_conic_round_trip);
    RUN_TEST(test_fit_exact_points);
    RUN_TEST(test_fit_degenerate_sets);
    RUN_TEST(test_ellipse_conic_refuses_what_float_cannot_hold);
    RUN_TEST(test_residual_refuses_overflow);
    RUN_TEST(test_residual_and_coverage);
    RUN_TEST(test_torch_pose_exact_and_from_fitted_points);
    RUN_TEST(test_torch_pose_rejects_what_the_model_cannot_produce);
    RUN_TEST(test_detect_ellipse_in_an_image);
    return UNITY_END();
}
