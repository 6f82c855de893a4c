/* SPDX-License-Identifier: MIT */
/* Unity tests of include/sbr/track.h: the channel-based tracker (paper E): model checks,
   tracking through misses, crossing targets, clutter, bad input. */
#include "sbr/track.h"
#include "sbr/models.h"

#include <math.h>
#include <string.h>

#include "test_status_table.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

#define VEL 41u
#define SPACING 1.0f
#define TARGETS 8u
#define WINDOW 31u
#define PERIOD 0.1f
#define PERIOD_US 100000u /* PERIOD in microseconds, what sbr_track_step() takes */

static float g_trans[SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, VEL)];
static float g_birth[SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, VEL)];
static uint32_t g_ws[SBR_TRACK_WORKSPACE_SIZE(TARGETS, WINDOW, VEL) / sizeof(uint32_t) + 1u];

static sbr_track_model_t g_model;

/* A constant-velocity model on a KITTI-sized image: 1.5 px of velocity change per
   frame, new targets' velocity within about +-10 px per frame. */
static void make_model(void)
{
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_cv(&g_model, 1242.0f, 375.0f, PERIOD, VEL, SPACING,
                                                 1.5f, 10.0f, g_trans,
                                                 sizeof(g_trans) / sizeof(g_trans[0]), g_birth,
                                                 sizeof(g_birth) / sizeof(g_birth[0])));
}

static void init_tracker(sbr_track_t *trk, uint32_t targets)
{
    sbr_track_config_t cfg;
    make_model();
    sbr_track_config_default(&cfg);
    cfg.model = &g_model;
    cfg.max_targets = targets;
    cfg.window = WINDOW;
    cfg.meas_sigma = 1.5f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    TEST_ASSERT_TRUE(sbr_track_workspace_size(&cfg) <= sizeof(g_ws));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_init(trk, &cfg, g_ws, sizeof(g_ws)));
}

static const sbr_track_target_t *find_id(const sbr_track_target_t *t, uint32_t n, uint32_t id)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        if (t[i].id == id) {
            return &t[i];
        }
    }
    return NULL;
}

void test_model_cv_rows_and_check(void)
{
    uint32_t r;
    uint32_t j;
    make_model();
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_check(&g_model));
    /* a row of the transition is a Gaussian around its own channel: mean j, sd 1.5 px */
    for (r = 0u; r < 6u; r++) {
        for (j = 6u; j < VEL - 6u; j++) {
            const float *row = &g_trans[(r * VEL + j) * VEL];
            float sum = 0.0f;
            float mean = 0.0f;
            float var = 0.0f;
            uint32_t k;
            for (k = 0u; k < VEL; k++) {
                sum += row[k];
                mean += row[k] * (float)k;
            }
            for (k = 0u; k < VEL; k++) {
                var += row[k] * ((float)k - mean) * ((float)k - mean);
            }
            TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, sum);
            TEST_ASSERT_FLOAT_WITHIN(1e-3f, (float)j, mean);
            TEST_ASSERT_FLOAT_WITHIN(0.05f, 1.5f * 1.5f, var);
        }
    }
    /* a row that is not a distribution is refused */
    g_trans[5] += 0.01f;
    TEST_ASSERT_EQUAL(SBR_ERR_CORRUPT, sbr_track_model_check(&g_model));
    make_model();
    g_birth[3] = -0.5f;
    TEST_ASSERT_EQUAL(SBR_ERR_CORRUPT, sbr_track_model_check(&g_model));
    make_model();
    g_model.order = 1u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_model_check(&g_model));
    make_model();
    g_model.vel_count = 24u;
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE, sbr_track_model_check(&g_model));
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE,
                      sbr_track_model_cv(&g_model, 100.0f, 100.0f, 0.1f, VEL, 1.0f, 1.0f, 1.0f,
                                         g_trans, 10u, g_birth, 1000u));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE,
                      sbr_track_model_cv(&g_model, 100.0f, NAN, 0.1f, VEL, 1.0f, 1.0f, 1.0f,
                                         g_trans, sizeof(g_trans) / sizeof(g_trans[0]), g_birth,
                                         sizeof(g_birth) / sizeof(g_birth[0])));
}

/* sbr_track_reset(): after it, the same detections give exactly what a fresh tracker
   gives (identities from 1 again), and a blank instance is refused. */
