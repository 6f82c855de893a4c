/* SPDX-License-Identifier: MIT */
/* The layering gate's self-test: half of an include circle (b_more.h includes this). */
#ifndef B_INTERNAL_H
#define B_INTERNAL_H
#include "b_more.h"
int sbr_b_priv_step(int x);
#endif
