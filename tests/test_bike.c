/* SPDX-License-Identifier: MIT */
/* Unity tests of include/sbr/bike.h: bicycle tracking from wheel ellipses (projection,
   pairing, particle filter). */
#include "sbr/bike.h"

#include <math.h>
#include <string.h>

#include "test_status_table.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

#define PF_PARTICLES 500u
static uint32_t g_ws[SBR_BIKE_PF_WORKSPACE_SIZE(PF_PARTICLES) / sizeof(uint32_t)];

static sbr_bike_pf_config_t config(uint32_t seed)
{
    sbr_bike_pf_config_t cfg;
    sbr_bike_pf_config_default(&cfg);
    cfg.particles = PF_PARTICLES;
    cfg.seed = seed;
    return cfg;
}

/* Pinhole projection of a point of the camera frame. */
static void project_point(const sbr_camera_t *cam, float x, float y, float z, sbr_pointf_t *p)
{
    p->x = cam->focal * x / z + cam->cx;
    p->y = cam->focal * y / z + cam->cy;
}

/* 64 points of a wheel circle (contact point cx, cz, plane direction th, roll), projected. */
static void wheel_points(const sbr_camera_t *cam, float r, float x, float z, float th, float roll,
                         sbr_pointf_t *p)
{
    const float dx = cosf(th), dz = sinf(th);
    const float ux = -sinf(roll) * dz, uy = -cosf(roll), uz = sinf(roll) * dx;
    const float px = x + r * ux, py = cam->height + r * uy, pz = z + r * uz;
    uint32_t k;
    for (k = 0u; k < 64u; k++) {
        const float t = 6.2831853f * (float)k / 64.0f;
        const float a = r * cosf(t), b = r * sinf(t);
        project_point(cam, px + a * dx + b * ux, py + b * uy, pz + a * dz + b * uz, &p[k]);
    }
}

static void test_projection_matches_projected_circle_points(void)
{
    const sbr_bike_pf_config_t cfg = config(1u);
    const sbr_camera_t *cam = &cfg.camera;
    const sbr_bike_model_t *m = &cfg.model;
    sbr_ellipse_t rear;
    sbr_ellipse_t front;
    sbr_pointf_t pts[64];
    sbr_conic_t q;
    float rms;
    float mx;
    /* side view, wheel planes parallel to the image: circles of radius f r / Z */
    sbr_bike_state_t s = {0.0f, 10.0f, 0.0f, 3.0f, 0.0f, 0.0f};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(cam, m, &s, &rear, &front));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 34.0f, rear.semi_major);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 34.0f, rear.semi_minor);
    TEST_ASSERT_FLOAT_WITHIN(1e-2f, 639.5f, rear.cx);
    TEST_ASSERT_FLOAT_WITHIN(1e-2f, 359.5f + 86.0f, rear.cy);
    TEST_ASSERT_FLOAT_WITHIN(1e-2f, 639.5f + 105.0f, front.cx);
    /* oblique, steered and leaning: every projected circle point lies on the ellipse */
    s.x = -2.0f;
    s.z = 9.0f;
    s.heading = 1.0f;
    s.steer = 0.3f;
    s.roll = 0.25f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(cam, m, &s, &rear, &front));
    wheel_points(cam, m->wheel_radius, s.x, s.z, s.heading, s.roll, pts);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&rear, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_residual(&q, pts, 64u, &rms, &mx));
    TEST_ASSERT_TRUE(rear.semi_minor < 0.8f * rear.semi_major); /* really oblique */
    TEST_ASSERT_TRUE(mx < 0.01f);
    wheel_points(cam, m->wheel_radius, s.x + m->wheelbase * cosf(s.heading), s.z + m->wheelbase * sinf(s.heading),
                 s.heading + s.steer, s.roll, pts);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_ellipse_to_conic(&front, &q));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_conic_residual(&q, pts, 64u, &rms, &mx));
    TEST_ASSERT_TRUE(mx < 0.01f);
    /* riding straight away through the optical axis: the wheels are seen edge-on */
    s.x = 0.0f;
    s.heading = 1.5707964f;
    s.steer = 0.0f;
    s.roll = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_bike_project(cam, m, &s, &rear, &front));
    /* behind the camera */
    s.x = 0.0f;
    s.z = -3.0f;
    s.heading = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_DEGENERATE, sbr_bike_project(cam, m, &s, &rear, NULL));
    /* bad input */
    s.z = 10.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_project(NULL, m, &s, &rear, &front));
    s.speed = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_project(cam, m, &s, &rear, &front));
    s.speed = 1.0f;
    s.roll = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_project(cam, m, &s, &rear, &front));
}