void test_reset_repeats_a_fresh_tracker(void)
{
    sbr_track_t trk;
    sbr_track_t blank;
    sbr_track_target_t first[10][TARGETS];
    sbr_track_target_t out[TARGETS];
    uint32_t nfirst[10];
    uint32_t n = 0u;
    uint32_t pass;
    uint32_t f;
    init_tracker(&trk, TARGETS);
    for (pass = 0u; pass < 2u; pass++) {
        for (f = 0u; f < 10u; f++) {
            sbr_track_detection_t d[2] = {{100.0f + 5.0f * (float)f, 50.0f, 1.0f},
                                          {600.0f - 3.0f * (float)f, 200.0f, 0.8f}};
            TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, d, 2u, out, TARGETS, &n));
            if (pass == 0u) {
                nfirst[f] = n;
                memcpy(first[f], out, sizeof out);
            } else {
                TEST_ASSERT_EQUAL_UINT32(nfirst[f], n);
                TEST_ASSERT_EQUAL_MEMORY(first[f], out, n * sizeof out[0]);
            }
        }
        TEST_ASSERT_EQUAL_UINT32(2u, n);
        TEST_ASSERT_EQUAL(SBR_OK, sbr_track_reset(&trk));
    }
    memset(&blank, 0, sizeof blank);
    TEST_ASSERT_EQUAL(SBR_ERR_STATE, sbr_track_reset(&blank));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_reset(NULL));
}

/* Constant velocity: position and velocity are decoded accurately. */
void test_straight_line_velocity(void)
{
    sbr_track_t trk;
    sbr_track_target_t out[TARGETS];
    uint32_t n = 0u;
    uint32_t f;
    tsup_rng_t rng = {7u};
    init_tracker(&trk, TARGETS);
    for (f = 0u; f < 30u; f++) {
        const float tx = 200.0f + 6.0f * (float)f;
        const float ty = 300.0f - 2.0f * (float)f;
        sbr_track_detection_t d;
        d.x = tx + 0.5f * tsup_gauss(&rng);
        d.y = ty + 0.5f * tsup_gauss(&rng);
        d.certainty = 1.0f;
        TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, &d, 1u, out, TARGETS, &n));
        TEST_ASSERT_EQUAL_UINT32(1u, n);
        TEST_ASSERT_EQUAL_UINT32(1u, out[0].id);
        if (f >= 1u) {
            TEST_ASSERT_TRUE((out[0].flags & SBR_TRACK_CONFIRMED) != 0u);
        }
        if (f >= 8u) {
            TEST_ASSERT_FLOAT_WITHIN(1.5f, tx, out[0].x);
            TEST_ASSERT_FLOAT_WITHIN(1.5f, ty, out[0].y);
            TEST_ASSERT_FLOAT_WITHIN(0.8f, 6.0f, out[0].vx);
            TEST_ASSERT_FLOAT_WITHIN(0.8f, -2.0f, out[0].vy);
            TEST_ASSERT_TRUE(out[0].certainty > 0.0f && out[0].certainty <= 1.0f);
            TEST_ASSERT_EQUAL_INT32(0, out[0].detection);
        }
    }
}

/* A target on a curved path is kept through 5 consecutive misses, with its id. */
void test_curved_path_through_five_misses(void)
{
    sbr_track_t trk;
    sbr_track_target_t out[TARGETS];
    uint32_t n = 0u;
    uint32_t f;
    uint32_t id = 0u;
    tsup_rng_t rng = {11u};
    init_tracker(&trk, TARGETS);
    for (f = 0u; f < 45u; f++) {
        /* an arc of radius 150 px at 0.05 rad per frame (7.5 px per frame) */
        const float ang = 0.05f * (float)f;
        const float tx = 600.0f + 150.0f * sinf(ang);
        const float ty = 330.0f - 150.0f * (1.0f - cosf(ang));
        const int missed = (f >= 20u) && (f < 25u);
        sbr_track_detection_t d;
        const sbr_track_target_t *t;
        d.x = tx + 0.7f * tsup_gauss(&rng);
        d.y = ty + 0.7f * tsup_gauss(&rng);
        d.certainty = 1.0f;
        TEST_ASSERT_EQUAL(SBR_OK,
                          sbr_track_step(&trk, PERIOD_US, &d, missed ? 0u : 1u, out, TARGETS, &n));
        TEST_ASSERT_EQUAL_UINT32(1u, n);
        if (f == 0u) {
            id = out[0].id;
        }
        t = find_id(out, n, id);
        TEST_ASSERT_NOT_NULL(t);
        if (missed) {
            TEST_ASSERT_EQUAL_INT32(-1, t->detection);
            TEST_ASSERT_EQUAL_UINT32(f - 19u, t->misses);
            /* coasting on constant velocity: the arc's centripetal acceleration
               a = 0.375 px per frame² makes 0.5 a k² after k frames, the velocity's lag
               behind the turning arc about as much again; 3 px for noise */
            const float k = (float)(f - 19u);
            const float tol = 0.375f * k * k + 3.0f;
            TEST_ASSERT_TRUE(hypotf(t->x - tx, t->y - ty) <= tol);
        } else if (f >= 6u) {
            TEST_ASSERT_EQUAL_UINT32(0u, t->misses);
            TEST_ASSERT_FLOAT_WITHIN(2.5f, tx, t->x);
            TEST_ASSERT_FLOAT_WITHIN(2.5f, ty, t->y);
        }
    }
}

