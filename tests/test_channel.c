/* SPDX-License-Identifier: MIT */
/* Unity tests of the channel representation (include/sbr/channel.h), with the thesis's
   worked example as recomputed in THESIS_NOTES.md. */
#include "unity.h"
#include "sbr/channel.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static sbr_channel_config_t thesis_cfg(void)
{
    sbr_channel_config_t cfg;
    sbr_channel_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_config_check(&cfg));
    return cfg;
}

static void test_default_is_thesis_layout(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    float lo;
    float hi;
    TEST_ASSERT_EQUAL_FLOAT(1.0f, cfg.first_centre);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, cfg.spacing);
    TEST_ASSERT_EQUAL_UINT32(10u, cfg.count);
    TEST_ASSERT_EQUAL_UINT32(3u, cfg.overlap);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_range(&cfg, &lo, &hi));
    TEST_ASSERT_EQUAL_FLOAT(1.5f, lo);
    TEST_ASSERT_EQUAL_FLOAT(9.5f, hi);
}

/* Encoding 3.3: c = [0, 0.0432, 0.9045, 0.5523, 0, ...] (thesis (3.12), 1-based ch. 2-4). */
static void test_thesis_encoding_of_3_3(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    const float expect[10] = {0.0f, 0.0432f, 0.9045f, 0.5523f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    float c[10 + 16];
    uint32_t k;
    tsup_guard_fill(&c[10], 16u * sizeof(float));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, 3.3f, 1.0f, c, 10u));
    for (k = 0; k < 10u; k++) {
        TEST_ASSERT_FLOAT_WITHIN(5e-5f, expect[k], c[k]);
    }
    TEST_ASSERT_TRUE(tsup_guard_intact(&c[10], 16u * sizeof(float)));
}

/* Decoding (3.14): x = [-0.02, 3.30, 3.31, 4.00, 5.00, 6.00, 7.00, 8.00],
   r = [0.95, 1.50, 1.46, 0.55, 0, 0, 0, 0]; only window 2 (1-based) is valid. */
static void test_thesis_decoding_table(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    const float ex[8] = {-0.02f, 3.30f, 3.31f, 4.00f, 5.00f, 6.00f, 7.00f, 8.00f};
    const float er[8] = {0.95f, 1.50f, 1.46f, 0.55f, 0.0f, 0.0f, 0.0f, 0.0f};
    float c[10];
    uint32_t l;
    sbr_channel_mode_t modes[4];
    uint32_t count = 99u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, 3.3f, 1.0f, c, 10u));
    for (l = 0; l < 8u; l++) {
        float x;
        float r;
        int valid;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode_window(&cfg, c, 10u, l, &x, &r, &valid));
        TEST_ASSERT_FLOAT_WITHIN(0.005f, ex[l], x);
        TEST_ASSERT_FLOAT_WITHIN(0.005f, er[l], r);
        TEST_ASSERT_EQUAL_INT(l == 1u ? 1 : 0, valid);
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, c, 10u, 0.0f, modes, 4u, &count));
    TEST_ASSERT_EQUAL_UINT32(1u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 3.3f, modes[0].value);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.5f, modes[0].certainty);
}

/* The thesis's (3.13) vector for 6.8 is inconsistent with (3.7); the cos² encoding is
   [0, 0, 0, 0, 0, 0.45, 0.96, 0.10, 0, 0] (THESIS_NOTES.md). */
static void test_encoding_of_6_8(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    const float expect[10] = {0, 0, 0, 0, 0, 0.45f, 0.96f, 0.10f, 0, 0};
    float c[10];
    uint32_t k;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, 6.8f, 1.0f, c, 10u));
    for (k = 0; k < 10u; k++) {
        TEST_ASSERT_FLOAT_WITHIN(0.006f, expect[k], c[k]);
    }
}