static void test_model_turns_and_leans(void)
{
    sbr_bike_model_t m;
    sbr_bike_state_t s = {0.0f, 10.0f, 0.0f, 4.0f, 0.2f, 0.0f};
    sbr_bike_state_t out;
    float yaw;
    sbr_bike_model_default(&m);
    yaw = 4.0f * tanf(0.2f) / m.wheelbase;
    /* straight: distance v t */
    s.steer = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &s, 2000000u, &out));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 8.0f, out.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 10.0f, out.z);
    /* steady turn: heading grows at v tan(delta) / L, the rear wheel stays on the circle
       of radius L / tan(delta), the roll settles at atan(v yaw / g) */
    s.steer = 0.2f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &s, 2000000u, &out));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 2.0f * yaw, out.heading);
    {
        const float rad = m.wheelbase / tanf(0.2f);
        const float dx = out.x - 0.0f;
        const float dz = out.z - (10.0f + rad);
        TEST_ASSERT_FLOAT_WITHIN(0.01f * rad, rad, sqrtf(dx * dx + dz * dz));
    }
    TEST_ASSERT_FLOAT_WITHIN(0.01f, atanf(4.0f * yaw / 9.81f), out.roll);
    TEST_ASSERT_TRUE(out.roll > 0.0f); /* leaning into a left turn */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &s, 10000001u, &out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &s, UINT32_MAX, &out));
    /* issue 70, item 15: a valid state advanced by the documented maximum leaves the
       state's range (x = 9999 m at 100 m/s for 10 s): refused, out untouched; what SBR_OK
       returns is always taken back */
    {
        const sbr_bike_state_t edge = {9999.0f, 10.0f, 0.0f, 100.0f, 0.0f, 0.0f};
        sbr_bike_state_t guard = {7.0f, 7.0f, 0.5f, 7.0f, 0.1f, 0.1f};
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &edge, 10000000u, &guard));
        TEST_ASSERT_EQUAL_FLOAT(7.0f, guard.x);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &edge, 5000u, &guard));
        TEST_ASSERT_FLOAT_WITHIN(1e-2f, 9999.5f, guard.x);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &guard, 0u, &out));
    }
    m.wheelbase = 0.5f; /* shorter than two wheel radii */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &s, 100000u, &out));
}


/* The projected rear (which = 0) or front (1) wheel of state s. */
static sbr_ellipse_t wheel_of(const sbr_bike_pf_config_t *cfg, const sbr_bike_state_t *s, int which)
{
    sbr_ellipse_t rear;
    sbr_ellipse_t front;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg->camera, &cfg->model, s, &rear, &front));
    return (which == 0) ? rear : front;
}

