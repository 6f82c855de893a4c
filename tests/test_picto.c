/* SPDX-License-Identifier: MIT */
/* Unity tests of the class stage's features and classifier (include/sbr/picto.h):
   feature values on constructed patches, RGB/BGR and scale agreement, softmax values of
   hand-made classifiers, the built-in classifier's consistency, and bad input. */
#include "unity.h"
#include "sbr/picto.h"
#include "sbr/models.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define W 128u
#define H 96u
#define F SBR_PICTO_FEATURES
#define HOG_LEN (SBR_PICTO_CELLS * SBR_PICTO_CELLS * 8u)
#define THUMB_AT HOG_LEN
#define COLOUR_AT (HOG_LEN + (SBR_PICTO_THUMB * SBR_PICTO_THUMB))
#define CENTRE_AT (COLOUR_AT + 32u)
#define CC SBR_PICTO_CENTRE_CELLS
/* the hand-made classifiers: GTSDB's 43 sign classes and the background */
#define K 43u
#define OUTPUTS (K + 1u)

static uint8_t g_rgb[H][W][3];
static uint8_t g_bgr[H][W][3];
static uint8_t g_grey[H][W];
static uint64_t g_ws[SBR_PICTO_WORKSPACE_SIZE / 8u + 1u];
static float g_f[F];
static float g_g[F];
static float g_w1[7u * (F + 1u)];
static float g_w2[OUTPUTS * (F + 1u)];
static float g_w3[SBR_PICTO_BOX_OUTPUTS * (F + 1u)];

void setUp(void) {}
void tearDown(void) {}

static sbr_image_t view(uint8_t (*px)[W][3], sbr_pixel_format_t fmt)
{
    sbr_image_t v;
    v.width = W;
    v.height = H;
    v.stride = 3u * W;
    v.format = fmt;
    v.data = &px[0][0][0];
    return v;
}

static void fill(uint8_t r, uint8_t g, uint8_t b)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = r;
            g_rgb[y][x][1] = g;
            g_rgb[y][x][2] = b;
        }
    }
}

/* Dark left half, bright right half inside [x0, x0 + s) x [y0, y0 + s), at scale k. */
static void step_edge(uint32_t x0, uint32_t y0, uint32_t s)
{
    uint32_t x;
    uint32_t y;
    fill(128u, 128u, 128u);
    for (y = y0; y < y0 + s; y++) {
        for (x = x0; x < x0 + s; x++) {
            const uint8_t v = (x < x0 + (s / 2u)) ? 40u : 220u;
            g_rgb[y][x][0] = v;
            g_rgb[y][x][1] = v;
            g_rgb[y][x][2] = v;
        }
    }
}

/* A hand-made classifier without hidden layer or box regression, all weights and the
   features zero (uniform probabilities). */
static void hand_model(sbr_picto_model_t *m)
{
    (void)memset(g_w2, 0, sizeof g_w2);
    (void)memset(g_w3, 0, sizeof g_w3);
    (void)memset(g_f, 0, sizeof g_f);
    m->version = SBR_PICTO_VERSION;
    m->features = F;
    m->hidden = 0u;
    m->classes = K;
    m->threshold = 0.5f;
    sbr_picto_looks_default(&m->looks);
    m->w1 = NULL;
    m->w2 = g_w2;
    m->w3 = NULL;
    m->rim_shape = NULL;
    m->rim_floor = NULL;
    m->gate = NULL;
    m->gate_hidden = 0u;
    m->gate_threshold = 0.0f;
}

static sbr_status_t feats(const sbr_image_t *v, float x0, float y0, float x1, float y1, float *f)
{
    const float box[4] = {x0, y0, x1, y1};
    return sbr_picto_features(v, box, f, F, g_ws, sizeof g_ws);
}

/* sbr_picto_features_outline(): the box outline is sbr_picto_features(); the triangle
   outline ignores what lies outside the triangle (the box's top corners) and puts half
   the inside's mean grey there, with that grey's chromaticity g / (3 g + 30). */
static void test_triangle_outline(void)
{
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    const float box[4] = {20.0f, 20.0f, 56.0f, 56.0f}; /* 36 px: one pixel per patch pixel */
    static float tri[F];
    uint32_t x;
    uint32_t y;
    uint32_t i;
    float most = 0.0f;
    /* uniform grey 100: outside 50, chromaticity 50 / 180 (top-left colour cell, all
       outside); inside 100 / 330 (bottom row's second cell, all inside) */
    fill(100u, 100u, 100u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE,
                                                             tri, F, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 50.0f / 180.0f, tri[COLOUR_AT]);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 50.0f / 180.0f, tri[COLOUR_AT + 1u]);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 100.0f / 330.0f, tri[COLOUR_AT + 26u]);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 100.0f / 330.0f, tri[COLOUR_AT + 27u]);
    /* a textured box: the box outline equals sbr_picto_features() bit for bit */
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = (uint8_t)(((x * 37u) + (y * 91u)) & 255u);
            g_rgb[y][x][1] = (uint8_t)(((x * 11u) + (y * 53u)) & 255u);
            g_rgb[y][x][2] = (uint8_t)(((x * 71u) + (y * 13u)) & 255u);
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, box[0], box[1], box[2], box[3], g_f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, (uint32_t)SBR_PICTO_OUTLINE_BOX, g_g, F,
                                                             g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(g_f, g_g, sizeof g_f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE,
                                                             tri, F, g_ws, sizeof g_ws));
    /* whiten both top corners (6 x 6 px, well outside the triangle): the triangle view
       stays bit for bit, the box view changes */
    for (y = 20u; y < 26u; y++) {
        for (x = 0u; x < 6u; x++) {
            (void)memset(g_rgb[y][20u + x], 255, 3u);
            (void)memset(g_rgb[y][50u + x], 255, 3u);
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE,
                                                             g_g, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(tri, g_g, sizeof tri);
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, box[0], box[1], box[2], box[3], g_g));
    for (i = 0u; i < F; i++) {
        most = fmaxf(most, fabsf(g_g[i] - g_f[i]));
    }
    TEST_ASSERT_TRUE(most > 0.01f);
    /* an outline out of range */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_features_outline(&v, box, 2u, tri, F, g_ws, sizeof g_ws));
}

