/* SPDX-License-Identifier: MIT */
/* Unity tests of Fourier descriptors and correlation matching (include/sbr/fd.h). */
#include "unity.h"
#include "sbr/fd.h"
#include "test_support.h"
#include "../lib/fd/fd_match.h" /* the table matcher's four-lane refinement */

#include <math.h>
#include <string.h>

#define NPTS 40u
#define PI_F 3.14159265f
#define DEG (PI_F / 180.0f)

static sbr_fft_t g_fft_n;  /* resampling, N = 256 */
static sbr_fft_t g_fft_p;  /* correlation, P = 64 */
static sbr_complex_t g_work[256];
static sbr_complex_t g_wide[SBR_FD_TABLE_WORK_LEN(64)];
static sbr_pointf_t g_shape[NPTS];
static sbr_pointf_t g_tmp[NPTS];
static sbr_fd_match_config_t g_cov;
static sbr_fd_match_config_t g_inv;
#define M 12u

void setUp(void)
{
    uint32_t i;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_256(&g_fft_n));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_64(&g_fft_p));
    sbr_fd_match_config_default(&g_cov);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_config_check(&g_cov));
    g_inv = g_cov;
    g_inv.mode = SBR_FD_ROTATION_INVARIANT;
    /* An irregular, asymmetric closed shape (no rotational or mirror symmetry). */
    for (i = 0; i < NPTS; i++) {
        const float a = 2.0f * PI_F * (float)i / (float)NPTS;
        const float r = 10.0f + 3.0f * cosf(2.0f * a) + 2.0f * sinf(3.0f * a + 0.4f) +
                        (i < 8u ? 4.0f : 0.0f);
        g_shape[i].x = r * cosf(a);
        g_shape[i].y = r * sinf(a);
    }
}
void tearDown(void) {}

/* Outer outline of a blocky "6": no rotational or mirror symmetry, far from a circle. */
static const sbr_pointf_t k_six[8] = {{0, 0}, {0, 10}, {6, 10}, {6, 8}, {2, 8}, {2, 6}, {6, 6}, {6, 0}};

/* The descriptor of a contour. The coefficients beyond 2M + 1 are zero, not stack
   residue: the tests that raise m on a copy (a header that no longer matches the query's)
   must see finite coefficients there, or sbr_fd_check() refuses the copy first. */
static sbr_fd_t fd_of(const sbr_pointf_t *p, uint32_t n)
{
    sbr_fd_t fd;
    (void)memset(&fd, 0, sizeof fd);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_from_pointsf(&g_fft_n, p, n, M, g_work, 256u, &fd));
    return fd;
}

static sbr_fd_match_t match(const sbr_fd_match_config_t *cfg, const sbr_fd_t *q, const sbr_fd_t *p)
{
    sbr_fd_match_t r;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&g_fft_p, cfg, q, p, g_work, 256u, &r));
    return r;
}

/* transform: rotate by theta (counter-clockwise, y up), scale, translate, start at k */
static void transform(float theta, float s, float tx, float ty, uint32_t k)
{
    uint32_t i;
    for (i = 0; i < NPTS; i++) {
        const sbr_pointf_t p = g_shape[(i + k) % NPTS];
        g_tmp[i].x = s * (p.x * cosf(theta) - p.y * sinf(theta)) + tx;
        g_tmp[i].y = s * (p.x * sinf(theta) + p.y * cosf(theta)) + ty;
    }
}

static float arc_fraction(uint32_t k)
{
    float total = 0.0f;
    float part = 0.0f;
    uint32_t i;
    for (i = 0; i < NPTS; i++) {
        const sbr_pointf_t a = g_shape[i];
        const sbr_pointf_t b = g_shape[(i + 1u) % NPTS];
        const float d = hypotf(b.x - a.x, b.y - a.y);
        if (i < k) {
            part += d;
        }
        total += d;
    }
    return part / total;
}

static void test_self_match_is_perfect(void)
{
    const sbr_fd_t a = fd_of(g_shape, NPTS);
    const sbr_fd_match_t r = match(&g_cov, &a, &a);
    float e = 0.0f;
    uint32_t k;
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, r.error);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.0f, r.rotation);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, r.scale_ratio);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, a.c[M].re); /* DC dropped */
    for (k = 0; k <= 2u * M; k++) {
        e += a.c[k].re * a.c[k].re + a.c[k].im * a.c[k].im;
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, e); /* unit energy */
}

/* Translation, scale, rotation and start point together: in rotation-invariant mode
   e ~ 0 and the rotation (within 1 deg), scale (within 1 %) and start-point shift (the
   arc-length fraction of the new start point) are recovered. */
