/* SPDX-License-Identifier: MIT */
/* Unity tests of MSER (include/sbr/mser.h). The maps it runs on: test_map.c. */
#include "unity.h"
#include "sbr/mser.h"
#include "test_support.h"


#include <string.h>

#define W 32u
#define H 32u
#define WS_BYTES SBR_MSER_WORKSPACE_SIZE(W, H, SBR_MSER_MAX_DELTA, SBR_MSER_WORST_NODES(W, H), 0u)

static uint8_t g_map[H][W];
static uint32_t g_ws[(WS_BYTES / 4u) + 1u];
static uint32_t g_mws[(SBR_MSER_MASK_WORKSPACE_SIZE(W, H) / 4u) + 1u];
static uint8_t g_mask[W * H + TSUP_GUARD_BYTES];
static sbr_mser_region_t g_reg[64];
static sbr_mser_config_t g_cfg;

void setUp(void)
{
    memset(g_map, 200, sizeof g_map);
    sbr_mser_config_default(&g_cfg);
}
void tearDown(void) {}

static sbr_image_t map_view(void)
{
    sbr_image_t v;
    v.width = W;
    v.height = H;
    v.stride = W;
    v.format = SBR_PIXEL_GRAY8;
    v.data = &g_map[0][0];
    return v;
}

static void fill(uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, uint8_t v)
{
    uint32_t x;
    uint32_t y;
    for (y = y0; y < y0 + h; y++) {
        for (x = x0; x < x0 + w; x++) {
            g_map[y][x] = v;
        }
    }
}

static sbr_status_t detect(uint32_t *n)
{
    const sbr_image_t v = map_view();
    return sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, n);
}

/* Rebuild a region's mask and return its pixel count (checks the status too). */
static uint32_t mask_of(const sbr_mser_region_t *r)
{
    const sbr_image_t v = map_view();
    uint32_t i;
    uint32_t on = 0u;
    tsup_guard_fill(&g_mask[r->bbox.width * r->bbox.height], TSUP_GUARD_BYTES);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_mser_region_mask(&v, r, g_mws, sizeof g_mws, g_mask,
                                                            r->bbox.width,
                                                            r->bbox.width * r->bbox.height));
    TEST_ASSERT_TRUE(tsup_guard_intact(&g_mask[r->bbox.width * r->bbox.height], TSUP_GUARD_BYTES));
    for (i = 0u; i < r->bbox.width * r->bbox.height; i++) {
        on += (g_mask[i] != 0u) ? 1u : 0u;
    }
    return on;
}

/* ---- MSER ----------------------------------------------------------------------------- */

/* A dark 10x10 square (value 50) on a 200 background: dark regions are the square at level
   50 and the whole interior (30 x 30, the map's outer ring is never part of a region). */
static void test_mser_dark_square(void)
{
    uint32_t n = 0u;
    fill(5u, 7u, 10u, 10u, 50u);
    g_cfg.polarity = SBR_MSER_DARK;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(100u, g_reg[0].area);
    TEST_ASSERT_EQUAL_UINT8(50u, g_reg[0].level);
    TEST_ASSERT_EQUAL_UINT8(SBR_MSER_DARK, g_reg[0].polarity);
    TEST_ASSERT_EQUAL_UINT32(5u, g_reg[0].bbox.x);
    TEST_ASSERT_EQUAL_UINT32(7u, g_reg[0].bbox.y);
    TEST_ASSERT_EQUAL_UINT32(10u, g_reg[0].bbox.width);
    TEST_ASSERT_EQUAL_UINT32(10u, g_reg[0].bbox.height);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, g_reg[0].variation);
    TEST_ASSERT_EQUAL_UINT32(100u, mask_of(&g_reg[0]));
    TEST_ASSERT_EQUAL_UINT32(900u, g_reg[1].area);
    TEST_ASSERT_EQUAL_UINT32(1u, g_reg[1].bbox.x);
    TEST_ASSERT_EQUAL_UINT32(30u, g_reg[1].bbox.width);
    TEST_ASSERT_EQUAL_UINT8(200u, g_reg[1].level);
    /* max_area removes the interior */
    g_cfg.max_area = 899u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(100u, g_reg[0].area);
    /* min_area above the square leaves only the interior */
    g_cfg.max_area = 14400u;
    g_cfg.min_area = 101u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT32(900u, g_reg[0].area);
}