/* A uniform patch has no edges (coarse or fine), a zero contrast-normalised thumbnail and
   the colour's chromaticity r / (r + g + b + 30) in every cell. */
static void test_uniform_patch(void)
{
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    uint32_t i;
    fill(200u, 50u, 50u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, 10.0f, 10.0f, 58.0f, 58.0f, g_f));
    for (i = 0u; i < COLOUR_AT; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, g_f[i]);
    }
    for (i = 0u; i < 16u; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 200.0f / 330.0f, g_f[COLOUR_AT + (2u * i)]);
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 50.0f / 330.0f, g_f[COLOUR_AT + (2u * i) + 1u]);
    }
    TEST_ASSERT_EQUAL_UINT32(F, CENTRE_AT + (CC * CC * 8u));
    for (i = CENTRE_AT; i < F; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, g_f[i]);
    }
}

/* A vertical dark-to-bright edge: all edge energy in the "gradient points right" bin
   (0) of the cells on the edge, none in the opposite bin (4); the histogram has unit
   norm; the thumbnail is negative left and positive right. */
static void test_step_edge(void)
{
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    float ss = 0.0f;
    float bin0 = 0.0f;
    uint32_t c;
    uint32_t i;
    /* two image pixels per patch pixel: no sample mixes in the grey outside the box */
    step_edge(16u, 16u, 2u * SBR_PICTO_SIZE);
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, 16.0f, 16.0f, 16.0f + (2.0f * (float)SBR_PICTO_SIZE),
                                        16.0f + (2.0f * (float)SBR_PICTO_SIZE), g_f));
    for (i = 0u; i < HOG_LEN; i++) {
        TEST_ASSERT_TRUE(g_f[i] >= 0.0f);
        ss += g_f[i] * g_f[i];
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, ss);
    for (c = 0u; c < SBR_PICTO_CELLS * SBR_PICTO_CELLS; c++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_f[(c * 8u) + 4u]); /* never bright-to-dark */
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_f[(c * 8u) + 2u]); /* no vertical gradient */
        bin0 += g_f[c * 8u];
    }
    TEST_ASSERT_TRUE(bin0 > 1.0f);
    /* middle cells carry the edge, border columns none */
    TEST_ASSERT_TRUE(g_f[((SBR_PICTO_CELLS / 2u) * 8u)] > 0.1f);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_f[0]);
    TEST_ASSERT_TRUE(g_f[THUMB_AT] < -0.9f);
    TEST_ASSERT_TRUE(g_f[THUMB_AT + SBR_PICTO_THUMB - 1u] > 0.9f);
    /* the middle half's finer cells (CC per side over patch columns PS/4 .. 3PS/4 - 1):
       the edge in the middle of the patch lies in the two middle cell columns only,
       pointing right; unit norm */
    ss = 0.0f;
    for (i = CENTRE_AT; i < F; i++) {
        ss += g_f[i] * g_f[i];
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, ss);
    for (c = 0u; c < CC; c++) {
        const float *row = &g_f[CENTRE_AT + (c * CC * 8u)];
        uint32_t cc;
        for (cc = 0u; cc < CC; cc++) {
            if ((cc == ((CC / 2u) - 1u)) || (cc == (CC / 2u))) {
                TEST_ASSERT_TRUE(row[cc * 8u] > 0.1f);            /* the edge's columns */
            } else {
                TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, row[cc * 8u]); /* the others */
            }
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, row[(cc * 8u) + 4u]); /* never bright-to-dark */
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, row[(cc * 8u) + 2u]); /* no vertical gradient */
        }
    }
}

/* The same pixels as RGB and as BGR give the same features; the same pattern at twice
   the size gives nearly the same features (area sampling). */
static void test_format_and_scale(void)
{
    sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    const sbr_image_t vb = view(g_bgr, SBR_PIXEL_BGR888);
    uint32_t x;
    uint32_t y;
    uint32_t i;
    float d = 0.0f;
    float n = 0.0f;
    fill(90u, 100u, 160u);
    for (y = 20u; y < 44u; y++) {
        for (x = 20u; x < 44u; x++) {
            const uint32_t r = ((x - 32u) * (x - 32u)) + ((y - 32u) * (y - 32u));
            g_rgb[y][x][0] = (r < 100u) ? 230u : 30u;
            g_rgb[y][x][1] = (r < 100u) ? 30u : 40u;
            g_rgb[y][x][2] = (r < 40u) ? 200u : 20u;
        }
    }
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_bgr[y][x][0] = g_rgb[y][x][2];
            g_bgr[y][x][1] = g_rgb[y][x][1];
            g_bgr[y][x][2] = g_rgb[y][x][0];
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, 20.0f, 20.0f, 44.0f, 44.0f, g_f));
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&vb, 20.0f, 20.0f, 44.0f, 44.0f, g_g));
    TEST_ASSERT_EQUAL_MEMORY(g_f, g_g, sizeof g_f);
    /* twice as large: each pixel becomes 2 x 2 */
    for (y = 0u; y < 48u; y++) {
        for (x = 0u; x < 48u; x++) {
            (void)memcpy(g_bgr[y + 40u][x + 70u], g_rgb[20u + (y / 2u)][20u + (x / 2u)], 3u);
        }
    }
    v = view(g_bgr, SBR_PIXEL_RGB888);
    TEST_ASSERT_EQUAL_INT(SBR_OK, feats(&v, 70.0f, 40.0f, 118.0f, 88.0f, g_g));
    for (i = 0u; i < F; i++) {
        d += (g_f[i] - g_g[i]) * (g_f[i] - g_g[i]);
        n += g_f[i] * g_f[i];
    }
    TEST_ASSERT_TRUE(d < 0.05f * n);
}

