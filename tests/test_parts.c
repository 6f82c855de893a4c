/* SPDX-License-Identifier: MIT */
/* Unity tests of part extraction (include/sbr/parts.h): maps -> MSER -> contours -> FDs. */
#include "unity.h"
#include "sbr/parts.h"
#include "test_status_table.h"
#include "test_support.h"

#include <math.h>
#include <string.h>

#define W 96u
#define H 64u
#define PI_F 3.14159265f

static uint8_t g_rgb[H][W][3];
static uint64_t g_ws[400000u / 8u];
static sbr_part_t g_parts[64];
static sbr_fft_t g_fft;
static sbr_parts_config_t g_cfg;
static sbr_complex_t g_work[128];

void setUp(void)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_rgb[y][x][0] = 110u;
            g_rgb[y][x][1] = 110u;
            g_rgb[y][x][2] = 110u;
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_128(&g_fft));
    sbr_parts_config_default(&g_cfg);
    g_cfg.max_side = 48u;
    g_cfg.max_contour = 512u;
    g_cfg.max_regions = 64u;
    g_cfg.mser.max_nodes = 0u;
}
void tearDown(void) {}

static sbr_image_t view(void)
{
    sbr_image_t v;
    v.width = W;
    v.height = H;
    v.stride = 3u * W;
    v.format = SBR_PIXEL_RGB888;
    v.data = &g_rgb[0][0][0];
    return v;
}

static void paint(uint32_t x, uint32_t y, uint8_t r, uint8_t g, uint8_t b)
{
    g_rgb[y][x][0] = r;
    g_rgb[y][x][1] = g;
    g_rgb[y][x][2] = b;
}

/* A prohibitory-like sign: red ring (radius 9..14) around a white disc, centred (cx, cy). */
static void draw_ring_sign(float cx, float cy)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const float d = hypotf((float)x - cx, (float)y - cy);
            if (d <= 9.0f) {
                paint(x, y, 240u, 240u, 240u);
            } else if (d <= 14.0f) {
                paint(x, y, 200u, 20u, 30u);
            }
        }
    }
}

/* A filled, upward triangle (danger-like outline), apex at (cx, cy - 12). */
static void draw_triangle(float cx, float cy)
{
    uint32_t x;
    uint32_t y;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            const float dy = (float)y - (cy - 12.0f);
            const float dx = fabsf((float)x - cx);
            if ((dy >= 0.0f) && (dy <= 22.0f) && (dx <= 0.58f * dy)) {
                paint(x, y, 30u, 30u, 30u);
            }
        }
    }
}

static sbr_fd_t circle_fd(void)
{
    sbr_pointf_t pts[64];
    sbr_fd_t fd;
    uint32_t i;
    for (i = 0u; i < 64u; i++) {
        /* counter-clockwise on screen, as traced outer boundaries run */
        const float a = 2.0f * PI_F * (float)i / 64.0f;
        pts[i].x = 10.0f * cosf(a);
        pts[i].y = -10.0f * sinf(a); /* y points down */
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_from_pointsf(&g_fft, pts, 64u, g_cfg.fd_m, g_work, 128u, &fd));
    return fd;
}

static float match_error(const sbr_fd_t *a, const sbr_fd_t *b)
{
    sbr_fft_t p;
    sbr_fd_match_config_t mc;
    sbr_fd_match_t r;
    sbr_complex_t work[32];
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_32(&p));
    sbr_fd_match_config_default(&mc);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match_config_check(&mc));
    mc.mode = SBR_FD_ROTATION_INVARIANT;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fd_match(&p, &mc, a, b, work, 32u, &r));
    return r.error;
}

/* The ring sign gives a red-map part and intensity parts centred on the sign, whose
   descriptors match a circle; the triangle gives a dark part that does not. */