static void test_similarity_transforms_recovered(void)
{
    static const float thetas[] = {0.0f, 37.0f, -101.5f, 179.0f};
    static const float scales[] = {1.0f, 2.5f, 0.4f, 7.0f};
    static const uint32_t starts[] = {0u, 5u, 17u, 33u};
    const sbr_fd_t proto = fd_of(g_shape, NPTS);
    uint32_t i;
    for (i = 0; i < 4u; i++) {
        const float th = thetas[i] * DEG;
        sbr_fd_t q;
        sbr_fd_match_t r;
        float dshift;
        transform(th, scales[i], 250.0f, -80.0f, starts[i]);
        q = fd_of(g_tmp, NPTS);
        r = match(&g_inv, &q, &proto);
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.0f, r.error);
        TEST_ASSERT_FLOAT_WITHIN(1.0f * DEG, th, r.rotation);
        TEST_ASSERT_FLOAT_WITHIN(0.01f * scales[i], scales[i], r.scale_ratio);
        dshift = fabsf(r.shift - arc_fraction(starts[i]));
        TEST_ASSERT_TRUE(fminf(dshift, 1.0f - dshift) < 0.005f);
        /* the centroid follows the translation */
        TEST_ASSERT_FLOAT_WITHIN(0.05f * scales[i], 250.0f + scales[i] * (proto.cx * cosf(th) - proto.cy * sinf(th)), q.cx);
        TEST_ASSERT_FLOAT_WITHIN(0.05f * scales[i], -80.0f + scales[i] * (proto.cx * sinf(th) + proto.cy * cosf(th)), q.cy);
    }
}

/* Without rotation, covariant mode also gives e ~ 0 under translation, scale and start
   point, and finds the start point. */
static void test_covariant_without_rotation(void)
{
    const sbr_fd_t proto = fd_of(g_shape, NPTS);
    sbr_fd_t q;
    sbr_fd_match_t r;
    float dshift;
    transform(0.0f, 3.0f, -40.0f, 12.0f, 21u);
    q = fd_of(g_tmp, NPTS);
    r = match(&g_cov, &q, &proto);
    TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.0f, r.error);
    TEST_ASSERT_FLOAT_WITHIN(1.0f * DEG, 0.0f, r.rotation);
    dshift = fabsf(r.shift - arc_fraction(21u));
    TEST_ASSERT_TRUE(fminf(dshift, 1.0f - dshift) < 0.005f);
}

static void rotate_six(float theta, sbr_pointf_t out[8])
{
    uint32_t i;
    for (i = 0; i < 8u; i++) {
        out[i].x = k_six[i].x * cosf(theta) - k_six[i].y * sinf(theta);
        out[i].y = k_six[i].x * sinf(theta) + k_six[i].y * cosf(theta);
    }
}

/* A "6" and a "9" (the 6 turned by 180 degrees) stay apart in covariant mode and match
   in invariant mode; a rotation bound limits what covariant mode accepts. */
static void test_six_and_nine(void)
{
    const sbr_fd_t six = fd_of(k_six, 8u);
    sbr_pointf_t p[8];
    sbr_fd_t nine;
    sbr_fd_t tilted;
    sbr_fd_match_t r;
    sbr_fd_match_config_t bounded = g_cov;
    rotate_six(PI_F, p);
    nine = fd_of(p, 8u);
    r = match(&g_inv, &nine, &six);
    TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.0f, r.error);
    TEST_ASSERT_FLOAT_WITHIN(1.0f * DEG, PI_F, fabsf(r.rotation));
    r = match(&g_cov, &nine, &six);
    TEST_ASSERT_TRUE(r.error > 0.5f);
    /* a slightly tilted 6 is still a 6 in covariant mode, within a 30 degree bound */
    bounded.max_rotation = 30.0f * DEG;
    rotate_six(10.0f * DEG, p);
    tilted = fd_of(p, 8u);
    r = match(&bounded, &tilted, &six);
    TEST_ASSERT_TRUE(r.error < 0.05f);
    TEST_ASSERT_TRUE(fabsf(r.rotation) <= 30.0f * DEG + 1e-4f);
    r = match(&bounded, &nine, &six);
    TEST_ASSERT_TRUE(r.error > 0.5f);
    TEST_ASSERT_TRUE(fabsf(r.rotation) <= 30.0f * DEG + 1e-4f);
}

/* Covariant mode with rotation bounded to 0 charges a 60 degree turn. */
static void test_covariant_penalises_rotation(void)
{
    const sbr_fd_t a = fd_of(k_six, 8u);
    sbr_pointf_t p[8];
    sbr_fd_t b;
    sbr_fd_match_t r;
    sbr_fd_match_config_t zero = g_cov;
    zero.max_rotation = 0.0f;
    rotate_six(60.0f * DEG, p);
    b = fd_of(p, 8u);
    r = match(&zero, &b, &a);
    TEST_ASSERT_TRUE(r.error > 0.5f);
    r = match(&g_inv, &b, &a);
    TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.0f, r.error);
}

