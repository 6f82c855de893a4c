/* SPDX-License-Identifier: MIT */
/* Unity tests of the status names (include/sbr/status.h). */
#include "unity.h"
#include "sbr/sbr.h"

#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static void test_every_status_has_its_name(void)
{
    TEST_ASSERT_EQUAL_STRING("SBR_OK", sbr_status_str(SBR_OK));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_NULL", sbr_status_str(SBR_ERR_NULL));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_SIZE", sbr_status_str(SBR_ERR_SIZE));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_RANGE", sbr_status_str(SBR_ERR_RANGE));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_ALIGN", sbr_status_str(SBR_ERR_ALIGN));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_CAPACITY", sbr_status_str(SBR_ERR_CAPACITY));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_WORKSPACE", sbr_status_str(SBR_ERR_WORKSPACE));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_STATE", sbr_status_str(SBR_ERR_STATE));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_OVERLAP", sbr_status_str(SBR_ERR_OVERLAP));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_DEGENERATE", sbr_status_str(SBR_ERR_DEGENERATE));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_CORRUPT", sbr_status_str(SBR_ERR_CORRUPT));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_UNKNOWN", sbr_status_str((sbr_status_t)-99));
    TEST_ASSERT_EQUAL_STRING("SBR_ERR_UNKNOWN", sbr_status_str((sbr_status_t)7));
}

static void test_ok_is_zero_and_errors_negative(void)
{
    TEST_ASSERT_EQUAL_INT(0, SBR_OK);
    TEST_ASSERT_TRUE(SBR_ERR_NULL < 0);
    TEST_ASSERT_TRUE(SBR_ERR_CORRUPT < 0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_status_has_its_name);
    RUN_TEST(test_ok_is_zero_and_errors_negative);
    return UNITY_END();
}