static void test_pairing_groups_tyre_edges_and_rejects_misfits(void)
{
    const sbr_bike_pf_config_t cfg = config(1u);
    sbr_ellipse_t el[6];
    sbr_wheel_pair_t pairs[4];
    uint32_t n = 99u;
    const sbr_bike_state_t s = {-1.0f, 10.0f, 0.3f, 3.0f, 0.0f, 0.0f};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &s, &el[0], &el[2]));
    /* each tyre as an inner and an outer edge, 2 px either side of the mid-line */
    el[1] = el[0];
    el[3] = el[2];
    el[0].semi_major -= 2.0f;
    el[0].semi_minor -= 2.0f;
    el[1].semi_major += 2.0f;
    el[1].semi_minor += 2.0f;
    el[2].semi_major -= 2.0f;
    el[2].semi_minor -= 2.0f;
    el[3].semi_major += 2.0f;
    el[3].semi_minor += 2.0f;
    /* a small far ellipse and a huge one: no wheel of this bicycle */
    el[4] = el[0];
    el[4].cx += 300.0f;
    el[4].semi_major = 8.0f;
    el[4].semi_minor = 7.0f;
    el[5] = el[2];
    el[5].cx -= 400.0f;
    el[5].semi_major = 120.0f;
    el[5].semi_minor = 110.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pair_wheels(el, 6u, &cfg.model, pairs, 4u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(((pairs[0].first == 0u) && (pairs[0].second == 2u)) ||
                     ((pairs[0].first == 2u) && (pairs[0].second == 0u)));
    {
        sbr_ellipse_t rear;
        sbr_ellipse_t front;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &s, &rear, &front));
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, rear.semi_major, pairs[0].wheel[0].semi_major);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, rear.cx, pairs[0].wheel[0].cx);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, front.semi_minor, pairs[0].wheel[1].semi_minor);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, front.angle, pairs[0].wheel[1].angle);
    }
    /* three wheels in a row: two pairs (neighbours), capacity 1 keeps the best */
    el[4] = el[2];
    el[4].cx += el[2].cx - el[0].cx;
    el[4].cy += el[2].cy - el[0].cy;
    el[4].cx += 3.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_bike_pair_wheels(el, 5u, &cfg.model, pairs, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_TRUE(pairs[0].first == 0u || pairs[0].second == 0u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pair_wheels(el, 5u, &cfg.model, pairs, 4u, &n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_TRUE(pairs[0].score <= pairs[1].score);
    /* bad input */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pair_wheels(NULL, 0u, &cfg.model, pairs, 4u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_pair_wheels(NULL, 2u, &cfg.model, pairs, 4u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_bike_pair_wheels(el, SBR_BIKE_MAX_ELLIPSES + 1u, &cfg.model, pairs, 4u, &n));
    el[1].semi_minor = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pair_wheels(el, 5u, &cfg.model, pairs, 4u, &n));
    el[1].semi_minor = 10.0f;
    el[1].cx = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pair_wheels(el, 5u, &cfg.model, pairs, 4u, &n));
    /* regression (fuzzer finding): a finite angle of 3.4e38 doubled to inf, and the pair's
       wheel came out with a NaN angle and SBR_OK */
    {
        sbr_ellipse_t two[2];
        two[0] = wheel_of(&cfg, &s, 0);
        two[1] = wheel_of(&cfg, &s, 1);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pair_wheels(two, 2u, &cfg.model, pairs, 4u, &n));
        TEST_ASSERT_EQUAL_UINT32(1u, n);
        two[1].angle = 3.4e38f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pair_wheels(two, 2u, &cfg.model, pairs, 4u, &n));
        two[1].angle = -1e6f;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pair_wheels(two, 2u, &cfg.model, pairs, 4u, &n));
    }
}

/* A bicycle crossing 12 m ahead at 5 m/s, 25 frames per second, wheel ellipses with
   0.5 px Gaussian noise on centres and axes (frames 30..34: nothing seen). Returns the
   largest position error from frame 10 on; `last` gets the final estimate. */
