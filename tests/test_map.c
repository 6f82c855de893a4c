/* SPDX-License-Identifier: MIT */
/* Unity tests of the channel maps (include/sbr/map.h): the intensity tone curve and the
   colour-opponent formulas on known pixels, block averaging, and bad input. */
#include "unity.h"
#include "sbr/map.h"
#include "test_support.h"

void setUp(void) {}
void tearDown(void) {}

static void test_map_formulas_on_known_colours(void)
{
    /* pure red, grey 100, pure blue, yellow (R=G=255, B=0) as RGB888 */
    static const uint8_t rgb[12] = {255, 0, 0, 100, 100, 100, 0, 0, 255, 255, 255, 0};
    uint8_t out[4];
    sbr_image_t src = {4u, 1u, 12u, SBR_PIXEL_RGB888, rgb};
    sbr_image_t ov;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, SBR_MAP_INTENSITY, 1u, out, 4u, 4u, &ov));
    TEST_ASSERT_EQUAL_UINT8(85u, out[0]);  /* (T(255) + 1) / 3 = (255 + 1) / 3 */
    TEST_ASSERT_EQUAL_UINT8(160u, out[1]); /* T(100) = round(sqrt(25500)) = round(159.7) */
    TEST_ASSERT_EQUAL_UINT8(170u, out[3]); /* (510 + 1) / 3 */
    TEST_ASSERT_EQUAL_UINT32(4u, ov.width);
    TEST_ASSERT_EQUAL_INT(SBR_PIXEL_GRAY8, ov.format);
    /* colour maps: C(d) = 128 + 128 d / (R + G + B + 60), truncated, clamped to 0..255 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, SBR_MAP_RED, 1u, out, 4u, 4u, NULL));
    TEST_ASSERT_EQUAL_UINT8(255u, out[0]); /* 128 + 65280 / 315 = 128 + 207, clamped */
    TEST_ASSERT_EQUAL_UINT8(128u, out[1]); /* grey: d = 0 */
    TEST_ASSERT_EQUAL_UINT8(25u, out[2]);  /* 128 - 32640 / 315 = 128 - 103 */
    TEST_ASSERT_EQUAL_UINT8(185u, out[3]); /* 128 + 32640 / 570 = 128 + 57 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, SBR_MAP_BLUE, 1u, out, 4u, 4u, NULL));
    TEST_ASSERT_EQUAL_UINT8(25u, out[0]);
    TEST_ASSERT_EQUAL_UINT8(128u, out[1]);
    TEST_ASSERT_EQUAL_UINT8(255u, out[2]);
    TEST_ASSERT_EQUAL_UINT8(14u, out[3]);  /* 128 - 65280 / 570 = 128 - 114 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, SBR_MAP_YELLOW, 1u, out, 4u, 4u, NULL));
    TEST_ASSERT_EQUAL_UINT8(231u, out[0]); /* 128 + 32640 / 315 = 128 + 103 */
    TEST_ASSERT_EQUAL_UINT8(128u, out[1]);
    TEST_ASSERT_EQUAL_UINT8(0u, out[2]);   /* 128 - 207, clamped */
    TEST_ASSERT_EQUAL_UINT8(242u, out[3]); /* 128 + 65280 / 570 = 128 + 114 */
    /* brightness drops out: dark red (60, 20, 20) and bright red (240, 80, 80) differ only
       through the dark bound 60: 128 + 10240 / 160 = 192 and 128 + 40960 / 460 = 217 */
    {
        static const uint8_t reds[6] = {60, 20, 20, 240, 80, 80};
        sbr_image_t s1 = {2u, 1u, 6u, SBR_PIXEL_RGB888, reds};
        TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&s1, SBR_MAP_RED, 1u, out, 2u, 2u, NULL));
        TEST_ASSERT_EQUAL_UINT8(192u, out[0]);
        TEST_ASSERT_EQUAL_UINT8(217u, out[1]);
    }
    /* near-black pixels stay near grey: (0, 0, 6) is 128 + 1536 / 66 = 151 in the blue map
       (with the bound 0 it would be 255) */
    {
        static const uint8_t dim[3] = {0, 0, 6};
        sbr_image_t s3 = {1u, 1u, 3u, SBR_PIXEL_RGB888, dim};
        TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&s3, SBR_MAP_BLUE, 1u, out, 1u, 1u, NULL));
        TEST_ASSERT_EQUAL_UINT8(151u, out[0]);
    }
    /* the same pixels in BGR order give the same maps */
    {
        static const uint8_t bgr[12] = {0, 0, 255, 100, 100, 100, 255, 0, 0, 0, 255, 255};
        sbr_image_t s2 = {4u, 1u, 12u, SBR_PIXEL_BGR888, bgr};
        TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&s2, SBR_MAP_RED, 1u, out, 4u, 4u, NULL));
        TEST_ASSERT_EQUAL_UINT8(255u, out[0]);
        TEST_ASSERT_EQUAL_UINT8(25u, out[2]);
    }
}

