/* SPDX-License-Identifier: MIT */
/* Unity tests of the sign tracking (include/sbr/signs.h): a drive with known truth (two
   signs passing, a missed frame, a one-frame misclassification, a false detection),
   renaming by evidence, the confirmation share, gaps, capacity and every status. */
#include "unity.h"
#include "sbr/signs.h"
#include <math.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define P 100000u /* the nominal period, us */
#define WS_WORDS 70000u

static uint32_t g_ws[WS_WORDS];
static sbr_signs_t g_s;
static sbr_sign_t g_out[SBR_SIGNS_MAX_TRACKS];
static uint32_t g_n;

static void start(const sbr_signs_config_t *cfg)
{
    TEST_ASSERT_TRUE(sbr_signs_workspace_size(cfg) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_init(&g_s, cfg, g_ws, sizeof g_ws));
}

static void start_default(void)
{
    sbr_signs_config_t cfg;
    sbr_signs_config_default(&cfg);
    start(&cfg);
}

/* A detection of class c, score s, a w-pixel box centred on (x, y). */
static sbr_detection_t det(float x, float y, float w, uint16_t c, float s)
{
    sbr_detection_t d;
    memset(&d, 0, sizeof d);
    /* centre (x, y) to the nearest half pixel */
    d.box.width = (uint32_t)w;
    d.box.height = (uint32_t)w;
    d.box.x = (uint32_t)(x - 0.5f * (float)d.box.width + 0.5f);
    d.box.y = (uint32_t)(y - 0.5f * (float)d.box.height + 0.5f);
    d.class_id = c;
    d.score = s;
    d.class_share = 1.0f;
    d.parts = 3u;
    return d;
}

static const sbr_sign_t *find(uint32_t id)
{
    uint32_t i;
    for (i = 0u; i < g_n; i++) {
        if (g_out[i].id == id) {
            return &g_out[i];
        }
    }
    return NULL;
}

/* Sign A (30 km/h, class 1) on the right, moving outwards and faster as the car comes
   closer, seen in frames 0..13 but 6, taken for class 2 in frame 9; sign B (stop, 14) on
   the left in frames 3..10; a one-frame false detection (class 25) in frame 8. */
