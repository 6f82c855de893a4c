/* SPDX-License-Identifier: MIT */
/* The layering gate's self-test: b's private step calls back into module a. */
#include "b_internal.h"

int sbr_a_back(int x);

int sbr_b_priv_step(int x)
{
    return sbr_a_back(x) * 2;
}