/* Linear classifier with biases only: the softmax of the biases. A hidden layer of one
   rectified unit: computed by hand. */
static void test_classify_values(void)
{
    sbr_picto_model_t m;
    float p[OUTPUTS];
    float sum = 0.0f;
    uint32_t i;
    hand_model(&m);
    g_w2[(5u * (F + 1u)) + F] = logf(2.0f); /* class 5: twice the weight of the others */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    for (i = 0u; i < OUTPUTS; i++) {
        sum += p[i];
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, ((i == 5u) ? 2.0f : 1.0f) / 45.0f, p[i]);
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, sum);
    /* hidden: a = max(0, 2 f0 - 1); logit of class 7 = 3 a */
    (void)memset(g_w1, 0, sizeof g_w1);
    (void)memset(g_w2, 0, sizeof g_w2);
    g_w1[0] = 2.0f;
    g_w1[F] = -1.0f;
    g_w2[7u * 2u] = 3.0f;
    m.hidden = 1u;
    m.w1 = g_w1;
    g_f[0] = 1.0f; /* a = 1, logit 3 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, expf(3.0f) / (expf(3.0f) + 43.0f), p[7]);
    g_f[0] = 0.25f; /* a = 0: uniform */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f / 44.0f, p[7]);
    /* regression (fuzzer finding): finite features so large that a logit overflows gave
       SBR_OK with NaN probabilities (a = 2 * 3e38 - 1 = inf, logit 3 a = inf) */
    g_f[0] = 3e38f;
    p[7] = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    g_f[0] = 1e6f; /* large but representable: one class takes all */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, p[7]);
    g_f[0] = 0.25f; /* as the uniform case left it */
}

/* A network with 7 hidden units (the classifier works on blocks of four units and four
   outputs: one block and a tail of three) and pseudo-random weights: its probabilities
   and refined box agree with a direct double-precision evaluation of the definitions in
   picto.h. */