static void test_map_subsample_averages_blocks(void)
{
    /* 4x2 grey image, 2x2 blocks: mean of {0, 255, 255, 255} = 191.25 -> 191, T(191) =
       round(220.7); of {10, 11, 12, 13} = 11.5 -> 12 (rounded to nearest), T(12) =
       round(55.3) */
    static const uint8_t g[8] = {0, 255, 10, 11, 255, 255, 12, 13};
    uint8_t out[2];
    sbr_image_t src = {4u, 2u, 4u, SBR_PIXEL_GRAY8, g};
    sbr_image_t ov;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, SBR_MAP_INTENSITY, 2u, out, 2u, 2u, &ov));
    TEST_ASSERT_EQUAL_UINT32(2u, ov.width);
    TEST_ASSERT_EQUAL_UINT32(1u, ov.height);
    TEST_ASSERT_EQUAL_UINT8(221u, out[0]);
    TEST_ASSERT_EQUAL_UINT8(55u, out[1]);
}

/* Colour frames at subsample 2 (the recogniser's blue map: its own loop): every pixel
   the map value of its 2 x 2 block's rounded mean colour, that value taken from the
   subsample-1 path on a one-pixel frame of the mean colour; RGB and BGR, every kind, an
   odd size (the last row and column dropped) and a padded stride. */
static void test_map_subsample2_colour_blocks(void)
{
    static uint8_t px[7u * 40u];
    static uint8_t out[3u * 8u];
    uint32_t f;
    uint32_t k;
    tsup_fill_bytes(px, sizeof px, 99u);
    for (f = 0u; f < 2u; f++) {
        const sbr_pixel_format_t fmt = (f == 0u) ? SBR_PIXEL_RGB888 : SBR_PIXEL_BGR888;
        const sbr_image_t src = {13u, 7u, 40u, fmt, px}; /* 13 x 7, stride 40 > 39 */
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            sbr_image_t ov;
            uint32_t x;
            uint32_t y;
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, (sbr_map_kind_t)k, 2u, out, 8u,
                                                            sizeof out, &ov));
            TEST_ASSERT_EQUAL_UINT32(6u, ov.width);
            TEST_ASSERT_EQUAL_UINT32(3u, ov.height);
            for (y = 0u; y < 3u; y++) {
                for (x = 0u; x < 6u; x++) {
                    uint8_t mean[3];
                    uint8_t one;
                    uint32_t c;
                    const sbr_image_t m = {1u, 1u, 3u, fmt, mean};
                    for (c = 0u; c < 3u; c++) {
                        const uint32_t a = (2u * y * 40u) + (2u * x * 3u) + c;
                        const uint32_t sum = (uint32_t)px[a] + px[a + 3u] + px[a + 40u] + px[a + 43u];
                        mean[c] = (uint8_t)((sum + 2u) / 4u);
                    }
                    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&m, (sbr_map_kind_t)k, 1u, &one, 1u,
                                                                    1u, NULL));
                    TEST_ASSERT_EQUAL_UINT8(one, out[(y * 8u) + x]);
                }
            }
        }
    }
}

/* The part stage's map for a bright-only pass with a floor above 128: every pixel whose
   red map value is above 128 as sbr_map_make() gives it, every other one exactly 128 (on
   the red map at subsample 1); other kinds and subsamples as sbr_map_make(). */