/* A sign-like pattern: a 12x12 square of value 50 with a 6x6 centre of value 120.
   Dark: the ring at level 50 (144 - 36 = 108 px, with a hole), the full square at 120 and
   the interior. Bright (inverted): the background outside the square (900 - 144 = 756 px,
   level 200); the interior differs from it by 16% of its area, below min_diversity 0.2,
   so one of the pair goes (both have variation 0: the larger). The 36-px centre is below
   min_area 60 unless min_area is lowered. */
static void test_mser_nested_regions_both_polarities(void)
{
    uint32_t n = 0u;
    uint32_t i;
    uint32_t dark = 0u;
    fill(8u, 8u, 12u, 12u, 50u);
    fill(11u, 11u, 6u, 6u, 120u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(4u, n);
    TEST_ASSERT_EQUAL_UINT32(108u, g_reg[0].area);
    TEST_ASSERT_EQUAL_UINT8(50u, g_reg[0].level);
    TEST_ASSERT_EQUAL_UINT32(108u, mask_of(&g_reg[0]));
    /* the hole: the centre pixel of the square is outside the ring's mask */
    TEST_ASSERT_EQUAL_UINT8(0u, g_mask[(14u - g_reg[0].bbox.y) * 12u + (14u - g_reg[0].bbox.x)]);
    TEST_ASSERT_EQUAL_UINT32(144u, g_reg[1].area);
    TEST_ASSERT_EQUAL_UINT8(120u, g_reg[1].level);
    TEST_ASSERT_EQUAL_UINT32(144u, mask_of(&g_reg[1]));
    TEST_ASSERT_EQUAL_UINT32(900u, g_reg[2].area);
    TEST_ASSERT_EQUAL_UINT8(SBR_MSER_BRIGHT, g_reg[3].polarity);
    TEST_ASSERT_EQUAL_UINT32(756u, g_reg[3].area);
    TEST_ASSERT_EQUAL_UINT8(200u, g_reg[3].level);
    TEST_ASSERT_EQUAL_UINT32(756u, mask_of(&g_reg[3]));
    /* without min_diversity both bright regions stay; a lower min_area adds the centre */
    g_cfg.min_diversity = 0.0f;
    g_cfg.min_area = 30u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    for (i = 0u; i < n; i++) {
        dark += (g_reg[i].polarity == SBR_MSER_DARK) ? 1u : 0u;
    }
    TEST_ASSERT_EQUAL_UINT32(3u, dark);
    TEST_ASSERT_EQUAL_UINT32(6u, n);
    /* completion order: the background (reached first) before the centre */
    TEST_ASSERT_EQUAL_UINT32(756u, g_reg[3].area);
    TEST_ASSERT_EQUAL_UINT32(36u, g_reg[4].area);
    TEST_ASSERT_EQUAL_UINT8(120u, g_reg[4].level);
    TEST_ASSERT_EQUAL_UINT8(SBR_MSER_BRIGHT, g_reg[4].polarity);
    TEST_ASSERT_EQUAL_UINT32(900u, g_reg[5].area);
}

/* A ramp of one grey level per column has no stable region: the region at level t has
   30 t pixels, so variation = (30 (t + 5) - 30 (t - 5)) / (30 t) = 10 / t >= 0.33 for every
   t <= 30 (and the same for the bright side). */
static void test_mser_ramp_is_not_stable(void)
{
    uint32_t x;
    uint32_t y;
    uint32_t n = 1u;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            g_map[y][x] = (uint8_t)x;
        }
    }
    g_cfg.max_area = 500u; /* excludes the interior as a whole */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
}

/* On random blobs every region is extremal: inside <= level (dark), every 4-neighbour
   outside the mask and inside the map's interior > level; the rebuilt area equals the
   reported one; and the result does not depend on the workspace contents. */