/* Two targets crossing each other keep their ids. */
void test_crossing_targets_keep_ids(void)
{
    sbr_track_t trk;
    sbr_track_target_t out[TARGETS];
    uint32_t n = 0u;
    uint32_t f;
    uint32_t id_a = 0u;
    uint32_t id_b = 0u;
    tsup_rng_t rng = {3u};
    init_tracker(&trk, TARGETS);
    for (f = 0u; f < 40u; f++) {
        /* A goes right, B left; they pass at frame 20, 4 px apart vertically */
        const float ax = 400.0f + 8.0f * (float)f;
        const float bx = 720.0f - 8.0f * (float)f;
        const float ay = 200.0f + 0.1f * (float)f;
        const float by = 204.0f - 0.1f * (float)f;
        sbr_track_detection_t d[2];
        const uint32_t first = f % 2u; /* the order of the detections alternates */
        d[first].x = ax + 0.5f * tsup_gauss(&rng);
        d[first].y = ay + 0.5f * tsup_gauss(&rng);
        d[first].certainty = 1.0f;
        d[1u - first].x = bx + 0.5f * tsup_gauss(&rng);
        d[1u - first].y = by + 0.5f * tsup_gauss(&rng);
        d[1u - first].certainty = 0.9f;
        TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, d, 2u, out, TARGETS, &n));
        TEST_ASSERT_EQUAL_UINT32(2u, n);
        if (f == 0u) {
            id_a = out[0].detection == (int32_t)first ? out[0].id : out[1].id;
            id_b = out[0].detection == (int32_t)first ? out[1].id : out[0].id;
            TEST_ASSERT_TRUE(id_a != id_b);
        } else {
            const sbr_track_target_t *a = find_id(out, n, id_a);
            const sbr_track_target_t *b = find_id(out, n, id_b);
            TEST_ASSERT_NOT_NULL(a);
            TEST_ASSERT_NOT_NULL(b);
            TEST_ASSERT_EQUAL_INT32((int32_t)first, a->detection);
            TEST_ASSERT_EQUAL_INT32((int32_t)(1u - first), b->detection);
            TEST_ASSERT_FLOAT_WITHIN(3.0f, ax, a->x);
            TEST_ASSERT_FLOAT_WITHIN(3.0f, bx, b->x);
        }
    }
}

/* Clutter seen once never becomes a confirmed target; a gap of two periods (dt = 0.2)
   is bridged. */
