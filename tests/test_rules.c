/* SPDX-License-Identifier: MIT */
/* Unity tests of the restrictions in force (include/sbr/rules.h): a drive's confirmed
   signs with known truth, expiry, the GTSDB table, and every documented status. */
#include "unity.h"
#include "sbr/rules.h"
#include "test_status_table.h"
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define S(x) ((uint64_t)(x) * 1000000u) /* seconds to microseconds */

static sbr_rules_t g_r;
static sbr_rules_state_t g_s;

static void start(uint32_t hold_ms)
{
    sbr_rules_config_t cfg;
    sbr_rules_config_default(&cfg);
    cfg.hold_ms = hold_ms;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_rules_init(&g_r, &cfg));
}

/* One frame with the given confirmed classes (count 0..4). */
static void frame(uint64_t t, uint32_t n, uint16_t a, uint16_t b)
{
    const uint16_t c[2] = {a, b};
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_rules_update(&g_r, t, n > 0u ? c : NULL, n, &g_s));
}

static void shown(uint32_t limit, uint32_t ban, uint32_t ban_trucks, uint32_t priority)
{
    TEST_ASSERT_EQUAL_UINT32(limit, g_s.speed_limit_kmh);
    TEST_ASSERT_EQUAL_UINT32(ban, g_s.no_overtaking);
    TEST_ASSERT_EQUAL_UINT32(ban_trucks, g_s.no_overtaking_trucks);
    TEST_ASSERT_EQUAL_UINT32(priority, g_s.priority_road);
}

/* GTSDB's meanings: the speed limits' values, the end signs, the bans, priority. */
static void test_gtsdb_table(void)
{
    const sbr_rules_meaning_t *m = NULL;
    uint32_t n = 0u;
    const uint8_t speeds[9] = {20u, 30u, 50u, 60u, 70u, 80u, 0u, 100u, 120u};
    uint32_t c;
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_rules_gtsdb(&m, &n));
    TEST_ASSERT_EQUAL_UINT32(43u, n);
    for (c = 0u; c < 9u; c++) {
        TEST_ASSERT_EQUAL_UINT8(c == 6u ? SBR_RULES_END_SPEED : SBR_RULES_SPEED, m[c].kind);
        TEST_ASSERT_EQUAL_UINT8(c == 6u ? 80u : speeds[c], m[c].value);
    }
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_NO_OVERTAKING, m[9].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_NO_OVERTAKING_TRUCKS, m[10].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_PRIORITY, m[12].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_END_PRIORITY, m[13].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_END_PRIORITY, m[14].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_END_ALL, m[32].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_END_NO_OVERTAKING, m[41].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_END_NO_OVERTAKING_TRUCKS, m[42].kind);
    TEST_ASSERT_EQUAL_UINT8(SBR_RULES_NONE, m[18].kind); /* danger: nothing here */
}

/* A drive: limits set and replaced, the end of 80 only ends 80, the end of all ends the
   limit and the bans, priority road until give way. */
static void test_drive(void)
{
    start(SBR_RULES_DEFAULT_HOLD_MS);
    frame(S(0), 0u, 0u, 0u);
    shown(0u, 0u, 0u, 0u);
    frame(S(1), 1u, 2u, 0u); /* 50 */
    shown(50u, 0u, 0u, 0u);
    TEST_ASSERT_EQUAL_UINT32(0u, g_s.speed_age_ms);
    frame(S(3), 1u, 18u, 0u); /* a danger sign changes nothing */
    shown(50u, 0u, 0u, 0u);
    TEST_ASSERT_EQUAL_UINT32(2000u, g_s.speed_age_ms);
    frame(S(4), 1u, 6u, 0u); /* end of 80 while 50 holds: 50 stays */
    shown(50u, 0u, 0u, 0u);
    frame(S(5), 2u, 5u, 9u); /* 80 and no overtaking */
    shown(80u, 1u, 0u, 0u);
    frame(S(6), 1u, 10u, 0u); /* no overtaking for trucks */
    shown(80u, 1u, 1u, 0u);
    frame(S(7), 1u, 6u, 0u); /* end of 80 */
    shown(0u, 1u, 1u, 0u);
    frame(S(8), 1u, 41u, 0u); /* end of no overtaking */
    shown(0u, 0u, 1u, 0u);
    frame(S(9), 2u, 8u, 12u); /* 120, priority road */
    shown(120u, 0u, 1u, 1u);
    frame(S(10), 1u, 32u, 0u); /* end of all restrictions: not priority */
    shown(0u, 0u, 0u, 1u);
    frame(S(11), 1u, 13u, 0u); /* give way */
    shown(0u, 0u, 0u, 0u);
    frame(S(12), 2u, 12u, 14u); /* in order: priority, then stop */
    shown(0u, 0u, 0u, 0u);
    frame(S(13), 2u, 4u, 42u); /* 70, end of the trucks' ban (none) */
    shown(70u, 0u, 0u, 0u);
}

/* Expiry: hold_ms after the last confirmation, refreshed when the sign is seen again;
   each restriction on its own clock. */
