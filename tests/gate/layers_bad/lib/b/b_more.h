/* SPDX-License-Identifier: MIT */
/* The layering gate's self-test: the other half of the include circle. */
#ifndef B_MORE_H
#define B_MORE_H
#include "b_internal.h"
#endif