static void test_drive(void)
{
    uint32_t id_a = 0u, id_b = 0u, news = 0u, renamed = 0u;
    uint16_t new_class[4] = {0};
    int f;
    start_default();
    for (f = 0; f < 20; f++) {
        sbr_detection_t in[3];
        uint32_t ds[3] = {99u, 99u, 99u};
        uint32_t n = 0u, i;
        int ia = -1, ib = -1, ifalse = -1;
        if ((f < 14) && (f != 6)) {
            const float x = 800.0f + 6.0f * (float)f + 0.8f * (float)(f * f);
            const float y = 420.0f - 2.0f * (float)f - 0.3f * (float)(f * f);
            ia = (int)n;
            in[n++] = det(x + (((f % 2) != 0) ? 1.5f : -1.5f), y, 20.0f + 2.0f * (float)f, f == 9 ? 2u : 1u, 0.8f);
        }
        if ((f >= 3) && (f <= 10)) {
            ib = (int)n;
            in[n++] = det(400.0f - 9.0f * (float)(f - 3), 450.0f - (float)(f - 3), 30.0f, 14u, 0.6f);
        }
        if (f == 8) {
            ifalse = (int)n;
            in[n++] = det(1000.0f, 200.0f, 25.0f, 25u, 0.5f);
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 5000000u + (uint64_t)f * P, n > 0u ? in : NULL, n, ds,
                                                       g_out, SBR_SIGNS_MAX_TRACKS, &g_n));
        for (i = 0u; i < n; i++) {
            TEST_ASSERT_TRUE(ds[i] != 99u); /* every entry written */
        }
        for (i = 0u; i < g_n; i++) {
            if ((g_out[i].flags & SBR_SIGN_NEW) != 0u) {
                TEST_ASSERT_TRUE(news < 4u);
                new_class[news++] = g_out[i].class_id;
                TEST_ASSERT_EQUAL_UINT32(0u, g_out[i].frames);
            }
            if ((g_out[i].flags & SBR_SIGN_RENAMED) != 0u) {
                renamed++;
            }
            if (i > 0u) {
                TEST_ASSERT_TRUE(g_out[i].id > g_out[i - 1u].id); /* by id */
            }
        }
        if ((ia >= 0) && (f >= 1)) {
            if (id_a == 0u) {
                id_a = ds[ia];
            }
            TEST_ASSERT_EQUAL_UINT32(id_a, ds[ia]); /* stable through the missed frame 6 */
            TEST_ASSERT_NOT_NULL(find(id_a));
            TEST_ASSERT_EQUAL_UINT16(1u, find(id_a)->class_id); /* frame 9 does not rename it */
            TEST_ASSERT_EQUAL_FLOAT(0.8f, find(id_a)->score);
        }
        if (f == 0) {
            TEST_ASSERT_EQUAL_UINT32(0u, g_n); /* one detection does not confirm */
            TEST_ASSERT_EQUAL_UINT32(0u, ds[0]);
        }
        if (f == 6) {
            /* A coasts: listed, without a detection */
            TEST_ASSERT_NOT_NULL(find(id_a));
            TEST_ASSERT_EQUAL_UINT16(0u, find(id_a)->flags & SBR_SIGN_SEEN);
            TEST_ASSERT_EQUAL_UINT32(5u, find(id_a)->frames);
        }
        if ((ib >= 0) && (f >= 4)) {
            if (id_b == 0u) {
                id_b = ds[ib];
            }
            TEST_ASSERT_EQUAL_UINT32(id_b, ds[ib]);
            TEST_ASSERT_EQUAL_FLOAT(30.0f, find(id_b)->width);
        }
        if (ifalse >= 0) {
            TEST_ASSERT_EQUAL_UINT32(0u, ds[ifalse]); /* never confirmed */
        }
        if (f == 9) {
            /* its class's share: 8 detections of 1 at 0.8 and one of 2 */
            TEST_ASSERT_FLOAT_WITHIN(1e-5f, 8.0f / 9.0f, find(id_a)->share);
        }
        if (f == 19) {
            /* A: last seen in frame 13, gone after 5 misses; B likewise */
            TEST_ASSERT_EQUAL_UINT32(0u, g_n);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(2u, news); /* each sign once per pass, the false one never */
    TEST_ASSERT_EQUAL_UINT32(0u, renamed);
    TEST_ASSERT_TRUE((id_a != 0u) && (id_b != 0u) && (id_a != id_b));
    TEST_ASSERT_EQUAL_UINT16(1u, new_class[0]);
    TEST_ASSERT_EQUAL_UINT16(14u, new_class[1]);
}

/* A still sign: frames of class `cls[f]` with score `sc[f]` at one place; returns the
   flags of the (single) sign in each frame, 0 when none is listed. */
static void still(uint32_t frames, const uint16_t *cls, const float *sc, uint16_t *flags, uint16_t *classes)
{
    uint32_t f;
    for (f = 0u; f < frames; f++) {
        const sbr_detection_t d = det(600.0f, 300.0f, 40.0f, cls[f], sc[f]);
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, (uint64_t)(f + 1u) * P, &d, 1u, NULL, g_out, 4u, &g_n));
        TEST_ASSERT_TRUE(g_n <= 1u);
        flags[f] = (g_n == 1u) ? g_out[0].flags : 0u;
        classes[f] = (g_n == 1u) ? g_out[0].class_id : 0xFFFFu;
    }
}

/* Evidence turns: confirmed as 3 by its first two frames, then class 5 at a higher score
   outweighs it in the fourth frame (0.5 + 0.5 < 0.9 + 0.9): reported again, same id. */