static float crossing_pass(sbr_bike_pf_t *pf_in, const sbr_bike_pf_config_t *cfg_in,
                           sbr_bike_result_t *last, sbr_bike_state_t *truth,
                           uint32_t *association_errors)
{
    sbr_bike_pf_t *const pfp = pf_in;
    const sbr_bike_pf_config_t cfg = *cfg_in;
    sbr_bike_state_t t = {-5.0f, 12.0f, 0.0f, 5.0f, 0.0f, 0.0f};
    tsup_rng_t rng = {4242u};
    float worst = 0.0f;
    uint32_t k;
    *association_errors = 0u;
    for (k = 0u; k < 60u; k++) {
        sbr_ellipse_t e[2];
        sbr_bike_result_t r;
        uint32_t w;
        const uint32_t seen = (k < 30u || k >= 35u) ? 2u : 0u;
        if (k > 0u) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&cfg.model, &t, 40000u, &t));
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &t, &e[0], &e[1]));
        for (w = 0u; w < 2u; w++) {
            e[w].cx += 0.5f * tsup_gauss(&rng);
            e[w].cy += 0.5f * tsup_gauss(&rng);
            e[w].semi_major += 0.5f * tsup_gauss(&rng);
            e[w].semi_minor = fminf(e[w].semi_minor + 0.5f * tsup_gauss(&rng), e[w].semi_major);
        }
        /* hand them over front first: the filter must find out which is which */
        {
            const sbr_ellipse_t swapped[2] = {e[1], e[0]};
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(pfp, 40000u, swapped, seen, &r));
        }
        TEST_ASSERT_TRUE((r.flags & SBR_BIKE_TRACKING) != 0u);
        if (seen != 0u) {
            TEST_ASSERT_EQUAL_UINT32(3u, r.wheels);
            TEST_ASSERT_TRUE((r.flags & SBR_BIKE_UPDATED) != 0u);
            if (k >= 5u && fabsf(r.rear.cx - e[0].cx) > 1e-3f) {
                (*association_errors)++;
            }
        } else {
            TEST_ASSERT_EQUAL_UINT32(0u, r.wheels);
            TEST_ASSERT_TRUE((r.flags & SBR_BIKE_UPDATED) == 0u);
        }
        if (k >= 10u) {
            worst = fmaxf(worst, hypotf(r.mean.x - t.x, r.mean.z - t.z));
        }
        *last = r;
    }
    *truth = t;
    return worst;
}

static float run_crossing(uint32_t seed, sbr_bike_result_t *last, sbr_bike_state_t *truth,
                          uint32_t *association_errors)
{
    sbr_bike_pf_config_t cfg = config(seed);
    sbr_bike_pf_t pf;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)sizeof g_ws, (uint32_t)sbr_bike_pf_workspace_size(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    return crossing_pass(&pf, &cfg, last, truth, association_errors);
}

/* sbr_bike_pf_reset(): a second crossing after a reset is the first one, bit for bit; a
   blank filter is refused. */
static void test_filter_reset_repeats_a_fresh_filter(void)
{
    sbr_bike_pf_config_t cfg = config(7u);
    sbr_bike_pf_t pf;
    sbr_bike_pf_t blank;
    sbr_bike_result_t a;
    sbr_bike_result_t b;
    sbr_bike_state_t t;
    uint32_t assoc = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    (void)crossing_pass(&pf, &cfg, &a, &t, &assoc);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_reset(&pf));
    (void)crossing_pass(&pf, &cfg, &b, &t, &assoc);
    TEST_ASSERT_EQUAL_MEMORY(&a.mean, &b.mean, sizeof a.mean);
    TEST_ASSERT_EQUAL_MEMORY(&a.stddev, &b.stddev, sizeof a.stddev);
    memset(&blank, 0, sizeof blank);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_bike_pf_reset(&blank));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_pf_reset(NULL));
}

