/* SPDX-License-Identifier: MIT */
/* Private to lib/conic: helpers its files share (small linear algebra, ellipse geometry,
   Sampson distance), defined in conic.c. Not installed. */
#ifndef SBR_CONIC_INTERNAL_H
#define SBR_CONIC_INTERNAL_H

#include "sbr/conic.h"

#include "../common/sbr_util.h"


/* A float-float value hi + lo (|lo| <= ulp(hi) / 2): determinants of a conic whose terms
   cancel to about 2^-44 of their terms, with float32 operations only (conic_ff.c). */
typedef struct sbr_conic_ff_s {
    float hi;
    float lo;
} sbr_conic_ff_t;

/* a + b exactly, as hi + lo (Knuth's two-sum). */
sbr_conic_ff_t sbr_conic_priv_ff_sum(float a, float b);
/* a * b exactly (|a|, |b| <= 2^100; Dekker's product). */
sbr_conic_ff_t sbr_conic_priv_ff_prod(float a, float b);
/* x + y. */
sbr_conic_ff_t sbr_conic_priv_ff_add(sbr_conic_ff_t x, sbr_conic_ff_t y);
/* -x. */
sbr_conic_ff_t sbr_conic_priv_ff_neg(sbr_conic_ff_t x);
/* x * b for a float-float x. */
sbr_conic_ff_t sbr_conic_priv_ff_scale(sbr_conic_ff_t x, float b);
/* a * b - c * d, correctly rounded but for the last bit. */
float sbr_conic_priv_ff_det2(float a, float b, float c, float d);

/* The largest magnitude of the six entries. */
float sbr_conic_priv_max_abs(const sbr_conic_t *q);

/* 1 if all six entries are finite. */
int sbr_conic_priv_finite(const sbr_conic_t *q);

/* The conic q divided by k (a division per entry: correctly rounded, which matters for
   conics far from the origin, whose constant term cancels against the others). */
sbr_conic_t sbr_conic_priv_div(const sbr_conic_t *q, float k);

/* Determinant of a row-major 3 x 3 matrix. */
float sbr_conic_priv_det3(const float m[9]);

/* Solve the n x n system a x = b (n <= 4) by Gaussian elimination with partial pivoting;
   a and b are overwritten. Returns 0 when a pivot is below tiny. */
int sbr_conic_priv_solve(float *a, float *b, uint32_t n, float tiny);

/* Geometry of a conic known to be finite; 0 if it is not a real ellipse. */
int sbr_conic_priv_ellipse_of(const sbr_conic_t *q0, sbr_ellipse_t *el);

/* 1 when the finite conic q is, computed exactly, a real ellipse with el's centre and
   semi-axes (within 1 % of the semi-axis; of the semi-major for the centre). */
int sbr_conic_priv_is_ellipse(const sbr_conic_t *q, const sbr_ellipse_t *el);

/* The conic of an ellipse, unchecked. */
sbr_conic_t sbr_conic_priv_of_ellipse(const sbr_ellipse_t *el);

/* An ellipse in the documented domain whose float32 conic is finite and still this
   ellipse (sbr_conic_priv_is_ellipse()): SBR_OK and the conic, else SBR_ERR_RANGE. */
sbr_status_t sbr_conic_priv_ellipse_checked(const sbr_ellipse_t *el, sbr_conic_t *out);

/* Sampson distance of (x, y) to the conic. */
float sbr_conic_priv_sampson(const sbr_conic_t *q, float x, float y);

/* Finite points within +-SBR_CONIC_MAX_COORD. */
int sbr_conic_priv_points_finite(const sbr_pointf_t *p, uint32_t n);

#endif /* SBR_CONIC_INTERNAL_H */