static void test_expiry(void)
{
    start(10000u); /* 10 s */
    frame(S(0), 2u, 3u, 9u); /* 60, no overtaking */
    frame(S(8), 1u, 3u, 0u); /* 60 again: refreshed */
    shown(60u, 1u, 0u, 0u);
    frame(S(10), 0u, 0u, 0u); /* exactly the hold: still in force */
    shown(60u, 1u, 0u, 0u);
    frame(S(10) + 1u, 0u, 0u, 0u); /* the ban was set 10 s + 1 us ago: gone */
    shown(60u, 0u, 0u, 0u);
    TEST_ASSERT_EQUAL_UINT32(2000u, g_s.speed_age_ms);
    frame(S(18), 0u, 0u, 0u);
    shown(60u, 0u, 0u, 0u);
    frame(S(18) + 1u, 0u, 0u, 0u);
    shown(0u, 0u, 0u, 0u);
    TEST_ASSERT_EQUAL_UINT32(0u, g_s.speed_age_ms);
    /* a sign confirmed in the frame that expires its predecessor holds */
    frame(S(100), 1u, 1u, 0u);
    shown(30u, 0u, 0u, 0u);
    /* reset: nothing in force, and time may start again */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_rules_reset(&g_r));
    frame(S(1), 0u, 0u, 0u);
    shown(0u, 0u, 0u, 0u);
}

/* Every status rules.h documents; an error changes nothing and writes nothing. */
static void test_statuses(void)
{
    status_table_t t;
    sbr_rules_config_t cfg;
    sbr_rules_config_t bad;
    sbr_rules_meaning_t own[2] = {{(uint8_t)SBR_RULES_SPEED, 30u}, {(uint8_t)SBR_RULES_NONE, 0u}};
    sbr_rules_state_t before;
    sbr_rules_state_t out;
    const sbr_rules_meaning_t *m = NULL;
    uint32_t n = 0u;
    const uint16_t c43 = 43u;
    const uint16_t c5 = 5u;
    sbr_rules_config_default(&cfg);
    sbr_rules_config_default(NULL); /* no-op */
    t.n = 0u;
    ROW(&t, SBR_OK, sbr_rules_config_check(&cfg));
    ROW(&t, SBR_ERR_NULL, sbr_rules_config_check(NULL));
    bad = cfg;
    bad.meanings = NULL;
    ROW(&t, SBR_ERR_NULL, sbr_rules_config_check(&bad));
    bad = cfg;
    bad.hold_ms = 0u;
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    bad.hold_ms = SBR_RULES_MAX_HOLD_MS + 1u;
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    bad = cfg;
    bad.class_count = SBR_RULES_MAX_CLASSES + 1u;
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    bad.class_count = 0u;
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    bad = cfg;
    bad.meanings = own;
    bad.class_count = 2u;
    ROW(&t, SBR_OK, sbr_rules_config_check(&bad));
    own[1].kind = (uint8_t)SBR_RULES_KINDS;
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    own[1].kind = (uint8_t)SBR_RULES_PRIORITY;
    own[1].value = 3u; /* a value where none belongs */
    ROW(&t, SBR_ERR_RANGE, sbr_rules_config_check(&bad));
    own[1].value = 0u;
    own[0].value = 0u; /* a speed limit of 0 */
    ROW(&t, SBR_ERR_RANGE, sbr_rules_init(&g_r, &bad));
    ROW(&t, SBR_ERR_STATE, sbr_rules_update(&g_r, 0u, NULL, 0u, &out)); /* refused init: unusable */
    ROW(&t, SBR_ERR_NULL, sbr_rules_init(NULL, &cfg));
    ROW(&t, SBR_ERR_NULL, sbr_rules_init(&g_r, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_rules_gtsdb(NULL, &n));
    ROW(&t, SBR_ERR_NULL, sbr_rules_gtsdb(&m, NULL));
    ROW(&t, SBR_OK, sbr_rules_init(&g_r, &cfg));
    ROW(&t, SBR_OK, sbr_rules_update(&g_r, S(5), &c5, 1u, &before));
    ROW(&t, SBR_ERR_NULL, sbr_rules_update(NULL, S(6), NULL, 0u, &out));
    ROW(&t, SBR_ERR_NULL, sbr_rules_update(&g_r, S(6), NULL, 0u, NULL));
    ROW(&t, SBR_ERR_NULL, sbr_rules_update(&g_r, S(6), NULL, 1u, &out));
    (void)memset(&out, 0xA5, sizeof out);
    ROW(&t, SBR_ERR_RANGE, sbr_rules_update(&g_r, S(4), NULL, 0u, &out)); /* time going back */
    ROW(&t, SBR_ERR_RANGE, sbr_rules_update(&g_r, S(6), &c43, 1u, &out)); /* no class 43 */
    ROW(&t, SBR_ERR_NULL, sbr_rules_reset(NULL));
    status_table_check(&t);
    TEST_ASSERT_EQUAL_UINT32(0xA5A5A5A5u, out.speed_limit_kmh); /* not written */
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_rules_update(&g_r, S(5), NULL, 0u, &out));
    TEST_ASSERT_EQUAL_MEMORY(&before, &out, sizeof out); /* unchanged by the refusals */
    /* an instance changed after init is refused */
    g_r.state.speed_limit_kmh = 10u;
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_rules_update(&g_r, S(7), NULL, 0u, &out));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_STATE, sbr_rules_reset(&g_r));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_gtsdb_table);
    RUN_TEST(test_drive);
    RUN_TEST(test_expiry);
    RUN_TEST(test_statuses);
    return UNITY_END();
}