static void test_classify_matches_reference(void)
{
    enum { HID = 7 };
    static float w2[OUTPUTS * (HID + 1)];
    static float w3[SBR_PICTO_BOX_OUTPUTS * (HID + 1)];
    sbr_picto_model_t m;
    double a[HID];
    double logit[OUTPUTS];
    double d[SBR_PICTO_BOX_OUTPUTS];
    double mx;
    double sum = 0.0;
    float p[OUTPUTS];
    const float box[4] = {10.0f, 20.0f, 50.0f, 40.0f};
    float r[4];
    uint32_t seed = 12345u;
    uint32_t i;
    uint32_t k;
    hand_model(&m);
    for (i = 0u; i < F; i++) {
        seed = (seed * 1664525u) + 1013904223u;
        g_f[i] = (float)((int32_t)(seed >> 20) - 2048) / 2048.0f;
    }
    for (i = 0u; i < (uint32_t)HID * (F + 1u); i++) {
        seed = (seed * 1664525u) + 1013904223u;
        g_w1[i] = (float)((int32_t)(seed >> 20) - 2048) / 40000.0f;
    }
    for (i = 0u; i < (uint32_t)OUTPUTS * (HID + 1u); i++) {
        seed = (seed * 1664525u) + 1013904223u;
        w2[i] = (float)((int32_t)(seed >> 20) - 2048) / 1024.0f;
    }
    for (i = 0u; i < (uint32_t)SBR_PICTO_BOX_OUTPUTS * (HID + 1u); i++) {
        seed = (seed * 1664525u) + 1013904223u;
        w3[i] = (float)((int32_t)(seed >> 20) - 2048) / 8192.0f;
    }
    m.hidden = HID;
    m.w1 = g_w1;
    m.w2 = w2;
    m.w3 = w3;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    for (i = 0u; i < (uint32_t)HID; i++) {
        double s = (double)g_w1[(i * (F + 1u)) + F];
        for (k = 0u; k < F; k++) {
            s += (double)g_w1[(i * (F + 1u)) + k] * (double)g_f[k];
        }
        a[i] = (s > 0.0) ? s : 0.0;
    }
    TEST_ASSERT_TRUE((a[0] > 0.0) || (a[4] > 0.0)); /* the units are not all idle */
    for (i = 0u; i < OUTPUTS; i++) {
        double s = (double)w2[(i * (HID + 1u)) + HID];
        for (k = 0u; k < (uint32_t)HID; k++) {
            s += (double)w2[(i * (HID + 1u)) + k] * a[k];
        }
        logit[i] = s;
    }
    mx = logit[0];
    for (i = 1u; i < OUTPUTS; i++) {
        mx = (logit[i] > mx) ? logit[i] : mx;
    }
    for (i = 0u; i < OUTPUTS; i++) {
        sum += exp(logit[i] - mx);
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    for (i = 0u; i < OUTPUTS; i++) {
        TEST_ASSERT_FLOAT_WITHIN(2e-6f, (float)(exp(logit[i] - mx) / sum), p[i]);
    }
    for (i = 0u; i < SBR_PICTO_BOX_OUTPUTS; i++) {
        double s = (double)w3[(i * (HID + 1u)) + HID];
        for (k = 0u; k < (uint32_t)HID; k++) {
            s += (double)w3[(i * (HID + 1u)) + k] * a[k];
        }
        d[i] = s;
    }
    TEST_ASSERT_TRUE(fabs(d[0]) < (double)SBR_PICTO_MAX_SHIFT); /* no clamping below */
    TEST_ASSERT_TRUE(fabs(d[1]) < (double)SBR_PICTO_MAX_SHIFT);
    TEST_ASSERT_TRUE(fabs(d[2]) < (double)SBR_PICTO_MAX_LOG_SCALE);
    TEST_ASSERT_TRUE(fabs(d[3]) < (double)SBR_PICTO_MAX_LOG_SCALE);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    /* centre (30, 30), half sizes 20 x 10 */
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, (float)((30.0 + 40.0 * d[0]) - 20.0 * exp(d[2])), r[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, (float)((30.0 + 40.0 * d[0]) + 20.0 * exp(d[2])), r[2]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, (float)((30.0 + 20.0 * d[1]) - 10.0 * exp(d[3])), r[1]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, (float)((30.0 + 20.0 * d[1]) + 10.0 * exp(d[3])), r[3]);
}

/* The built-in classifier passes its check; corrupted copies do not. */
static void test_builtin_and_corrupt(void)
{
    sbr_picto_model_t m;
    sbr_picto_model_t bad;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_gtsdb(NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    TEST_ASSERT_TRUE(m.hidden <= SBR_PICTO_HIDDEN_MAX);
    TEST_ASSERT_NOT_NULL(m.w3); /* it carries its box regression */
    bad = m;
    bad.version = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    bad = m;
    bad.features = F + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    bad = m;
    bad.threshold = 1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    bad.threshold = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    bad = m;
    bad.hidden = SBR_PICTO_HIDDEN_MAX + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    bad = m;
    bad.w2 = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    (void)memset(g_w2, 0, sizeof g_w2);
    bad.hidden = 0u;
    bad.w1 = NULL;
    bad.w2 = g_w2;
    bad.w3 = NULL; /* the built-in rows are sized for its hidden layer, not for hidden = 0 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&bad));
    g_w2[100] = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    g_w2[100] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_check(NULL));
}

/* The rim outlines of picto.h, written out independently: (u, v) of the unit box
   inside `shape` shrunk to k about its centroid. */
static int rim_in(uint32_t shape, float u, float v, float k)
{
    float cy = 0.5f;
    float x;
    float y;
    if (shape == (uint32_t)SBR_PICTO_RIM_TRIANGLE) {
        cy = 2.0f / 3.0f;
    } else if (shape == (uint32_t)SBR_PICTO_RIM_TRIANGLE_DOWN) {
        cy = 1.0f / 3.0f;
    }
    x = 0.5f + ((u - 0.5f) / k);
    y = cy + ((v - cy) / k);
    if (shape == (uint32_t)SBR_PICTO_RIM_DISC) {
        return (((x - 0.5f) * (x - 0.5f)) + ((y - 0.5f) * (y - 0.5f))) <= 0.25f;
    }
    if (shape == (uint32_t)SBR_PICTO_RIM_TRIANGLE) {
        return (y <= 1.0f) && (fabsf(x - 0.5f) <= (0.5f * y));
    }
    return (y >= 0.0f) && (fabsf(x - 0.5f) <= (0.5f * (1.0f - y)));
}

/* A sign of `shape` painted into the 64 x 64 box at (8, 16): a pure red rim, a white
   middle, mid-grey elsewhere (the band between rim and middle included). Pixel (x, y) is
   classified at ((x - 8) / 64, (y - 16) / 64), where sbr_picto_rim_contrast()'s grid
   samples land on whole pixels. */
static void paint_rim_sign(uint32_t shape)
{
    const float k_in = (shape == (uint32_t)SBR_PICTO_RIM_DISC) ? 0.75f : 0.6f;
    const float k_mid = (shape == (uint32_t)SBR_PICTO_RIM_DISC) ? 0.6f : 0.45f;
    uint32_t x;
    uint32_t y;
    fill(128u, 128u, 128u);
    for (y = 16u; y < 80u; y++) {
        for (x = 8u; x < 72u; x++) {
            const float u = (float)(x - 8u) / 64.0f;
            const float v = (float)(y - 16u) / 64.0f;
            if ((rim_in(shape, u, v, 1.0f) != 0) && (rim_in(shape, u, v, k_in) == 0)) {
                g_rgb[y][x][0] = 255u;
                g_rgb[y][x][1] = 0u;
                g_rgb[y][x][2] = 0u;
            } else if (rim_in(shape, u, v, k_mid) != 0) {
                (void)memset(g_rgb[y][x], 255, 3u);
            } else {
                /* grey */
            }
        }
    }
}

/* Colour check: a red rim around a white middle gives redness 255 / 258 - 0 for each
   outline; the same pixels read as BGR (the "red" is then blue) give the negative; a
   grey image gives exactly 0; a box twice as large around the same sign samples other
   pixels and gives less. Bad input gets its status and leaves *contrast alone. */
static void test_rim_contrast(void)
{
    const float box[4] = {8.0f, 16.0f, 72.0f, 80.0f};
    const float wide[4] = {-24.0f, -16.0f, 104.0f, 112.0f};
    const float red = 255.0f / 258.0f;
    uint32_t shape;
    float c = 0.0f;
    sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    for (shape = 1u; shape <= 3u; shape++) {
        paint_rim_sign(shape);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_rim_contrast(&v, box, shape, &c));
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, red, c);
        v.format = SBR_PIXEL_BGR888;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_rim_contrast(&v, box, shape, &c));
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, -red, c);
        v.format = SBR_PIXEL_RGB888;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_rim_contrast(&v, wide, shape, &c));
        TEST_ASSERT_TRUE(c < 0.5f * red);
    }
    fill(128u, 128u, 128u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_rim_contrast(&v, box, 3u, &c));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, c);
    /* bad input */
    c = 7.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_rim_contrast(NULL, box, 1u, &c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_rim_contrast(&v, NULL, 1u, &c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_rim_contrast(&v, box, 1u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, box, 0u, &c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, box, 4u, &c));
    {
        float b[4] = {8.0f, 16.0f, 9.0f, 80.0f}; /* 1 px wide */
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, b, 1u, &c));
        b[2] = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, b, 1u, &c));
        b[2] = 2.0f * SBR_PICTO_MAX_COORD;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, b, 1u, &c));
    }
    v.format = SBR_PIXEL_GRAY8;
    v.stride = W;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, box, 1u, &c));
    v.format = SBR_PIXEL_RGB888;
    v.stride = 3u * W - 1u;
    TEST_ASSERT_NOT_EQUAL(SBR_OK, sbr_picto_rim_contrast(&v, box, 1u, &c));
    TEST_ASSERT_EQUAL_FLOAT(7.0f, c);
}

