/* SPDX-License-Identifier: MIT */
/* Unity tests of the recogniser's configuration table (recog.h, sbr_recog_field_at()):
   it covers every field once, its defaults are sbr_recog_config_default()'s, and the check
   (sbr_recog_config_check_field(), sbr_recog_config_check()) accepts exactly its ranges,
   names the field that fails, and agrees with the part stage's own check. */
#include "unity.h"
#include "sbr/recog.h"
#include "sbr/recog_strips.h"
#include "test_support.h"
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static uint8_t *at(sbr_recog_config_t *c, const sbr_field_t *f, uint32_t k)
{
    return &((uint8_t *)c)[f->offset + (k * 4u)];
}

static void set_u(sbr_recog_config_t *c, const sbr_field_t *f, uint32_t k, uint32_t v)
{
    memcpy(at(c, f, k), &v, sizeof v);
}

static void set_f(sbr_recog_config_t *c, const sbr_field_t *f, float v)
{
    memcpy(at(c, f, 0u), &v, sizeof v);
}

static uint32_t get_u(sbr_recog_config_t *c, const sbr_field_t *f, uint32_t k)
{
    uint32_t v;
    memcpy(&v, at(c, f, k), sizeof v);
    return v;
}

static float get_f(sbr_recog_config_t *c, const sbr_field_t *f)
{
    float v;
    memcpy(&v, at(c, f, 0u), sizeof v);
    return v;
}

/* Field i of the table (a copy: the table's function fills it). */
static sbr_field_t g_fld;
static const sbr_field_t *at_index(uint32_t i)
{
    static sbr_field_t copies[128];
    TEST_ASSERT_TRUE(i < 128u);
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_field_at(i, &copies[i]));
    return &copies[i];
}

static const sbr_field_t *field(const char *name)
{
    const uint32_t i = sbr_recog_field_find(name);
    TEST_ASSERT_NOT_EQUAL_UINT32(SBR_FIELD_NONE, i);
    return at_index(i);
}

/* Every byte of the configuration before the clock belongs to exactly one field. */
static void test_table_covers_every_field_once(void)
{
    static uint8_t owner[sizeof(sbr_recog_config_t)];
    const uint32_t n = sbr_recog_field_count();
    uint32_t i;
    uint32_t j;
    size_t b;
    memset(owner, 0, sizeof owner);
    TEST_ASSERT_TRUE(n >= 50u);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_field_at(n, &g_fld));
    TEST_ASSERT_EQUAL_INT(SBR_ERR_NULL, sbr_recog_field_at(0u, NULL));
    for (i = 0u; i < n; i++) {
        const sbr_field_t *f = at_index(i);
        TEST_ASSERT_TRUE(strlen(f->name) < SBR_FIELD_NAME_LEN && strlen(f->help) < SBR_FIELD_HELP_LEN);
        TEST_ASSERT_TRUE(f->count == 1u || f->count == SBR_MAP_KINDS);
        TEST_ASSERT_TRUE(f->kind == SBR_FIELD_U32 || (f->kind == SBR_FIELD_F32 && f->count == 1u));
        TEST_ASSERT_TRUE(strlen(f->help) >= 10u);
        TEST_ASSERT_TRUE(f->offset + (4u * f->count) <= offsetof(sbr_recog_config_t, clock));
        for (b = f->offset; b < f->offset + (4u * f->count); b++) {
            TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, owner[b], f->name);
            owner[b] = 1u;
        }
        for (b = 0u; f->name[b] != '\0'; b++) {
            const char ch = f->name[b];
            TEST_ASSERT_TRUE_MESSAGE((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_', f->name);
        }
        for (j = 0u; j < i; j++) {
            TEST_ASSERT_TRUE_MESSAGE(strcmp(at_index(j)->name, f->name) != 0, f->name);
        }
        TEST_ASSERT_EQUAL_UINT32(i, sbr_recog_field_find(f->name));
    }
    /* the fields tile the struct up to the clock (all are 4-byte values), but for the
       padding before the clock's pointer */
    for (b = 0u; (b < offsetof(sbr_recog_config_t, clock)) && (owner[b] == 1u); b++) {
    }
    TEST_ASSERT_TRUE(offsetof(sbr_recog_config_t, clock) - b < sizeof(void *));
    for (; b < offsetof(sbr_recog_config_t, clock); b++) {
        TEST_ASSERT_EQUAL_UINT8(0u, owner[b]);
    }
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_NONE, sbr_recog_field_find("no_such_field"));
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_NONE, sbr_recog_field_find(NULL));
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_NONE, sbr_recog_config_check_field(NULL));
}