/* Mirror images: the mirrored shape matches the mirrored descriptor, not the original. */
static void test_mirror(void)
{
    const sbr_fd_t a = fd_of(k_six, 8u);
    sbr_fd_t mir;
    sbr_fd_t am;
    sbr_fd_match_t r;
    uint32_t i;
    /* x -> -x, and the order reversed so the trace direction stays the same */
    for (i = 0; i < 8u; i++) {
        g_tmp[i].x = -k_six[(8u - i) % 8u].x;
        g_tmp[i].y = k_six[(8u - i) % 8u].y;
    }
    mir = fd_of(g_tmp, 8u);
    r = match(&g_inv, &mir, &a);
    TEST_ASSERT_TRUE(r.error > 0.05f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_mirror(&a, &am));
    r = match(&g_inv, &mir, &am);
    TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.0f, r.error);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_mirror(&am, &am)); /* in place, twice = identity */
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, a.c[M + 1u].re, am.c[M + 1u].re);
}

/* Traced integer contours work the same: a rasterised rectangle matches its float twin. */
static void test_integer_points(void)
{
    sbr_point_t p[4] = {{10, 10}, {10, 30}, {50, 30}, {50, 10}};
    sbr_pointf_t f[4] = {{0, 0}, {0, 2}, {4, 2}, {4, 0}};
    sbr_fd_t a;
    sbr_fd_t b;
    sbr_fd_match_t r;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_from_points(&g_fft_n, p, 4u, M, g_work, 256u, &a));
    b = fd_of(f, 4u);
    r = match(&g_cov, &a, &b);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.0f, r.error);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 10.0f, r.scale_ratio);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 30.0f, a.cx);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 20.0f, a.cy);
}

/* Smoothing weights C(n) by exp(-2 pi^2 n^2 sigma^2) and renormalises. */
static void test_smooth(void)
{
    const sbr_fd_t a = fd_of(g_shape, NPTS);
    sbr_fd_t b;
    float e = 0.0f;
    float ratio;
    uint32_t k;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_smooth(&a, 0.05f, &b));
    for (k = 0; k <= 2u * M; k++) {
        e += b.c[k].re * b.c[k].re + b.c[k].im * b.c[k].im;
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, e);
    /* relative weight of n = 3 against n = 1 */
    ratio = hypotf(b.c[M + 3u].re, b.c[M + 3u].im) / hypotf(b.c[M + 1u].re, b.c[M + 1u].im) /
            (hypotf(a.c[M + 3u].re, a.c[M + 3u].im) / hypotf(a.c[M + 1u].re, a.c[M + 1u].im));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, expf(-2.0f * PI_F * PI_F * 0.0025f * 8.0f), ratio);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_smooth(&a, 0.0f, &b));
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_smooth(&a, -0.1f, &b));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_smooth(&a, nanf(""), &b));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_smooth(&a, 0.1f, NULL));
}

static void test_table(void)
{
    sbr_fd_t protos[3];
    sbr_fd_match_t res[3];
    uint32_t best = 99u;
    sbr_fd_t q;
    sbr_pointf_t sq[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    sbr_pointf_t tri[3] = {{0, 0}, {0, 1}, {1, 0}};
    protos[0] = fd_of(sq, 4u);
    protos[1] = fd_of(g_shape, NPTS);
    protos[2] = fd_of(tri, 3u);
    transform(5.0f * DEG, 3.0f, 1.0f, 2.0f, 9u);
    q = fd_of(g_tmp, NPTS);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 3u, g_work, 256u, res, &best));
    TEST_ASSERT_EQUAL_UINT32(1u, best);
    TEST_ASSERT_TRUE(res[0].error > 0.05f && res[2].error > 0.05f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 0u, g_work, 256u, res, &best));
}

/* The four-lane table path (scratch of SBR_FD_TABLE_WORK_LEN(P)) gives every prototype the
   match sbr_fd_match() gives it, in all three modes, with a partial last block (7 = 4 + 3). */
/* The table matcher refines four pairs at once (sbr_fd_priv_corr_at_lanes()): each lane's
   correlation at its refined lag, and the result built from it, equal the one-pair
   refinement's bit for bit, whatever the lags and prototypes of the other lanes. */
