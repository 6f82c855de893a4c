/* SPDX-License-Identifier: MIT */
/* Self-test input of cmake/check_api_docs.py: `b` has no direction, `c` no line at all. */
/**
 * @brief Not a real function.
 * @param[in] a documented.
 * @param b    no direction.
 * @return 0.
 */
int sbr_bad_example(int a, int b, int c);
