/* SPDX-License-Identifier: MIT */
/* Unity tests of image views and contour tracing (include/sbr/image.h, contour.h). */
#include "unity.h"
#include "sbr/contour.h"
#include "test_support.h"

#include <string.h>

#define W 16u
#define H 12u

static uint8_t g_mask[H][W];
static uint8_t g_ws[SBR_CONTOUR_WORKSPACE_SIZE(W, H)];
static sbr_point_t g_pts[512];
static sbr_contour_t g_ct[16];

void setUp(void) { memset(g_mask, 0, sizeof g_mask); }
void tearDown(void) {}

static sbr_image_t mask_view(void)
{
    sbr_image_t v;
    v.width = W;
    v.height = H;
    v.stride = W;
    v.format = SBR_PIXEL_GRAY8;
    v.data = &g_mask[0][0];
    return v;
}

static void fill_rect(uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, uint8_t v)
{
    uint32_t x;
    uint32_t y;
    for (y = y0; y < y0 + h; y++) {
        for (x = x0; x < x0 + w; x++) {
            g_mask[y][x] = v;
        }
    }
}

static uint32_t trace(uint32_t *count)
{
    const sbr_image_t v = mask_view();
    return (uint32_t)sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 512u, g_ct, 16u,
                                                count);
}

/* A 3x3 square: 8 boundary pixels starting at the top-left, counter-clockwise on screen
   (down the left side first), as OpenCV lists outer contours. */
static void test_square_boundary_order(void)
{
    static const sbr_point_t expect[8] = {{2, 3}, {2, 4}, {2, 5}, {3, 5}, {4, 5}, {4, 4}, {4, 3}, {3, 3}};
    uint32_t n = 0u;
    uint32_t i;
    int64_t a2 = 0;
    fill_rect(2u, 3u, 3u, 3u, 255u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)trace(&n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(8u, g_ct[0].length);
    for (i = 0; i < 8u; i++) {
        TEST_ASSERT_EQUAL_INT16(expect[i].x, g_pts[i].x);
        TEST_ASSERT_EQUAL_INT16(expect[i].y, g_pts[i].y);
    }
    TEST_ASSERT_EQUAL_UINT32(2u, g_ct[0].bbox.x);
    TEST_ASSERT_EQUAL_UINT32(3u, g_ct[0].bbox.y);
    TEST_ASSERT_EQUAL_UINT32(3u, g_ct[0].bbox.width);
    TEST_ASSERT_EQUAL_UINT32(3u, g_ct[0].bbox.height);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_contour_area2(g_pts, 8u, &a2));
    TEST_ASSERT_EQUAL_INT(-8, (int)a2); /* 2x2 polygon through pixel centres, negative */
}

static void test_single_pixel_and_line(void)
{
    uint32_t n = 0u;
    g_mask[1][1] = 1u;
    fill_rect(5u, 6u, 5u, 1u, 9u); /* horizontal line: each pixel twice except the ends */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)trace(&n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(1u, g_ct[0].length);
    TEST_ASSERT_EQUAL_INT16(1, g_pts[0].x);
    TEST_ASSERT_EQUAL_UINT32(8u, g_ct[1].length);
    TEST_ASSERT_EQUAL_INT16(5, g_pts[1].x);
    TEST_ASSERT_EQUAL_INT16(6, g_pts[1].y);
}