/* Every encoding sums to M/2 (1.5 for M = 3), for every M. */
static void test_constant_sum_invariant(void)
{
    uint32_t m;
    for (m = SBR_CHANNEL_MIN_OVERLAP; m <= SBR_CHANNEL_MAX_OVERLAP; m++) {
        sbr_channel_config_t cfg = {-2.0f, 0.5f, 24u, 0u};
        float lo;
        float hi;
        float x;
        float c[24];
        cfg.overlap = m;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_range(&cfg, &lo, &hi));
        for (x = lo; x < hi; x += 0.0173f) {
            float sum = 0.0f;
            uint32_t k;
            uint32_t active = 0u;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, x, 1.0f, c, 24u));
            for (k = 0; k < 24u; k++) {
                sum += c[k];
                active += (c[k] > 0.0f) ? 1u : 0u;
            }
            TEST_ASSERT_FLOAT_WITHIN(2e-5f, 0.5f * (float)m, sum);
            TEST_ASSERT_TRUE(active <= m);
        }
    }
}

/* Well-separated values in one soft histogram decode independently, with weights. */
static void test_separated_values_decode_independently(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    float h[10] = {0};
    sbr_channel_mode_t modes[4];
    uint32_t count = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, 7.4f, 0.5f, h, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, 2.7f, 1.0f, h, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, h, 10u, 0.1f, modes, 4u, &count));
    TEST_ASSERT_EQUAL_UINT32(2u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 2.7f, modes[0].value);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.5f, modes[0].certainty);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 7.4f, modes[1].value);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.75f, modes[1].certainty);
}

/* Sub-bin accuracy over a dense sweep: the channel decoding error stays <= 1/20 of the
   spacing, while an ordinary histogram with the same bins errs by up to half a bin.
   Measured on single values and on clusters of five samples (a soft histogram). */
static void test_subbin_accuracy_against_histogram(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    const float spread[5] = {-0.2f, -0.1f, 0.0f, 0.1f, 0.2f};
    float max_single = 0.0f;
    float max_cluster = 0.0f;
    float max_hist = 0.0f;
    float max_hist_cluster = 0.0f;
    uint32_t steps = 0u;
    uint32_t i;
    char msg[160];
    for (i = 0; i < 7600u; i++) {
        const float x = 1.7f + 0.001f * (float)i; /* 1.7 .. 9.3: clusters stay in range */
        float c[10];
        float h[10] = {0};
        uint32_t bins[10] = {0};
        sbr_channel_mode_t mode;
        uint32_t count = 0u;
        uint32_t s;
        uint32_t best = 0u;
        sbr_status_t st;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, x, 1.0f, c, 10u));
        st = sbr_channel_decode(&cfg, c, 10u, 0.0f, &mode, 1u, &count);
        TEST_ASSERT_TRUE(st == SBR_OK);
        TEST_ASSERT_EQUAL_UINT32(1u, count);
        max_single = fmaxf(max_single, fabsf(mode.value - x));
        /* ordinary histogram: bin k covers [k + 0.5, k + 1.5), estimate its centre */
        max_hist = fmaxf(max_hist, fabsf(floorf(x + 0.5f) - x));

        for (s = 0; s < 5u; s++) {
            const float v = x + spread[s];
            const uint32_t bin = (uint32_t)floorf(v + 0.5f) - 1u;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, v, 1.0f, h, 10u));
            bins[bin]++;
        }
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, h, 10u, 1.0f, &mode, 1u, &count));
        TEST_ASSERT_TRUE(count == 1u);
        max_cluster = fmaxf(max_cluster, fabsf(mode.value - x));
        for (s = 1; s < 10u; s++) {
            if (bins[s] > bins[best]) {
                best = s;
            }
        }
        max_hist_cluster = fmaxf(max_hist_cluster, fabsf((float)(best + 1u) - x));
        steps++;
    }
    snprintf(msg, sizeof msg,
             "%u values: channel max error %.5f (single) %.5f (5-sample cluster); "
             "histogram max error %.3f (single) %.3f (cluster)",
             (unsigned)steps, (double)max_single, (double)max_cluster, (double)max_hist,
             (double)max_hist_cluster);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE(max_single <= 0.05f);
    TEST_ASSERT_TRUE(max_cluster <= 0.05f);
    TEST_ASSERT_TRUE(max_hist >= 0.45f);
    TEST_ASSERT_TRUE(max_hist_cluster >= 0.45f);
}