/* The colour check's tables in sbr_picto_check(): both or neither, outlines in range,
   floors finite in [-2, 2]. */
static void test_rim_tables_checked(void)
{
    static uint8_t shape[K];
    static float floor_[K];
    sbr_picto_model_t m;
    hand_model(&m);
    (void)memset(shape, 0, sizeof shape);
    (void)memset(floor_, 0, sizeof floor_);
    shape[13] = (uint8_t)SBR_PICTO_RIM_TRIANGLE_DOWN;
    floor_[13] = 0.01f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    m.rim_shape = shape;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m)); /* one table alone */
    m.rim_floor = floor_;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    m.rim_shape = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    m.rim_shape = shape;
    shape[42] = 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    shape[42] = 0u;
    floor_[0] = 2.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    floor_[0] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    floor_[0] = -2.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
}

/* Box regression: hand-made rows move and scale the box by the stated amounts, clamped
   to SBR_PICTO_MAX_SHIFT and SBR_PICTO_MAX_LOG_SCALE; the hidden layer feeds it; without
   w3 the box stays; non-finite weights are refused by the check. */
static void test_refine_values(void)
{
    sbr_picto_model_t m;
    const float box[4] = {10.0f, 20.0f, 50.0f, 40.0f}; /* centre (30, 30), 40 x 20 */
    float r[4];
    hand_model(&m);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_FLOAT(10.0f, r[0]);
    TEST_ASSERT_EQUAL_FLOAT(20.0f, r[1]);
    TEST_ASSERT_EQUAL_FLOAT(50.0f, r[2]);
    TEST_ASSERT_EQUAL_FLOAT(40.0f, r[3]);
    /* dx = 0.1 + 0.2 f0, dy = -0.25, log w = ln 1.5, log h = 0 */
    g_w3[F] = 0.1f;
    g_w3[0] = 0.2f;
    g_w3[(F + 1u) + F] = -0.25f;
    g_w3[(2u * (F + 1u)) + F] = logf(1.5f);
    m.w3 = g_w3;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    g_f[0] = 0.5f; /* dx = 0.2: centre x 30 + 0.2 * 40 = 38, width 60 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 8.0f, r[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 68.0f, r[2]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 15.0f, r[1]); /* centre y 30 - 0.25 * 20 = 25, height 20 */
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 35.0f, r[3]);
    /* clamped: dx = 10 moves by half the width at most, log w = -5 scales by e^-0.7 */
    g_w3[F] = 10.0f;
    g_w3[0] = 0.0f;
    g_w3[(2u * (F + 1u)) + F] = -5.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 50.0f - (20.0f * expf(-SBR_PICTO_MAX_LOG_SCALE)), r[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 50.0f + (20.0f * expf(-SBR_PICTO_MAX_LOG_SCALE)), r[2]);
    /* in place, through a hidden unit a = max(0, f0 - 0.25) = 0.25, dx = 0.4 a = 0.1 */
    (void)memset(g_w1, 0, sizeof g_w1);
    (void)memset(g_w3, 0, sizeof g_w3);
    g_w1[0] = 1.0f;
    g_w1[F] = -0.25f;
    g_w3[0] = 0.4f;
    m.hidden = 1u;
    m.w1 = g_w1;
    r[0] = box[0];
    r[1] = box[1];
    r[2] = box[2];
    r[3] = box[3];
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, r, r, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 14.0f, r[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 54.0f, r[2]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 20.0f, r[1]);
    /* bad input */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_refine(NULL, g_f, F, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_refine(&m, NULL, F, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_refine(&m, g_f, F, NULL, r, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_refine(&m, g_f, F, box, NULL, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_refine(&m, g_f, F - 1u, box, r, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_refine(&m, g_f, F, box, r, g_ws, 4u));
    r[0] = 50.0f; /* empty box */
    r[1] = 20.0f;
    r[2] = 10.0f;
    r[3] = 40.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_refine(&m, g_f, F, r, r, g_ws, sizeof g_ws));
    r[2] = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_refine(&m, g_f, F, r, r, g_ws, sizeof g_ws));
    {
        /* regression (fuzzer finding): a finite box whose width overflows gave SBR_OK
           with a NaN/Inf box; boxes beyond SBR_PICTO_MAX_COORD are refused, the largest
           accepted one stays finite at the largest scaling */
        const float huge[4] = {-3e38f, -3e38f, 3e38f, 3e38f};
        const float edge[4] = {-SBR_PICTO_MAX_COORD, -SBR_PICTO_MAX_COORD, SBR_PICTO_MAX_COORD,
                               SBR_PICTO_MAX_COORD};
        float out[4] = {1.0f, 2.0f, 3.0f, 4.0f};
        uint32_t k;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_refine(&m, g_f, F, huge, out, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_FLOAT(1.0f, out[0]); /* nothing written */
        g_w3[(2u * (F + 1u)) + F] = 5.0f;       /* log w clamped to +0.7 */
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, edge, out, g_ws, sizeof g_ws));
        for (k = 0u; k < 4u; k++) {
            TEST_ASSERT_TRUE(isfinite(out[k]));
        }
        TEST_ASSERT_TRUE(out[2] > out[0]);
        /* regression (fuzzer finding): a box narrower than the features take gave an empty
           refined box through rounding; the smallest accepted box, far out and shrunk
           as much as allowed, stays a box */
        {
            const float thin[4] = {100.0f, 10.0f, 100.0f + 1e-5f, 30.0f};
            const float small[4] = {6e4f, 6e4f, 6e4f + SBR_PICTO_MIN_BOX, 6e4f + SBR_PICTO_MIN_BOX};
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_refine(&m, g_f, F, thin, out, g_ws, sizeof g_ws));
            g_w3[(2u * (F + 1u)) + F] = -5.0f; /* log w clamped to -0.7 */
            g_w3[(3u * (F + 1u)) + F] = -5.0f; /* log h too */
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, small, out, g_ws, sizeof g_ws));
            TEST_ASSERT_TRUE(out[2] > out[0]);
            TEST_ASSERT_TRUE(out[3] > out[1]);
            g_w3[(3u * (F + 1u)) + F] = 0.0f;
        }
        g_w3[(2u * (F + 1u)) + F] = 0.0f;
    }
    g_f[1] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    g_f[1] = 0.0f;
    m.version = SBR_PICTO_VERSION - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_refine(&m, g_f, F, box, r, g_ws, sizeof g_ws));
    m.version = SBR_PICTO_VERSION;
    g_w3[2] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    g_w3[2] = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
}