static void test_refinement_lanes_equal_one_pair(void)
{
    sbr_fd_t protos[4];
    const sbr_fd_t *lane[4];
    float lag[4];
    sbr_complex_t at_d[4];
    sbr_fd_t q;
    uint32_t refined = 0u;
    uint32_t b;
    uint32_t t;
    for (b = 0u; b < 4u; b++) {
        transform((float)b * 11.0f * DEG, 1.0f + 0.5f * (float)b, 0.0f, 0.0f, 5u * b);
        protos[b] = fd_of(g_tmp, NPTS);
        protos[b].c[M + 2u].re += 0.03f * (float)b;
        lane[b] = &protos[b];
    }
    transform(17.0f * DEG, 1.5f, 1.0f, 2.0f, 3u);
    q = fd_of(g_tmp, NPTS);
    for (t = 0u; t < 6u; t++) {
        sbr_complex_t around[4][3];
        int found[4];
        int need[4];
        for (b = 0u; b < 4u; b++) {
            float d = 0.0f;
            const float base = 0.7f + (0.05f * (float)b) - (0.02f * (float)t);
            /* a concave triple (refined) except lane t % 4, a convex one (not refined) */
            around[b][0].re = base - 0.03f - (0.01f * (float)t);
            around[b][0].im = 0.01f * (float)b;
            around[b][1].re = (b == (t % 4u)) ? base - 0.1f : base;
            around[b][1].im = -0.02f;
            around[b][2].re = base - 0.05f + (0.004f * (float)b);
            around[b][2].im = 0.03f;
            found[b] = 1;
            need[b] = sbr_fd_priv_refine_offset(&g_cov, found[b], around[b], &d);
            lag[b] = (float)(3u * t + b) + d;
            refined += (uint32_t)need[b];
        }
        sbr_fd_priv_corr_at_lanes(&q, lane, lag, 64u, at_d);
        for (b = 0u; b < 4u; b++) {
            sbr_fd_match_t one;
            sbr_fd_match_t four;
            sbr_fd_priv_finish_match(64u, &g_cov, &q, &protos[b], found[b], 3u * t + b, around[b],
                                     NULL, &one);
            sbr_fd_priv_finish_match(64u, &g_cov, &q, &protos[b], found[b], 3u * t + b, around[b],
                                     (need[b] != 0) ? &at_d[b] : NULL, &four);
            TEST_ASSERT_EQUAL_MEMORY(&one, &four, sizeof one);
            TEST_ASSERT_TRUE(one.error < 4.0f);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(18u, refined); /* three of four lanes refined each time */
}

static void test_table_lanes_equal_single_matches(void)
{
    sbr_fd_t protos[7];
    sbr_fd_match_t res[7];
    sbr_fd_match_t one;
    uint32_t best = 99u;
    uint32_t i;
    uint32_t c;
    sbr_fd_t q;
    sbr_fd_match_config_t cfgs[3];
    cfgs[0] = g_cov;
    cfgs[1] = g_inv;
    cfgs[2] = g_cov;
    cfgs[2].max_rotation = 10.0f * DEG;
    for (i = 0u; i < 7u; i++) {
        transform((float)i * 25.0f * DEG, 1.0f + (float)i, (float)i, -2.0f, 3u * i);
        protos[i] = fd_of(g_tmp, NPTS);
        protos[i].c[M + 2u].re += 0.05f * (float)i; /* make them differ in shape too */
    }
    transform(30.0f * DEG, 2.0f, 0.0f, 0.0f, 5u);
    q = fd_of(g_tmp, NPTS);
    for (c = 0u; c < 3u; c++) {
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cfgs[c], &q, protos, 7u, g_wide,
                                                         SBR_FD_TABLE_WORK_LEN(64), res, &best));
        for (i = 0u; i < 7u; i++) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&g_fft_p, &cfgs[c], &q, &protos[i], g_work, 256u, &one));
            TEST_ASSERT_FLOAT_WITHIN(1e-5f, one.error, res[i].error);
            TEST_ASSERT_FLOAT_WITHIN(1e-4f, one.rotation, res[i].rotation);
            TEST_ASSERT_FLOAT_WITHIN(1e-4f, one.shift, res[i].shift);
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, one.scale_ratio, res[i].scale_ratio);
        }
    }
    /* the prototype rotated by 25 degrees (index 1) is the best covariant match of a 30-degree
       query; with a 10-degree bound, no prototype within 10 degrees matches well except
       index 1 (5 degrees away) */
    TEST_ASSERT_EQUAL_UINT32(1u, best);
    /* a corrupted coefficient in the last, partial block is caught */
    protos[6].c[M + 1u].im = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 7u, g_wide,
                                                            SBR_FD_TABLE_WORK_LEN(64), res, &best));
}

/* Screening (max_error): every match whose error is at most max_error is bit for bit the
   unscreened one, in the lane path (which then packs non-adjacent prototypes into lanes),
   the one-by-one table path and sbr_fd_match(); a screened pair gets error 4, rotation 0,
   shift 0 and only ever one whose real error is above max_error. */