static void test_ring_sign_and_triangle(void)
{
    const sbr_image_t v = view();
    const sbr_fd_t circ = circle_fd();
    sbr_parts_stats_t stats;
    uint32_t n = 0u;
    uint32_t i;
    int red_ring = 0;
    int white_disc = 0;
    int triangle = 0;
    draw_ring_sign(30.0f, 32.0f);
    draw_triangle(70.0f, 32.0f);
    TEST_ASSERT_TRUE(sbr_parts_workspace_size(&g_cfg, W, H) <= sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u,
                                                    &n, &stats));
    TEST_ASSERT_TRUE(n >= 3u);
    TEST_ASSERT_TRUE(stats.regions >= n);
    for (i = 0u; i < n; i++) {
        const sbr_part_t *p = &g_parts[i];
        const float e = match_error(&p->fd, &circ);
        if ((p->map == SBR_MAP_RED) && (p->polarity == SBR_MSER_BRIGHT) &&
            (fabsf(p->fd.cx - 30.0f) < 1.0f) && (fabsf(p->fd.cy - 32.0f) < 1.0f)) {
            red_ring = 1;
            TEST_ASSERT_TRUE(e < 0.01f);
            /* the outer boundary of a radius-14 disc: about 2 * pi * 14 long, scale ~ 14 */
            TEST_ASSERT_FLOAT_WITHIN(2.0f, 14.0f, p->fd.scale);
        }
        if ((p->map == SBR_MAP_INTENSITY) && (p->polarity == SBR_MSER_BRIGHT) &&
            (p->bbox.width <= 20u) && (fabsf(p->fd.cx - 30.0f) < 1.0f)) {
            white_disc = 1;
            TEST_ASSERT_TRUE(e < 0.01f);
        }
        if ((p->polarity == SBR_MSER_DARK) && (fabsf(p->fd.cx - 70.0f) < 1.5f)) {
            /* an ideal triangle's boundary has |C(1)|^2 = 1 / (1 + 1/16 + 1/256 + ...) of
               its energy, so its best match with a circle is e = 2 - 2 * 0.967 = 0.065 */
            triangle = 1;
            TEST_ASSERT_FLOAT_WITHIN(0.03f, 0.065f, e);
        }
    }
    TEST_ASSERT_TRUE(red_ring);
    TEST_ASSERT_TRUE(white_disc);
    TEST_ASSERT_TRUE(triangle);
}

/* Subsampling by 2 keeps coordinates in input pixels. */
static void test_subsample_keeps_input_coordinates(void)
{
    const sbr_image_t v = view();
    uint32_t n = 0u;
    uint32_t i;
    int found = 0;
    draw_ring_sign(48.0f, 32.0f);
    g_cfg.subsample = 2u;
    g_cfg.mser.min_area = 20u;
    g_cfg.min_side = 4u;
    g_cfg.maps = 1u << SBR_MAP_RED;
    g_cfg.max_side = 40u; /* not the whole 46 x 30 map interior */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u,
                                                    &n, NULL));
    for (i = 0u; i < n; i++) {
        /* the bright red ring (the dark background region is centred there as well) */
        if ((g_parts[i].polarity == SBR_MSER_BRIGHT) && (fabsf(g_parts[i].fd.cx - 48.0f) < 1.5f) &&
            (fabsf(g_parts[i].fd.cy - 32.0f) < 1.5f)) {
            found = 1;
            TEST_ASSERT_FLOAT_WITHIN(2.5f, 14.0f, g_parts[i].fd.scale);
            TEST_ASSERT_TRUE(g_parts[i].bbox.width >= 26u && g_parts[i].bbox.width <= 32u);
        }
    }
    TEST_ASSERT_TRUE(found);
}

/* Parts of one map kind from an extraction, in order. */
static uint32_t parts_of_map(const sbr_part_t *all, uint32_t n, uint8_t kind, sbr_part_t *out)
{
    uint32_t i;
    uint32_t k = 0u;
    for (i = 0u; i < n; i++) {
        if (all[i].map == kind) {
            out[k] = all[i];
            k++;
        }
    }
    return k;
}

/* The ring sign on the intensity and red maps, regions from 20 pixels, boxes 4..40. */
static void ring_on_intensity_and_red(void)
{
    draw_ring_sign(48.0f, 32.0f);
    g_cfg.mser.min_area = 20u;
    g_cfg.min_side = 4u;
    g_cfg.max_side = 40u;
    g_cfg.maps = (1u << SBR_MAP_INTENSITY) | (1u << SBR_MAP_RED);
}