/* A GRAY8 view: the features (box, triangle, gate) of an image with R = G = B, exactly;
   the colour check, which needs colour, refuses it. */
static void test_grey_view(void)
{
    sbr_image_t g = view(g_rgb, SBR_PIXEL_GRAY8);
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    const float box[4] = {12.0f, 9.0f, 51.0f, 47.0f};
    static float grey_f[F];
    float c = 0.0f;
    uint32_t x;
    uint32_t y;
    uint32_t i;
    float spread = 0.0f;
    step_edge(16u, 12u, 32u);
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_grey[y][x] = (uint8_t)(g_rgb[y][x][0] + ((x * 7u + y * 3u) % 11u)); /* some texture */
            g_rgb[y][x][0] = g_grey[y][x];
            g_rgb[y][x][1] = g_grey[y][x];
            g_rgb[y][x][2] = g_grey[y][x];
        }
    }
    g.stride = W;
    g.data = &g_grey[0][0];
    for (i = 0u; i <= (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE; i++) {
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, i, g_f, F, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&g, box, i, grey_f, F, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_MEMORY(g_f, grey_f, sizeof grey_f);
    }
    for (i = 0u; i < HOG_LEN; i++) {
        spread = fmaxf(spread, g_f[i]); /* the edge is seen */
    }
    TEST_ASSERT_TRUE(spread > 0.1f);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&g, box, grey_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_MEMORY(g_f, grey_f, SBR_PICTO_GATE_FEATURES * sizeof(float));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_rim_contrast(&g, box, SBR_PICTO_RIM_DISC, &c));
    g.stride = W - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_picto_features(&g, box, grey_f, F, g_ws, sizeof g_ws));
}