static void test_mser_random_regions_are_extremal(void)
{
    tsup_rng_t rng = {12345u};
    uint32_t n = 0u;
    uint32_t n2 = 0u;
    uint32_t i;
    uint32_t k;
    static sbr_mser_region_t first[64];
    for (k = 0u; k < 12u; k++) {
        const uint32_t bx = (uint32_t)tsup_uniform(&rng, 1.0f, 24.0f);
        const uint32_t by = (uint32_t)tsup_uniform(&rng, 1.0f, 24.0f);
        const uint32_t bw = (uint32_t)tsup_uniform(&rng, 3.0f, 9.0f);
        const uint32_t bh = (uint32_t)tsup_uniform(&rng, 3.0f, 9.0f);
        fill(bx, by, bw, bh, (uint8_t)tsup_uniform(&rng, 0.0f, 255.0f));
    }
    g_cfg.min_area = 8u;
    g_cfg.max_variation = 1.0f;
    memset(g_ws, 0x00, sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_TRUE(n > 3u);
    memcpy(first, g_reg, sizeof first);
    memset(g_ws, 0xFF, sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n2));
    TEST_ASSERT_EQUAL_UINT32(n, n2);
    TEST_ASSERT_EQUAL_MEMORY(first, g_reg, n * sizeof(sbr_mser_region_t));
    for (i = 0u; i < n; i++) {
        const sbr_mser_region_t *r = &g_reg[i];
        const int dark = (r->polarity == SBR_MSER_DARK) ? 1 : 0;
        uint32_t x;
        uint32_t y;
        TEST_ASSERT_EQUAL_UINT32(r->area, mask_of(r));
        {
            /* the box is tight: the region touches its first and last row and column */
            uint32_t top = 0u;
            uint32_t bottom = 0u;
            uint32_t left = 0u;
            uint32_t right = 0u;
            for (x = 0u; x < r->bbox.width; x++) {
                top += g_mask[x];
                bottom += g_mask[((r->bbox.height - 1u) * r->bbox.width) + x];
            }
            for (y = 0u; y < r->bbox.height; y++) {
                left += g_mask[y * r->bbox.width];
                right += g_mask[(y * r->bbox.width) + r->bbox.width - 1u];
            }
            TEST_ASSERT_TRUE((top > 0u) && (bottom > 0u) && (left > 0u) && (right > 0u));
        }
        for (y = 1u; y < H - 1u; y++) {
            for (x = 1u; x < W - 1u; x++) {
                const int inbox = (x >= r->bbox.x) && (y >= r->bbox.y) &&
                                  (x < r->bbox.x + r->bbox.width) && (y < r->bbox.y + r->bbox.height);
                const int in = inbox && g_mask[(y - r->bbox.y) * r->bbox.width + (x - r->bbox.x)];
                const uint8_t v = g_map[y][x];
                const int pass = dark ? (v <= r->level) : (v >= r->level);
                if (in) {
                    TEST_ASSERT_TRUE(pass);
                } else if (pass) {
                    /* a passing pixel outside the region must not touch it */
                    const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
                    uint32_t j;
                    for (j = 0u; j < 4u; j++) {
                        const uint32_t nx = (uint32_t)((int)x + d[j][0]);
                        const uint32_t ny = (uint32_t)((int)y + d[j][1]);
                        const int ninbox = (nx >= r->bbox.x) && (ny >= r->bbox.y) &&
                                           (nx < r->bbox.x + r->bbox.width) &&
                                           (ny < r->bbox.y + r->bbox.height);
                        TEST_ASSERT_FALSE(ninbox && g_mask[(ny - r->bbox.y) * r->bbox.width +
                                                           (nx - r->bbox.x)]);
                    }
                }
            }
        }
    }
}

/* Level limits: pixels beyond a limit are not flooded, regions within delta of it are not
   reported, and the regions well inside are those of the unrestricted flood. Two bright
   squares (220) apart from each other (two floods of the walled map), a faint one (140)
   and a dark one (40) on a 128 background. */