/* map_subsample coarsens one map only: the red map at 2 gives exactly the parts of a
   whole extraction at subsample 2, the intensity map those at full resolution. */
static void test_map_subsample_per_kind(void)
{
    static sbr_part_t ref[64];
    static sbr_part_t got[64];
    static sbr_part_t mixed[64];
    const sbr_image_t v = view();
    sbr_parts_config_t c;
    uint32_t n = 0u;
    uint32_t nm = 0u;
    uint32_t nr;
    uint32_t ng;
    uint32_t i;
    ring_on_intensity_and_red();
    c = g_cfg;
    c.map_subsample[SBR_MAP_RED] = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, mixed, 64u,
                                                    &nm, NULL));
    /* red parts: as with subsample 2 for every map */
    c = g_cfg;
    c.subsample = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, g_parts, 64u,
                                                    &n, NULL));
    nr = parts_of_map(g_parts, n, (uint8_t)SBR_MAP_RED, ref);
    ng = parts_of_map(mixed, nm, (uint8_t)SBR_MAP_RED, got);
    TEST_ASSERT_TRUE(nr >= 1u);
    TEST_ASSERT_EQUAL_UINT32(nr, ng);
    for (i = 0u; i < nr; i++) {
        TEST_ASSERT_EQUAL_UINT32(ref[i].bbox.x, got[i].bbox.x);
        TEST_ASSERT_EQUAL_UINT32(ref[i].bbox.width, got[i].bbox.width);
        TEST_ASSERT_EQUAL_UINT32(ref[i].area, got[i].area);
        TEST_ASSERT_EQUAL_FLOAT(ref[i].fd.cx, got[i].fd.cx);
        TEST_ASSERT_EQUAL_FLOAT(ref[i].fd.scale, got[i].fd.scale);
    }
    /* intensity parts: as at full resolution */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts,
                                                    64u, &n, NULL));
    nr = parts_of_map(g_parts, n, (uint8_t)SBR_MAP_INTENSITY, ref);
    ng = parts_of_map(mixed, nm, (uint8_t)SBR_MAP_INTENSITY, got);
    TEST_ASSERT_TRUE(nr >= 1u);
    TEST_ASSERT_EQUAL_UINT32(nr, ng);
    for (i = 0u; i < nr; i++) {
        TEST_ASSERT_EQUAL_UINT32(ref[i].area, got[i].area);
        TEST_ASSERT_EQUAL_FLOAT(ref[i].fd.cy, got[i].fd.cy);
    }
    /* bad factors: 0, above the map's largest, a product above it */
    c = g_cfg;
    c.map_subsample[SBR_MAP_BLUE] = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    c = g_cfg;
    c.map_subsample[SBR_MAP_YELLOW] = SBR_MAP_MAX_SUBSAMPLE + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    c = g_cfg;
    c.subsample = 4u;
    c.map_subsample[SBR_MAP_RED] = 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, g_parts,
                                                           64u, &n, NULL));
    /* a selected map below 3 x 3 at its own factor: SBR_ERR_SIZE, unselected ones do not
       matter */
    c = g_cfg;
    c.map_subsample[SBR_MAP_RED] = 8u;
    {
        sbr_image_t small = v;
        small.width = 20u; /* red map 2 x 2, intensity map 20 x 20 */
        small.height = 20u;
        TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_parts_extract(&small, &c, &g_fft, g_ws, sizeof g_ws,
                                                              g_parts, 64u, &n, NULL));
        TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_parts_workspace_size(&c, 20u, 20u));
        c.maps = 1u << SBR_MAP_INTENSITY;
        TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&small, &c, &g_fft, g_ws, sizeof g_ws,
                                                        g_parts, 64u, &n, NULL));
        TEST_ASSERT_TRUE(sbr_parts_workspace_size(&c, 20u, 20u) > 0u);
    }
}

/* map_polarity selects one map's polarities only: the red map's bright regions alone are
   exactly the bright red parts of a two-polarity extraction, no dark red part is left,
   the intensity map keeps both; a value above SBR_MSER_BOTH is refused. */