/* A blob touching every image border is traced along the border. */
static void test_blob_touching_border(void)
{
    uint32_t n = 0u;
    fill_rect(0u, 0u, W, H, 1u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)trace(&n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(2u * (W + H) - 4u, g_ct[0].length);
    TEST_ASSERT_EQUAL_UINT32(W, g_ct[0].bbox.width);
}

/* RETR_EXTERNAL: a ring's hole and a blob inside the hole are not reported; a blob to the
   right of the ring is. Diagonal neighbours connect (8-connectivity). */
static void test_external_only_and_connectivity(void)
{
    uint32_t n = 0u;
    fill_rect(1u, 1u, 7u, 7u, 1u);
    fill_rect(2u, 2u, 5u, 5u, 0u); /* hole */
    g_mask[4][4] = 1u;             /* blob inside the hole */
    fill_rect(10u, 2u, 2u, 2u, 1u);
    g_mask[4][12] = 1u; /* touches (11,3) diagonally: same blob */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)trace(&n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(24u, g_ct[0].length);
    TEST_ASSERT_EQUAL_UINT32(7u, g_ct[0].bbox.width);
    TEST_ASSERT_EQUAL_UINT32(10u, g_ct[1].bbox.x);
    TEST_ASSERT_EQUAL_UINT32(3u, g_ct[1].bbox.width);
    TEST_ASSERT_EQUAL_UINT32(3u, g_ct[1].bbox.height);
}

/* Strided view and ROI: the same square seen through a sub-view. */
static void test_roi_and_stride(void)
{
    const sbr_image_t full = mask_view();
    sbr_image_t sub;
    sbr_rect_t roi = {2u, 2u, 6u, 6u};
    uint32_t n = 0u;
    fill_rect(3u, 4u, 3u, 3u, 1u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_roi(&full, &roi, &sub));
    TEST_ASSERT_EQUAL_UINT32(W, sub.stride);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_contour_find_external(&sub, g_ws, sizeof g_ws, g_pts, 512u,
                                                            g_ct, 16u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_INT16(1, g_pts[0].x);
    TEST_ASSERT_EQUAL_INT16(2, g_pts[0].y);
    roi.x = 12u; /* leaves the image */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&full, &roi, &sub));
    roi.x = 0u;
    roi.width = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&full, &roi, &sub));
}