static void test_filter_keeps_a_crossing_bicycle(void)
{
    sbr_bike_result_t a;
    sbr_bike_result_t b;
    sbr_bike_state_t t;
    uint32_t assoc = 99u;
    const float worst = run_crossing(7u, &a, &t, &assoc);
    /* stated accuracy: within 0.3 m from frame 10 on (0.4 s), also through 5 frames
       without measurements; speed within 0.3 m/s and heading within 5 degrees at the end */
    TEST_ASSERT_TRUE(worst < 0.3f);
    TEST_ASSERT_FLOAT_WITHIN(0.3f, t.speed, a.mean.speed);
    TEST_ASSERT_FLOAT_WITHIN(0.087f, t.heading, a.mean.heading);
    TEST_ASSERT_FLOAT_WITHIN(0.1f, t.steer, a.mean.steer);
    TEST_ASSERT_TRUE(a.stddev.x > 0.0f && a.stddev.x < 0.3f);
    TEST_ASSERT_EQUAL_UINT32(0u, assoc);
    /* the same seed gives the same run, bit for bit */
    (void)run_crossing(7u, &b, &t, &assoc);
    TEST_ASSERT_EQUAL_MEMORY(&a.mean, &b.mean, sizeof a.mean);
    /* another seed: another run, as accurate */
    TEST_ASSERT_TRUE(run_crossing(99u, &b, &t, &assoc) < 0.3f);
    TEST_ASSERT_TRUE(memcmp(&a.mean, &b.mean, sizeof a.mean) != 0);
}

static void test_filter_drops_a_lost_track_and_restarts(void)
{
    sbr_bike_pf_config_t cfg = config(3u);
    sbr_bike_pf_t pf;
    sbr_bike_result_t r;
    sbr_ellipse_t e[2];
    const sbr_bike_state_t t = {-2.0f, 10.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    uint32_t k;
    cfg.max_missed = 3u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    /* nothing seen: no track */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, NULL, 0u, &r));
    TEST_ASSERT_EQUAL_UINT32(0u, r.flags);
    /* one ellipse alone starts nothing */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &t, &e[0], &e[1]));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, e, 1u, &r));
    TEST_ASSERT_EQUAL_UINT32(0u, r.flags);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    TEST_ASSERT_EQUAL_UINT32(SBR_BIKE_TRACKING | SBR_BIKE_STARTED | SBR_BIKE_UPDATED,
                             r.flags & ~SBR_BIKE_RESAMPLED);
    for (k = 0u; k < 2u; k++) {
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, NULL, 0u, &r));
        TEST_ASSERT_EQUAL_UINT32(SBR_BIKE_TRACKING, r.flags & ~SBR_BIKE_RESAMPLED);
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, NULL, 0u, &r));
    TEST_ASSERT_EQUAL_UINT32(SBR_BIKE_LOST, r.flags);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    TEST_ASSERT_TRUE((r.flags & SBR_BIKE_STARTED) != 0u);
}

static void test_filter_rejects_bad_input(void)
{
    sbr_bike_pf_config_t cfg = config(1u);
    sbr_bike_pf_t pf;
    sbr_bike_result_t r;
    sbr_ellipse_t e[2] = {{100.0f, 100.0f, 20.0f, 18.0f, 0.0f}, {160.0f, 100.0f, 20.0f, 18.0f, 0.0f}};
    memset(&pf, 0, sizeof pf);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_pf_init(NULL, &cfg, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws - 4u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_bike_pf_init(&pf, &cfg, (uint8_t *)g_ws + 2, sizeof g_ws - 4u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_bike_pf_init(&pf, &cfg, NULL, sizeof g_ws));
    cfg.particles = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_bike_pf_workspace_size(&cfg));
    cfg = config(1u);
    cfg.meas_px = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    cfg = config(1u);
    cfg.camera.focal = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    /* regression (fuzzer finding): a positive but denormal focal length (9e-40) was taken,
       and the first measurement started a track with a NaN mean and SBR_OK; the camera
       and model now have physical bounds */
    cfg.camera.focal = 9.18714e-40f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_config_check(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    cfg.camera.focal = 0.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_config_check(&cfg));
    cfg.camera.focal = 1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_config_check(&cfg));
    cfg = config(1u);
    cfg.camera.height = 1e-30f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_config_check(&cfg));
    cfg = config(1u);
    cfg.model.roll_tau = 1e-30f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_config_check(&cfg));
    cfg = config(1u);
    cfg.model.wheel_radius = 1e-30f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_config_check(&cfg));
    cfg = config(1u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 1000001u, e, 2u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_step(&pf, UINT32_MAX, e, 2u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 2000000u, e, 2u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_bike_pf_step(&pf, 40000u, e, SBR_BIKE_MAX_ELLIPSES + 1u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_pf_step(&pf, 40000u, NULL, 2u, &r));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_bike_pf_step(&pf, 40000u, e, 2u, NULL));
    e[1].semi_major = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    e[1].semi_major = 10.0f; /* smaller than its minor axis */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    /* corrupted instance */
    pf.cfg.particles = 3u;
    e[1].semi_major = 20.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
}