/* A value on the boundary between two windows is reported exactly once. */
static void test_window_boundaries_give_one_mode(void)
{
    const sbr_channel_config_t cfg = thesis_cfg();
    float x;
    for (x = 1.5f; x < 9.5f; x += 0.5f) {
        float c[10];
        sbr_channel_mode_t m[3];
        uint32_t count = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, x, 1.0f, c, 10u));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, c, 10u, 0.0f, m, 3u, &count));
        TEST_ASSERT_EQUAL_UINT32(1u, count);
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, x, m[0].value);
    }
}

/* Another layout: negative centres, spacing 0.25, M = 5. */
static void test_general_layout_roundtrip(void)
{
    const sbr_channel_config_t cfg = {-5.0f, 0.25f, 41u, 5u};
    float lo;
    float hi;
    float x;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_range(&cfg, &lo, &hi));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, -4.625f, lo);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 4.625f, hi);
    for (x = lo; x < hi; x += 0.0371f) {
        float c[41];
        sbr_channel_mode_t m[2];
        uint32_t count = 0u;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_encode(&cfg, x, 2.0f, c, 41u));
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, c, 41u, 0.0f, m, 2u, &count));
        TEST_ASSERT_EQUAL_UINT32(1u, count);
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, x, m[0].value);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, 5.0f, m[0].certainty); /* w * M / 2 */
    }
}

static void test_capacity_keeps_strongest(void)
{
    const sbr_channel_config_t cfg = {0.0f, 1.0f, 30u, 3u};
    float h[30] = {0};
    sbr_channel_mode_t modes[3];
    uint32_t count = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, 4.2f, 0.3f, h, 30u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, 12.6f, 0.9f, h, 30u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_accumulate(&cfg, 21.1f, 0.6f, h, 30u));
    memset(modes, 0, sizeof modes);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_channel_decode(&cfg, h, 30u, 0.0f, modes, 2u, &count));
    TEST_ASSERT_EQUAL_UINT32(2u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 12.6f, modes[0].value);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 21.1f, modes[1].value);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, modes[2].value); /* nothing written past capacity */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, h, 30u, 0.0f, modes, 3u, &count));
    TEST_ASSERT_EQUAL_UINT32(3u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 4.2f, modes[2].value);
    /* a threshold drops the weak mode */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode(&cfg, h, 30u, 0.5f, modes, 3u, &count));
    TEST_ASSERT_EQUAL_UINT32(2u, count);
    /* capacity 0 with no array: counts nothing, reports that results were dropped */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_channel_decode(&cfg, h, 30u, 0.0f, NULL, 0u, &count));
    TEST_ASSERT_EQUAL_UINT32(0u, count);
}

