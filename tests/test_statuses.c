/* SPDX-License-Identifier: MIT */
/* Every documented status, header by header: one table-driven test per public header
   (image, fft, map, contour, mser, fd, conic, channel, pictogram, status). Each row is a
   call and the status its header documents for it; the rows are evaluated in order and
   every one is checked, so a failure names the call. The tables of the recogniser,
   parts, tracker, bicycle and CAN headers are in their own test files (they need those
   tests' scenes and models): test_recog.c, test_parts.c, test_track.c,
   test_bike.c, test_can.c, each a test_<header>_h_statuses(). */
#include <math.h>
#include <string.h>

#include "sbr/channel.h"
#include "sbr/conic.h"
#include "sbr/contour.h"
#include "sbr/fd.h"
#include "sbr/fft.h"
#include "sbr/image.h"
#include "sbr/map.h"
#include "sbr/mser.h"
#include "sbr/picto.h"
#include "sbr/status.h"
#include "sbr/models.h"
#include "test_status_table.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

/* a 16 x 16 RGB frame: a dark disc on a bright ground */
static uint8_t g_rgb[16 * 16 * 3];
static uint8_t g_grey[16 * 16];
static uint8_t g_out[32 * 32];
static uint64_t g_ws[20000]; /* 8-byte aligned on every target */

static sbr_image_t rgb_view(void)
{
    sbr_image_t v;
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < 16u; y++) {
        for (x = 0u; x < 16u; x++) {
            const int32_t dx = (int32_t)x - 8;
            const int32_t dy = (int32_t)y - 8;
            const uint8_t g = ((dx * dx) + (dy * dy) <= 16) ? 30u : 220u;
            g_rgb[(y * 16u + x) * 3u] = g;
            g_rgb[(y * 16u + x) * 3u + 1u] = g;
            g_rgb[(y * 16u + x) * 3u + 2u] = g;
            g_grey[y * 16u + x] = g;
        }
    }
    v.width = 16u;
    v.height = 16u;
    v.stride = 48u;
    v.format = SBR_PIXEL_RGB888;
    v.data = g_rgb;
    return v;
}

static sbr_image_t grey_view(void)
{
    sbr_image_t v = rgb_view();
    v.stride = 16u;
    v.format = SBR_PIXEL_GRAY8;
    v.data = g_grey;
    return v;
}

static void test_image_h(void)
{
    status_table_t t;
    sbr_image_t v = rgb_view();
    sbr_image_t bad;
    sbr_image_t out;
    sbr_rect_t roi = {2u, 3u, 8u, 8u};
    const sbr_rect_t outside = {10u, 3u, 8u, 8u};
    const sbr_rect_t empty = {2u, 3u, 0u, 8u};
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_image_check(&v));
    ROW(&t, SBR_ERR_NULL, sbr_image_check(NULL));
    bad = v;
    bad.data = NULL;
    ROW(&t, SBR_ERR_NULL, sbr_image_check(&bad));
    bad = v;
    bad.width = 0u;
    ROW(&t, SBR_ERR_SIZE, sbr_image_check(&bad));
    bad = v;
    bad.height = SBR_IMAGE_MAX_DIM + 1u;
    ROW(&t, SBR_ERR_SIZE, sbr_image_check(&bad));
    bad = v;
    bad.format = (sbr_pixel_format_t)2;
    ROW(&t, SBR_ERR_RANGE, sbr_image_check(&bad));
    bad = v;
    bad.stride = 47u; /* shorter than a row */
    ROW(&t, SBR_ERR_ALIGN, sbr_image_check(&bad));
    bad.stride = SBR_IMAGE_MAX_STRIDE + 1u;
    ROW(&t, SBR_ERR_ALIGN, sbr_image_check(&bad));
    ROW(&t, SBR_OK, sbr_image_roi(&v, &roi, &out));
    ROW(&t, SBR_ERR_NULL, sbr_image_roi(&v, NULL, &out));
    ROW(&t, SBR_ERR_NULL, sbr_image_roi(&v, &roi, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_image_roi(&v, &outside, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_image_roi(&v, &empty, &out));
    bad = v;
    bad.width = 0u;
    ROW(&t, SBR_ERR_SIZE, sbr_image_roi(&bad, &roi, &out)); /* as sbr_image_check() */
    status_table_check(&t);
    TEST_ASSERT_EQUAL_UINT32(3u, sbr_image_bytes_per_pixel(SBR_PIXEL_RGB888));
    TEST_ASSERT_EQUAL_UINT32(1u, sbr_image_bytes_per_pixel(SBR_PIXEL_GRAY8));
    TEST_ASSERT_EQUAL_UINT32(0u, sbr_image_bytes_per_pixel((sbr_pixel_format_t)9));
}

static void test_fft_h(void)
{
    status_table_t t;
    sbr_fft_t fft;
    sbr_fft_t bad;
    sbr_complex_t a[64];
    sbr_complex_t b[64];
    memset(a, 0, sizeof a);
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_fft_init(&fft, 64u));
    ROW(&t, SBR_ERR_NULL, sbr_fft_init(NULL, 64u));
    ROW(&t, SBR_ERR_SIZE, sbr_fft_init(&bad, 48u));
    ROW(&t, SBR_ERR_STATE, sbr_fft_check(&bad)); /* cleared by the failed init */
    ROW(&t, SBR_ERR_STATE, sbr_fft_forward(&bad, a, b));
    ROW(&t, SBR_OK, sbr_fft_init_16(&bad));
    ROW(&t, SBR_ERR_NULL, sbr_fft_init_1024(NULL));
    ROW(&t, SBR_OK, sbr_fft_check(&fft));
    ROW(&t, SBR_ERR_NULL, sbr_fft_check(NULL));
    ROW(&t, SBR_OK, sbr_fft_forward(&fft, a, b));
    ROW(&t, SBR_OK, sbr_fft_forward(&fft, a, a)); /* in place */
    ROW(&t, SBR_ERR_NULL, sbr_fft_forward(&fft, NULL, b));
    ROW(&t, SBR_ERR_NULL, sbr_fft_forward(&fft, a, NULL));
    ROW(&t, SBR_ERR_OVERLAP, sbr_fft_forward(&fft, a, &a[1]));
    ROW(&t, SBR_OK, sbr_fft_inverse(&fft, a, b));
    ROW(&t, SBR_ERR_OVERLAP, sbr_fft_inverse(&fft, &a[2], a));
    ROW(&t, SBR_ERR_NULL, sbr_fft_inverse(NULL, a, b));
    memset(&bad, 0x5A, sizeof bad); /* overwritten */
    ROW(&t, SBR_ERR_STATE, sbr_fft_check(&bad));
    ROW(&t, SBR_ERR_STATE, sbr_fft_inverse(&bad, a, b));
    /* regression (fuzzer finding, campaign): an instance whose integrity word was right
       but whose table pointer was overwritten was dereferenced (SEGV); every field is in
       the seal now, checked before a table is read */
    bad = fft;
    bad.bitrev = (const uint16_t *)(const void *)&a[3];
    ROW(&t, SBR_ERR_STATE, sbr_fft_check(&bad));
    bad = fft;
    bad.twiddle[0] = &a[0];
    ROW(&t, SBR_ERR_STATE, sbr_fft_forward(&bad, a, b));
    bad = fft;
    bad.stages += 1u;
    ROW(&t, SBR_ERR_STATE, sbr_fft_check(&bad));
    bad = fft; /* a copy of a sound instance is sound */
    ROW(&t, SBR_OK, sbr_fft_check(&bad));
    status_table_check(&t);
    TEST_ASSERT_EQUAL_INT(1, sbr_fft_size_supported(1024u));
    TEST_ASSERT_EQUAL_INT(0, sbr_fft_size_supported(2048u));
    TEST_ASSERT_EQUAL_INT(0, sbr_fft_size_supported(8u));
}

