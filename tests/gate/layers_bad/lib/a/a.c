/* SPDX-License-Identifier: MIT */
/* The layering gate's self-test (cmake/check_layers.py): module a reaches into module b's
   insides (an include and a private function), and b calls back into a (a circle). */
#include "../b/b_internal.h"

int sbr_a_back(int x);

int sbr_a_back(int x)
{
    return x + 1;
}

int sbr_a_run(int x);

int sbr_a_run(int x)
{
    return sbr_b_priv_step(x);
}