static void test_mser_level_limits(void)
{
    static sbr_mser_region_t full[64];
    uint32_t n = 0u;
    uint32_t nfull = 0u;
    uint32_t i;
    uint32_t kept = 0u;
    memset(g_map, 128, sizeof g_map);
    fill(3u, 3u, 8u, 8u, 220u);
    fill(18u, 18u, 8u, 8u, 220u);
    fill(3u, 18u, 8u, 8u, 140u);
    fill(18u, 3u, 8u, 8u, 40u);
    TEST_ASSERT_EQUAL_UINT32(255u, g_cfg.dark_max);
    TEST_ASSERT_EQUAL_UINT32(0u, g_cfg.bright_min);
    g_cfg.min_area = 30u;
    g_cfg.polarity = SBR_MSER_BRIGHT;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&nfull));
    memcpy(full, g_reg, sizeof full);
    /* unrestricted: the three squares (and the background's bright regions) */
    for (i = 0u; i < nfull; i++) {
        kept += ((full[i].area == 64u) && (full[i].level >= 140u)) ? 1u : 0u;
    }
    TEST_ASSERT_EQUAL_UINT32(3u, kept);
    /* from 150 up: the two 220 squares exactly as unrestricted, nothing else */
    g_cfg.bright_min = 150u;
    memset(g_ws, 0xA5, sizeof g_ws);
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    for (i = 0u; i < n; i++) {
        uint32_t j;
        uint32_t same = 0u;
        TEST_ASSERT_EQUAL_UINT8(220u, g_reg[i].level);
        TEST_ASSERT_EQUAL_UINT32(64u, mask_of(&g_reg[i]));
        for (j = 0u; j < nfull; j++) {
            /* every field but the seed (any pixel of the region: where its flood began) */
            same += ((full[j].bbox.x == g_reg[i].bbox.x) && (full[j].bbox.y == g_reg[i].bbox.y) &&
                     (full[j].bbox.width == g_reg[i].bbox.width) &&
                     (full[j].bbox.height == g_reg[i].bbox.height) && (full[j].area == g_reg[i].area) &&
                     (full[j].variation == g_reg[i].variation) && (full[j].level == g_reg[i].level) &&
                     (full[j].polarity == g_reg[i].polarity)) ? 1u : 0u;
        }
        TEST_ASSERT_EQUAL_UINT32(1u, same);
    }
    TEST_ASSERT_TRUE(g_reg[0].bbox.x != g_reg[1].bbox.x);
    /* a region within delta (5) of the limit is not reported: 220 < 216 + 5 */
    g_cfg.bright_min = 216u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    g_cfg.bright_min = 215u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    /* everything a wall: no region, no error */
    g_cfg.bright_min = 255u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* dark regions up to 100: the dark square alone; up to 44 it is within delta */
    g_cfg.bright_min = 0u;
    g_cfg.polarity = SBR_MSER_DARK;
    g_cfg.dark_max = 100u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(1u, n);
    TEST_ASSERT_EQUAL_UINT8(40u, g_reg[0].level);
    TEST_ASSERT_EQUAL_UINT32(18u, g_reg[0].bbox.x);
    TEST_ASSERT_EQUAL_UINT32(64u, g_reg[0].area);
    g_cfg.dark_max = 44u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    /* both polarities, each with its limit (the bright pass counts its own levels) */
    g_cfg.polarity = SBR_MSER_BOTH;
    g_cfg.dark_max = 100u;
    g_cfg.bright_min = 150u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(3u, n);
    g_cfg.dark_max = 255u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_TRUE(n > 3u);
    /* out of range */
    g_cfg.dark_max = 256u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&g_cfg));
    g_cfg.dark_max = 255u;
    g_cfg.bright_min = 256u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&g_cfg));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)detect(&n));
}