static void test_screening_keeps_every_match_up_to_max_error(void)
{
    enum { NP = 22 };
    static const float k_cut[3] = {0.05f, 0.3f, 1.0f};
    sbr_fd_t protos[NP];
    sbr_fd_match_t all[NP];
    sbr_fd_match_t lanes[NP];
    sbr_fd_match_t scalar[NP];
    sbr_fd_match_t one;
    sbr_pointf_t sq[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    sbr_pointf_t tri[3] = {{0, 0}, {0, 1}, {1, 0}};
    sbr_pointf_t ell[24];
    sbr_fd_match_config_t cfgs[3];
    sbr_fd_t q;
    uint32_t best = 0u;
    uint32_t screened = 0u;
    uint32_t kept = 0u;
    uint32_t c;
    uint32_t t;
    uint32_t i;
    cfgs[0] = g_cov;
    cfgs[1] = g_inv;
    cfgs[2] = g_cov;
    cfgs[2].max_rotation = 10.0f * DEG;
    /* the shape under rotations (some close to the query), squares, triangles, ellipses */
    for (i = 0u; i < 8u; i++) {
        transform((float)i * 7.0f * DEG, 1.0f + 0.3f * (float)i, 0.0f, 0.0f, 2u * i);
        protos[i] = fd_of(g_tmp, NPTS);
        protos[i].c[M + 3u].im += 0.02f * (float)i;
    }
    for (i = 8u; i < (uint32_t)NP; i++) {
        const uint32_t kind = i % 3u;
        if (kind == 0u) {
            protos[i] = fd_of(sq, 4u);
        } else if (kind == 1u) {
            protos[i] = fd_of(tri, 3u);
        } else {
            uint32_t k;
            for (k = 0u; k < 24u; k++) {
                const float a = 2.0f * PI_F * (float)k / 24.0f;
                ell[k].x = (1.0f + 0.4f * (float)i) * cosf(a);
                ell[k].y = sinf(a);
            }
            protos[i] = fd_of(ell, 24u);
        }
    }
    transform(20.0f * DEG, 2.0f, 3.0f, -1.0f, 7u);
    q = fd_of(g_tmp, NPTS);
    for (c = 0u; c < 3u; c++) {
        sbr_fd_match_config_t cut = cfgs[c];
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cfgs[c], &q, protos, NP, g_wide,
                                                         SBR_FD_TABLE_WORK_LEN(64), all, &best));
        for (t = 0u; t < 3u; t++) {
            cut.max_error = k_cut[t];
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cut, &q, protos, NP, g_wide,
                                                             SBR_FD_TABLE_WORK_LEN(64), lanes, &best));
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cut, &q, protos, NP, g_work,
                                                             256u, scalar, &best));
            for (i = 0u; i < (uint32_t)NP; i++) {
                TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&g_fft_p, &cut, &q, &protos[i], g_work,
                                                           256u, &one));
                TEST_ASSERT_EQUAL_MEMORY(&one, &scalar[i], sizeof one);
                TEST_ASSERT_EQUAL_FLOAT(all[i].scale_ratio, lanes[i].scale_ratio);
                if (all[i].error <= k_cut[t]) {
                    TEST_ASSERT_EQUAL_MEMORY(&all[i], &lanes[i], sizeof all[i]);
                    kept++;
                } else if (memcmp(&all[i], &lanes[i], sizeof all[i]) != 0) {
                    TEST_ASSERT_EQUAL_FLOAT(4.0f, lanes[i].error);
                    TEST_ASSERT_EQUAL_FLOAT(0.0f, lanes[i].rotation);
                    TEST_ASSERT_EQUAL_FLOAT(0.0f, lanes[i].shift);
                    TEST_ASSERT_EQUAL_FLOAT(4.0f, one.error);
                    screened++;
                }
            }
        }
    }
    /* the test means something: pairs were kept and pairs were screened */
    TEST_ASSERT_TRUE(kept >= 6u);
    TEST_ASSERT_TRUE(screened >= 20u);
    /* screening does not hide a corrupt prototype, nor accept a bad threshold */
    {
        sbr_fd_match_config_t cut = g_cov;
        cut.max_error = 0.05f;
        protos[NP - 1].c[M + 1u].re = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &cut, &q, protos, NP, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), lanes, &best));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &cut, &q, &protos[NP - 1], g_work,
                                                          256u, &one));
        cut.max_error = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &cut, &q, &q, g_work, 256u, &one));
        cut.max_error = -0.01f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &cut, &q, &q, g_work, 256u, &one));
        /* 0 (the default, and what a zero-initialised configuration holds) screens
           nothing: every pair as without the field */
        TEST_ASSERT_EQUAL_FLOAT(0.0f, g_cov.max_error);
        protos[NP - 1] = protos[NP - 2];
        cut.max_error = 0.0f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cut, &q, protos, NP, g_wide,
                                                         SBR_FD_TABLE_WORK_LEN(64), lanes, &best));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, NP, g_wide,
                                                         SBR_FD_TABLE_WORK_LEN(64), all, &best));
        TEST_ASSERT_EQUAL_MEMORY(all, lanes, sizeof all);
        {
            /* the worst pair (far above the thresholds that screened pairs above) is
               correlated: a real error, not the no-match 4 */
            float worst = 0.0f;
            for (i = 0u; i < (uint32_t)NP; i++) {
                worst = (all[i].error > worst) ? all[i].error : worst;
            }
            TEST_ASSERT_TRUE(worst > 0.3f);
            TEST_ASSERT_TRUE(worst < 4.0f);
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&g_fft_p, &cut, &q, &q, g_work, 256u, &one));
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.0f, one.error);
    }
}