void test_clutter_and_longer_dt(void)
{
    sbr_track_t trk;
    sbr_track_target_t out[TARGETS];
    uint32_t n = 0u;
    uint32_t f;
    uint32_t i;
    tsup_rng_t rng = {5u};
    float t = 0.0f;
    init_tracker(&trk, TARGETS);
    for (f = 0u; f < 30u; f++) {
        const uint32_t dt = (f % 3u == 2u) ? 2u * PERIOD_US : PERIOD_US;
        sbr_track_detection_t d[2];
        uint32_t confirmed = 0u;
        t += (float)dt / 1.0e6f; /* seconds */
        d[0].x = 100.0f + 50.0f * t;
        d[0].y = 100.0f + 20.0f * t;
        d[0].certainty = 1.0f;
        /* clutter: random, alternately in the left and the right third, so that two
           consecutive clutter detections are never within a gate of each other */
        if ((f % 2u) == 0u) {
            d[1].x = tsup_uniform(&rng, 0.0f, 400.0f);
        } else {
            d[1].x = tsup_uniform(&rng, 840.0f, 1241.0f);
        }
        d[1].y = tsup_uniform(&rng, 0.0f, 374.0f);
        d[1].certainty = 1.0f;
        TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, dt, d, 2u, out, TARGETS, &n));
        for (i = 0u; i < n; i++) {
            if ((out[i].flags & SBR_TRACK_CONFIRMED) != 0u) {
                confirmed++;
                TEST_ASSERT_EQUAL_UINT32(1u, out[i].id);
                if (f >= 5u) {
                    TEST_ASSERT_FLOAT_WITHIN(2.0f, d[0].x, out[i].x);
                    TEST_ASSERT_FLOAT_WITHIN(2.0f, d[0].y, out[i].y);
                    TEST_ASSERT_FLOAT_WITHIN(0.8f, 5.0f, out[i].vx);
                }
            }
        }
        if (f >= 1u) {
            TEST_ASSERT_EQUAL_UINT32(1u, confirmed);
        }
    }
}

void test_bad_input(void)
{
    sbr_track_t trk;
    sbr_track_config_t cfg;
    sbr_track_target_t out[2];
    sbr_track_detection_t d[3];
    uint32_t n = 9u;
    uint32_t i;
    init_tracker(&trk, 2u);
    for (i = 0u; i < 3u; i++) {
        d[i].x = 100.0f + 200.0f * (float)i;
        d[i].y = 100.0f;
        d[i].certainty = 1.0f;
    }
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_step(NULL, PERIOD_US, d, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_step(&trk, PERIOD_US, NULL, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, NULL));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, 0u, d, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, UINT32_MAX, d, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, 9u * PERIOD_US, d, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE,
                      sbr_track_step(&trk, PERIOD_US, d, SBR_TRACK_MAX_DETECTIONS + 1u, out, 2u, &n));
    d[1].x = NAN;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n));
    d[1].x = 1242.0f; /* outside the grid */
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n));
    d[1].x = 300.0f;
    d[1].y = -0.5f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n));
    d[1].y = 100.0f;
    d[1].certainty = 0.0f; /* zero certainty */
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n));
    d[1].certainty = 1.5f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n));
    d[1].certainty = 1.0f;
    /* nothing changed by the refused calls: the first good step starts target 1 */
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(1u, out[0].id);
    /* capacity: two slots, three detections -> one cannot start a target */
    TEST_ASSERT_EQUAL(SBR_ERR_CAPACITY, sbr_track_step(&trk, PERIOD_US, d, 3u, out, 2u, &n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    /* result array too short: the step is done, the first entry written */
    TEST_ASSERT_EQUAL(SBR_ERR_CAPACITY, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    /* no result array: the step is done, nothing written, the overflow reported */
    TEST_ASSERT_EQUAL(SBR_ERR_CAPACITY, sbr_track_step(&trk, PERIOD_US, d, 2u, NULL, 0u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* corrupted instance */
    trk.magic ^= 1u;
    TEST_ASSERT_EQUAL(SBR_ERR_STATE, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, &n));
    trk.magic ^= 1u;
    trk.cfg.window = 4u;
    TEST_ASSERT_EQUAL(SBR_ERR_STATE, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, &n));
    memset(&trk, 0, sizeof(trk));
    TEST_ASSERT_EQUAL(SBR_ERR_STATE, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, &n));
    /* configuration and workspace */
    sbr_track_config_default(&cfg);
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_config_check(&cfg)); /* no model */
    TEST_ASSERT_EQUAL(0u, sbr_track_workspace_size(&cfg));
    cfg.model = &g_model;
    cfg.window = 32u;
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE, sbr_track_config_check(&cfg));
    cfg.window = 31u;
    cfg.max_targets = SBR_TRACK_MAX_TARGETS + 1u;
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE, sbr_track_config_check(&cfg));
    cfg.max_targets = 2u;
    cfg.meas_sigma = -1.0f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.meas_sigma = 2.0f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    TEST_ASSERT_EQUAL(SBR_ERR_WORKSPACE,
                      sbr_track_init(&trk, &cfg, g_ws, sbr_track_workspace_size(&cfg) - 1u));
    TEST_ASSERT_EQUAL(SBR_ERR_WORKSPACE,
                      sbr_track_init(&trk, &cfg, (uint8_t *)g_ws + 2, sizeof(g_ws) - 4u));
    TEST_ASSERT_EQUAL(SBR_ERR_WORKSPACE, sbr_track_init(&trk, &cfg, NULL, sizeof(g_ws)));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_init(NULL, &cfg, g_ws, sizeof(g_ws)));
    TEST_ASSERT_EQUAL((size_t)SBR_TRACK_WORKSPACE_SIZE(2u, 31u, VEL), sbr_track_workspace_size(&cfg));
}