static void test_mser_capacity_and_node_bound(void)
{
    uint32_t n = 0u;
    const sbr_image_t v = map_view();
    fill(8u, 8u, 12u, 12u, 50u);
    fill(11u, 11u, 6u, 6u, 120u);
    /* 4 regions, room for 2 */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY,
                          (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 2u, &n));
    TEST_ASSERT_EQUAL_UINT32(2u, n);
    TEST_ASSERT_EQUAL_UINT32(108u, g_reg[0].area);
    /* a node bound of 1 cannot hold the tree: distinct status, smaller workspace */
    g_cfg.max_nodes = 1u;
    TEST_ASSERT_TRUE(sbr_mser_workspace_size(&g_cfg, W, H) <
                     sbr_mser_workspace_size(&(sbr_mser_config_t){5u, 60u, 14400u, 0.25f, 0.2f, 3u, 0u, 255u, 0u, 0u}, W, H));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, (int)detect(&n));
    /* the size macro and the size query agree */
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_MSER_WORKSPACE_SIZE(W, H, 5u, 1u, 0u),
                             (uint32_t)sbr_mser_workspace_size(&g_cfg, W, H));
    /* a sufficient bound gives the full result */
    g_cfg.max_nodes = 16u;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    TEST_ASSERT_EQUAL_UINT32(4u, n);
}

/* The boundary heap's bound (config.max_heap): a map whose flood keeps many pixels
   waiting (a snake of level 10 through walls of 200: every wall pixel beside the snake
   waits until the whole snake is flooded), with dark and bright squares below it. A bound
   above the most pixels waiting gives the worst case's regions exactly, in less memory;
   a bound far below it completes with SBR_ERR_CAPACITY. */
#define HW 256u
#define HW_NODES 4000u
static uint8_t g_big[HW][HW];
static uint32_t g_bws[(SBR_MSER_WORKSPACE_SIZE(HW, HW, 5u, HW_NODES, 0u) / 4u) + 1u];
static sbr_mser_region_t g_breg[2][128];

static sbr_status_t big_detect(uint32_t max_heap, uint32_t k, uint32_t *n)
{
    const sbr_image_t v = {HW, HW, HW, SBR_PIXEL_GRAY8, &g_big[0][0]};
    g_cfg.max_nodes = HW_NODES;
    g_cfg.max_heap = max_heap;
    memset(g_bws, 0xA5, sizeof g_bws); /* no state may survive from the previous call */
    return sbr_mser_detect(&v, &g_cfg, g_bws, sbr_mser_workspace_size(&g_cfg, HW, HW), g_breg[k],
                           128u, n);
}

static void test_mser_heap_bound(void)
{
    uint32_t nfull = 0u;
    uint32_t n = 0u;
    uint32_t x;
    uint32_t y;
    size_t worst;
    memset(g_big, 200, sizeof g_big);
    for (y = 1u; y < 160u; y += 4u) {
        const uint32_t link = (((y / 4u) % 2u) == 0u) ? (HW - 2u) : 1u;
        for (x = 1u; x < (HW - 1u); x++) {
            g_big[y][x] = 10u;
        }
        for (x = 1u; (x < 4u) && ((y + x) < 160u); x++) {
            g_big[y + x][link] = 10u;
        }
    }
    for (x = 0u; x < 6u; x++) {
        const uint32_t x0 = 8u + (x * 40u);
        const uint8_t level = (uint8_t)(((x % 2u) == 0u) ? 60u : 240u);
        for (y = 180u; y < (192u + (x * 4u)); y++) {
            memset(&g_big[y][x0], level, 12u + (x * 4u));
        }
    }
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)big_detect(0u, 0u, &nfull));
    TEST_ASSERT_TRUE(nfull >= 6u);
    worst = sbr_mser_workspace_size(&g_cfg, HW, HW);
    /* 30,000 of the 64,516 interior pixels: more than ever wait at once here */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)big_detect(30000u, 1u, &n));
    TEST_ASSERT_EQUAL_UINT32(nfull, n);
    TEST_ASSERT_EQUAL_MEMORY(g_breg[0], g_breg[1], nfull * sizeof(sbr_mser_region_t));
    TEST_ASSERT_TRUE(sbr_mser_workspace_size(&g_cfg, HW, HW) < worst);
    TEST_ASSERT_EQUAL_UINT32((uint32_t)SBR_MSER_WORKSPACE_SIZE(HW, HW, 5u, HW_NODES, 30000u),
                             (uint32_t)sbr_mser_workspace_size(&g_cfg, HW, HW));
    /* a bound of one pixel (the heap's least: a chunk per level) cannot hold the snake's
       walls: the call completes and says so */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, (int)big_detect(1u, 1u, &n));
    TEST_ASSERT_TRUE(n <= 128u);
    g_cfg.max_heap = 0u;
    g_cfg.max_nodes = 0u;
}