static void test_map_bright_only_red(void)
{
    static uint8_t px[9u * 64u];
    static uint8_t exact[9u * 21u];
    static uint8_t bright[9u * 21u];
    uint32_t i;
    uint32_t f;
    uint32_t k;
    uint32_t above = 0u;
    tsup_fill_bytes(px, sizeof px, 7u);
    for (f = 0u; f < 2u; f++) {
        const sbr_pixel_format_t fmt = (f == 0u) ? SBR_PIXEL_RGB888 : SBR_PIXEL_BGR888;
        const sbr_image_t src = {20u, 9u, 64u, fmt, px}; /* stride 64 > 60 */
        for (k = 0u; k < SBR_MAP_KINDS; k++) {
            uint32_t sub;
            for (sub = 1u; sub <= 2u; sub++) {
                sbr_image_t ov;
                TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, (sbr_map_kind_t)k, sub, exact, 21u,
                                                                sizeof exact, NULL));
                TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make_bright(&src, (sbr_map_kind_t)k, sub,
                                                                            bright, 21u, sizeof bright, &ov));
                TEST_ASSERT_EQUAL_UINT32(20u / sub, ov.width);
                TEST_ASSERT_EQUAL_UINT32(9u / sub, ov.height);
                for (i = 0u; i < ((9u / sub) * 21u); i++) {
                    if ((i % 21u) >= (20u / sub)) {
                        continue; /* the stride's padding */
                    }
                    if ((k == (uint32_t)SBR_MAP_RED) && (sub == 1u) && (exact[i] <= 128u)) {
                        TEST_ASSERT_EQUAL_UINT8(128u, bright[i]);
                    } else {
                        TEST_ASSERT_EQUAL_UINT8(exact[i], bright[i]);
                        above += ((k == (uint32_t)SBR_MAP_RED) && (sub == 1u)) ? 1u : 0u;
                    }
                }
            }
        }
    }
    TEST_ASSERT_TRUE(above > 20u); /* random colours: some pixels are red */
    {
        const sbr_image_t src = {20u, 9u, 64u, SBR_PIXEL_RGB888, px};
        TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_map_make_bright(NULL, SBR_MAP_RED, 1u, bright, 21u,
                                                                          sizeof bright, NULL));
        TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_map_make_bright(&src, SBR_MAP_RED, 1u, bright, 21u,
                                                                           20u, NULL));
    }
}

static void test_map_tone_curve_every_level(void)
{
    /* a grey ramp 0..255: the intensity map is T(c) = round(sqrt(255 c)), checked in
       integers: v = T(c) exactly when (2v - 1)^2 <= 1020 c < (2v + 1)^2 */
    static uint8_t ramp[256];
    static uint8_t out[256];
    sbr_image_t src = {256u, 1u, 256u, SBR_PIXEL_GRAY8, ramp};
    uint32_t c;
    for (c = 0u; c < 256u; c++) {
        ramp[c] = (uint8_t)c;
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK,
                          (int)sbr_map_make(&src, SBR_MAP_INTENSITY, 1u, out, 256u, 256u, NULL));
    for (c = 0u; c < 256u; c++) {
        const uint32_t v = out[c];
        const uint32_t lo = (v == 0u) ? 0u : (((2u * v) - 1u) * ((2u * v) - 1u));
        TEST_ASSERT_TRUE_MESSAGE(lo <= 1020u * c, "tone curve too high");
        TEST_ASSERT_TRUE_MESSAGE(1020u * c < (((2u * v) + 1u) * ((2u * v) + 1u)),
                                 "tone curve too low");
        if (c > 0u) {
            TEST_ASSERT_TRUE(out[c] >= out[c - 1u]); /* monotonic */
        }
    }
    TEST_ASSERT_EQUAL_UINT8(64u, out[16]);
    TEST_ASSERT_EQUAL_UINT8(128u, out[64]);
    TEST_ASSERT_EQUAL_UINT8(255u, out[255]);
}

/* The integer nearest sqrt(255 c) (the tone curve's definition, map.h). */
static uint32_t tone_def(uint32_t c)
{
    uint32_t v = 0u;
    while ((((2u * v) + 1u) * ((2u * v) + 1u)) <= (1020u * c)) {
        v++;
    }
    return v;
}

/* 128 + 128 d / (sum + 60), truncated towards zero, clamped to 0..255 (map.h). */
static uint8_t chroma_def(int32_t d, int32_t sum)
{
    int32_t v = 128 + ((128 * d) / (sum + 60));
    v = (v < 0) ? 0 : v;
    v = (v > 255) ? 255 : v;
    return (uint8_t)v;
}