/* Capacity: a contour that does not fit is left out whole, the others stay complete. */
static void test_capacity(void)
{
    const sbr_image_t v = mask_view();
    uint32_t n = 99u;
    fill_rect(1u, 1u, 2u, 2u, 1u); /* 4 points */
    fill_rect(6u, 1u, 6u, 6u, 1u); /* 20 points */
    fill_rect(1u, 9u, 1u, 1u, 1u); /* 1 point */
    tsup_guard_fill(&g_pts[10], 16u);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 10u,
                                                                      g_ct, 16u, &n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(4u, g_ct[0].length);
    TEST_ASSERT_EQUAL_UINT32(1u, g_ct[1].length);
    TEST_ASSERT_EQUAL_UINT32(4u, g_ct[1].first);
    TEST_ASSERT_TRUE(tsup_guard_intact(&g_pts[10], 16u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 512u,
                                                                      g_ct, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
}

/* Random blobs (overlapping rectangles, random non-zero bytes) of every width 1..40 in a
   frame of 48 columns: the contours equal those of the same mask as 0/255 bytes (any
   non-zero byte is foreground), and those of the mask with 1..8 more background columns
   on its right (the scan skips runs of equal pixels eight at a time, and the copy reads
   eight bytes at a time: every alignment of a transition is met). */
static void test_random_masks_every_width(void)
{
    static uint8_t m[H][48];
    static uint8_t bin[H][48];
    static uint8_t ws[SBR_CONTOUR_WORKSPACE_SIZE(48u, H)];
    static sbr_point_t pa[2048];
    static sbr_point_t pb[2048];
    sbr_contour_t ca[32];
    sbr_contour_t cb[32];
    tsup_rng_t rng = {777u};
    uint32_t w;
    uint32_t total = 0u;
    for (w = 1u; w <= 40u; w++) {
        uint32_t k;
        uint32_t extra;
        uint32_t na = 0u;
        memset(m, 0, sizeof m);
        for (k = 0u; k < 5u; k++) {
            const uint32_t x0 = (uint32_t)tsup_uniform(&rng, 0.0f, (float)w);
            const uint32_t y0 = (uint32_t)tsup_uniform(&rng, 0.0f, (float)H);
            const uint32_t bw = 1u + (uint32_t)tsup_uniform(&rng, 0.0f, 9.0f);
            const uint32_t bh = 1u + (uint32_t)tsup_uniform(&rng, 0.0f, 5.0f);
            uint32_t x;
            uint32_t y;
            for (y = y0; (y < (y0 + bh)) && (y < H); y++) {
                for (x = x0; (x < (x0 + bw)) && (x < w); x++) {
                    m[y][x] = (uint8_t)(1u + (uint32_t)tsup_uniform(&rng, 0.0f, 254.0f));
                }
            }
        }
        for (k = 0u; k < (H * 48u); k++) {
            (&bin[0][0])[k] = ((&m[0][0])[k] != 0u) ? 255u : 0u;
        }
        {
            const sbr_image_t va = {w, H, 48u, SBR_PIXEL_GRAY8, &m[0][0]};
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_contour_find_external(&va, ws, sizeof ws, pa, 2048u,
                                                                         ca, 32u, &na));
            TEST_ASSERT_TRUE(na >= 1u);
            for (k = 0u; k < na; k++) {
                /* a contour starts where a row enters its blob: a foreground pixel whose
                   left neighbour is background */
                const sbr_point_t p0 = pa[ca[k].first];
                TEST_ASSERT_TRUE(m[p0.y][p0.x] != 0u);
                TEST_ASSERT_TRUE((p0.x == 0) || (m[p0.y][p0.x - 1] == 0u));
            }
        }
        for (extra = 0u; extra <= 8u; extra++) {
            const sbr_image_t vb = {w + extra, H, 48u, SBR_PIXEL_GRAY8,
                                    (extra == 0u) ? &bin[0][0] : &m[0][0]};
            uint32_t nb = 0u;
            uint32_t c;
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_contour_find_external(&vb, ws, sizeof ws, pb, 2048u,
                                                                         cb, 32u, &nb));
            TEST_ASSERT_EQUAL_UINT32(na, nb);
            for (c = 0u; c < na; c++) {
                TEST_ASSERT_EQUAL_UINT32(ca[c].length, cb[c].length);
                TEST_ASSERT_EQUAL_UINT32(ca[c].bbox.x, cb[c].bbox.x);
                TEST_ASSERT_EQUAL_UINT32(ca[c].bbox.width, cb[c].bbox.width);
                TEST_ASSERT_EQUAL_MEMORY(&pa[ca[c].first], &pb[cb[c].first],
                                         ca[c].length * sizeof(sbr_point_t));
            }
        }
        total += na;
    }
    TEST_ASSERT_TRUE(total > 40u);
}

static void test_bad_input(void)
{
    sbr_image_t v = mask_view();
    uint32_t n = 7u;
    int64_t a2;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_contour_find_external(NULL, g_ws, sizeof g_ws, g_pts, 1u, g_ct, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_contour_find_external(&v, NULL, sizeof g_ws, g_pts, 1u, g_ct, 1u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 1u, g_ct, 1u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_contour_find_external(&v, g_ws, sizeof g_ws - 1u, g_pts, 1u, g_ct, 1u, &n));
    v.stride = W - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 1u, g_ct, 1u, &n));
    v = mask_view();
    v.format = SBR_PIXEL_RGB888;
    v.width = W / 3u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_contour_find_external(&v, g_ws, sizeof g_ws, g_pts, 1u, g_ct, 1u, &n));
    v = mask_view();
    v.height = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_image_check(&v));
    v = mask_view();
    v.format = (sbr_pixel_format_t)77;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_check(&v));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_contour_workspace_size(0u, 5u));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_contour_workspace_size(5u, SBR_IMAGE_MAX_DIM + 1u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_contour_area2(g_pts, 0u, &a2));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_contour_area2(NULL, 3u, &a2));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_square_boundary_order);
    RUN_TEST(test_single_pixel_and_line);
    RUN_TEST(test_blob_touching_border);
    RUN_TEST(test_external_only_and_connectivity);
    RUN_TEST(test_roi_and_stride);
    RUN_TEST(test_capacity);
    RUN_TEST(test_random_masks_every_width);
    RUN_TEST(test_bad_input);
    return UNITY_END();
}