/* The lane path finds corrupted prototypes from the correlation they produce (a non-finite
   coefficient makes every lag non-finite) and their headers up front; the status is that of
   the first bad prototype in table order, in both modes. */
static void test_table_lanes_refuse_corrupt_prototypes(void)
{
    sbr_fd_t protos[8];
    sbr_fd_t q;
    sbr_fd_match_t res[8];
    uint32_t best = 0u;
    uint32_t c;
    uint32_t i;
    sbr_fd_match_config_t cfgs[2];
    cfgs[0] = g_inv;
    cfgs[1] = g_cov;
    transform(10.0f * DEG, 1.5f, 0.0f, 0.0f, 0u);
    q = fd_of(g_tmp, NPTS);
    for (c = 0u; c < 2u; c++) {
        const sbr_fd_match_config_t *cfg = &cfgs[c];
        for (i = 0u; i < 8u; i++) {
            protos[i] = q;
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                         SBR_FD_TABLE_WORK_LEN(64), res, &best));
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.0f, res[7].error);
        /* NaN in a full block */
        protos[2].c[3].re = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        /* every coefficient NaN (no lag is ever a peak) */
        for (i = 0u; i <= (2u * M); i++) {
            protos[2].c[i].re = NAN;
            protos[2].c[i].im = NAN;
        }
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        /* -infinity in the second block, the first block clean */
        protos[2] = q;
        protos[5].c[M - 1u].im = -INFINITY;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        /* a bad header before the bad coefficient decides the status ... */
        protos[4].m = M + 1u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                               SBR_FD_TABLE_WORK_LEN(64), res, &best));
        /* ... and a bad coefficient (5) before a bad header (6) decides it */
        protos[4] = q;
        protos[6].m = M + 1u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        protos[5] = q;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                               SBR_FD_TABLE_WORK_LEN(64), res, &best));
        protos[6] = q;
        protos[6].scale = 0.0f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        protos[6].scale = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
        protos[6] = q;
        protos[7].m = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, cfg, &q, protos, 8u, g_wide,
                                                                SBR_FD_TABLE_WORK_LEN(64), res, &best));
    }
}