static void test_map_rows_every_width(void)
{
    /* random colour rows of every width 1..11 (the makers work in steps of four pixels
       and a tail), both channel orders: every map value against the formulas of map.h,
       and the part stage's bright-only red map (128 where 2R - G - B <= 0) */
    static uint8_t px[3u * 11u * 2u];
    uint8_t out[2u * 11u];
    uint8_t bright[2u * 11u];
    uint32_t w;
    uint32_t f;
    uint32_t k;
    uint32_t checked = 0u;
    tsup_fill_bytes(px, sizeof px, 11u);
    px[0] = 250u; /* a strong red first pixel: the red map above 128 */
    px[1] = 10u;
    px[2] = 10u;
    for (w = 1u; w <= 11u; w++) {
        for (f = 0u; f < 2u; f++) {
            const sbr_pixel_format_t fmt = (f == 0u) ? SBR_PIXEL_RGB888 : SBR_PIXEL_BGR888;
            const sbr_image_t src = {w, 2u, 33u, fmt, px};
            for (k = 0u; k < SBR_MAP_KINDS; k++) {
                uint32_t y;
                TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make(&src, (sbr_map_kind_t)k, 1u, out, 11u,
                                                                sizeof out, NULL));
                TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_map_make_bright(&src, (sbr_map_kind_t)k, 1u,
                                                                            bright, 11u, sizeof bright, NULL));
                for (y = 0u; y < 2u; y++) {
                    uint32_t x;
                    for (x = 0u; x < w; x++) {
                        const uint8_t *q = &px[(y * 33u) + (x * 3u)];
                        const int32_t r = (f == 0u) ? (int32_t)q[0] : (int32_t)q[2];
                        const int32_t g = (int32_t)q[1];
                        const int32_t b = (f == 0u) ? (int32_t)q[2] : (int32_t)q[0];
                        uint8_t want;
                        if (k == (uint32_t)SBR_MAP_INTENSITY) {
                            want = (uint8_t)((tone_def((uint32_t)r) + tone_def((uint32_t)g) +
                                              tone_def((uint32_t)b) + 1u) / 3u);
                        } else if (k == (uint32_t)SBR_MAP_RED) {
                            want = chroma_def((2 * r) - g - b, r + g + b);
                        } else if (k == (uint32_t)SBR_MAP_BLUE) {
                            want = chroma_def((2 * b) - r - g, r + g + b);
                        } else {
                            want = chroma_def((r + g) - (2 * b), r + g + b);
                        }
                        TEST_ASSERT_EQUAL_UINT8(want, out[(y * 11u) + x]);
                        if ((k == (uint32_t)SBR_MAP_RED) && (want <= 128u)) {
                            want = 128u;
                        }
                        TEST_ASSERT_EQUAL_UINT8(want, bright[(y * 11u) + x]);
                        checked++;
                    }
                }
            }
        }
    }
    TEST_ASSERT_EQUAL_UINT32(2u * 2u * SBR_MAP_KINDS * 66u, checked);
    TEST_ASSERT_EQUAL_UINT8(0u, out[0]); /* the last map made: yellow of (10, 10, 250) (BGR) */
}

static void test_map_bad_input(void)
{
    static uint8_t buf[16];
    uint8_t out[16];
    sbr_image_t gray = {4u, 2u, 4u, SBR_PIXEL_GRAY8, buf};
    sbr_image_t rgb = {2u, 2u, 6u, SBR_PIXEL_RGB888, buf};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_map_make(NULL, SBR_MAP_RED, 1u, out, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_map_make(&gray, SBR_MAP_INTENSITY, 1u, NULL, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_map_make(&gray, SBR_MAP_RED, 1u, out, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_map_make(&rgb, (sbr_map_kind_t)7, 1u, out, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_map_make(&rgb, SBR_MAP_RED, 0u, out, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_map_make(&rgb, SBR_MAP_RED, 3u, out, 4u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_map_make(&rgb, SBR_MAP_RED, 1u, out, 1u, 16u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_map_make(&rgb, SBR_MAP_RED, 1u, out, 2u, 3u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_OVERLAP, (int)sbr_map_make(&gray, SBR_MAP_INTENSITY, 1u, &buf[4], 4u, 8u, NULL));
    gray.stride = 3u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_map_make(&gray, SBR_MAP_INTENSITY, 1u, out, 4u, 16u, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_map_formulas_on_known_colours);
    RUN_TEST(test_map_subsample_averages_blocks);
    RUN_TEST(test_map_subsample2_colour_blocks);
    RUN_TEST(test_map_bright_only_red);
    RUN_TEST(test_map_rows_every_width);
    RUN_TEST(test_map_tone_curve_every_level);
    RUN_TEST(test_map_bad_input);
    return UNITY_END();
}