static void test_renamed_by_evidence(void)
{
    const uint16_t cls[6] = {3u, 3u, 5u, 5u, 5u, 5u};
    const float sc[6] = {0.5f, 0.5f, 0.9f, 0.9f, 0.9f, 0.9f};
    uint16_t fl[6], cl[6];
    uint32_t id;
    start_default();
    still(6u, cls, sc, fl, cl);
    TEST_ASSERT_EQUAL_UINT16(0u, fl[0]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_NEW | SBR_SIGN_SEEN, fl[1]);
    TEST_ASSERT_EQUAL_UINT16(3u, cl[1]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_SEEN, fl[2]); /* 1.0 against 0.9: still 3 */
    TEST_ASSERT_EQUAL_UINT16(3u, cl[2]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_RENAMED | SBR_SIGN_SEEN, fl[3]);
    TEST_ASSERT_EQUAL_UINT16(5u, cl[3]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_SEEN, fl[4]);
    TEST_ASSERT_EQUAL_UINT16(5u, cl[5]);
    id = g_out[0].id;
    TEST_ASSERT_EQUAL_UINT32(1u, id);
    TEST_ASSERT_EQUAL_UINT32(6u, g_out[0].hits);
    TEST_ASSERT_EQUAL_UINT32(4u, g_out[0].frames);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 3.6f / 4.6f, g_out[0].share);
}

/* confirm_share 0.7: alternating classes hold the confirmation back until one class has
   70 % of the evidence. */
static void test_confirm_share(void)
{
    const uint16_t cls[6] = {3u, 5u, 3u, 3u, 3u, 3u};
    const float sc[6] = {0.6f, 0.6f, 0.6f, 0.6f, 0.6f, 0.6f};
    uint16_t fl[6], cl[6];
    sbr_signs_config_t cfg;
    sbr_signs_config_default(&cfg);
    cfg.confirm_share = 0.7f;
    start(&cfg);
    still(6u, cls, sc, fl, cl);
    /* shares of class 3: 1, 0.5, 0.67, 0.75 */
    TEST_ASSERT_EQUAL_UINT16(0u, fl[0]);
    TEST_ASSERT_EQUAL_UINT16(0u, fl[1]);
    TEST_ASSERT_EQUAL_UINT16(0u, fl[2]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_NEW | SBR_SIGN_SEEN, fl[3]);
    TEST_ASSERT_EQUAL_UINT16(3u, cl[3]);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_SEEN, fl[4]);
}

/* A gap of more than SBR_SIGNS_MAX_GAP periods ends the tracks; the next sign's id is new. */
static void test_gap(void)
{
    const sbr_detection_t d = det(300.0f, 200.0f, 30.0f, 7u, 0.9f);
    uint32_t ds = 0u, first;
    start_default();
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 2u * P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    first = ds;
    TEST_ASSERT_TRUE(first != 0u);
    /* 8 periods: kept */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 10u * P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    TEST_ASSERT_EQUAL_UINT32(first, ds);
    /* 8 periods and 1 us: ended */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 18u * P + 1u, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(0u, g_n);
    TEST_ASSERT_EQUAL_UINT32(0u, ds);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 19u * P + 1u, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    TEST_ASSERT_TRUE(ds > first);
    TEST_ASSERT_EQUAL_UINT16(SBR_SIGN_NEW | SBR_SIGN_SEEN, g_out[0].flags);
    /* reset: ids go on */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_reset(&g_s));
    first = ds;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 20u * P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 21u * P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_TRUE(ds > first);
}

/* Capacity: more confirmed signs than the result array, more signs than max_tracks,
   more detections than the tracker takes; and a centre outside the image. */