static void test_degenerate_input_gets_status(void)
{
    sbr_fd_t fd;
    sbr_fd_t ok;
    sbr_fd_match_t r;
    sbr_pointf_t line[5] = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
    sbr_pointf_t same[4] = {{5, 5}, {5, 5}, {5, 5}, {5, 5}};
    sbr_pointf_t huge[3] = {{0, 0}, {2e6f, 0}, {0, 1}};
    sbr_pointf_t nanp[3] = {{0, 0}, {1, 0}, {0, 1}};
    sbr_fft_t bad;
    nanp[1].x = nanf("");
    ok = fd_of(g_shape, NPTS);
    memset(&fd, 0x77, sizeof fd);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_from_pointsf(&g_fft_n, g_shape, 0u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_fd_from_pointsf(&g_fft_n, g_shape, 1u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_fd_from_pointsf(&g_fft_n, g_shape, 2u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_fd_from_pointsf(&g_fft_n, line, 5u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_fd_from_pointsf(&g_fft_n, same, 4u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_from_pointsf(&g_fft_n, huge, 3u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_from_pointsf(&g_fft_n, nanp, 3u, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(0x77777777, (int)fd.m); /* untouched on error */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_from_pointsf(&g_fft_n, g_shape, NPTS, 0u, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_from_pointsf(&g_fft_n, g_shape, NPTS, 33u, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_from_pointsf(&g_fft_n, g_shape, NPTS, M, g_work, 255u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_from_pointsf(&g_fft_n, NULL, NPTS, M, g_work, 256u, &fd));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_from_points(&g_fft_n, NULL, NPTS, M, g_work, 256u, &fd));
    memset(&bad, 0, sizeof bad);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fd_from_pointsf(&bad, g_shape, NPTS, M, g_work, 256u, &fd));
    /* an instance with an overwritten integrity word is refused by the matcher too (it
       must not run a transform that would fail and leave a meaningless result) */
    bad = g_fft_p;
    bad.check ^= 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fd_match(&bad, &g_cov, &ok, &ok, g_work, 256u, &r));
    {
        sbr_fd_match_t res[1];
        uint32_t best = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_fd_match_table(&bad, &g_cov, &ok, &ok, 1u, g_work, 256u, res, &best));
        fd = ok;
        fd.scale = -1.0f; /* a corrupted prototype in a table stops the table */
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &g_cov, &ok, &fd, 1u, g_work, 256u, res, &best));
    }
    /* matching: mismatched M, too small P, corrupted descriptors, bad config */
    fd = ok;
    fd.m = M - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match(&g_fft_p, &g_cov, &fd, &ok, g_work, 256u, &r));
    {
        sbr_fft_t p16;
        sbr_fd_t big;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_16(&p16));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_from_pointsf(&g_fft_n, g_shape, NPTS, 8u, g_work, 256u, &big));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match(&p16, &g_cov, &big, &big, g_work, 256u, &r));
    }
    fd = ok;
    fd.scale = nanf("");
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &g_cov, &fd, &ok, g_work, 256u, &r));
    fd = ok;
    fd.c[3].im = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &g_cov, &ok, &fd, g_work, 256u, &r));
    fd = ok;
    fd.m = 1000u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_mirror(&fd, &fd));
    {
        sbr_fd_match_config_t c = g_cov;
        c.mode = (sbr_fd_mode_t)5;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &c, &ok, &ok, g_work, 256u, &r));
        c = g_cov;
        c.max_rotation = -1.0f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match(&g_fft_p, &c, &ok, &ok, g_work, 256u, &r));
    }
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_fd_match(&g_fft_p, &g_cov, &ok, &ok, g_work, 63u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_match(&g_fft_p, &g_cov, &ok, &ok, g_work, 256u, NULL));
    sbr_fd_match_config_default(NULL); /* no-op */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_match_config_check(NULL));
}

/* The descriptor check: valid descriptors pass with unit energy, damaged ones do not. */
static void test_check_reports_energy(void)
{
    sbr_fd_t fd;
    float e = -1.0f;
    transform(0.0f, 1.0f, 0.0f, 0.0f, 0u);
    fd = fd_of(g_tmp, NPTS);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&fd, &e));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, e);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&fd, NULL));
    fd.c[0].re += 1.0f; /* C(-M) = c[0] */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&fd, &e));
    TEST_ASSERT_TRUE(e > 1.5f);
    fd.c[1].im = nanf("");
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_check(&fd, &e));
    fd = fd_of(g_tmp, NPTS);
    fd.scale = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_check(&fd, &e));
    fd.scale = 1.0f;
    fd.m = SBR_FD_MAX_M + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_check(&fd, &e));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_fd_check(NULL, &e));
}

/* Regression (fuzzer finding): a NaN/Inf centroid passed the check, and sbr_fd_mirror()
   and sbr_fd_smooth() returned SBR_OK with it. */
static void test_check_refuses_non_finite_centroid(void)
{
    static const float bad[3] = {NAN, INFINITY, -INFINITY};
    sbr_fd_t fd;
    sbr_fd_t out;
    uint32_t i;
    transform(0.0f, 1.0f, 0.0f, 0.0f, 0u);
    for (i = 0u; i < 6u; i++) {
        fd = fd_of(g_tmp, NPTS);
        if (i < 3u) {
            fd.cx = bad[i];
        } else {
            fd.cy = bad[i - 3u];
        }
        memset(&out, 0x5A, sizeof(out));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_check(&fd, NULL));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_mirror(&fd, &out));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_smooth(&fd, 0.05f, &out));
        {
            sbr_fd_match_t r;
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE,
                                  sbr_fd_match(&g_fft_p, &g_cov, &fd, &fd, g_work, 256u, &r));
        }
    }
    fd = fd_of(g_tmp, NPTS);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_mirror(&fd, &out));
    TEST_ASSERT_TRUE(isfinite(out.cx) && isfinite(out.cy));
    TEST_ASSERT_EQUAL_FLOAT(-fd.cx, out.cx);
}

/* Regression (fuzzer finding): smoothing a damaged descriptor that passes the check (a DC
   term of 1e19, one tiny coefficient) returned SBR_OK with coefficients whose energy is
   not finite. */