/* The defaults are the table's, inside its ranges, and a few documented values hold. */
static void test_defaults_are_the_table(void)
{
    sbr_recog_config_t c;
    const uint32_t n = sbr_recog_field_count();
    uint32_t i;
    uint32_t k;
    memset(&c, 0x5A, sizeof c);
    sbr_recog_config_default(&c);
    for (i = 0u; i < n; i++) {
        const sbr_field_t *f = at_index(i);
        if (f->kind == SBR_FIELD_F32) {
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(f->def_f, get_f(&c, f), f->name);
            TEST_ASSERT_TRUE_MESSAGE(f->lo_f <= f->def_f && f->def_f <= f->hi_f, f->name);
        } else {
            for (k = 0u; k < f->count; k++) {
                TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->def_u[k], get_u(&c, f, k), f->name);
                TEST_ASSERT_TRUE_MESSAGE(f->lo_u <= f->def_u[k] && f->def_u[k] <= f->hi_u, f->name);
            }
        }
    }
    TEST_ASSERT_NULL(c.clock);
    TEST_ASSERT_NULL(c.clock_ctx);
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_NONE, sbr_recog_config_check_field(&c));
    TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_config_check(&c));
    /* values the workspace macros and the docs rely on */
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_DEFAULT_MAX_PARTS, c.max_parts);
    TEST_ASSERT_EQUAL_UINT32(3u, c.parts.mser.delta);
    TEST_ASSERT_EQUAL_UINT32(136u, c.parts.map_bright_min[SBR_MAP_RED]);
    TEST_ASSERT_EQUAL_UINT32(2u, c.parts.map_subsample[SBR_MAP_BLUE]);
    TEST_ASSERT_EQUAL_FLOAT(0.3f, c.min_score);
    sbr_recog_config_strips(&c);
    TEST_ASSERT_EQUAL_UINT32(SBR_RECOG_STRIP_MAX_PARTS, c.max_parts);
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_NONE, sbr_recog_config_check_field(&c));
}

/* Expect field i to be blamed for c. */
static void refused(const sbr_recog_config_t *c, uint32_t i)
{
    const uint32_t got = sbr_recog_config_check_field(c);
    TEST_ASSERT_EQUAL_STRING(at_index(i)->name, got == SBR_FIELD_NONE ? "(none)" : at_index(got)->name);
    TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(c));
}

static void accepted(const sbr_recog_config_t *c, const char *name)
{
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(SBR_FIELD_NONE, sbr_recog_config_check_field(c), name);
    TEST_ASSERT_EQUAL_INT_MESSAGE(SBR_OK, sbr_recog_config_check(c), name);
}

/* Each value at its range's ends is accepted (fields with a rule to others: at the ends
   their partners allow), one step beyond is refused and blamed on the field, and so is
   NaN. */
static void test_check_accepts_exactly_the_ranges(void)
{
    const uint32_t n = sbr_recog_field_count();
    uint32_t i;
    uint32_t k;
    for (i = 0u; i < n; i++) {
        const sbr_field_t *f = at_index(i);
        const int linked = (f->flags & SBR_FIELD_LINKED) != 0u;
        for (k = 0u; k < f->count; k++) {
            sbr_recog_config_t c;
            sbr_recog_config_default(&c);
            if (f->kind == SBR_FIELD_F32) {
                set_f(&c, f, nextafterf(f->hi_f, INFINITY));
                refused(&c, i);
                set_f(&c, f, NAN);
                refused(&c, i);
                set_f(&c, f, INFINITY);
                refused(&c, i);
                set_f(&c, f, nextafterf(f->lo_f, -INFINITY));
                refused(&c, i);
                if (!linked) {
                    set_f(&c, f, f->lo_f);
                    accepted(&c, f->name);
                    set_f(&c, f, f->hi_f);
                    accepted(&c, f->name);
                }
            } else {
                if (f->hi_u < UINT32_MAX) {
                    set_u(&c, f, k, f->hi_u + 1u);
                    refused(&c, i);
                }
                if (f->lo_u > 0u) {
                    set_u(&c, f, k, f->lo_u - 1u);
                    refused(&c, i);
                }
                if (!linked) {
                    set_u(&c, f, k, f->lo_u);
                    accepted(&c, f->name);
                    set_u(&c, f, k, f->hi_u);
                    accepted(&c, f->name);
                }
            }
        }
    }
}

