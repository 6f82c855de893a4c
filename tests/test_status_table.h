/* SPDX-License-Identifier: MIT */
/* A table of calls and the status each one's header documents for it, for the
   "every documented status" tests: ROW() evaluates the call in sequence and records it;
   status_table_check() asserts every row and names the failing call. */
#ifndef SBR_TEST_STATUS_TABLE_H
#define SBR_TEST_STATUS_TABLE_H

#include <stdint.h>

#include "sbr/status.h"
#include "unity.h"

#define STATUS_TABLE_ROWS 64u

typedef struct {
    const char *call;
    sbr_status_t want;
    sbr_status_t got;
} status_row_t;

typedef struct {
    status_row_t rows[STATUS_TABLE_ROWS];
    uint32_t n;
} status_table_t;

static inline void status_table_add(status_table_t *t, const char *call, sbr_status_t want,
                                    sbr_status_t got)
{
    TEST_ASSERT_TRUE(t->n < STATUS_TABLE_ROWS);
    t->rows[t->n].call = call;
    t->rows[t->n].want = want;
    t->rows[t->n].got = got;
    t->n++;
}

/* ROW(t, want, call): the call is evaluated here, in sequence */
#define ROW(t, want, call) status_table_add((t), #call, (want), (call))

static inline void status_table_check(const status_table_t *t)
{
    uint32_t i;
    for (i = 0u; i < t->n; i++) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(t->rows[i].want, t->rows[i].got, t->rows[i].call);
    }
}

#endif