/* The extremal component of a region's level around its seed (4-connected, the map's
   interior: the border is never flooded), counted by a plain fill: the definition. */
static uint32_t g_fill[HW * HW];
static uint8_t g_seen[HW][HW];
static uint32_t component_area(const sbr_mser_region_t *r)
{
    static const int32_t dx[4] = {1, -1, 0, 0};
    static const int32_t dy[4] = {0, 0, 1, -1};
    uint32_t n = 0u;
    uint32_t h = 0u;
    memset(g_seen, 0, sizeof g_seen);
    g_fill[n++] = ((uint32_t)r->seed_y * HW) + r->seed_x;
    g_seen[r->seed_y][r->seed_x] = 1u;
    while (h < n) {
        const uint32_t p = g_fill[h++];
        uint32_t k;
        for (k = 0u; k < 4u; k++) {
            const int32_t x = (int32_t)(p % HW) + dx[k];
            const int32_t y = (int32_t)(p / HW) + dy[k];
            if ((x >= 1) && (y >= 1) && (x < (int32_t)HW - 1) && (y < (int32_t)HW - 1) &&
                (g_seen[y][x] == 0u)) {
                const uint8_t v = g_big[y][x];
                if ((r->polarity == (uint8_t)SBR_MSER_DARK) ? (v <= r->level) : (v >= r->level)) {
                    g_seen[y][x] = 1u;
                    g_fill[n++] = ((uint32_t)y * HW) + (uint32_t)x;
                }
            }
        }
    }
    return n;
}

/* A heap bound below what a textured map needs (waves plus noise): where the bound is
   reached the flood stops, the call says so, writes nothing past the workspace it was
   given, and every region it reports is part of its extremal component (all of it when
   the call completes). Before the flood stopped, a lost heap entry could leave the
   component stack out of level order: regions larger than their component, and on a
   GTSDB frame a crash. Bounds from one chunk per level up to the worst case. */
static void test_mser_heap_bound_texture(void)
{
    static const uint32_t bounds[5] = {1u, 40u, 300u, 3000u, 0u};
    const sbr_image_t v = {HW, HW, HW, SBR_PIXEL_GRAY8, &g_big[0][0]};
    uint32_t seed = 7920u;
    uint32_t x;
    uint32_t y;
    uint32_t b;
    for (y = 0u; y < HW; y++) {
        for (x = 0u; x < HW; x++) {
            /* triangle waves across x and y, and up to 127 levels of noise */
            const uint32_t tx = (x * 3u) % 200u;
            const uint32_t ty = ((y * 5u) + x) % 160u;
            const uint32_t wx = (tx < 100u) ? tx : (200u - tx);
            const uint32_t wy = (ty < 80u) ? ty : (160u - ty);
            seed = (seed * 1664525u) + 1013904223u;
            g_big[y][x] = (uint8_t)(((wx + wy) + ((seed >> 24) & 127u)) & 255u);
        }
    }
    g_cfg.polarity = SBR_MSER_BOTH;
    for (b = 0u; b < 5u; b++) {
        const uint8_t *bytes = (const uint8_t *)(const void *)g_bws;
        uint32_t n = 0u;
        uint32_t i;
        size_t need;
        sbr_status_t st;
        g_cfg.max_nodes = HW_NODES;
        g_cfg.max_heap = bounds[b];
        need = sbr_mser_workspace_size(&g_cfg, HW, HW);
        TEST_ASSERT_TRUE((need > 0u) && (need <= sizeof g_bws));
        memset(g_bws, 0xA5, sizeof g_bws);
        st = sbr_mser_detect(&v, &g_cfg, g_bws, need, g_breg[0], 128u, &n);
        if (bounds[b] == 0u) {
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)st);
            TEST_ASSERT_TRUE(n >= 10u);
        } else if (bounds[b] <= 300u) {
            TEST_ASSERT_EQUAL_INT(SBR_ERR_CAPACITY, (int)st);
        } else {
            TEST_ASSERT_TRUE((st == SBR_OK) || (st == SBR_ERR_CAPACITY));
        }
        TEST_ASSERT_TRUE(n <= 128u);
        for (i = need; i < sizeof g_bws; i++) {
            TEST_ASSERT_EQUAL_HEX8(0xA5, bytes[i]);
        }
        for (i = 0u; i < n; i++) {
            const sbr_mser_region_t *r = &g_breg[0][i];
            const uint32_t whole = component_area(r);
            TEST_ASSERT_TRUE(((r->bbox.x + r->bbox.width) <= HW) && ((r->bbox.y + r->bbox.height) <= HW));
            TEST_ASSERT_TRUE(r->area >= g_cfg.min_area);
            TEST_ASSERT_TRUE(r->area <= whole);
            if (st == SBR_OK) {
                TEST_ASSERT_EQUAL_UINT32(whole, r->area);
            }
        }
    }
    g_cfg.max_heap = 0u;
    g_cfg.max_nodes = 0u;
}