/* Each rule between fields, broken, is blamed on the field its help names. */
static void test_links_blame_one_field(void)
{
    sbr_recog_config_t c;
    sbr_recog_config_default(&c);
    c.max_size = c.min_size - 1.0f;
    refused(&c, sbr_recog_field_find("max_size"));
    sbr_recog_config_default(&c);
    c.match_p = 48u; /* in range, not an FFT size */
    refused(&c, sbr_recog_field_find("match_p"));
    sbr_recog_config_default(&c);
    c.match_p = 16u; /* an FFT size below 2 fd_m + 1 = 25 */
    refused(&c, sbr_recog_field_find("match_p"));
    c.parts.fd_m = 7u;
    accepted(&c, "match_p 16 with fd_m 7");
    sbr_recog_config_default(&c);
    c.parts.fd_n = 100u;
    refused(&c, sbr_recog_field_find("fd_n"));
    sbr_recog_config_default(&c);
    c.parts.fd_n = 16u;
    refused(&c, sbr_recog_field_find("fd_m"));
    sbr_recog_config_default(&c);
    c.parts.subsample = 8u;
    refused(&c, sbr_recog_field_find("map_subsample")); /* the blue map's 2 */
    c.parts.map_subsample[SBR_MAP_BLUE] = 1u;
    accepted(&c, "subsample 8");
    sbr_recog_config_default(&c);
    c.parts.map_min_area[SBR_MAP_RED] = c.parts.mser.max_area + 1u;
    refused(&c, sbr_recog_field_find("map_min_area"));
    sbr_recog_config_default(&c);
    c.parts.mser.min_area = c.parts.mser.max_area + 1u;
    refused(&c, sbr_recog_field_find("max_area"));
    sbr_recog_config_default(&c);
    c.parts.min_side = c.parts.max_side + 1u;
    refused(&c, sbr_recog_field_find("max_side"));
}

/* Many configurations near the ranges' ends: the table's verdict, the recogniser's check
   and the part stage's own check agree (the table is no looser than the part stage). */
static void test_check_agrees_with_the_part_stage(void)
{
    const uint32_t n = sbr_recog_field_count();
    uint32_t seed = 12345u;
    uint32_t trial;
    uint32_t passed = 0u;
    for (trial = 0u; trial < 20000u; trial++) {
        sbr_recog_config_t c;
        uint32_t changes;
        sbr_recog_config_default(&c);
        for (changes = 0u; changes < 3u; changes++) {
            const sbr_field_t *f;
            uint32_t k;
            seed = (seed * 1664525u) + 1013904223u;
            f = at_index((seed >> 8) % n);
            k = (seed >> 20) % f->count;
            seed = (seed * 1664525u) + 1013904223u;
            if (f->kind == SBR_FIELD_F32) {
                const float pick[6] = {f->lo_f, f->hi_f, f->def_f, 0.0f, -1.0f, 2.0f * f->hi_f};
                set_f(&c, f, pick[(seed >> 16) % 6u]);
            } else {
                const uint32_t pick[8] = {f->lo_u, f->hi_u, f->def_u[k], 0u, 1u, 16u, f->hi_u + 1u, 255u};
                set_u(&c, f, k, pick[(seed >> 16) % 8u]);
            }
        }
        if (sbr_recog_config_check_field(&c) == SBR_FIELD_NONE) {
            passed++;
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_parts_config_check(&c.parts));
            TEST_ASSERT_EQUAL_INT(SBR_OK, sbr_recog_config_check(&c));
        } else {
            TEST_ASSERT_EQUAL_INT(SBR_ERR_RANGE, sbr_recog_config_check(&c));
        }
    }
    TEST_ASSERT_TRUE(passed > 1000u);
}

/* A few names the host tools and the Python package spell as options and keywords. */
static void test_known_names(void)
{
    TEST_ASSERT_EQUAL_UINT32(offsetof(sbr_recog_config_t, max_extra_looks), field("max_extra_looks")->offset);
    TEST_ASSERT_EQUAL_UINT32(offsetof(sbr_recog_config_t, parts) + offsetof(sbr_parts_config_t, mser) +
                                 offsetof(sbr_mser_config_t, max_nodes),
                             field("max_nodes")->offset);
    TEST_ASSERT_EQUAL_UINT32(SBR_MAP_KINDS, field("map_polarity")->count);
    TEST_ASSERT_EQUAL_UINT32(SBR_FIELD_F32, field("min_score")->kind);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_table_covers_every_field_once);
    RUN_TEST(test_defaults_are_the_table);
    RUN_TEST(test_check_accepts_exactly_the_ranges);
    RUN_TEST(test_links_blame_one_field);
    RUN_TEST(test_check_agrees_with_the_part_stage);
    RUN_TEST(test_known_names);
    return UNITY_END();
}