/* The generated model learned from KITTI: a valid model; a car driving along the image
   with it is tracked. */
static uint32_t g_ws_kitti[SBR_TRACK_WORKSPACE_SIZE(1u, 25u, 41u) / sizeof(uint32_t) + 1u];

void test_kitti_model(void)
{
    sbr_track_model_t m;
    sbr_track_config_t cfg;
    sbr_track_t trk;
    sbr_track_target_t out[1];
    uint32_t n = 0u;
    uint32_t f;
    tsup_rng_t rng = {9u};
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_model_kitti(NULL));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_kitti(&m));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_check(&m));
    TEST_ASSERT_EQUAL_UINT32(SBR_TRACK_ORDER, m.order);
    TEST_ASSERT_EQUAL_FLOAT(1242.0f, m.extent[0]);
    TEST_ASSERT_EQUAL_UINT32(41u, m.vel_count);
    sbr_track_config_default(&cfg);
    cfg.model = &m;
    cfg.max_targets = 1u;
    cfg.window = 25u;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_init(&trk, &cfg, g_ws_kitti, sizeof(g_ws_kitti)));
    for (f = 0u; f < 25u; f++) {
        /* a car overtaken on the right: moving right and down, speeding up */
        const float tx = 700.0f + 4.0f * (float)f + 0.2f * (float)(f * f);
        const float ty = 190.0f + 0.5f * (float)f;
        sbr_track_detection_t d;
        d.x = tx + 2.0f * tsup_gauss(&rng);
        d.y = ty + 2.0f * tsup_gauss(&rng);
        d.certainty = 1.0f;
        TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, &d, 1u, out, 1u, &n));
        TEST_ASSERT_EQUAL_UINT32(1u, n);
        TEST_ASSERT_EQUAL_UINT32(1u, out[0].id);
        if (f >= 5u) {
            TEST_ASSERT_TRUE(hypotf(out[0].x - tx, out[0].y - ty) <= 4.5f);
        }
    }
}

/* Regression (fuzzer finding): a huge meas_sigma reached the decoder, where the kernel's
   half width in channels overflowed a uint32_t. The kernel must fit in the window. */
void test_meas_sigma_bounded_by_window(void)
{
    sbr_track_model_t m;
    sbr_track_config_t cfg;
    sbr_track_t trk;
    sbr_track_target_t out[1];
    sbr_track_detection_t d = {600.0f, 200.0f, 1.0f};
    uint32_t n = 7u;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_kitti(&m));
    sbr_track_config_default(&cfg);
    cfg.model = &m;
    cfg.max_targets = 1u;
    cfg.window = 25u;
    cfg.meas_sigma = 1e12f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    TEST_ASSERT_EQUAL(0u, sbr_track_workspace_size(&cfg));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_init(&trk, &cfg, g_ws_kitti, sizeof(g_ws_kitti)));
    /* the bound: 5.53 * sigma / spacing channels <= window (spacing 3.5 px, window 25) */
    cfg.meas_sigma = (25.0f * m.vel_spacing / 5.53f) * 1.01f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.meas_sigma = (25.0f * m.vel_spacing / 5.53f) * 0.99f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_init(&trk, &cfg, g_ws_kitti, sizeof(g_ws_kitti)));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_step(&trk, PERIOD_US, &d, 1u, out, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(isfinite(out[0].x) && isfinite(out[0].y));
    TEST_ASSERT_FLOAT_WITHIN(2.0f, 600.0f, out[0].x);
    TEST_ASSERT_FLOAT_WITHIN(2.0f, 200.0f, out[0].y);
}

/* Regression (fuzzer finding, campaign): a velocity spacing of 1.7e38 px passed the
   model check, and the decoder's kernel width 3 s overflowed to inf before a float to
   uint32_t conversion (UB). Spacings above the image and extents above
   SBR_TRACK_MAX_EXTENT are refused. */