/* The part stage's entry (sbr_mser_map_slot(), sbr_mser_detect_in_place()): the map written into the workspace's
   slot gives sbr_mser_detect()'s regions of that map, and afterwards the same map, byte
   for byte, at the start of the pixel words; for each polarity and with level limits
   (walls keep their level for the next pass); on the whole 256 x 256 map and on a 251 x
   250 part of it (the level loops work in blocks of 16 pixels: rows and pixel counts that
   are not a multiple of it leave pixels to their one-by-one tails). */
static void test_mser_in_place(void)
{
    static const uint32_t setups[4][3] = {
        {SBR_MSER_BOTH, 255u, 0u}, {SBR_MSER_DARK, 255u, 0u}, {SBR_MSER_BRIGHT, 255u, 100u},
        {SBR_MSER_BOTH, 150u, 100u}};
    static const uint32_t sizes[2][2] = {{HW, HW}, {HW - 5u, HW - 6u}};
    uint32_t k;
    uint32_t z;
    test_mser_heap_bound(); /* fills g_big: the snake and the squares */
    for (z = 0u; z < 2u; z++) {
        const uint32_t w = sizes[z][0];
        const uint32_t h = sizes[z][1];
        const sbr_image_t v = {w, h, HW, SBR_PIXEL_GRAY8, &g_big[0][0]};
        for (k = 0u; k < 4u; k++) {
            sbr_image_t back;
            uint8_t *slot;
            uint32_t n = 0u;
            uint32_t m = 0u;
            uint32_t y;
            size_t need;
            g_cfg.polarity = setups[k][0];
            g_cfg.dark_max = setups[k][1];
            g_cfg.bright_min = setups[k][2];
            g_cfg.max_nodes = HW_NODES;
            need = sbr_mser_workspace_size(&g_cfg, w, h);
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_mser_detect(&v, &g_cfg, g_bws, need, g_breg[0], 128u, &n));
            TEST_ASSERT_TRUE(n >= 3u);
            memset(g_bws, 0xA5, sizeof g_bws);
            slot = sbr_mser_map_slot(&g_cfg, w, h, g_bws, need);
            TEST_ASSERT_NOT_NULL(slot);
            for (y = 0u; y < h; y++) {
                memcpy(&slot[(size_t)y * w], g_big[y], w);
            }
            TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_mser_detect_in_place(w, h, &g_cfg, g_bws, need,
                                                                           g_breg[1], 128u, &m, &back));
            TEST_ASSERT_EQUAL_UINT32(n, m);
            TEST_ASSERT_EQUAL_MEMORY(g_breg[0], g_breg[1], n * sizeof(sbr_mser_region_t));
            TEST_ASSERT_EQUAL_UINT32(w, back.width);
            TEST_ASSERT_EQUAL_UINT32(w, back.stride);
            for (y = 0u; y < h; y++) {
                TEST_ASSERT_EQUAL_MEMORY(g_big[y], &back.data[(size_t)y * w], w);
            }
        }
    }
    g_cfg.max_nodes = 0u;
}