static void test_map_polarity_per_kind(void)
{
    static sbr_part_t both[64];
    static sbr_part_t one[64];
    const sbr_image_t v = view();
    sbr_parts_config_t c;
    uint32_t nb = 0u;
    uint32_t no = 0u;
    uint32_t bright = 0u;
    uint32_t dark_int = 0u;
    uint32_t i;
    uint32_t k = 0u;
    ring_on_intensity_and_red();
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, both, 64u,
                                                    &nb, NULL));
    c = g_cfg;
    c.map_polarity[SBR_MAP_RED] = (uint32_t)SBR_MSER_BRIGHT;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_config_check(&c));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, one, 64u,
                                                    &no, NULL));
    for (i = 0u; i < nb; i++) {
        const sbr_part_t *p = &both[i];
        if ((p->map == (uint8_t)SBR_MAP_RED) && (p->polarity == (uint8_t)SBR_MSER_DARK)) {
            continue; /* dropped by the selection */
        }
        bright += (p->map == (uint8_t)SBR_MAP_RED) ? 1u : 0u;
        dark_int += ((p->map == (uint8_t)SBR_MAP_INTENSITY) && (p->polarity == (uint8_t)SBR_MSER_DARK)) ? 1u : 0u;
        TEST_ASSERT_TRUE(k < no);
        TEST_ASSERT_EQUAL_UINT8(p->map, one[k].map);
        TEST_ASSERT_EQUAL_UINT8(p->polarity, one[k].polarity);
        TEST_ASSERT_EQUAL_UINT32(p->area, one[k].area);
        TEST_ASSERT_EQUAL_UINT32(p->bbox.x, one[k].bbox.x);
        TEST_ASSERT_EQUAL_FLOAT(p->fd.cx, one[k].fd.cx);
        k++;
    }
    TEST_ASSERT_EQUAL_UINT32(k, no);
    TEST_ASSERT_TRUE(bright >= 1u);   /* the red ring is bright in the red map */
    TEST_ASSERT_TRUE(dark_int >= 1u); /* the intensity map still gives its dark regions */
    TEST_ASSERT_TRUE(no < nb);        /* and the red map's dark ones are gone */
    c.map_polarity[SBR_MAP_BLUE] = (uint32_t)SBR_MSER_BOTH + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, one, 64u,
                                                           &no, NULL));
}

/* SBR_PARTS_WORKSPACE_SIZE is sbr_parts_workspace_size() as a constant expression: the
   defaults at full and at a quarter of the resolution (where the node bound exceeds the
   worst case), and a configuration with other bounds. */
static void test_workspace_macro_equals_function(void)
{
    static const size_t full = SBR_PARTS_WORKSPACE_SIZE(
        1360u, 800u, 5u, SBR_PARTS_DEFAULT_MAX_NODES, SBR_PARTS_DEFAULT_MAX_HEAP,
        SBR_PARTS_DEFAULT_MAX_REGIONS,
        SBR_PARTS_DEFAULT_MAX_SIDE, SBR_PARTS_DEFAULT_MAX_CONTOUR, SBR_PARTS_DEFAULT_FD_N);
    sbr_parts_config_t c;
    sbr_parts_config_default(&c);
    TEST_ASSERT_EQUAL_UINT32(5u, c.mser.delta);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)full, (uint32_t)sbr_parts_workspace_size(&c, 1360u, 800u));
    c.subsample = 4u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_PARTS_WORKSPACE_SIZE(340u, 200u, 5u, 68000u, SBR_PARTS_DEFAULT_MAX_HEAP, 2048u,
                                                                160u, 2048u, 128u),
                             (uint32_t)sbr_parts_workspace_size(&c, 1360u, 800u));
    c.subsample = 1u;
    c.map_subsample[SBR_MAP_INTENSITY] = 2u;
    c.maps = 1u << SBR_MAP_INTENSITY;
    c.mser.delta = 7u;
    c.mser.max_nodes = 0u;
    c.mser.max_heap = 5000u;
    c.max_regions = 100u;
    c.max_side = 64u;
    c.max_contour = 300u;
    c.fd_n = 64u;
    c.fd_m = 8u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_config_check(&c));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_PARTS_WORKSPACE_SIZE(321u, 99u, 7u, 0u, 5000u, 100u, 64u,
                                                                300u, 64u),
                             (uint32_t)sbr_parts_workspace_size(&c, 643u, 199u));
}

