/* SPDX-License-Identifier: MIT */
/* Unity tests of the core's private helpers (lib/common/sbr_util.h, sort.c): byte-range
   overlap, alignment, the fixed-order dot product, the polynomial atan2, min/max/clamp
   (NaN and infinities included), box IoU, microseconds as seconds, and the heap sort the
   recogniser orders its votes and hypotheses with. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "../lib/common/sbr_util.h" /* private to the core */
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void test_overlap_and_alignment(void)
{
    static uint8_t buf[64];
    TEST_ASSERT_EQUAL_INT(1, sbr_util_overlap(buf, 8u, &buf[7], 8u));  /* one shared byte */
    TEST_ASSERT_EQUAL_INT(0, sbr_util_overlap(buf, 8u, &buf[8], 8u));  /* adjacent */
    TEST_ASSERT_EQUAL_INT(0, sbr_util_overlap(&buf[8], 8u, buf, 8u));
    TEST_ASSERT_EQUAL_INT(1, sbr_util_overlap(buf, 64u, &buf[30], 1u)); /* inside */
    TEST_ASSERT_EQUAL_INT(0, sbr_util_overlap(buf, 0u, buf, 8u));       /* empty range */
    {
        static uint64_t words[4];
        const uint8_t *p = (const uint8_t *)(const void *)words;
        TEST_ASSERT_EQUAL_INT(1, sbr_util_aligned(p, 8u));
        TEST_ASSERT_EQUAL_INT(1, sbr_util_aligned(&p[4], 4u));
        TEST_ASSERT_EQUAL_INT(0, sbr_util_aligned(&p[4], 8u));
        TEST_ASSERT_EQUAL_INT(0, sbr_util_aligned(&p[1], 2u));
        TEST_ASSERT_EQUAL_INT(1, sbr_util_aligned(&p[3], 1u));
    }
}

/* The documented order: element k into sum k mod 4, the tail into sum 0, then
   (s0 + s1) + (s2 + s3). Values chosen so that another order rounds differently. */
static void test_dot_fixed_order(void)
{
    float a[7];
    float b[7];
    float s[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float want;
    uint32_t k;
    for (k = 0u; k < 7u; k++) {
        a[k] = (k % 2u == 0u) ? 1.0e8f : 1.0f;
        b[k] = (k == 4u) ? -1.0f : (1.0f + ((float)k * 0.1f));
    }
    /* n = 7: the four-lane part is elements 0..3, the tail 4..6 all goes into s0 */
    for (k = 0u; k < 4u; k++) {
        s[k] += a[k] * b[k];
    }
    for (k = 4u; k < 7u; k++) {
        s[0] += a[k] * b[k];
    }
    want = (s[0] + s[1]) + (s[2] + s[3]);
    TEST_ASSERT_TRUE(memcmp(&want, &(float){sbr_util_dot(a, b, 7u)}, sizeof want) == 0);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_dot(a, b, 0u));
    TEST_ASSERT_EQUAL_FLOAT(a[0] * b[0], sbr_util_dot(a, b, 1u));
}

/* The matcher's polynomial atan2 against libm's over all four quadrants, the axes and
   the signed zeros: within 6e-7 rad, and in (-pi, pi]. */
