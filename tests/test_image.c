/* SPDX-License-Identifier: MIT */
/* Unity tests of image views (include/sbr/image.h): bytes per pixel, the view check at its
   bounds (sizes, strides, formats), and regions of interest (where a sub-view starts, the
   edges, no wrap-around). Every status of the header is also in test_statuses.c. */
#include <stdint.h>

#include "sbr/image.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static uint8_t g_px[64 * 16 * 3];

static sbr_image_t view(uint32_t w, uint32_t h, uint32_t stride, sbr_pixel_format_t f)
{
    sbr_image_t v;
    v.width = w;
    v.height = h;
    v.stride = stride;
    v.format = f;
    v.data = g_px;
    return v;
}

static void test_bytes_per_pixel(void)
{
    TEST_ASSERT_EQUAL_UINT32(1u, sbr_image_bytes_per_pixel(SBR_PIXEL_GRAY8));
    TEST_ASSERT_EQUAL_UINT32(3u, sbr_image_bytes_per_pixel(SBR_PIXEL_RGB888));
    TEST_ASSERT_EQUAL_UINT32(3u, sbr_image_bytes_per_pixel(SBR_PIXEL_BGR888));
    TEST_ASSERT_EQUAL_UINT32(0u, sbr_image_bytes_per_pixel((sbr_pixel_format_t)0));
    TEST_ASSERT_EQUAL_UINT32(0u, sbr_image_bytes_per_pixel((sbr_pixel_format_t)2));
    TEST_ASSERT_EQUAL_UINT32(0u, sbr_image_bytes_per_pixel((sbr_pixel_format_t)5));
}

/* The check accepts exactly the documented ranges: 1 .. SBR_IMAGE_MAX_DIM per side, a
   stride from one row's bytes up to SBR_IMAGE_MAX_STRIDE. (Only the view is checked: no
   pixel is read, so a large view of a small buffer is enough here.) */
static void test_check_bounds(void)
{
    sbr_image_t v = view(1u, 1u, 1u, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    v = view(SBR_IMAGE_MAX_DIM, SBR_IMAGE_MAX_DIM, SBR_IMAGE_MAX_DIM, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    v.width = SBR_IMAGE_MAX_DIM + 1u;
    v.stride = SBR_IMAGE_MAX_DIM + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_image_check(&v));
    v = view(4u, SBR_IMAGE_MAX_DIM + 1u, 4u, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_image_check(&v));
    v = view(0u, 4u, 4u, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_image_check(&v));
    /* stride: exactly a row is enough, one byte less is not, padding is allowed */
    v = view(10u, 2u, 30u, SBR_PIXEL_RGB888);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    v.stride = 29u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_image_check(&v));
    v.stride = 31u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    /* the widest colour row fits the largest stride; a larger stride is refused even
       for a narrow image (row offsets stay within 32 bits) */
    v = view(SBR_IMAGE_MAX_DIM, 1u, 3u * SBR_IMAGE_MAX_DIM, SBR_PIXEL_BGR888);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    v = view(4u, 4u, SBR_IMAGE_MAX_STRIDE, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&v));
    v.stride = SBR_IMAGE_MAX_STRIDE + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_image_check(&v));
    v.stride = UINT32_MAX;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_image_check(&v));
    /* unknown formats, NULL data */
    v = view(4u, 4u, 4u, (sbr_pixel_format_t)2);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_check(&v));
    v = view(4u, 4u, 4u, SBR_PIXEL_GRAY8);
    v.data = NULL;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_image_check(&v));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_image_check(NULL));
}

/* A sub-view starts at y * stride + x * bytes per pixel, keeps the stride and format,
   and may touch the right and bottom edges but not pass them. */
static void test_roi_layout_and_edges(void)
{
    const sbr_image_t rgb = view(64u, 16u, 200u, SBR_PIXEL_RGB888);
    const sbr_image_t grey = view(64u, 16u, 64u, SBR_PIXEL_GRAY8);
    sbr_rect_t r = {5u, 3u, 10u, 4u};
    sbr_image_t out;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_roi(&rgb, &r, &out));
    TEST_ASSERT_EQUAL_PTR(&g_px[(3u * 200u) + (5u * 3u)], out.data);
    TEST_ASSERT_EQUAL_UINT32(10u, out.width);
    TEST_ASSERT_EQUAL_UINT32(4u, out.height);
    TEST_ASSERT_EQUAL_UINT32(200u, out.stride);
    TEST_ASSERT_EQUAL_INT(SBR_PIXEL_RGB888, out.format);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_check(&out));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_roi(&grey, &r, &out));
    TEST_ASSERT_EQUAL_PTR(&g_px[(3u * 64u) + 5u], out.data);
    /* the whole image, and the last pixel alone */
    r = (sbr_rect_t){0u, 0u, 64u, 16u};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_roi(&grey, &r, &out));
    TEST_ASSERT_EQUAL_PTR(grey.data, out.data); /* fields, not bytes: enum padding */
    TEST_ASSERT_EQUAL_UINT32(64u, out.width);
    TEST_ASSERT_EQUAL_UINT32(16u, out.height);
    TEST_ASSERT_EQUAL_UINT32(64u, out.stride);
    TEST_ASSERT_EQUAL_INT(SBR_PIXEL_GRAY8, out.format);
    r = (sbr_rect_t){63u, 15u, 1u, 1u};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_image_roi(&grey, &r, &out));
    TEST_ASSERT_EQUAL_PTR(&g_px[(15u * 64u) + 63u], out.data);
    /* one past the right or bottom edge, empty, starting outside */
    r = (sbr_rect_t){60u, 0u, 5u, 1u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
    r = (sbr_rect_t){0u, 12u, 1u, 5u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
    r = (sbr_rect_t){0u, 0u, 0u, 1u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
    r = (sbr_rect_t){64u, 0u, 1u, 1u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
}

/* Sizes whose sum wraps around 32 bits are refused, not wrapped into range. */
static void test_roi_no_wraparound(void)
{
    const sbr_image_t grey = view(64u, 16u, 64u, SBR_PIXEL_GRAY8);
    sbr_rect_t r = {1u, 0u, UINT32_MAX, 1u};
    sbr_image_t out;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
    r = (sbr_rect_t){0u, 2u, 1u, UINT32_MAX - 1u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
    r = (sbr_rect_t){UINT32_MAX, 0u, 2u, 1u};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_image_roi(&grey, &r, &out));
}

/* A bad view is reported with sbr_image_check()'s status before the rectangle is looked
   at. */
static void test_roi_of_bad_view(void)
{
    sbr_image_t bad = view(64u, 16u, 63u, SBR_PIXEL_GRAY8);
    const sbr_rect_t r = {0u, 0u, 1u, 1u};
    sbr_image_t out;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_image_roi(&bad, &r, &out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, sbr_image_roi(&bad, NULL, &out));
    bad = view(64u, 0u, 64u, SBR_PIXEL_GRAY8);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_image_roi(&bad, &r, &out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_image_roi(NULL, &r, &out));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_bytes_per_pixel);
    RUN_TEST(test_check_bounds);
    RUN_TEST(test_roi_layout_and_edges);
    RUN_TEST(test_roi_no_wraparound);
    RUN_TEST(test_roi_of_bad_view);
    return UNITY_END();
}