/* The map and MSER buffers follow the finest selected map: every selected kind at
   map_subsample 2 needs the workspace of subsample 2, less than full resolution, and
   gives the same parts as subsample 2 in exactly that many bytes. */
static void test_workspace_follows_finest_map(void)
{
    static sbr_part_t ref[64];
    const sbr_image_t v = view();
    sbr_parts_config_t c = g_cfg;
    sbr_parts_config_t c2 = g_cfg;
    size_t full;
    size_t half;
    uint32_t n = 0u;
    uint32_t nr = 0u;
    uint32_t i;
    draw_ring_sign(48.0f, 32.0f);
    g_cfg.mser.min_area = 20u;
    g_cfg.min_side = 4u;
    g_cfg.maps = (1u << SBR_MAP_INTENSITY) | (1u << SBR_MAP_RED);
    c = g_cfg;
    c.map_subsample[SBR_MAP_INTENSITY] = 2u;
    c.map_subsample[SBR_MAP_RED] = 2u;
    c2 = g_cfg;
    c2.subsample = 2u;
    full = sbr_parts_workspace_size(&g_cfg, W, H);
    half = sbr_parts_workspace_size(&c, W, H);
    TEST_ASSERT_TRUE(half > 0u);
    TEST_ASSERT_TRUE(half < full);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)sbr_parts_workspace_size(&c2, W, H), (uint32_t)half);
    /* one map at full resolution sizes it for full resolution again */
    c.map_subsample[SBR_MAP_RED] = 1u;
    TEST_ASSERT_EQUAL_UINT32((uint32_t)full, (uint32_t)sbr_parts_workspace_size(&c, W, H));
    c.map_subsample[SBR_MAP_RED] = 2u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c2, &g_fft, g_ws, half, ref, 64u, &nr,
                                                    NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_parts_extract(&v, &c, &g_fft, g_ws, half - 1u,
                                                               g_parts, 64u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c, &g_fft, g_ws, half, g_parts, 64u, &n,
                                                    NULL));
    TEST_ASSERT_TRUE(nr >= 2u);
    TEST_ASSERT_EQUAL_UINT32(nr, n);
    for (i = 0u; i < n; i++) {
        TEST_ASSERT_EQUAL_UINT32(ref[i].bbox.x, g_parts[i].bbox.x);
        TEST_ASSERT_EQUAL_UINT32(ref[i].bbox.height, g_parts[i].bbox.height);
        TEST_ASSERT_EQUAL_UINT32(ref[i].area, g_parts[i].area);
        TEST_ASSERT_EQUAL_FLOAT(ref[i].fd.cx, g_parts[i].fd.cx);
    }
}

/* parts.map_min_area: a smaller region bound for one map kind keeps that map's small
   regions; the other maps keep mser.min_area. */
static void test_map_min_area_per_kind(void)
{
    static sbr_part_t with[64];
    const sbr_image_t v = view();
    sbr_parts_config_t c;
    uint32_t x;
    uint32_t y;
    uint32_t n = 0u;
    uint32_t nw = 0u;
    uint32_t i;
    uint32_t small_blue = 0u;
    /* a dark blue disc of radius 5 (81 pixels) */
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            if (hypotf((float)x - 20.0f, (float)y - 20.0f) <= 5.0f) {
                paint(x, y, 30u, 40u, 150u);
            }
        }
    }
    g_cfg.maps = (1u << SBR_MAP_INTENSITY) | (1u << SBR_MAP_BLUE);
    g_cfg.mser.min_area = 120u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts,
                                                    64u, &n, NULL));
    c = g_cfg;
    c.map_min_area[SBR_MAP_BLUE] = 40u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, with, 64u,
                                                    &nw, NULL));
    /* below mser.min_area: no part of either map */
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* the blue map's own bound keeps the disc there, and only there */
    for (i = 0u; i < nw; i++) {
        TEST_ASSERT_EQUAL_UINT8((uint8_t)SBR_MAP_BLUE, with[i].map);
        if ((with[i].area >= 60u) && (with[i].area <= 100u) &&
            (fabsf(with[i].fd.cx - 20.0f) < 1.0f) && (fabsf(with[i].fd.cy - 20.0f) < 1.0f)) {
            small_blue++;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(1u, small_blue);
    /* bounds: at most mser.max_area */
    c.map_min_area[SBR_MAP_BLUE] = c.mser.max_area;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_config_check(&c));
    c.map_min_area[SBR_MAP_RED] = c.mser.max_area + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, g_parts,
                                                           64u, &n, NULL));
}