/* bike.h: every documented status, in one table. */
static void test_bike_h_statuses(void)
{
    status_table_t t;
    sbr_bike_pf_config_t cfg = config(1u);
    sbr_bike_pf_config_t bad = config(1u);
    sbr_bike_pf_config_t few = config(1u);
    sbr_bike_model_t badm;
    sbr_bike_state_t s = {0.0f, 10.0f, 0.0f, 5.0f, 0.0f, 0.0f};
    sbr_bike_state_t behind = {0.0f, -3.0f, 0.0f, 5.0f, 0.0f, 0.0f};
    sbr_bike_state_t out;
    sbr_bike_pf_t pf;
    sbr_bike_pf_t blank;
    sbr_bike_result_t r;
    sbr_ellipse_t e[2];
    sbr_ellipse_t nan_e[1] = {{NAN, 100.0f, 20.0f, 18.0f, 0.0f}};
    sbr_wheel_pair_t pairs[1];
    uint32_t n = 0u;
    memset(&blank, 0, sizeof blank);
    badm = cfg.model;
    badm.wheelbase = 0.5f; /* shorter than two wheel radii */
    bad.meas_px = 0.0f;
    few.particles = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &s, &e[0], &e[1]));
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_bike_predict_state(&cfg.model, &s, 100000u, &out));
    ROW(&t, SBR_ERR_NULL, sbr_bike_predict_state(&cfg.model, &s, 100000u, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_predict_state(&badm, &s, 100000u, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_predict_state(&cfg.model, &s, 11000000u, &out));
    ROW(&t, SBR_OK, sbr_bike_project(&cfg.camera, &cfg.model, &s, &e[0], NULL)); /* either may be NULL */
    ROW(&t, SBR_ERR_NULL, sbr_bike_project(NULL, &cfg.model, &s, &e[0], &e[1]));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_project(&cfg.camera, &badm, &s, &e[0], &e[1]));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_bike_project(&cfg.camera, &cfg.model, &behind, &e[0], NULL)); /* behind the camera */
    ROW(&t, SBR_OK, sbr_bike_pair_wheels(e, 2u, &cfg.model, pairs, 1u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_bike_pair_wheels(e, 2u, &cfg.model, pairs, 1u, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_bike_pair_wheels(e, SBR_BIKE_MAX_ELLIPSES + 1u, &cfg.model, pairs, 1u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_pair_wheels(nan_e, 1u, &cfg.model, pairs, 1u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_bike_pair_wheels(e, 2u, &cfg.model, NULL, 0u, &n));
    ROW(&t, SBR_OK, sbr_bike_pf_config_check(&cfg));
    ROW(&t, SBR_ERR_NULL, sbr_bike_pf_config_check(NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_pf_config_check(&bad));
    ROW(&t, SBR_ERR_SIZE, sbr_bike_pf_config_check(&few));
    ROW(&t, SBR_OK, sbr_bike_pf_init(&pf, &cfg, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_NULL, sbr_bike_pf_init(NULL, &cfg, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_pf_init(&blank, &bad, g_ws, sizeof g_ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_bike_pf_init(&blank, &cfg, g_ws, 64u));
    ROW(&t, SBR_OK, sbr_bike_pf_step(&pf, 40000u, e, 2u, &r));
    ROW(&t, SBR_ERR_NULL, sbr_bike_pf_step(&pf, 40000u, e, 2u, NULL));
    ROW(&t, SBR_ERR_STATE, sbr_bike_pf_step(&blank, 40000u, e, 2u, &r));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 1000001u, e, 2u, &r));
    ROW(&t, SBR_ERR_RANGE, sbr_bike_pf_step(&pf, 40000u, nan_e, 1u, &r));
    ROW(&t, SBR_ERR_SIZE, sbr_bike_pf_step(&pf, 40000u, e, SBR_BIKE_MAX_ELLIPSES + 1u, &r));
    status_table_check(&t);
}

/* Issue 55, items 1 and 2: a sub-step that turns by more than 2 pi keeps the heading in
   (-pi, pi] and equal to the turn's angle modulo 2 pi; the state's ranges are those of
   bike.h (heading (-pi, pi], |x|, |z| < 1e4, speed 0 .. 100, wheelbase < 100). */
static void test_heading_stays_wrapped_and_ranges_match_the_header(void)
{
    sbr_bike_model_t m;
    sbr_bike_state_t s = {0.0f, 10.0f, 0.0f, 29.2706f, 1.52471f, 0.0f};
    sbr_bike_state_t out;
    sbr_ellipse_t rear;
    sbr_camera_t cam = {800.0f, 640.0f, 360.0f, 1.2f};
    sbr_bike_model_default(&m);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &s, 10000000u, &out));
    TEST_ASSERT_TRUE(out.heading > -3.14159265f && out.heading <= 3.14159274f);
    s.speed = 30.0f;
    s.steer = 1.53852f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &s, 90000u, &out));
    TEST_ASSERT_TRUE(out.heading > -3.14159265f && out.heading <= 3.14159274f);
    {
        /* the turn in 90 ms (sub-steps of 18 ms): yaw rate v tan(steer) / L */
        const float turn = 30.0f * tanf(1.53852f) / m.wheelbase * 0.09f;
        const float want = turn - 6.2831853f * floorf((turn + 3.14159265f) / 6.2831853f);
        TEST_ASSERT_FLOAT_WITHIN(2e-3f * turn / 6.2831853f + 1e-4f, want, out.heading);
    }
    /* heading 3.3 is outside (-pi, pi]: refused by both calls */
    s.heading = 3.3f;
    s.speed = 2.0f;
    s.steer = 0.1f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &s, 1000u, &out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_project(&cam, &m, &s, &rear, NULL));
    s.heading = 3.14159274f; /* pi as a float: in range */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&m, &s, 1000u, &out));
    s.heading = -3.14159274f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&m, &s, 1000u, &out));
    s.heading = 0.0f;
    {
        /* each bound of bike.h: the last value inside, the first outside */
        static const float inside[3] = {9999.0f, 100.0f, 99.0f};
        static const float outside[3] = {1e4f, 100.5f, 100.0f};
        uint32_t k;
        for (k = 0u; k < 3u; k++) {
            sbr_bike_state_t t = s;
            sbr_bike_model_t mm = m;
            float *field[3] = {&t.x, &t.speed, &mm.wheelbase};
            *field[k] = inside[k];
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_bike_predict_state(&mm, &t, 1000u, &out));
            *field[k] = outside[k];
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_bike_predict_state(&mm, &t, 1000u, &out));
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_projection_matches_projected_circle_points);
    RUN_TEST(test_model_turns_and_leans);
    RUN_TEST(test_heading_stays_wrapped_and_ranges_match_the_header);
    RUN_TEST(test_pairing_groups_tyre_edges_and_rejects_misfits);
    RUN_TEST(test_filter_keeps_a_crossing_bicycle);
    RUN_TEST(test_filter_reset_repeats_a_fresh_filter);
    RUN_TEST(test_filter_drops_a_lost_track_and_restarts);
    RUN_TEST(test_filter_rejects_bad_input);
    RUN_TEST(test_bike_h_statuses);
    return UNITY_END();
}