static void test_smooth_refuses_non_finite_result(void)
{
    sbr_fd_t fd;
    sbr_fd_t out;
    float e = 0.0f;
    memset(&fd, 0, sizeof fd);
    fd.m = 1u;
    fd.scale = 1.0f;
    fd.c[0].re = 1e-19f; /* C(-1) */
    fd.c[1].re = 1e19f;  /* the DC term, 0 in any descriptor sbr computes */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&fd, &e));
    memset(&out, 0x5A, sizeof out);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_smooth(&fd, 0.0f, &out));
    TEST_ASSERT_EQUAL_HEX8(0x5Au, ((const unsigned char *)&out)[0]); /* untouched */
    /* a sound descriptor still smooths to unit energy */
    transform(0.0f, 1.0f, 0.0f, 0.0f, 0u);
    fd = fd_of(g_tmp, NPTS);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_smooth(&fd, 0.1f, &out));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&out, &e));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, e);
}

/* Issue 55, item 7: a prototype with a non-finite centre stops sbr_fd_match_table() on
   the four-lane path (work_len >= SBR_FD_TABLE_WORK_LEN) as on the single path. */
static void test_table_lanes_refuse_non_finite_centre(void)
{
    sbr_fd_t q;
    sbr_fd_t protos[6];
    sbr_fd_match_t res[6];
    uint32_t best = 99u;
    uint32_t i;
    transform(0.0f, 1.0f, 0.0f, 0.0f, 0u);
    q = fd_of(g_tmp, NPTS);
    for (i = 0u; i < 6u; i++) {
        protos[i] = q;
    }
    protos[4].cx = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 6u, g_work,
                                                            256u, res, &best));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 6u, g_wide,
                                                            SBR_FD_TABLE_WORK_LEN(64), res, &best));
    protos[4].cx = q.cx;
    protos[1].cy = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_match_table(&g_fft_p, &g_cov, &q, protos, 6u, g_wide,
                                                            SBR_FD_TABLE_WORK_LEN(64), res, &best));
    TEST_ASSERT_EQUAL_UINT32(99u, best);
}

/* Issue 55, item 8: with max_rotation 0, a query of tiny coefficients (|r|^2 underflows)
   is accepted only at rotation 0; otherwise the error is 4. */
static void test_rotation_bound_holds_for_tiny_coefficients(void)
{
    sbr_fd_t q;
    sbr_fd_t p;
    sbr_fd_match_config_t cfg = g_cov;
    sbr_fd_match_t r;
    uint32_t k;
    uint32_t pass;
    transform(0.0f, 1.0f, 0.0f, 0.0f, 0u);
    p = fd_of(g_tmp, NPTS);
    q = p;
    for (k = 0u; k <= 2u * q.m; k++) {
        q.c[k].re = 1e-30f;
        q.c[k].im = 1e-30f;
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_check(&q, NULL));
    {
        /* fd.h: a finite coefficient whose energy overflows float32 is refused */
        sbr_fd_t big = p;
        big.c[0].re = 1e20f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_fd_check(&big, NULL));
    }
    cfg.max_rotation = 0.0f;
    for (pass = 0u; pass < 2u; pass++) {
        cfg.refine = (int)pass;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&g_fft_p, &cfg, &q, &p, g_work, 256u, &r));
        TEST_ASSERT_TRUE((r.error == 4.0f) || (fabsf(r.rotation) <= cfg.max_rotation));
        {
            uint32_t best = 0u;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_table(&g_fft_p, &cfg, &q, &p, 1u, g_wide,
                                                             SBR_FD_TABLE_WORK_LEN(64), &r, &best));
            TEST_ASSERT_TRUE((r.error == 4.0f) || (fabsf(r.rotation) <= cfg.max_rotation));
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_table_lanes_refuse_non_finite_centre);
    RUN_TEST(test_rotation_bound_holds_for_tiny_coefficients);
    RUN_TEST(test_self_match_is_perfect);
    RUN_TEST(test_check_refuses_non_finite_centroid);
    RUN_TEST(test_smooth_refuses_non_finite_result);
    RUN_TEST(test_similarity_transforms_recovered);
    RUN_TEST(test_covariant_without_rotation);
    RUN_TEST(test_six_and_nine);
    RUN_TEST(test_covariant_penalises_rotation);
    RUN_TEST(test_mirror);
    RUN_TEST(test_integer_points);
    RUN_TEST(test_smooth);
    RUN_TEST(test_table);
    RUN_TEST(test_refinement_lanes_equal_one_pair);
    RUN_TEST(test_table_lanes_equal_single_matches);
    RUN_TEST(test_table_lanes_refuse_corrupt_prototypes);
    RUN_TEST(test_screening_keeps_every_match_up_to_max_error);
    RUN_TEST(test_degenerate_input_gets_status);
    RUN_TEST(test_check_reports_energy);
    return UNITY_END();
}