static void test_fast_atan2_accuracy(void)
{
    float worst = 0.0f;
    uint32_t i;
    for (i = 0u; i < 3600u; i++) {
        const float a = ((float)i * (2.0f * 3.14159265f)) / 3600.0f;
        uint32_t k;
        for (k = 0u; k < 3u; k++) {
            const float rad = (k == 0u) ? 1.0f : ((k == 1u) ? 1.0e-20f : 3.0e20f);
            const float y = rad * sinf(a);
            const float x = rad * cosf(a);
            const float got = sbr_util_atan2f(y, x);
            float d = fabsf(got - atan2f(y, x));
            if (d > 3.14159265f) {
                d = fabsf(d - (2.0f * 3.14159265f)); /* +pi against -pi at y = -0 */
            }
            worst = (d > worst) ? d : worst;
            TEST_ASSERT_TRUE((got > -3.1415930f) && (got <= 3.1415930f));
        }
    }
    TEST_ASSERT_TRUE(worst < 6.0e-7f);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_atan2f(0.0f, 0.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 3.14159265f, sbr_util_atan2f(0.0f, -1.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 3.14159265f, sbr_util_atan2f(-0.0f, -1.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, -1.57079633f, sbr_util_atan2f(-2.0f, 0.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.78539816f, sbr_util_atan2f(5.0f, 5.0f));
}

/* min/max of finite values; clamp also maps NaN to lo (so a later cast is defined) and
   the infinities to the ends. */
static void test_min_max_clamp(void)
{
    const float inf = INFINITY;
    const float nan = NAN;
    TEST_ASSERT_EQUAL_FLOAT(2.0f, sbr_util_maxf(-1.0f, 2.0f));
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, sbr_util_minf(-1.0f, 2.0f));
    TEST_ASSERT_EQUAL_FLOAT(3.0f, sbr_util_maxf(3.0f, 3.0f));
    TEST_ASSERT_EQUAL_FLOAT(0.5f, sbr_util_clampf(0.5f, 0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_clampf(-0.5f, 0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(1.0f, sbr_util_clampf(1.5f, 0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_clampf(0.0f, 0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(1.0f, sbr_util_clampf(1.0f, 0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(-4.0f, sbr_util_clampf(nan, -4.0f, 4.0f));
    TEST_ASSERT_EQUAL_FLOAT(4.0f, sbr_util_clampf(inf, -4.0f, 4.0f));
    TEST_ASSERT_EQUAL_FLOAT(-4.0f, sbr_util_clampf(-inf, -4.0f, 4.0f));
}

static void test_box_iou(void)
{
    const float a[4] = {0.0f, 0.0f, 10.0f, 10.0f};
    const float half[4] = {5.0f, 0.0f, 15.0f, 10.0f};     /* 50 of 150 */
    const float inside[4] = {2.0f, 2.0f, 7.0f, 7.0f};     /* 25 of 100 */
    const float touching[4] = {10.0f, 0.0f, 20.0f, 10.0f}; /* shares an edge only */
    const float far[4] = {30.0f, 30.0f, 40.0f, 40.0f};
    const float empty[4] = {3.0f, 3.0f, 3.0f, 8.0f};
    TEST_ASSERT_EQUAL_FLOAT(1.0f, sbr_util_box_iou(a, a));
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 1.0f / 3.0f, sbr_util_box_iou(a, half));
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 1.0f / 3.0f, sbr_util_box_iou(half, a));
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.25f, sbr_util_box_iou(a, inside));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_box_iou(a, touching));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_box_iou(a, far));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_box_iou(a, empty));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, sbr_util_box_iou(empty, empty));
}

static void test_seconds_exact(void)
{
    TEST_ASSERT_TRUE(sbr_util_seconds(100000u) == 0.1f);
    TEST_ASSERT_TRUE(sbr_util_seconds(1000000u) == 1.0f);
    TEST_ASSERT_TRUE(sbr_util_seconds(33333u) == 0.033333f);
    TEST_ASSERT_TRUE(sbr_util_seconds(0u) == 0.0f);
}

/* ---- heap sort ---- */

typedef struct {
    int32_t key;
    uint32_t tag; /* where the element started */
    uint8_t pad[4];
} item_t;

/* mode 0: ascending key; mode 1: descending */
static int item_before(const void *a, const void *b, int mode)
{
    const item_t *x = (const item_t *)a;
    const item_t *y = (const item_t *)b;
    return (mode == 0) ? (x->key < y->key) : (x->key > y->key);
}

static uint32_t g_rng = 12345u;
static uint32_t rnd(void)
{
    g_rng = (g_rng * 1103515245u) + 12345u;
    return (g_rng >> 8) & 0xFFFFu;
}

/* Every length 0..200 in both modes, keys with many repeats: the result is ordered and a
   permutation of the input (each tag once, with its own key). */
static void test_heap_sort_orders_a_permutation(void)
{
    static item_t v[200];
    static int32_t key_of[200];
    static uint8_t seen[200];
    uint32_t n;
    int mode;
    for (mode = 0; mode <= 1; mode++) {
        for (n = 0u; n <= 200u; n++) {
            uint32_t i;
            for (i = 0u; i < n; i++) {
                v[i].key = (int32_t)(rnd() % 37u) - 18;
                v[i].tag = i;
                key_of[i] = v[i].key;
                seen[i] = 0u;
            }
            sbr_util_heap_sort((uint8_t *)(void *)v, n, sizeof(item_t), item_before, mode);
            for (i = 0u; i < n; i++) {
                TEST_ASSERT_TRUE(v[i].tag < n);
                TEST_ASSERT_EQUAL_UINT8(0u, seen[v[i].tag]);
                seen[v[i].tag] = 1u;
                TEST_ASSERT_EQUAL_INT32(key_of[v[i].tag], v[i].key);
                if (i > 0u) {
                    TEST_ASSERT_FALSE(item_before(&v[i], &v[i - 1u], mode));
                }
            }
        }
    }
}

static int item3_before(const void *a, const void *b, int mode)
{
    (void)mode;
    return ((const uint8_t *)a)[0] < ((const uint8_t *)b)[0];
}

/* Elements of an odd size (3 bytes) are moved whole. */
static void test_heap_sort_odd_element_size(void)
{
    static uint8_t b[5 * 3] = {9, 'a', 'A', 2, 'b', 'B', 7, 'c', 'C', 2, 'd', 'D', 0, 'e', 'E'};
    static const uint8_t keys[5] = {0, 2, 2, 7, 9};
    uint32_t i;
    sbr_util_heap_sort(b, 5u, 3u, item3_before, 0);
    for (i = 0u; i < 5u; i++) {
        TEST_ASSERT_EQUAL_UINT8(keys[i], b[3u * i]);
        TEST_ASSERT_EQUAL_UINT8((uint8_t)(b[(3u * i) + 1u] - 'a' + 'A'), b[(3u * i) + 2u]);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_overlap_and_alignment);
    RUN_TEST(test_dot_fixed_order);
    RUN_TEST(test_fast_atan2_accuracy);
    RUN_TEST(test_min_max_clamp);
    RUN_TEST(test_box_iou);
    RUN_TEST(test_seconds_exact);
    RUN_TEST(test_heap_sort_orders_a_permutation);
    RUN_TEST(test_heap_sort_odd_element_size);
    return UNITY_END();
}