/* Bad input: a status, never a crash. */
static void test_bad_input(void)
{
    sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    sbr_picto_model_t m;
    float p[OUTPUTS];
    float box[4] = {10.0f, 10.0f, 40.0f, 40.0f};
    fill(100u, 100u, 100u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&m));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_features(NULL, box, g_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_features(&v, NULL, g_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_features(&v, box, NULL, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_features(&v, box, g_f, F - 1u, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_features(&v, box, g_f, F, NULL, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_features(&v, box, g_f, F, g_ws, 16u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_picto_features(&v, box, g_f, F, (uint8_t *)g_ws + 2, sizeof g_ws - 8u));
    box[2] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    box[2] = 11.0f; /* 1 px wide */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    box[0] = 1000.0f; /* far outside, inverted */
    box[2] = 1040.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    /* partly outside (by less than its size): border pixels repeat */
    box[0] = -10.0f;
    box[1] = -10.0f;
    box[2] = 20.0f;
    box[3] = 20.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    v = view(g_rgb, SBR_PIXEL_RGB888);
    v.stride = 3u * W - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    v = view(g_rgb, SBR_PIXEL_RGB888);
    v.width = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    /* a 1 x 1 image: every sample is that pixel */
    v = view(g_rgb, SBR_PIXEL_RGB888);
    v.width = 1u;
    v.height = 1u;
    box[0] = 0.0f;
    box[1] = 0.0f;
    box[2] = 2.0f;
    box[3] = 2.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features(&v, box, g_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_f[0]);
    /* classifier */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_classify(NULL, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_classify(&m, NULL, F, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_classify(&m, g_f, F, NULL, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_classify(&m, g_f, F - 1u, p, OUTPUTS, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_classify(&m, g_f, F, p, 43u, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, 8u));
    g_f[3] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
    g_f[3] = 0.0f;
    m.version = 7u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_classify(&m, g_f, F, p, OUTPUTS, g_ws, sizeof g_ws));
}

/* The gate's features: a uniform box gives a zero grey grid and zero edges and the grey
   chromaticity 1/3 * sum / (sum + 30); a vertical step edge gives grey values of opposite
   signs on its two halves and edge energy only in the +x bin; RGB and BGR views agree. */
#define GGRID SBR_PICTO_GATE_GRID
#define GCOLOUR (GGRID * GGRID)
#define GEDGES (GCOLOUR + 32u)
static float g_gf[SBR_PICTO_GATE_FEATURES];
static float g_gf2[SBR_PICTO_GATE_FEATURES];
static float g_gate[SBR_PICTO_GATE_FEATURES + 1u];

static void test_gate_features(void)
{
    const float box[4] = {20.0f, 10.0f, 68.0f, 58.0f};
    sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    sbr_image_t vb = view(g_bgr, SBR_PIXEL_BGR888);
    uint32_t i;
    uint32_t x;
    uint32_t y;
    float pos = 0.0f;
    float other = 0.0f;
    fill(120u, 120u, 120u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                          g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    for (i = 0u; i < GCOLOUR; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_gf[i]);
    }
    for (i = 0u; i < 32u; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 120.0f / 390.0f, g_gf[GCOLOUR + i]);
    }
    for (i = 0u; i < 72u; i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, g_gf[GEDGES + i]);
    }
    /* dark left half, bright right half of the box */
    step_edge(20u, 10u, 48u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                          g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_TRUE(g_gf[0] < -0.5f);
    TEST_ASSERT_TRUE(g_gf[GGRID - 1u] > 0.5f);
    for (i = 0u; i < 9u; i++) {
        pos += g_gf[GEDGES + (i * 8u)];
        other += g_gf[GEDGES + (i * 8u) + 1u] + g_gf[GEDGES + (i * 8u) + 2u] +
                 g_gf[GEDGES + (i * 8u) + 3u];
    }
    TEST_ASSERT_TRUE(pos > 0.5f);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, other);
    /* the same pixels as BGR */
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = (uint8_t)(x * 2u);
            g_rgb[y][x][1] = (uint8_t)(y * 2u);
            g_rgb[y][x][2] = (uint8_t)(x + y);
            g_bgr[y][x][0] = g_rgb[y][x][2];
            g_bgr[y][x][1] = g_rgb[y][x][1];
            g_bgr[y][x][2] = g_rgb[y][x][0];
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                          g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&vb, box, g_gf2, SBR_PICTO_GATE_FEATURES,
                                                          g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_FLOAT_ARRAY(g_gf, g_gf2, SBR_PICTO_GATE_FEATURES);
    TEST_ASSERT_TRUE(g_gf[GCOLOUR] != g_gf[GCOLOUR + 1u]); /* red and blue differ here */
}

/* The gate's score is its weights' dot product with the features plus the bias; the
   check refuses non-finite gate weights and thresholds; bad input gets its status. */
static void test_gate_score_and_bad_input(void)
{
    sbr_picto_model_t m;
    const float box[4] = {20.0f, 10.0f, 68.0f, 58.0f};
    const float tiny[4] = {20.0f, 10.0f, 21.0f, 58.0f};
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    float score = 0.0f;
    double ref = 0.0;
    uint32_t i;
    hand_model(&m);
    step_edge(20u, 10u, 48u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                          g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    for (i = 0u; i <= SBR_PICTO_GATE_FEATURES; i++) {
        g_gate[i] = 0.01f * (float)((int)(i % 7u) - 3);
    }
    for (i = 0u; i < SBR_PICTO_GATE_FEATURES; i++) {
        ref += (double)g_gate[i] * (double)g_gf[i];
    }
    ref += (double)g_gate[SBR_PICTO_GATE_FEATURES];
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_gate(&m, g_gf, SBR_PICTO_GATE_FEATURES, &score));
    m.gate = g_gate;
    m.gate_threshold = 0.25f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate(&m, g_gf, SBR_PICTO_GATE_FEATURES, &score));
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, (float)ref, score);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_gate(&m, g_gf, SBR_PICTO_GATE_FEATURES - 1u, &score));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_gate(&m, NULL, SBR_PICTO_GATE_FEATURES, &score));
    g_gf2[0] = g_gf[0];
    (void)memcpy(g_gf2, g_gf, sizeof g_gf2);
    g_gf2[5] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_gate(&m, g_gf2, SBR_PICTO_GATE_FEATURES, &score));
    m.gate_threshold = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    m.gate_threshold = 0.0f;
    g_gate[17] = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
    g_gate[17] = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
    /* features: NULLs, grey images, boxes out of the domain, short output, workspace */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_gate_features(NULL, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                                g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_gate_features(&v, box, NULL, SBR_PICTO_GATE_FEATURES,
                                                                g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_gate_features(&v, tiny, g_gf, SBR_PICTO_GATE_FEATURES,
                                                                 g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES - 1u,
                                                                g_ws, SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES, g_ws,
                                                  SBR_PICTO_GATE_WORKSPACE_SIZE - 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES,
                                                  (uint8_t *)g_ws + 1, SBR_PICTO_GATE_WORKSPACE_SIZE));
}

/* Looks (sbr_picto_look*()): the same probabilities, refined box and gate score as the
   separate calls, bit for bit; the regression refers to the last successful look; bad
   input and a workspace without a look get their statuses. */