static void test_capacity(void)
{
    sbr_detection_t d[3];
    sbr_signs_config_t cfg;
    uint32_t ds[3];
    d[0] = det(300.0f, 200.0f, 30.0f, 7u, 0.9f);
    d[1] = det(900.0f, 500.0f, 30.0f, 8u, 0.9f);
    d[2] = det(1400.0f, 500.0f, 30.0f, 8u, 0.9f); /* centre right of the image */
    start_default();
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, P, d, 3u, ds, g_out, 1u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_signs_update(&g_s, 2u * P, d, 3u, ds, g_out, 1u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    TEST_ASSERT_TRUE((ds[0] != 0u) && (ds[1] != 0u));
    TEST_ASSERT_EQUAL_UINT32(0u, ds[2]);
    TEST_ASSERT_EQUAL_UINT32(ds[0] < ds[1] ? ds[0] : ds[1], g_out[0].id);
    /* one track for two signs */
    sbr_signs_config_default(&cfg);
    cfg.max_tracks = 1u;
    start(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_signs_update(&g_s, P, d, 2u, ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_signs_update(&g_s, 2u * P, d, 2u, ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    TEST_ASSERT_EQUAL_UINT16(7u, g_out[0].class_id);
}

static void test_config_and_workspace(void)
{
    sbr_signs_config_t cfg, bad;
    sbr_signs_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_config_check(&cfg));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_SIGNS_WORKSPACE_SIZE(16u, 43u), (uint32_t)sbr_signs_workspace_size(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_config_check(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_signs_workspace_size(NULL));
    bad = cfg; bad.class_count = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_signs_config_check(&bad));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_signs_workspace_size(&bad));
    bad = cfg; bad.class_count = 65u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_signs_config_check(&bad));
    bad = cfg; bad.max_tracks = 33u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_signs_config_check(&bad));
    bad = cfg; bad.width = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.height = 4.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.period_us = 999u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.confirm_hits = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.confirm_share = 1.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.max_misses = 256u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.meas_sigma = INFINITY;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    bad = cfg; bad.min_certainty = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_config_check(&bad));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_init(&g_s, &bad, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_init(NULL, &cfg, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_init(&g_s, NULL, g_ws, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_signs_init(&g_s, &cfg, NULL, sizeof g_ws));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_signs_init(&g_s, &cfg, g_ws, sbr_signs_workspace_size(&cfg) - 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_signs_init(&g_s, &cfg, (unsigned char *)g_ws + 2, sizeof g_ws - 4u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_init(&g_s, &cfg, g_ws, sbr_signs_workspace_size(&cfg)));
}

static void test_statuses(void)
{
    sbr_detection_t d = det(300.0f, 200.0f, 30.0f, 7u, 0.9f), bad;
    sbr_signs_t blank;
    uint32_t ds = 0u;
    start_default();
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_update(NULL, P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_update(&g_s, P, NULL, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_update(&g_s, P, &d, 1u, &ds, NULL, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_update(&g_s, P, &d, 1u, &ds, g_out, 4u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, P, &d, 1u, NULL, NULL, 0u, &g_n));
    /* time must go forward; nothing changes on a refusal */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_update(&g_s, P, &d, 1u, &ds, g_out, 4u, &g_n));
    bad = d; bad.score = 1.5f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_update(&g_s, 2u * P, &bad, 1u, &ds, g_out, 4u, &g_n));
    bad = d; bad.score = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_update(&g_s, 2u * P, &bad, 1u, &ds, g_out, 4u, &g_n));
    bad = d; bad.class_id = 43u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_signs_update(&g_s, 2u * P, &bad, 1u, &ds, g_out, 4u, &g_n));
    /* the refusals changed nothing: the second detection confirms the sign */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_signs_update(&g_s, 2u * P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_UINT32(1u, g_n);
    TEST_ASSERT_EQUAL_UINT32(2u, g_out[0].hits);
    memset(&blank, 0, sizeof blank);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_signs_update(&blank, P, &d, 1u, &ds, g_out, 4u, &g_n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_signs_reset(&blank));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_signs_reset(NULL));
    /* a corrupted tracker inside is found */
    g_s.trk.magic ^= 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_signs_update(&g_s, 3u * P, &d, 1u, &ds, g_out, 4u, &g_n));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_drive);
    RUN_TEST(test_renamed_by_evidence);
    RUN_TEST(test_confirm_share);
    RUN_TEST(test_gap);
    RUN_TEST(test_capacity);
    RUN_TEST(test_config_and_workspace);
    RUN_TEST(test_statuses);
    return UNITY_END();
}