static void test_map_h(void)
{
    status_table_t t;
    const sbr_image_t v = rgb_view();
    const sbr_image_t gv = grey_view();
    sbr_image_t bad = v;
    sbr_image_t out;
    sbr_image_t self;
    bad.stride = 1u;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_map_make(&v, SBR_MAP_INTENSITY, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_OK, sbr_map_make(&v, SBR_MAP_RED, 2u, g_out, 8u, 64u, &out));
    ROW(&t, SBR_OK, sbr_map_make(&gv, SBR_MAP_INTENSITY, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_NULL, sbr_map_make(NULL, SBR_MAP_INTENSITY, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_NULL, sbr_map_make(&v, SBR_MAP_INTENSITY, 1u, NULL, 16u, sizeof g_out, &out));
    ROW(&t, SBR_OK, sbr_map_make(&v, SBR_MAP_INTENSITY, 1u, g_out, 16u, sizeof g_out, NULL)); /* may be NULL */
    ROW(&t, SBR_ERR_ALIGN, sbr_map_make(&bad, SBR_MAP_INTENSITY, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_map_make(&v, (sbr_map_kind_t)4, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_map_make(&gv, SBR_MAP_BLUE, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_map_make(&v, SBR_MAP_INTENSITY, 0u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_RANGE,
        sbr_map_make(&v, SBR_MAP_INTENSITY, SBR_MAP_MAX_SUBSAMPLE + 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_ALIGN, sbr_map_make(&v, SBR_MAP_INTENSITY, 1u, g_out, 15u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_ALIGN, sbr_map_make(&v, SBR_MAP_INTENSITY, 1u, g_out, 16u, 255u, &out));
    /* the output over the source's own pixels */
    self = gv;
    ROW(&t, SBR_ERR_OVERLAP, sbr_map_make(&self, SBR_MAP_INTENSITY, 1u, g_grey, 16u, sizeof g_grey, &out));
    ROW(&t, SBR_OK, sbr_map_make_bright(&v, SBR_MAP_RED, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_NULL, sbr_map_make_bright(NULL, SBR_MAP_RED, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_RANGE, sbr_map_make_bright(&gv, SBR_MAP_RED, 1u, g_out, 16u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_ALIGN, sbr_map_make_bright(&v, SBR_MAP_RED, 1u, g_out, 15u, sizeof g_out, &out));
    ROW(&t, SBR_ERR_OVERLAP, sbr_map_make_bright(&self, SBR_MAP_INTENSITY, 1u, g_grey, 16u, sizeof g_grey, &out));
    status_table_check(&t);
}

static void test_contour_h(void)
{
    status_table_t t;
    const sbr_image_t gv = grey_view();
    sbr_image_t mask = gv;
    sbr_image_t rgb = rgb_view();
    sbr_point_t pts[256];
    sbr_contour_t cs[4];
    uint32_t n = 0u;
    int64_t a2 = 0;
    uint32_t i;
    static uint8_t m[16 * 16];
    const size_t ws = sbr_contour_workspace_size(16u, 16u);
    for (i = 0u; i < 256u; i++) {
        m[i] = (g_grey[i] < 128u) ? 255u : 0u; /* the disc */
    }
    mask.data = m;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_contour_find_external(&mask, g_ws, ws, pts, 256u, cs, 4u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_contour_find_external(NULL, g_ws, ws, pts, 256u, cs, 4u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_contour_find_external(&mask, g_ws, ws, pts, 256u, cs, 4u, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_contour_find_external(&rgb, g_ws, ws, pts, 256u, cs, 4u, &n));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_contour_find_external(&mask, g_ws, ws - 1u, pts, 256u, cs, 4u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_contour_find_external(&mask, g_ws, ws, pts, 4u, cs, 4u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_contour_find_external(&mask, g_ws, ws, pts, 256u, cs, 0u, &n));
    mask.stride = 3u;
    ROW(&t, SBR_ERR_ALIGN, sbr_contour_find_external(&mask, g_ws, ws, pts, 256u, cs, 4u, &n));
    ROW(&t, SBR_OK, sbr_contour_area2(pts, 4u, &a2));
    ROW(&t, SBR_ERR_NULL, sbr_contour_area2(NULL, 4u, &a2));
    ROW(&t, SBR_ERR_NULL, sbr_contour_area2(pts, 4u, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_contour_area2(pts, 0u, &a2));
    status_table_check(&t);
}

static void test_mser_h(void)
{
    status_table_t t;
    const sbr_image_t gv = grey_view();
    sbr_image_t small = gv;
    sbr_image_t rgb = rgb_view();
    sbr_mser_config_t cfg;
    sbr_mser_config_t bad;
    sbr_mser_region_t r[8];
    sbr_mser_region_t moved;
    uint32_t n = 0u;
    size_t ws;
    sbr_mser_config_default(&cfg);
    cfg.min_area = 10u;
    cfg.max_area = 200u;
    ws = sbr_mser_workspace_size(&cfg, 16u, 16u);
    TEST_ASSERT_TRUE(ws > 0u && ws <= sizeof g_ws);
    bad = cfg;
    bad.max_variation = NAN;
    small.width = 2u;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_mser_config_check(&cfg));
    ROW(&t, SBR_ERR_NULL, sbr_mser_config_check(NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_mser_config_check(&bad));
    ROW(&t, SBR_OK, sbr_mser_detect(&gv, &cfg, g_ws, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_mser_detect(NULL, &cfg, g_ws, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_mser_detect(&gv, &cfg, g_ws, ws, r, 8u, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_mser_detect(&rgb, &cfg, g_ws, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_mser_detect(&gv, &bad, g_ws, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_SIZE, sbr_mser_detect(&small, &cfg, g_ws, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_mser_detect(&gv, &cfg, g_ws, ws - 1u, r, 8u, &n));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_mser_detect(&gv, &cfg, (uint8_t *)g_ws + 1, ws, r, 8u, &n));
    ROW(&t, SBR_ERR_SIZE, sbr_mser_detect(&gv, &cfg, g_ws, ws, r, 0u, &n));
    status_table_check(&t);
    /* the in-place entry: the slot refuses what the detection refuses */
    {
        sbr_image_t back;
        uint8_t *slot;
        uint32_t y;
        TEST_ASSERT_NULL(sbr_mser_map_slot(NULL, 16u, 16u, g_ws, ws));
        TEST_ASSERT_NULL(sbr_mser_map_slot(&bad, 16u, 16u, g_ws, ws));
        TEST_ASSERT_NULL(sbr_mser_map_slot(&cfg, 2u, 16u, g_ws, ws));
        TEST_ASSERT_NULL(sbr_mser_map_slot(&cfg, 16u, 16u, NULL, ws));
        TEST_ASSERT_NULL(sbr_mser_map_slot(&cfg, 16u, 16u, g_ws, ws - 1u));
        TEST_ASSERT_NULL(sbr_mser_map_slot(&cfg, 16u, 16u, (uint8_t *)g_ws + 1, ws));
        slot = sbr_mser_map_slot(&cfg, 16u, 16u, g_ws, ws);
        TEST_ASSERT_NOT_NULL(slot);
        for (y = 0u; y < 16u; y++) {
            memcpy(&slot[y * 16u], &gv.data[(size_t)y * gv.stride], 16u);
        }
        t.n = 0u;
        ROW(&t, SBR_OK, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws, r, 8u, &n, &back));
        ROW(&t, SBR_ERR_NULL, sbr_mser_detect_in_place(16u, 16u, NULL, g_ws, ws, r, 8u, &n, &back));
        ROW(&t, SBR_ERR_NULL, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws, NULL, 8u, &n, &back));
        ROW(&t, SBR_ERR_NULL, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws, r, 8u, NULL, &back));
        ROW(&t, SBR_ERR_NULL, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws, r, 8u, &n, NULL));
        ROW(&t, SBR_ERR_RANGE, sbr_mser_detect_in_place(16u, 16u, &bad, g_ws, ws, r, 8u, &n, &back));
        ROW(&t, SBR_ERR_SIZE, sbr_mser_detect_in_place(2u, 16u, &cfg, g_ws, ws, r, 8u, &n, &back));
        ROW(&t, SBR_ERR_SIZE, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws, r, 0u, &n, &back));
        ROW(&t, SBR_ERR_WORKSPACE, sbr_mser_detect_in_place(16u, 16u, &cfg, g_ws, ws - 1u, r, 8u, &n, &back));
        status_table_check(&t);
    }
    /* the node bound reached: a distinct status, the regions found so far exact */
    {
        sbr_mser_config_t few = cfg;
        size_t fws;
        few.max_nodes = 1u;
        fws = sbr_mser_workspace_size(&few, 16u, 16u);
        TEST_ASSERT_TRUE(fws > 0u && fws <= sizeof g_ws);
        TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_mser_detect(&gv, &few, g_ws, fws, r, 8u, &n));
    }
    /* the region masks of what was found */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_mser_detect(&gv, &cfg, g_ws, ws, r, 8u, &n));
    TEST_ASSERT_TRUE(n >= 1u);
    {
        const size_t mws = SBR_MSER_MASK_WORKSPACE_SIZE(r[0].bbox.width, r[0].bbox.height);
        const uint32_t mst = r[0].bbox.width;
        t.n = 0u;
        ROW(&t, SBR_OK, sbr_mser_region_mask(&gv, &r[0], g_ws, mws, g_out, mst, sizeof g_out));
        ROW(&t, SBR_ERR_NULL, sbr_mser_region_mask(&gv, NULL, g_ws, mws, g_out, mst, sizeof g_out));
        ROW(&t, SBR_ERR_NULL, sbr_mser_region_mask(&gv, &r[0], g_ws, mws, NULL, mst, sizeof g_out));
        ROW(&t, SBR_ERR_RANGE, sbr_mser_region_mask(&rgb, &r[0], g_ws, mws, g_out, mst, sizeof g_out));
        ROW(&t, SBR_ERR_ALIGN, sbr_mser_region_mask(&gv, &r[0], g_ws, mws, g_out, mst - 1u, sizeof g_out));
        ROW(&t, SBR_ERR_ALIGN, sbr_mser_region_mask(&gv, &r[0], g_ws, mws, g_out, mst, 1u));
        ROW(&t, SBR_ERR_WORKSPACE, sbr_mser_region_mask(&gv, &r[0], g_ws, mws - 1u, g_out, mst, sizeof g_out));
        moved = r[0];
        moved.seed_x = (uint16_t)(moved.bbox.x + moved.bbox.width); /* outside its box */
        ROW(&t, SBR_ERR_RANGE, sbr_mser_region_mask(&gv, &moved, g_ws, mws, g_out, mst, sizeof g_out));
        moved = r[0];
        moved.area += 1u; /* not the region of this map */
        ROW(&t, SBR_ERR_CORRUPT, sbr_mser_region_mask(&gv, &moved, g_ws, mws, g_out, mst, sizeof g_out));
        status_table_check(&t);
    }
}

static void test_fd_h(void)
{
    status_table_t t;
    static sbr_fft_t fft;
    static sbr_fft_t p;
    static sbr_fft_t none;
    static sbr_complex_t work[SBR_FD_TABLE_WORK_LEN(64u)];
    const sbr_point_t sq[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const sbr_point_t line[3] = {{0, 0}, {5, 5}, {10, 10}};
    sbr_pointf_t far[4] = {{0.0f, 0.0f}, {10.0f, 0.0f}, {10.0f, 10.0f}, {0.0f, 10.0f}};
    sbr_fd_t a;
    sbr_fd_t b;
    sbr_fd_t table[2];
    sbr_fd_match_config_t cfg;
    sbr_fd_match_config_t badcfg;
    sbr_fd_match_t r[2];
    uint32_t best = 0u;
    float e = 0.0f;
    memset(&none, 0, sizeof none);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&fft, 128u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init(&p, 64u));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_from_points(&fft, sq, 4u, 8u, work, 128u, &b));
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_fd_from_points(&fft, sq, 4u, 8u, work, 128u, &a));
    ROW(&t, SBR_ERR_NULL, sbr_fd_from_points(&fft, NULL, 4u, 8u, work, 128u, &a));
    ROW(&t, SBR_ERR_STATE, sbr_fd_from_points(&none, sq, 4u, 8u, work, 128u, &a));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_from_points(&fft, sq, 0u, 8u, work, 128u, &a));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_from_points(&fft, sq, 4u, 8u, work, 127u, &a));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_from_points(&fft, sq, 4u, 0u, work, 128u, &a));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_from_points(&fft, sq, 4u, SBR_FD_MAX_M + 1u, work, 128u, &a));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_fd_from_points(&fft, sq, 2u, 8u, work, 128u, &a));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_fd_from_points(&fft, line, 3u, 8u, work, 128u, &a));
    ROW(&t, SBR_OK, sbr_fd_from_pointsf(&fft, far, 4u, 8u, work, 128u, &a));
    far[2].x = NAN;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_from_pointsf(&fft, far, 4u, 8u, work, 128u, &a));
    far[2].x = 2.0f * SBR_FD_MAX_COORD;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_from_pointsf(&fft, far, 4u, 8u, work, 128u, &a));
    ROW(&t, SBR_OK, sbr_fd_check(&b, &e));
    ROW(&t, SBR_ERR_NULL, sbr_fd_check(NULL, &e));
    a = b;
    a.scale = -1.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_check(&a, &e));
    ROW(&t, SBR_OK, sbr_fd_mirror(&b, &a));
    ROW(&t, SBR_ERR_NULL, sbr_fd_mirror(&b, NULL));
    a = b;
    a.m = 0u;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_mirror(&a, &a));
    ROW(&t, SBR_OK, sbr_fd_smooth(&b, 0.1f, &a));
    ROW(&t, SBR_ERR_NULL, sbr_fd_smooth(NULL, 0.1f, &a));
    ROW(&t, SBR_ERR_RANGE, sbr_fd_smooth(&b, 0.6f, &a));
    sbr_fd_match_config_default(&cfg);
    ROW(&t, SBR_OK, sbr_fd_match_config_check(&cfg));
    ROW(&t, SBR_ERR_NULL, sbr_fd_match_config_check(NULL));
    badcfg = cfg;
    badcfg.max_rotation = -0.5f;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_match_config_check(&badcfg));
    ROW(&t, SBR_OK, sbr_fd_match(&p, &cfg, &b, &b, work, 64u, &r[0]));
    ROW(&t, SBR_ERR_NULL, sbr_fd_match(&p, &cfg, &b, NULL, work, 64u, &r[0]));
    ROW(&t, SBR_ERR_STATE, sbr_fd_match(&none, &cfg, &b, &b, work, 64u, &r[0]));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_match(&p, &cfg, &b, &b, work, 63u, &r[0]));
    a = b;
    a.m = 7u;
    ROW(&t, SBR_ERR_SIZE, sbr_fd_match(&p, &cfg, &b, &a, work, 64u, &r[0]));
    ROW(&t, SBR_ERR_RANGE, sbr_fd_match(&p, &badcfg, &b, &b, work, 64u, &r[0]));
    a = b;
    a.c[0].re = INFINITY;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_match(&p, &cfg, &a, &b, work, 64u, &r[0]));
    table[0] = b;
    table[1] = b;
    ROW(&t, SBR_OK, sbr_fd_match_table(&p, &cfg, &b, table, 2u, work, SBR_FD_TABLE_WORK_LEN(64u), r, &best));
    ROW(&t, SBR_ERR_SIZE, sbr_fd_match_table(&p, &cfg, &b, table, 0u, work, 64u, r, &best));
    ROW(&t, SBR_ERR_NULL, sbr_fd_match_table(&p, &cfg, &b, table, 2u, work, 64u, r, NULL));
    table[1].scale = 0.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_fd_match_table(&p, &cfg, &b, table, 2u, work, 64u, r, &best));
    status_table_check(&t);
}