static void test_look(void)
{
    static uint64_t look_ws[SBR_PICTO_LOOK_WORKSPACE_SIZE / 8u + 1u];
    sbr_picto_model_t m;
    const float box[4] = {20.0f, 10.0f, 68.0f, 58.0f};
    const float other[4] = {10.0f, 5.0f, 80.0f, 70.0f};
    const float tiny[4] = {20.0f, 10.0f, 21.0f, 58.0f};
    const sbr_image_t v = view(g_rgb, SBR_PIXEL_RGB888);
    float p_ref[SBR_PICTO_MAX_OUTPUTS];
    float p[SBR_PICTO_MAX_OUTPUTS];
    float r_ref[4];
    float r[4];
    float s_ref = 0.0f;
    float s = 0.0f;
    uint32_t i;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gtsdb(&m));
    TEST_ASSERT_NOT_NULL(m.w3);
    step_edge(20u, 10u, 48u);
    /* without a look there is nothing to refine */
    (void)memset(look_ws, 0, sizeof look_ws);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_picto_look_refine(&m, r, look_ws, sizeof look_ws));
    for (i = 0u; i < 2u; i++) { /* the whole box, then the triangle inside it */
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features_outline(&v, box, i, g_f, F, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_classify(&m, g_f, F, p_ref, OUTPUTS, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, box, r_ref, g_ws, sizeof g_ws));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look(&m, &v, box, i, p, OUTPUTS, look_ws, sizeof look_ws));
        TEST_ASSERT_EQUAL_MEMORY(p_ref, p, OUTPUTS * sizeof(float));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look_refine(&m, r, look_ws, sizeof look_ws));
        TEST_ASSERT_EQUAL_MEMORY(r_ref, r, sizeof r);
    }
    /* a failed look leaves none: its probabilities untouched, nothing to refine */
    p[0] = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_look(&m, &v, tiny, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, p[0]);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_picto_look_refine(&m, r, look_ws, sizeof look_ws));
    /* the regression is of the last look's box */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_features(&v, other, g_f, F, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_refine(&m, g_f, F, other, r_ref, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look(&m, &v, box, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look(&m, &v, other, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look_refine(&m, r, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_MEMORY(r_ref, r, sizeof r);
    /* the gate: the same score; the look is gone afterwards */
    for (i = 0u; i <= SBR_PICTO_GATE_FEATURES; i++) {
        g_gate[i] = 0.01f * (float)((int)(i % 5u) - 2);
    }
    m.gate = g_gate;
    m.gate_hidden = 0u;
    m.gate_threshold = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate_features(&v, box, g_gf, SBR_PICTO_GATE_FEATURES, g_ws,
                                                          SBR_PICTO_GATE_WORKSPACE_SIZE));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_gate(&m, g_gf, SBR_PICTO_GATE_FEATURES, &s_ref));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look_gate(&m, &v, box, &s, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_MEMORY(&s_ref, &s, sizeof s);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_picto_look_refine(&m, r, look_ws, sizeof look_ws));
    /* bad input */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look(NULL, &v, box, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look(&m, NULL, box, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look(&m, &v, NULL, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look(&m, &v, box, 0u, NULL, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_picto_look(&m, &v, box, 0u, p, K, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_look(&m, &v, box, 2u, p, OUTPUTS, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_look(&m, &v, box, 0u, p, OUTPUTS, NULL, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_picto_look(&m, &v, box, 0u, p, OUTPUTS, look_ws, SBR_PICTO_LOOK_WORKSPACE_SIZE - 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_picto_look(&m, &v, box, 0u, p, OUTPUTS, (uint8_t *)look_ws + 4, sizeof look_ws - 8u));
    m.version = 99u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_look(&m, &v, box, 0u, p, OUTPUTS, look_ws, sizeof look_ws));
    m.version = SBR_PICTO_VERSION;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look_refine(NULL, r, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look_refine(&m, NULL, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_look_refine(&m, r, look_ws, 8u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look_gate(&m, &v, box, NULL, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_look_gate(&m, &v, tiny, &s, look_ws, sizeof look_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_picto_look_gate(&m, &v, box, &s, look_ws, 8u));
    m.gate = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look_gate(&m, &v, box, &s, look_ws, sizeof look_ws));
}

/* The looks' table: the defaults the trainer writes, each threshold's range enforced by
   the model check, the table's offsets those of sbr_picto_looks_t. */
static void test_looks_table(void)
{
    sbr_picto_model_t m;
    sbr_picto_looks_t l;
    sbr_field_t fld;
    const uint32_t n = sbr_picto_look_field_count();
    uint32_t i;
    hand_model(&m);
    sbr_picto_looks_default(NULL); /* no-op */
    sbr_picto_looks_default(&l);
    TEST_ASSERT_EQUAL_FLOAT(0.01f, l.refine_first_score);
    TEST_ASSERT_EQUAL_FLOAT(0.0003f, l.grey_refine_first_score);
    TEST_ASSERT_EQUAL_FLOAT(0.001f, l.refine_score);
    TEST_ASSERT_EQUAL_FLOAT(0.1f, l.view_score);
    TEST_ASSERT_EQUAL_FLOAT(0.001f, l.triangle_score);
    TEST_ASSERT_EQUAL_UINT32(5u, n);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_picto_look_field_at(n, &fld));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_picto_look_field_at(0u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look_field_at(3u, &fld));
    TEST_ASSERT_EQUAL_STRING("view_score", fld.name);
    TEST_ASSERT_EQUAL_UINT32(offsetof(sbr_picto_model_t, looks) + offsetof(sbr_picto_looks_t, view_score), fld.offset);
    for (i = 0u; i < n; i++) {
        const sbr_field_t *f = &fld;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_look_field_at(i, &fld));
        float *at = (float *)(void *)&((uint8_t *)&m)[f->offset];
        const float keep = *at;
        TEST_ASSERT_EQUAL_INT(SBR_FIELD_F32, f->kind);
        TEST_ASSERT_EQUAL_FLOAT(f->def_f, keep);
        *at = f->lo_f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
        *at = f->hi_f;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_picto_check(&m));
        *at = nextafterf(f->hi_f, INFINITY);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
        *at = nextafterf(f->lo_f, -INFINITY);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
        *at = NAN;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, sbr_picto_check(&m));
        *at = keep;
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_uniform_patch);
    RUN_TEST(test_step_edge);
    RUN_TEST(test_format_and_scale);
    RUN_TEST(test_classify_values);
    RUN_TEST(test_builtin_and_corrupt);
    RUN_TEST(test_classify_matches_reference);
    RUN_TEST(test_refine_values);
    RUN_TEST(test_triangle_outline);
    RUN_TEST(test_grey_view);
    RUN_TEST(test_bad_input);
    RUN_TEST(test_rim_contrast);
    RUN_TEST(test_rim_tables_checked);
    RUN_TEST(test_gate_features);
    RUN_TEST(test_gate_score_and_bad_input);
    RUN_TEST(test_look);
    RUN_TEST(test_looks_table);
    return UNITY_END();
}