static void test_mser_bad_input(void)
{
    uint32_t n = 7u;
    sbr_image_t v = map_view();
    sbr_mser_config_t c;
    static const uint8_t small[4] = {0, 0, 0, 0};
    sbr_image_t tiny = {2u, 2u, 2u, SBR_PIXEL_GRAY8, small};
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_detect(NULL, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_detect(&v, NULL, g_ws, sizeof g_ws, g_reg, 64u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, NULL, 64u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, NULL));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, (int)sbr_mser_detect(&tiny, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, &n));
    TEST_ASSERT_EQUAL_UINT32(0u, n);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_SIZE, (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 0u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, (int)sbr_mser_detect(&v, &g_cfg, NULL, sizeof g_ws, g_reg, 64u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          (int)sbr_mser_detect(&v, &g_cfg, g_ws, sbr_mser_workspace_size(&g_cfg, W, H) - 1u,
                                               g_reg, 64u, &n));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE,
                          (int)sbr_mser_detect(&v, &g_cfg, (uint8_t *)g_ws + 1, sizeof g_ws - 4u, g_reg, 64u, &n));
    v.format = SBR_PIXEL_RGB888;
    v.stride = 3u * W;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, &n));
    v = map_view();
    v.stride = W - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_mser_detect(&v, &g_cfg, g_ws, sizeof g_ws, g_reg, 64u, &n));
    /* configuration ranges */
    sbr_mser_config_default(&c);
    c.delta = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    c.delta = SBR_MSER_MAX_DELTA + 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.min_area = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.max_area = c.min_area - 1u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.max_variation = 1e30f; /* mser.h: > 0 and at most 1e30 */
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)sbr_mser_config_check(&c));
    c.max_variation = 1e31f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.max_variation = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    c.max_variation = 0.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.min_diversity = 1.0f;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    c.min_diversity = NAN;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    sbr_mser_config_default(&c);
    c.polarity = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    c.polarity = 4u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_config_check(&c));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_mser_workspace_size(&c, W, H));
    TEST_ASSERT_EQUAL_UINT32(0u, (uint32_t)sbr_mser_workspace_size(&g_cfg, 2u, H));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_config_check(NULL));
}

static void test_mser_region_mask_rejects_bad_regions(void)
{
    uint32_t n = 0u;
    sbr_mser_region_t r;
    const sbr_image_t v = map_view();
    fill(5u, 7u, 10u, 10u, 50u);
    g_cfg.polarity = SBR_MSER_DARK;
    TEST_ASSERT_EQUAL_INT(SBR_OK, (int)detect(&n));
    r = g_reg[0];
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, (int)sbr_mser_region_mask(&v, NULL, g_mws, sizeof g_mws, g_mask, 10u, 100u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 9u, 100u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_ALIGN, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 99u));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_WORKSPACE, (int)sbr_mser_region_mask(&v, &r, g_mws, 399u, g_mask, 10u, 100u));
    r.bbox.x = 0u; /* the outer ring is never part of a region */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 100u));
    r = g_reg[0];
    r.bbox.width = 30u; /* leaves the interior */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 30u, 900u));
    r = g_reg[0];
    r.seed_x = 20u; /* seed outside the box */
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 100u));
    r = g_reg[0];
    r.polarity = 0u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 100u));
    /* the map changed since detection: one pixel of the square brightened */
    r = g_reg[0];
    g_map[10][10] = 250u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 100u));
    /* the seed itself no longer passes */
    g_map[r.seed_y][r.seed_x] = 251u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_CORRUPT, (int)sbr_mser_region_mask(&v, &r, g_mws, sizeof g_mws, g_mask, 10u, 100u));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mser_dark_square);
    RUN_TEST(test_mser_nested_regions_both_polarities);
    RUN_TEST(test_mser_ramp_is_not_stable);
    RUN_TEST(test_mser_random_regions_are_extremal);
    RUN_TEST(test_mser_level_limits);
    RUN_TEST(test_mser_capacity_and_node_bound);
    RUN_TEST(test_mser_heap_bound);
    RUN_TEST(test_mser_heap_bound_texture);
    RUN_TEST(test_mser_in_place);
    RUN_TEST(test_mser_bad_input);
    RUN_TEST(test_mser_region_mask_rejects_bad_regions);
    return UNITY_END();
}
