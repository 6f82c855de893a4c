/* SPDX-License-Identifier: MIT */
/* Deliberately breaks every rule the core-symbol gate enforces; built only to prove that
   the gate fails on it (gate_core_symbols_selftest). Never part of the library. */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>

int bad_core_fn(int n);
double bad_core_math(double x);

double bad_core_math(double x)
{
    return (cos(x) * x) + 1.0; /* double arithmetic: __aeabi_dmul/__aeabi_dadd on Cortex-M4F */
}

static int counter;

int bad_core_fn(int n)
{
    FILE *f = fopen("x", "r");
    char *p = (char *)malloc((size_t)n);
    counter += n;
    printf("%d %p %p\n", counter, (void *)f, (void *)p);
    return counter;
}