static void test_conic_h(void)
{
    status_table_t t;
    const sbr_conic_t circle = {1.0f, 0.0f, 1.0f, 0.0f, 0.0f, -100.0f}; /* radius 10 */
    const sbr_conic_t zero = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    const sbr_conic_t hyper = {1.0f, 0.0f, -1.0f, 0.0f, 0.0f, -1.0f};
    sbr_conic_t nan_c = circle;
    sbr_conic_t q;
    sbr_conic_class_t cls;
    sbr_ellipse_t el;
    sbr_ellipse_t bad_el = {0.0f, 0.0f, 5.0f, 6.0f, 0.0f};
    sbr_pointf_t pts[8];
    sbr_pointf_t collinear[8];
    sbr_torch_pose_t pose;
    sbr_ellipse_detect_config_t dc;
    sbr_ellipse_detect_config_t bad_dc;
    sbr_ellipse_det_t det[4];
    const sbr_image_t gv = grey_view();
    const sbr_image_t rgb = rgb_view();
    uint32_t n = 0u;
    float rms = 0.0f;
    float cov = 0.0f;
    uint32_t i;
    size_t ws;
    nan_c.d = NAN;
    for (i = 0u; i < 8u; i++) {
        const float a = 0.7853982f * (float)i;
        pts[i].x = 10.0f * cosf(a);
        pts[i].y = 10.0f * sinf(a);
        collinear[i].x = (float)i;
        collinear[i].y = 2.0f * (float)i;
    }
    sbr_ellipse_detect_config_default(&dc);
    ws = sbr_ellipse_detect_workspace_size(&dc, 16u, 16u);
    TEST_ASSERT_TRUE(ws > 0u);
    bad_dc = dc;
    bad_dc.min_coverage = 2.0f;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_conic_classify(&circle, SBR_CONIC_ZERO_TOL, &cls));
    ROW(&t, SBR_ERR_NULL, sbr_conic_classify(NULL, SBR_CONIC_ZERO_TOL, &cls));
    ROW(&t, SBR_ERR_RANGE, sbr_conic_classify(&nan_c, SBR_CONIC_ZERO_TOL, &cls));
    ROW(&t, SBR_ERR_RANGE, sbr_conic_classify(&circle, 1.0f, &cls));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_conic_classify(&zero, SBR_CONIC_ZERO_TOL, &cls));
    ROW(&t, SBR_OK, sbr_conic_to_ellipse(&circle, &el));
    ROW(&t, SBR_ERR_NULL, sbr_conic_to_ellipse(&circle, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_conic_to_ellipse(&nan_c, &el));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_conic_to_ellipse(&hyper, &el));
    ROW(&t, SBR_OK, sbr_ellipse_to_conic(&el, &q));
    ROW(&t, SBR_ERR_NULL, sbr_ellipse_to_conic(NULL, &q));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_to_conic(&bad_el, &q));
    ROW(&t, SBR_OK, sbr_ellipse_fit(pts, 8u, &q, &el));
    ROW(&t, SBR_ERR_NULL, sbr_ellipse_fit(NULL, 8u, &q, &el));
    ROW(&t, SBR_ERR_SIZE, sbr_ellipse_fit(pts, 4u, &q, &el));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_ellipse_fit(collinear, 8u, &q, &el));
    pts[3].x = 2e6f;
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_fit(pts, 8u, &q, &el));
    ROW(&t, SBR_ERR_RANGE, sbr_conic_residual(&circle, pts, 8u, &rms, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_coverage(&circle, pts, 8u, 1.0f, &cov));
    pts[3].x = 0.0f;
    ROW(&t, SBR_OK, sbr_conic_residual(&circle, pts, 8u, &rms, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_conic_residual(&circle, pts, 8u, NULL, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_conic_residual(&circle, pts, 0u, &rms, NULL));
    ROW(&t, SBR_OK, sbr_ellipse_coverage(&circle, pts, 8u, 1.0f, &cov));
    ROW(&t, SBR_ERR_NULL, sbr_ellipse_coverage(&circle, pts, 8u, 1.0f, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_ellipse_coverage(&circle, pts, 0u, 1.0f, &cov));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_coverage(&circle, pts, 8u, 0.0f, &cov));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_ellipse_coverage(&hyper, pts, 8u, 1.0f, &cov));
    ROW(&t, SBR_ERR_NULL, sbr_torch_pose(&circle, 500.0f, SBR_TORCH_MAX_RESIDUAL, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_torch_pose(&circle, 0.0f, SBR_TORCH_MAX_RESIDUAL, &pose));
    ROW(&t, SBR_ERR_RANGE, sbr_torch_pose(&circle, 500.0f, 0.0f, &pose));
    ROW(&t, SBR_ERR_DEGENERATE, sbr_torch_pose(&hyper, 500.0f, SBR_TORCH_MAX_RESIDUAL, &pose));
    ROW(&t, SBR_OK, sbr_ellipse_detect_config_check(&dc));
    ROW(&t, SBR_ERR_NULL, sbr_ellipse_detect_config_check(NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_detect_config_check(&bad_dc));
    ROW(&t, SBR_OK, sbr_ellipse_detect(&gv, &dc, g_ws, ws, det, 4u, &n));
    ROW(&t, SBR_ERR_NULL, sbr_ellipse_detect(&gv, &dc, g_ws, ws, det, 4u, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_detect(&gv, &bad_dc, g_ws, ws, det, 4u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_ellipse_detect(&rgb, &dc, g_ws, ws, det, 4u, &n));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_ellipse_detect(&gv, &dc, g_ws, ws - 1u, det, 4u, &n));
    status_table_check(&t);
    TEST_ASSERT_EQUAL_size_t(0u, sbr_ellipse_detect_workspace_size(&bad_dc, 16u, 16u));
}

static void test_channel_h(void)
{
    status_table_t t;
    sbr_channel_config_t c;
    sbr_channel_config_t bad;
    sbr_channel_mode_t modes[2];
    float hist[10];
    float lo = 0.0f;
    float hi = 0.0f;
    float v = 0.0f;
    float cert = 0.0f;
    int valid = 0;
    uint32_t n = 0u;
    memset(hist, 0, sizeof hist);
    t.n = 0u;
    sbr_channel_config_default(&c);
    ROW(&t, SBR_OK, sbr_channel_config_check(&c));
    ROW(&t, SBR_ERR_NULL, sbr_channel_config_check(NULL));
    ROW(&t, SBR_OK, sbr_channel_config_check(&c));
    ROW(&t, SBR_ERR_NULL, sbr_channel_config_check(NULL));
    bad = c;
    bad.spacing = 0.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_channel_config_check(&bad));
    bad = c;
    bad.overlap = 9u;
    ROW(&t, SBR_ERR_RANGE, sbr_channel_config_check(&bad));
    bad = c;
    bad.count = 2u;
    ROW(&t, SBR_ERR_SIZE, sbr_channel_config_check(&bad));
    bad = c;
    bad.first_centre = 3e38f; /* the last centre overflows */
    bad.spacing = 3e37f;
    ROW(&t, SBR_ERR_RANGE, sbr_channel_config_check(&bad));
    ROW(&t, SBR_OK, sbr_channel_range(&c, &lo, &hi));
    ROW(&t, SBR_ERR_NULL, sbr_channel_range(&c, NULL, &hi));
    ROW(&t, SBR_OK, sbr_channel_encode(&c, 4.0f, 1.0f, hist, 10u));
    ROW(&t, SBR_ERR_NULL, sbr_channel_encode(&c, 4.0f, 1.0f, NULL, 10u));
    ROW(&t, SBR_ERR_SIZE, sbr_channel_encode(&c, 4.0f, 1.0f, hist, 9u));
    ROW(&t, SBR_ERR_RANGE, sbr_channel_encode(&c, 40.0f, 1.0f, hist, 10u));
    ROW(&t, SBR_ERR_RANGE, sbr_channel_encode(&c, 4.0f, 0.0f, hist, 10u));
    ROW(&t, SBR_OK, sbr_channel_accumulate(&c, 6.0f, 1.0f, hist, 10u));
    ROW(&t, SBR_ERR_RANGE, sbr_channel_accumulate(&c, 6.0f, NAN, hist, 10u));
    ROW(&t, SBR_OK, sbr_channel_decode_window(&c, hist, 10u, 2u, &v, &cert, &valid));
    ROW(&t, SBR_ERR_NULL, sbr_channel_decode_window(&c, hist, 10u, 2u, NULL, &cert, &valid));
    ROW(&t, SBR_ERR_SIZE, sbr_channel_decode_window(&c, hist, 9u, 2u, &v, &cert, &valid));
    ROW(&t, SBR_ERR_RANGE, sbr_channel_decode_window(&c, hist, 10u, 8u, &v, &cert, &valid));
    ROW(&t, SBR_OK, sbr_channel_decode(&c, hist, 10u, 0.1f, modes, 2u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_channel_decode(&c, hist, 10u, 0.1f, NULL, 0u, &n)); /* modes exist */
    ROW(&t, SBR_OK, sbr_channel_decode(&c, hist, 10u, 100.0f, NULL, 0u, &n));         /* none above */
    ROW(&t, SBR_ERR_NULL, sbr_channel_decode(&c, hist, 10u, 0.1f, modes, 2u, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_channel_decode(&c, hist, 9u, 0.1f, modes, 2u, &n));
    ROW(&t, SBR_ERR_RANGE, sbr_channel_decode(&c, hist, 10u, -1.0f, modes, 2u, &n));
    ROW(&t, SBR_ERR_CAPACITY, sbr_channel_decode(&c, hist, 10u, 0.1f, modes, 1u, &n));
    hist[5] = -1.0f;
    ROW(&t, SBR_ERR_RANGE, sbr_channel_decode(&c, hist, 10u, 0.1f, modes, 2u, &n));
    status_table_check(&t);
}

static void test_pictogram_h(void)
{
    status_table_t t;
    sbr_picto_model_t m;
    sbr_picto_model_t bad;
    const sbr_image_t v = rgb_view();
    const sbr_image_t gv = grey_view();
    static float feat[SBR_PICTO_FEATURES];
    float prob[SBR_PICTO_MAX_OUTPUTS];
    const float box[4] = {2.0f, 2.0f, 14.0f, 14.0f};
    const float tiny[4] = {2.0f, 2.0f, 3.0f, 14.0f};
    float refined[4];
    static uint32_t ws[SBR_PICTO_WORKSPACE_SIZE / 4u + 1u];
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_picto_gtsdb(&m));
    ROW(&t, SBR_ERR_NULL, sbr_picto_gtsdb(NULL));
    ROW(&t, SBR_OK, sbr_picto_check(&m));
    ROW(&t, SBR_ERR_NULL, sbr_picto_check(NULL));
    bad = m;
    bad.version = 0u;
    ROW(&t, SBR_ERR_CORRUPT, sbr_picto_check(&bad));
    ROW(&t, SBR_OK, sbr_picto_features(&v, box, feat, SBR_PICTO_FEATURES, ws, sizeof ws));
    ROW(&t, SBR_ERR_NULL, sbr_picto_features(&v, NULL, feat, SBR_PICTO_FEATURES, ws, sizeof ws));
    ROW(&t, SBR_ERR_SIZE, sbr_picto_features(&v, box, feat, SBR_PICTO_FEATURES - 1u, ws, sizeof ws));
    ROW(&t, SBR_ERR_RANGE, sbr_picto_features(&v, tiny, feat, SBR_PICTO_FEATURES, ws, sizeof ws));
    ROW(&t, SBR_OK, sbr_picto_features(&gv, box, feat, SBR_PICTO_FEATURES, ws, sizeof ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_picto_features(&v, box, feat, SBR_PICTO_FEATURES, ws, 16u));
    ROW(&t, SBR_ERR_RANGE, sbr_picto_features_outline(&v, box, 2u, feat, SBR_PICTO_FEATURES, ws, sizeof ws));
    ROW(&t, SBR_OK, sbr_picto_features_outline(&v, box, SBR_PICTO_OUTLINE_TRIANGLE, feat, SBR_PICTO_FEATURES,
                                               ws, sizeof ws));
    ROW(&t, SBR_OK, sbr_picto_classify(&m, feat, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws, sizeof ws));
    ROW(&t, SBR_ERR_NULL, sbr_picto_classify(&m, NULL, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws, sizeof ws));
    ROW(&t, SBR_ERR_SIZE, sbr_picto_classify(&m, feat, SBR_PICTO_FEATURES, prob, m.classes, ws, sizeof ws));
    ROW(&t, SBR_ERR_CORRUPT, sbr_picto_classify(&bad, feat, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws, sizeof ws));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_picto_classify(&m, feat, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws, 4u));
    ROW(&t, SBR_OK, sbr_picto_refine(&m, feat, SBR_PICTO_FEATURES, box, refined, ws, sizeof ws));
    ROW(&t, SBR_ERR_RANGE, sbr_picto_refine(&m, feat, SBR_PICTO_FEATURES, tiny, refined, ws, sizeof ws));
    ROW(&t, SBR_ERR_SIZE, sbr_picto_refine(&m, feat, 3u, box, refined, ws, sizeof ws));
    feat[7] = NAN;
    ROW(&t, SBR_ERR_RANGE, sbr_picto_classify(&m, feat, SBR_PICTO_FEATURES, prob, SBR_PICTO_MAX_OUTPUTS, ws, sizeof ws));
    ROW(&t, SBR_ERR_RANGE, sbr_picto_refine(&m, feat, SBR_PICTO_FEATURES, box, refined, ws, sizeof ws));
    {
        float contrast = 0.0f;
        ROW(&t, SBR_OK, sbr_picto_rim_contrast(&v, box, SBR_PICTO_RIM_DISC, &contrast));
        ROW(&t, SBR_ERR_NULL, sbr_picto_rim_contrast(&v, box, SBR_PICTO_RIM_DISC, NULL));
        ROW(&t, SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, box, SBR_PICTO_RIM_NONE, &contrast));
        ROW(&t, SBR_ERR_RANGE, sbr_picto_rim_contrast(&v, tiny, SBR_PICTO_RIM_TRIANGLE, &contrast));
        ROW(&t, SBR_ERR_RANGE, sbr_picto_rim_contrast(&gv, box, SBR_PICTO_RIM_TRIANGLE_DOWN, &contrast));
    }
    {
        static float gf[SBR_PICTO_GATE_FEATURES];
        static float gw[SBR_PICTO_GATE_WEIGHTS(0u)];
        float score = 0.0f;
        sbr_picto_model_t gm = m;
        ROW(&t, SBR_OK, sbr_picto_gate_features(&v, box, gf, SBR_PICTO_GATE_FEATURES, ws, sizeof ws));
        ROW(&t, SBR_ERR_NULL, sbr_picto_gate_features(&v, NULL, gf, SBR_PICTO_GATE_FEATURES, ws, sizeof ws));
        ROW(&t, SBR_ERR_RANGE, sbr_picto_gate_features(&v, tiny, gf, SBR_PICTO_GATE_FEATURES, ws, sizeof ws));
        ROW(&t, SBR_OK, sbr_picto_gate_features(&gv, box, gf, SBR_PICTO_GATE_FEATURES, ws, sizeof ws));
        ROW(&t, SBR_ERR_SIZE, sbr_picto_gate_features(&v, box, gf, 3u, ws, sizeof ws));
        ROW(&t, SBR_ERR_WORKSPACE, sbr_picto_gate_features(&v, box, gf, SBR_PICTO_GATE_FEATURES, ws, 16u));
        gm.gate = NULL;
        ROW(&t, SBR_ERR_NULL, sbr_picto_gate(&gm, gf, SBR_PICTO_GATE_FEATURES, &score));
        gm.gate = gw;
        gm.gate_hidden = 0u;
        gm.gate_threshold = 0.0f;
        ROW(&t, SBR_OK, sbr_picto_check(&gm));
        ROW(&t, SBR_OK, sbr_picto_gate(&gm, gf, SBR_PICTO_GATE_FEATURES, &score));
        ROW(&t, SBR_ERR_NULL, sbr_picto_gate(&gm, gf, SBR_PICTO_GATE_FEATURES, NULL));
        ROW(&t, SBR_ERR_SIZE, sbr_picto_gate(&gm, gf, 3u, &score));
        gf[2] = NAN;
        ROW(&t, SBR_ERR_RANGE, sbr_picto_gate(&gm, gf, SBR_PICTO_GATE_FEATURES, &score));
        gf[2] = 0.0f;
        gm.gate_hidden = SBR_PICTO_GATE_HIDDEN_MAX + 1u;
        ROW(&t, SBR_ERR_CORRUPT, sbr_picto_check(&gm));
        ROW(&t, SBR_ERR_CORRUPT, sbr_picto_gate(&gm, gf, SBR_PICTO_GATE_FEATURES, &score));
    }
    status_table_check(&t);
}

static void test_status_h(void)
{
    static const sbr_status_t all[] = {SBR_OK, SBR_ERR_NULL, SBR_ERR_SIZE, SBR_ERR_RANGE,
                                       SBR_ERR_ALIGN, SBR_ERR_CAPACITY, SBR_ERR_WORKSPACE,
                                       SBR_ERR_STATE, SBR_ERR_OVERLAP, SBR_ERR_DEGENERATE,
                                       SBR_ERR_CORRUPT};
    uint32_t i;
    uint32_t j;
    /* each status has its own name, none the unknown one */
    for (i = 0u; i < sizeof all / sizeof all[0]; i++) {
        TEST_ASSERT_NOT_NULL(sbr_status_str(all[i]));
        TEST_ASSERT_TRUE(strcmp(sbr_status_str(all[i]), "SBR_ERR_UNKNOWN") != 0);
        for (j = 0u; j < i; j++) {
            TEST_ASSERT_TRUE(strcmp(sbr_status_str(all[i]), sbr_status_str(all[j])) != 0);
        }
    }
    TEST_ASSERT_EQUAL_STRING("SBR_OK", sbr_status_str(SBR_OK));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_CORRUPT", sbr_status_str(SBR_ERR_CORRUPT));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_UNKNOWN", sbr_status_str((sbr_status_t)-11));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_UNKNOWN", sbr_status_str((sbr_status_t)1));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_image_h);
    RUN_TEST(test_fft_h);
    RUN_TEST(test_map_h);
    RUN_TEST(test_contour_h);
    RUN_TEST(test_mser_h);
    RUN_TEST(test_fd_h);
    RUN_TEST(test_conic_h);
    RUN_TEST(test_channel_h);
    RUN_TEST(test_pictogram_h);
    RUN_TEST(test_status_h);
    return UNITY_END();
}
