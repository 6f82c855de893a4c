/* SPDX-License-Identifier: MIT */
/* Conics: float-float arithmetic (exact products, compensated sums) for the determinants
   of conic.c. See conic_internal.h. */
#include "conic_internal.h"

/* Dekker's product and Knuth's sum: C99 without contraction keeps them exact. */

sbr_conic_ff_t sbr_conic_priv_ff_sum(float a, float b)
{
    sbr_conic_ff_t r;
    const float s = a + b;
    const float bb = s - a;
    r.hi = s;
    r.lo = (a - (s - bb)) + (b - bb);
    return r;
}

static void ff_split(float a, float *hi, float *lo)
{
    const float c = 4097.0f * a; /* 2^12 + 1 */
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* a * b exactly (for |a|, |b| <= 2^100: no overflow in the split) */
sbr_conic_ff_t sbr_conic_priv_ff_prod(float a, float b)
{
    sbr_conic_ff_t r;
    float ah;
    float al;
    float bh;
    float bl;
    ff_split(a, &ah, &al);
    ff_split(b, &bh, &bl);
    r.hi = a * b;
    r.lo = (((ah * bh) - r.hi) + (ah * bl) + (al * bh)) + (al * bl);
    return r;
}

sbr_conic_ff_t sbr_conic_priv_ff_add(sbr_conic_ff_t x, sbr_conic_ff_t y)
{
    const sbr_conic_ff_t s = sbr_conic_priv_ff_sum(x.hi, y.hi);
    return sbr_conic_priv_ff_sum(s.hi, s.lo + x.lo + y.lo);
}

sbr_conic_ff_t sbr_conic_priv_ff_neg(sbr_conic_ff_t x)
{
    sbr_conic_ff_t r;
    r.hi = -x.hi;
    r.lo = -x.lo;
    return r;
}

/* x * b for a float-float x */
sbr_conic_ff_t sbr_conic_priv_ff_scale(sbr_conic_ff_t x, float b)
{
    const sbr_conic_ff_t p = sbr_conic_priv_ff_prod(x.hi, b);
    return sbr_conic_priv_ff_sum(p.hi, p.lo + (x.lo * b));
}

/* a * b - c * d, correctly rounded but for the last bit */
float sbr_conic_priv_ff_det2(float a, float b, float c, float d)
{
    const sbr_conic_ff_t r = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(a, b), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(c, d)));
    return r.hi + r.lo;
}