void test_model_spacing_and_extent_bounded(void)
{
    sbr_track_model_t bad;
    sbr_track_model_t m;
    static float tr[SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, 37u)];
    static float bi[SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, 37u)];
    make_model();
    bad = g_model;
    bad.vel_spacing = 1.70141e38f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_model_check(&bad));
    bad.vel_spacing = 1243.0f; /* above the larger extent, 1242 */
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_model_check(&bad));
    bad.vel_spacing = 1242.0f;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_model_check(&bad));
    bad = g_model;
    bad.extent[1] = 2.0e6f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_model_check(&bad));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE,
                      sbr_track_model_cv(&m, 373.66f, 125.176f, 0.94f, 37u, 1.70141e38f, 1.0f, 5.0f, tr,
                                         sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE,
                      sbr_track_model_cv(&m, 2.0e6f, 125.0f, 0.94f, 37u, 3.0f, 1.0f, 5.0f, tr,
                                         sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    TEST_ASSERT_EQUAL(SBR_OK,
                      sbr_track_model_cv(&m, 373.66f, 125.176f, 0.94f, 37u, 3.0f, 1.0f, 5.0f, tr,
                                         sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
}

/* Every documented status of the configuration checks. */
void test_config_statuses(void)
{
    sbr_track_config_t cfg;
    sbr_channel_config_t rc;
    sbr_track_model_t bad;
    make_model();
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_config_check(NULL));
    sbr_track_config_default(&cfg);
    cfg.model = &g_model;
    cfg.window = WINDOW;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    cfg.gate = 0.0f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.gate = INFINITY;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.gate = 4.0f;
    cfg.confirm_hits = 0u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.confirm_hits = 17u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.confirm_hits = 16u;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    cfg.max_misses = 256u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.max_misses = 255u;
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_config_check(&cfg));
    cfg.meas_sigma = NAN;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_config_check(&cfg));
    cfg.meas_sigma = 3.0f;
    cfg.window = 6u;
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE, sbr_track_config_check(&cfg));
    cfg.window = WINDOW;
    /* a model error comes through */
    bad = g_model;
    bad.vel_count = 4u;
    cfg.model = &bad;
    TEST_ASSERT_EQUAL(SBR_ERR_SIZE, sbr_track_config_check(&cfg));
    /* sbr_track_region_config(): every status */
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_region_config(NULL, 0u, &rc));
    TEST_ASSERT_EQUAL(SBR_ERR_NULL, sbr_track_region_config(&g_model, 0u, NULL));
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_region_config(&g_model, 2u, &rc));
    bad = g_model;
    bad.regions[1] = 2u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_region_config(&bad, 1u, &rc));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_region_config(&bad, 0u, &rc));
    bad.regions[1] = SBR_TRACK_MAX_REGIONS + 1u;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_region_config(&bad, 1u, &rc));
    bad = g_model;
    bad.extent[0] = NAN;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_region_config(&bad, 0u, &rc));
    bad.extent[0] = 7.0f;
    TEST_ASSERT_EQUAL(SBR_ERR_RANGE, sbr_track_region_config(&bad, 0u, &rc));
    TEST_ASSERT_EQUAL(SBR_OK, sbr_track_region_config(&g_model, 0u, &rc));
    /* 3 regions on 1242 px: spacing 1242 / (3 - 2), first centre -621 */
    TEST_ASSERT_EQUAL_UINT32(3u, rc.count);
    TEST_ASSERT_EQUAL_FLOAT(1242.0f, rc.spacing);
    TEST_ASSERT_EQUAL_FLOAT(-621.0f, rc.first_centre);
    TEST_ASSERT_EQUAL_UINT32(3u, rc.overlap);
}