static void test_bad_input_gets_status(void)
{
    sbr_channel_config_t cfg = thesis_cfg();
    float c[10];
    float keep[10];
    sbr_channel_mode_t m[2];
    uint32_t count = 5u;
    float x;
    float r;
    int v;
    uint32_t k;
    const float nan = nanf("");
    for (k = 0; k < 10u; k++) {
        c[k] = 0.25f * (float)k;
    }
    memcpy(keep, c, sizeof c);
    sbr_channel_config_default(NULL); /* no-op */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_config_check(NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_encode(NULL, 3.0f, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_encode(&cfg, 3.0f, 1.0f, NULL, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_channel_encode(&cfg, 3.0f, 1.0f, c, 9u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, nan, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, INFINITY, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 1.49f, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 9.5f, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 1e30f, 1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 3.0f, 0.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 3.0f, -1.0f, c, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 3.0f, nan, c, 10u));
    TEST_ASSERT_EQUAL_MEMORY(keep, c, sizeof c); /* nothing was added on error */

    cfg.spacing = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&cfg));
    cfg = thesis_cfg();
    cfg.spacing = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_encode(&cfg, 3.0f, 1.0f, c, 10u));
    cfg = thesis_cfg();
    cfg.overlap = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&cfg));
    cfg.overlap = 9u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&cfg));
    cfg = thesis_cfg();
    cfg.count = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_channel_config_check(&cfg));
    cfg.count = SBR_CHANNEL_MAX_COUNT + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_channel_config_check(&cfg));
    cfg = thesis_cfg();
    cfg.first_centre = nan;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&cfg));
    cfg = thesis_cfg();
    cfg.spacing = 3e38f; /* last centre overflows to infinity */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&cfg));
    cfg = thesis_cfg();

    /* decoding: corrupted histograms, bad windows, bad outputs */
    c[4] = -0.1f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode(&cfg, c, 10u, 0.0f, m, 2u, &count));
    TEST_ASSERT_EQUAL_UINT32(0u, count);
    c[4] = nan;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode_window(&cfg, c, 10u, 3u, &x, &r, &v));
    memcpy(c, keep, sizeof c);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode_window(&cfg, c, 10u, 8u, &x, &r, &v));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_decode_window(&cfg, c, 10u, 0u, NULL, &r, &v));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_decode(&cfg, c, 10u, 0.0f, NULL, 2u, &count));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_decode(&cfg, c, 10u, 0.0f, m, 2u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_channel_decode(&cfg, c, 5u, 0.0f, m, 2u, &count));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode(&cfg, c, 10u, -1.0f, m, 2u, &count));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode(&cfg, c, 10u, nan, m, 2u, &count));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel_range(&cfg, NULL, &x));
}

/* 2-D: two points in one grid decode independently, exactly, with certainty w*M*M/4. */
static void test_2d_points(void)
{
    static float grid[32 * 24 + 16];
    sbr_channel2d_config_t cfg;
    sbr_channel_mode2d_t modes[4];
    uint32_t count = 0u;
    uint32_t len;
    cfg.x.first_centre = 0.0f;
    cfg.x.spacing = 10.0f;
    cfg.x.count = 32u;
    cfg.x.overlap = 3u;
    cfg.y.first_centre = 0.0f;
    cfg.y.spacing = 10.0f;
    cfg.y.count = 24u;
    cfg.y.overlap = 3u;
    len = sbr_channel2d_grid_len(&cfg);
    TEST_ASSERT_EQUAL_UINT32(32u * 24u, len);
    memset(grid, 0, sizeof grid);
    tsup_guard_fill(&grid[len], 16u * sizeof(float));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel2d_accumulate(&cfg, 123.4f, 56.7f, 1.0f, grid, len));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel2d_accumulate(&cfg, 250.2f, 180.9f, 0.5f, grid, len));
    TEST_ASSERT_TRUE(tsup_guard_intact(&grid[len], 16u * sizeof(float)));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel2d_decode(&cfg, grid, len, 0.1f, modes, 4u, &count));
    TEST_ASSERT_EQUAL_UINT32(2u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 123.4f, modes[0].x);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 56.7f, modes[0].y);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 2.25f, modes[0].certainty);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 250.2f, modes[1].x);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 180.9f, modes[1].y);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.125f, modes[1].certainty);
    /* capacity 1 keeps the stronger point */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_channel2d_decode(&cfg, grid, len, 0.1f, modes, 1u, &count));
    TEST_ASSERT_EQUAL_UINT32(1u, count);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 123.4f, modes[0].x);
    /* outside the grid, bad sizes, corrupted grid */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel2d_accumulate(&cfg, 400.0f, 50.0f, 1.0f, grid, len));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel2d_accumulate(&cfg, 100.0f, -20.0f, 1.0f, grid, len));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel2d_accumulate(&cfg, 100.0f, 50.0f, 0.0f, grid, len));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_channel2d_accumulate(&cfg, 100.0f, 50.0f, 1.0f, grid, len - 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel2d_accumulate(&cfg, 100.0f, 50.0f, 1.0f, NULL, len));
    grid[100] = -1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel2d_decode(&cfg, grid, len, 0.1f, modes, 4u, &count));
    cfg.y.count = 1u;
    TEST_ASSERT_EQUAL_UINT32(0u, sbr_channel2d_grid_len(&cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_channel2d_config_check(NULL));
}