static void test_parts_capacity_and_bad_input(void)
{
    sbr_image_t v = view();
    uint32_t n = 0u;
    sbr_parts_config_t c;
    sbr_fft_t f64;
    draw_ring_sign(30.0f, 32.0f);
    draw_triangle(70.0f, 32.0f);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws,
                                                              g_parts, 1u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_parts_extract(NULL, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, 100u, g_parts, 64u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          sbr_parts_extract(&v, &g_cfg, &g_fft, (uint8_t *)g_ws + 4, sizeof g_ws - 8u, g_parts, 64u, &n, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_64(&f64));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_parts_extract(&v, &g_cfg, &f64, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    c = g_cfg;
    c.fd_m = 64u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    c = g_cfg;
    c.maps = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    c = g_cfg;
    c.min_fill = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_config_check(&c));
    c = g_cfg;
    c.subsample = 8u;
    v.width = 16u; /* a 2 x 2 map after subsampling */
    v.height = 16u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, sbr_parts_extract(&v, &c, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    v = view();
    /* a grey frame can only give intensity parts */
    v.format = SBR_PIXEL_GRAY8;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_parts_workspace_size(&g_cfg, 2u, 5u));
}

/* parts.h: every documented status, in one table. */
static void test_parts_h_statuses(void)
{
    status_table_t t;
    const sbr_image_t v = view();
    sbr_image_t small = view();
    sbr_image_t grey = view();
    sbr_parts_config_t bad = g_cfg;
    sbr_parts_config_t coarse = g_cfg;
    sbr_fft_t f64;
    sbr_fft_t blank;
    uint32_t n = 0u;
    draw_ring_sign(30.0f, 32.0f);
    draw_triangle(70.0f, 32.0f);
    memset(&blank, 0, sizeof blank);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_fft_init_64(&f64));
    bad.maps = 0u;
    coarse.subsample = 8u;
    small.width = 16u;
    small.height = 16u;
    grey.format = SBR_PIXEL_GRAY8;
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_parts_config_check(&g_cfg));
    ROW(&t, SBR_ERR_NULL, sbr_parts_config_check(NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_parts_config_check(&bad));
    ROW(&t, SBR_OK, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_parts_extract(&v, &g_cfg, NULL, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, NULL, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_parts_extract(&v, &bad, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_RANGE, sbr_parts_extract(&grey, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_SIZE, sbr_parts_extract(&small, &coarse, &g_fft, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_STATE, sbr_parts_extract(&v, &g_cfg, &f64, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_STATE, sbr_parts_extract(&v, &g_cfg, &blank, g_ws, sizeof g_ws, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_WORKSPACE, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, 100u, g_parts, 64u, &n, NULL));
    ROW(&t, SBR_ERR_CAPACITY, sbr_parts_extract(&v, &g_cfg, &g_fft, g_ws, sizeof g_ws, g_parts, 1u, &n, NULL));
    status_table_check(&t);
    TEST_ASSERT_EQUAL_size_t(0u, sbr_parts_workspace_size(&bad, W, H));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ring_sign_and_triangle);
    RUN_TEST(test_subsample_keeps_input_coordinates);
    RUN_TEST(test_map_subsample_per_kind);
    RUN_TEST(test_map_min_area_per_kind);
    RUN_TEST(test_map_polarity_per_kind);
    RUN_TEST(test_workspace_follows_finest_map);
    RUN_TEST(test_workspace_macro_equals_function);
    RUN_TEST(test_parts_capacity_and_bad_input);
    RUN_TEST(test_parts_h_statuses);
    return UNITY_END();
}