/* track.h: every documented status, in one table. */
void test_track_h_statuses(void)
{
    status_table_t t;
    sbr_track_model_t bad;
    sbr_track_model_t k;
    sbr_track_config_t cfg;
    sbr_track_t trk;
    sbr_track_t blank;
    sbr_track_target_t out[2];
    sbr_track_detection_t d[2] = {{600.0f, 200.0f, 1.0f}, {300.0f, 100.0f, 1.0f}};
    sbr_track_detection_t outside = {2000.0f, 200.0f, 1.0f};
    sbr_track_model_t m;
    uint32_t n = 0u;
    static float tr[SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, VEL)];
    static float bi[SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, VEL)];
    make_model();
    memset(&blank, 0, sizeof blank);
    sbr_track_config_default(&cfg);
    cfg.model = &g_model;
    cfg.max_targets = 1u;
    cfg.window = WINDOW;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_track_model_check(&g_model));
    ROW(&t, SBR_ERR_NULL, sbr_track_model_check(NULL));
    bad = g_model;
    bad.vel_count = 6u;
    ROW(&t, SBR_ERR_SIZE, sbr_track_model_check(&bad));
    bad = g_model;
    bad.period = 0.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_track_model_check(&bad));
    bad = g_model;
    bad.transition = NULL;
    ROW(&t, SBR_ERR_NULL, sbr_track_model_check(&bad));
    g_trans[3] += 0.5f; /* a row that no longer sums to 1 */
    ROW(&t, SBR_ERR_CORRUPT, sbr_track_model_check(&g_model));
    g_trans[3] -= 0.5f;
    ROW(&t, SBR_OK, sbr_track_model_cv(&m, 1242.0f, 375.0f, PERIOD, VEL, SPACING, 1.5f, 10.0f, tr,
                                       sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    ROW(&t, SBR_ERR_NULL, sbr_track_model_cv(&m, 1242.0f, 375.0f, PERIOD, VEL, SPACING, 1.5f, 10.0f, NULL,
                                             sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    ROW(&t, SBR_ERR_SIZE, sbr_track_model_cv(&m, 1242.0f, 375.0f, PERIOD, VEL, SPACING, 1.5f, 10.0f, tr,
                                             (sizeof tr / sizeof tr[0]) - 1u, bi, sizeof bi / sizeof bi[0]));
    ROW(&t, SBR_ERR_SIZE, sbr_track_model_cv(&m, 1242.0f, 375.0f, PERIOD, 4u, SPACING, 1.5f, 10.0f, tr,
                                             sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    ROW(&t, SBR_ERR_RANGE, sbr_track_model_cv(&m, 1242.0f, 375.0f, NAN, VEL, SPACING, 1.5f, 10.0f, tr,
                                              sizeof tr / sizeof tr[0], bi, sizeof bi / sizeof bi[0]));
    ROW(&t, SBR_OK, sbr_track_model_kitti(&k));
    ROW(&t, SBR_ERR_NULL, sbr_track_model_kitti(NULL));
    make_model(); /* g_trans / g_birth as the tests expect them */
    ROW(&t, SBR_OK, sbr_track_init(&trk, &cfg, g_ws, sizeof(g_ws)));
    ROW(&t, SBR_ERR_NULL, sbr_track_init(NULL, &cfg, g_ws, sizeof(g_ws)));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_track_init(&trk, &cfg, g_ws, 16u));
    cfg.window = 4u;
    ROW(&t, SBR_ERR_SIZE, sbr_track_init(&blank, &cfg, g_ws, sizeof(g_ws))); /* a configuration error */
    cfg.window = WINDOW;
    ROW(&t, SBR_OK, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_track_step(&trk, PERIOD_US, d, 1u, out, 2u, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_track_step(&trk, PERIOD_US, NULL, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_STATE, sbr_track_step(&blank, PERIOD_US, d, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_track_step(&trk, 0u, d, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_track_step(&trk, (8u * PERIOD_US) + 1u, d, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_track_step(&trk, PERIOD_US, &outside, 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_SIZE, sbr_track_step(&trk, PERIOD_US, d, SBR_TRACK_MAX_DETECTIONS + 1u, out, 2u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_track_step(&trk, PERIOD_US, d, 2u, out, 2u, &n)); /* room for 1 target */
    status_table_check(&t);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_model_cv_rows_and_check);
    RUN_TEST(test_reset_repeats_a_fresh_tracker);
    RUN_TEST(test_straight_line_velocity);
    RUN_TEST(test_curved_path_through_five_misses);
    RUN_TEST(test_crossing_targets_keep_ids);
    RUN_TEST(test_clutter_and_longer_dt);
    RUN_TEST(test_bad_input);
    RUN_TEST(test_kitti_model);
    RUN_TEST(test_meas_sigma_bounded_by_window);
    RUN_TEST(test_model_spacing_and_extent_bounded);
    RUN_TEST(test_config_statuses);
    RUN_TEST(test_track_h_statuses);
    return UNITY_END();
}