/* Regression (fuzzer finding): finite channel values near the float limit gave a window
   sum of inf and a NaN estimate with SBR_OK. Values and weights are bounded by
   SBR_CHANNEL_MAX_VALUE; an accumulation that would pass it is refused. */
static void test_values_bounded_by_max_value(void)
{
    sbr_channel_config_t cfg;
    float hist[10];
    float value = -1.0f;
    float cert = -1.0f;
    int valid = -1;
    sbr_channel_mode_t modes[4];
    uint32_t n = 0u;
    uint32_t k;
    sbr_channel_config_default(&cfg);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_config_check(&cfg));
    for (k = 0u; k < 10u; k++) {
        hist[k] = 0.0f;
    }
    hist[3] = 3e38f;
    hist[4] = 3e38f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode_window(&cfg, hist, 10u, 3u, &value, &cert, &valid));
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, value);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_decode(&cfg, hist, 10u, 0.0f, modes, 4u, &n));
    hist[3] = SBR_CHANNEL_MAX_VALUE;
    hist[4] = SBR_CHANNEL_MAX_VALUE;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_decode_window(&cfg, hist, 10u, 3u, &value, &cert, &valid));
    TEST_ASSERT_TRUE(isfinite(value) && isfinite(cert));
    /* between channels 4 and 5 (centres 1..10): the two equal channels' midpoint */
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 4.5f, value);
    /* accumulating past the bound adds nothing */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 4.0f, SBR_CHANNEL_MAX_VALUE, hist, 10u));
    TEST_ASSERT_EQUAL_FLOAT(SBR_CHANNEL_MAX_VALUE, hist[3]);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_accumulate(&cfg, 4.0f, 2e30f, hist, 10u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_encode(&cfg, 4.0f, 2e30f, hist, 10u));
    TEST_ASSERT_EQUAL_FLOAT(SBR_CHANNEL_MAX_VALUE, hist[3]); /* untouched */
}

/* Regression (fuzzer finding, campaign): first centre -3.4e38 and spacing 6.2e35 passed
   the check (the last centre was finite), and a window's estimate half a channel below
   the first centre came out as -inf with SBR_OK. Centres one kernel beyond either end
   must be finite. */
static void test_config_keeps_decoded_values_finite(void)
{
    sbr_channel_config_t c;
    sbr_channel_config_default(&c);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_config_check(&c));
    c.first_centre = -3.4e38f;
    c.spacing = 6.23676e35f;
    c.count = 19u;
    c.overlap = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&c));
    c.first_centre = 3.0e38f; /* the upper end overflows */
    c.spacing = 1.0e37f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_channel_config_check(&c));
    c.first_centre = -1.0e30f; /* far out but with room */
    c.spacing = 1.0e28f;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel_config_check(&c));
}

/* The 2D default: both axes the 1D default, a valid configuration. */
static void test_2d_default(void)
{
    sbr_channel2d_config_t c2;
    sbr_channel2d_config_default(&c2);
    TEST_ASSERT_EQUAL_UINT32(10u, c2.x.count);
    TEST_ASSERT_EQUAL_UINT32(3u, c2.y.overlap);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, c2.y.first_centre);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_channel2d_config_check(&c2));
    sbr_channel2d_config_default(NULL); /* no-op */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_default_is_thesis_layout);
    RUN_TEST(test_2d_default);
    RUN_TEST(test_thesis_encoding_of_3_3);
    RUN_TEST(test_thesis_decoding_table);
    RUN_TEST(test_encoding_of_6_8);
    RUN_TEST(test_constant_sum_invariant);
    RUN_TEST(test_separated_values_decode_independently);
    RUN_TEST(test_subbin_accuracy_against_histogram);
    RUN_TEST(test_window_boundaries_give_one_mode);
    RUN_TEST(test_general_layout_roundtrip);
    RUN_TEST(test_capacity_keeps_strongest);
    RUN_TEST(test_bad_input_gets_status);
    RUN_TEST(test_2d_points);
    RUN_TEST(test_values_bounded_by_max_value);
    RUN_TEST(test_config_keeps_decoded_values_finite);
    return UNITY_END();
}
