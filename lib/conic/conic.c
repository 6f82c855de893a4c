/* SPDX-License-Identifier: MIT */
/* Conics: classification, ellipse geometry, residual and coverage, and the helpers the
   fit (conic_fit.c), the torchlight pose (conic_torch.c) and the detector
   (conic_detect.c) share. See include/sbr/conic.h. */
#include "conic_internal.h"

#include <math.h>
#include <string.h>

#define COVERAGE_SECTORS 64u

/* ---------------------------------------------------------------- small linear algebra */

float sbr_conic_priv_max_abs(const sbr_conic_t *q)
{
    float m = fabsf(q->a);
    const float v[5] = {q->b, q->c, q->d, q->e, q->f};
    uint32_t i;
    for (i = 0u; i < 5u; ++i) {
        m = fmaxf(m, fabsf(v[i]));
    }
    return m;
}

int sbr_conic_priv_finite(const sbr_conic_t *q)
{
    return (isfinite(q->a) != 0) && (isfinite(q->b) != 0) && (isfinite(q->c) != 0) &&
           (isfinite(q->d) != 0) && (isfinite(q->e) != 0) && (isfinite(q->f) != 0);
}

/* The conic q divided by k (a division per entry: correctly rounded, which matters for
   conics far from the origin, whose constant term cancels against the others). */
sbr_conic_t sbr_conic_priv_div(const sbr_conic_t *q, float k)
{
    const sbr_conic_t r = {q->a / k, q->b / k, q->c / k, q->d / k, q->e / k, q->f / k};
    return r;
}

float sbr_conic_priv_det3(const float m[9])
{
    return (m[0] * ((m[4] * m[8]) - (m[5] * m[7]))) - (m[1] * ((m[3] * m[8]) - (m[5] * m[6]))) +
           (m[2] * ((m[3] * m[7]) - (m[4] * m[6])));
}

static void conic_matrix(const sbr_conic_t *q, float s, float m[9])
{
    m[0] = q->a * s;
    m[1] = q->b * s;
    m[2] = q->d * s;
    m[3] = q->b * s;
    m[4] = q->c * s;
    m[5] = q->e * s;
    m[6] = q->d * s;
    m[7] = q->e * s;
    m[8] = q->f * s;
}

/* Solve the n x n system a x = b (n <= 4) by Gaussian elimination with partial pivoting;
   a and b are overwritten. Returns 0 when a pivot is below tiny. */
int sbr_conic_priv_solve(float *a, float *b, uint32_t n, float tiny)
{
    uint32_t col;
    int ok = 1;
    for (col = 0u; (col < n) && (ok != 0); ++col) {
        uint32_t piv = col;
        uint32_t r;
        for (r = col + 1u; r < n; ++r) {
            if (fabsf(a[(r * n) + col]) > fabsf(a[(piv * n) + col])) {
                piv = r;
            }
        }
        if (fabsf(a[(piv * n) + col]) <= tiny) {
            ok = 0;
        } else {
            uint32_t k;
            if (piv != col) {
                for (k = 0u; k < n; ++k) {
                    const float t = a[(col * n) + k];
                    a[(col * n) + k] = a[(piv * n) + k];
                    a[(piv * n) + k] = t;
                }
                {
                    const float t = b[col];
                    b[col] = b[piv];
                    b[piv] = t;
                }
            }
            for (r = col + 1u; r < n; ++r) {
                const float fct = a[(r * n) + col] / a[(col * n) + col];
                for (k = col; k < n; ++k) {
                    a[(r * n) + k] -= fct * a[(col * n) + k];
                }
                b[r] -= fct * b[col];
            }
        }
    }
    if (ok != 0) {
        uint32_t i = n;
        while (i > 0u) {
            uint32_t k;
            float s;
            --i;
            s = b[i];
            for (k = i + 1u; k < n; ++k) {
                s -= a[(i * n) + k] * b[k];
            }
            b[i] = s / a[(i * n) + i];
        }
    }
    return ok;
}

/* What the conic's centre gives: the conic scaled by a power of two (exact) so that its
   quadratic part's largest entry is in [0.5, 1) and a + c >= 0; det(C22); det(C) in
   float-float (so its sign is right even where its terms cancel, a thin ellipse far from
   the origin); and det(C22) times the terms the value at the centre is summed from,
   |d xnum| + |e ynum| + |f det(C22)| (xnum, ynum the centre's numerators): the zero rule
   |f0| <= tol (|d xc| + |e yc| + |f|) without dividing, so a centre beyond float32's
   range does not matter to the class. */
typedef struct conic_centre_s {
    sbr_conic_t q;
    float d22;
    float xnum;
    float ynum;
    float det;
    float terms22;
} conic_centre_t;

/* Largest |d|, |e| and |f| of the scaled conic that the float-float determinant takes
   without overflow (a centre about 10^15 from the origin in units of the quadratic part). */
#define CONIC_MAX_LINEAR 1.1259e15f /* 2^50 */
#define CONIC_MAX_CONST 1.2676e30f  /* 2^100 */

/* Entries below 2^-33 of the scaled quadratic part count as zero (conic.h): the
   float-float products of three entries then stay normal floats (>= 2^-99, their low
   parts >= 2^-123), so det(C) keeps its 2^-40 relative accuracy. */
#define CONIC_FLUSH 1.16415322e-10f /* 2^-33 */

static float conic_flush(float v)
{
    return (fabsf(v) < CONIC_FLUSH) ? 0.0f : v;
}

/* The scaled conic and det(C22) of a finite conic with a non-zero quadratic part. */
static void conic_scaled(const sbr_conic_t *q0, conic_centre_t *cc)
{
    const float qa = fmaxf(fabsf(q0->a), fmaxf(fabsf(q0->b), fabsf(q0->c)));
    const float sg = ((q0->a + q0->c) < 0.0f) ? -1.0f : 1.0f;
    int ex = 0;
    (void)frexpf(qa, &ex);
    /* each entry times 2^-ex (ldexpf: exact, also where 2^-ex itself is beyond float32,
       as for a subnormal quadratic part) */
    cc->q.a = conic_flush(sg * ldexpf(q0->a, -ex));
    cc->q.b = conic_flush(sg * ldexpf(q0->b, -ex));
    cc->q.c = conic_flush(sg * ldexpf(q0->c, -ex));
    cc->q.d = conic_flush(sg * ldexpf(q0->d, -ex));
    cc->q.e = conic_flush(sg * ldexpf(q0->e, -ex));
    cc->q.f = conic_flush(sg * ldexpf(q0->f, -ex));
    cc->d22 = sbr_conic_priv_ff_det2(cc->q.a, cc->q.c, cc->q.b, cc->q.b);
}

/* det(C), the centre's numerators and the zero rule's terms of the scaled conic; 0 when
   its linear or constant terms are beyond what the float-float products take. */
static int conic_centre(conic_centre_t *cc)
{
    const sbr_conic_t *q = &cc->q;
    int ok = 0;
    if ((fabsf(q->d) <= CONIC_MAX_LINEAR) && (fabsf(q->e) <= CONIC_MAX_LINEAR) &&
        (fabsf(q->f) <= CONIC_MAX_CONST)) {
        /* det(C) = a (c f - e^2) - b (b f - d e) + d (b e - c d) */
        const sbr_conic_ff_t m1 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(q->c, q->f), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(q->e, q->e)));
        const sbr_conic_ff_t m2 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(q->b, q->f), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(q->d, q->e)));
        const sbr_conic_ff_t m3 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(q->b, q->e), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(q->c, q->d)));
        const sbr_conic_ff_t det =
            sbr_conic_priv_ff_add(sbr_conic_priv_ff_add(sbr_conic_priv_ff_scale(m1, q->a), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_scale(m2, q->b))), sbr_conic_priv_ff_scale(m3, q->d));
        cc->xnum = m3.hi + m3.lo;
        cc->ynum = sbr_conic_priv_ff_det2(q->b, q->d, q->a, q->e);
        cc->det = det.hi + det.lo;
        cc->terms22 = fabsf(q->d * cc->xnum) + fabsf(q->e * cc->ynum) + fabsf(q->f * cc->d22);
        if ((isfinite(cc->det) != 0) && (isfinite(cc->terms22) != 0)) {
            ok = 1;
        }
    }
    return ok;
}

/* ---------------------------------------------------------------- classification */

/* Below this share of the terms they are summed from, a determinant or minor computed in
   float-float is indistinguishable from zero (its error is about 2^-44 of those terms):
   it counts as zero at every tolerance, tol = 0 included (conic.h). */
#define CONIC_EXACT_FLOOR 9.09494702e-13f /* 2^-40 */

/* The sign of v 2^k + w 2^j, each term kept with an exponent of its own: both are scaled
   to the larger one's exponent (the larger then in [0.5, 1); the smaller underflows only
   when it is below 2^-126 of the other, where it cannot change the sign). */
static float sum_scaled(float v, int k, float w, int j)
{
    float s;
    if (v == 0.0f) {
        s = w;
    } else if (w == 0.0f) {
        s = v;
    } else {
        int ev = 0;
        int ew = 0;
        int top;
        (void)frexpf(v, &ev);
        (void)frexpf(w, &ew);
        top = ev + k;
        if ((ew + j) > top) {
            top = ew + j;
        }
        s = ldexpf(v, k - top) + ldexpf(w, j - top);
    }
    return s;
}

/* The 2 x 2 minor of rows (i, j) and columns (k, l) of a row-major 3 x 3 matrix, in
   float-float; `terms` gets |m_ik m_jl| + |m_il m_jk|. */
static float minor2(const float m[9], uint32_t i, uint32_t j, uint32_t k, uint32_t l, float *terms)
{
    *terms = fabsf(m[(i * 3u) + k] * m[(j * 3u) + l]) + fabsf(m[(i * 3u) + l] * m[(j * 3u) + k]);
    return sbr_conic_priv_ff_det2(m[(i * 3u) + k], m[(j * 3u) + l], m[(i * 3u) + l], m[(j * 3u) + k]);
}

/* 1 when every 2 x 2 minor of C / max vanishes (rank 1): zero to within float-float's
   reach, or at most tol. M is C with row i scaled by 2^r[i] (a minor of rows i, j of M is
   2^(r[i] + r[j]) times C's), 2^mx the power of two of C's largest entry, mant that entry
   over 2^mx, in [0.5, 1). */
static int no_centre_rank1(const float m[9], const int r[3], int mx, float mant, float tol)
{
    const uint8_t rows[3][2] = {{0u, 1u}, {0u, 2u}, {1u, 2u}};
    int rank1 = 1;
    uint32_t a;
    uint32_t b;
    for (a = 0u; a < 3u; ++a) {
        for (b = 0u; b < 3u; ++b) {
            const uint32_t ri = rows[a][0];
            const uint32_t rj = rows[a][1];
            float mt;
            const float mn = minor2(m, ri, rj, rows[b][0], rows[b][1], &mt);
            /* the minor of C / 2^mx; that of conic.h's C / max is it over mant^2 */
            const float scaled = ldexpf(mn, -(r[ri] + r[rj]) - (2 * mx));
            if ((fabsf(mn) > (CONIC_EXACT_FLOOR * mt)) && ((tol <= 0.0f) || (fabsf(scaled) > (tol * mant * mant)))) {
                rank1 = 0;
            }
        }
    }
    return rank1;
}

/* No centre (det(C22) counts as zero): parabola or a pair of lines. Each row i of C is
   scaled exactly by its own power of two 2^r[i] (its largest entry into [0.5, 1)), so
   that products neither overflow nor underflow whatever the entries' range; det(C), the
   2 x 2 minors and the principal minors are taken in float-float on that matrix, and the
   row scales put back as exponents. The rules are conic.h's, on C scaled to a largest
   entry of 1 (the determinant's is scale-free: |det| against the product of the rows'
   norms). */
static sbr_conic_class_t classify_no_centre(const sbr_conic_t *conic, float tol)
{
    sbr_conic_class_t cls;
    float c[9];
    float m[9];
    int r[3];
    float norm[3];
    float terms;
    float det;
    int mx = 0;
    uint32_t i;
    uint32_t j;
    conic_matrix(conic, 1.0f, c);
    (void)frexpf(sbr_conic_priv_max_abs(conic), &mx);
    for (i = 0u; i < 3u; ++i) {
        float rowmax = 0.0f;
        int ex = 0;
        float sq = 0.0f;
        for (j = 0u; j < 3u; ++j) {
            rowmax = fmaxf(rowmax, fabsf(c[(i * 3u) + j]));
        }
        if (rowmax > 0.0f) {
            (void)frexpf(rowmax, &ex);
        }
        r[i] = -ex;
        for (j = 0u; j < 3u; ++j) {
            m[(i * 3u) + j] = ldexpf(c[(i * 3u) + j], r[i]);
            sq += m[(i * 3u) + j] * m[(i * 3u) + j];
        }
        norm[i] = sqrtf(sq);
    }
    {
        /* det(M) = m0 (m4 m8 - m5 m7) - m1 (m3 m8 - m5 m6) + m2 (m3 m7 - m4 m6) */
        float t1;
        float t2;
        float t3;
        const sbr_conic_ff_t k1 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(m[4], m[8]), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(m[5], m[7])));
        const sbr_conic_ff_t k2 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(m[3], m[8]), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(m[5], m[6])));
        const sbr_conic_ff_t k3 = sbr_conic_priv_ff_add(sbr_conic_priv_ff_prod(m[3], m[7]), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_prod(m[4], m[6])));
        const sbr_conic_ff_t dd = sbr_conic_priv_ff_add(sbr_conic_priv_ff_add(sbr_conic_priv_ff_scale(k1, m[0]), sbr_conic_priv_ff_neg(sbr_conic_priv_ff_scale(k2, m[1]))), sbr_conic_priv_ff_scale(k3, m[2]));
        (void)minor2(m, 1u, 2u, 1u, 2u, &t1);
        (void)minor2(m, 1u, 2u, 0u, 2u, &t2);
        (void)minor2(m, 1u, 2u, 0u, 1u, &t3);
        det = dd.hi + dd.lo;
        terms = (fabsf(m[0]) * t1) + (fabsf(m[1]) * t2) + (fabsf(m[2]) * t3);
    }
    /* det(C / max) against the product of its rows' norms is det(M) against M's */
    if ((fabsf(det) <= (CONIC_EXACT_FLOOR * terms)) || (fabsf(det) <= (tol * norm[0] * norm[1] * norm[2]))) {
        /* rank 1 when every 2 x 2 minor of C / max vanishes */
        const int rank1 = no_centre_rank1(m, r, mx, ldexpf(sbr_conic_priv_max_abs(conic), -mx), tol);
        if (rank1 != 0) {
            cls = SBR_CONIC_DOUBLE_LINE;
        } else {
            /* the product of the two non-zero eigenvalues: the principal minors of rows
               (1, 2) and (0, 2) (the third, det(C22), is zero), each 2^-(r[i] + r[j]) times
               M's; < 0: two real parallel lines, > 0: imaginary */
            float t;
            const float p12 = minor2(m, 1u, 2u, 1u, 2u, &t);
            const float p02 = minor2(m, 0u, 2u, 0u, 2u, &t);
            const float cof = sum_scaled(p12, -(r[1] + r[2]), p02, -(r[0] + r[2]));
            cls = (cof < 0.0f) ? SBR_CONIC_PARALLEL_LINES : SBR_CONIC_IMAGINARY_PARALLEL_LINES;
        }
    } else {
        cls = SBR_CONIC_PARABOLA;
    }
    return cls;
}

sbr_status_t sbr_conic_classify(const sbr_conic_t *conic, float tol, sbr_conic_class_t *cls)
{
    sbr_status_t st = SBR_OK;
    if ((conic == NULL) || (cls == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((sbr_conic_priv_finite(conic) == 0) || (isfinite(tol) == 0) || (tol < 0.0f) ||
               (tol >= 1.0f)) {
        st = SBR_ERR_RANGE;
    } else if (sbr_conic_priv_max_abs(conic) <= 0.0f) {
        st = SBR_ERR_DEGENERATE;
    } else {
        conic_centre_t cc;
        const float qa = fmaxf(fabsf(conic->a), fmaxf(fabsf(conic->b), fabsf(conic->c)));
        (void)memset(&cc, 0, sizeof cc);
        if (qa > 0.0f) {
            float qs;
            conic_scaled(conic, &cc);
            qs = fmaxf(fabsf(cc.q.a), fmaxf(fabsf(cc.q.b), fabsf(cc.q.c)));
            /* det(C22) relative to the quadratic part's own scale */
            if (fabsf(cc.d22) <= (tol * qs * qs)) {
                cc.d22 = 0.0f;
            }
        }
        if (cc.d22 == 0.0f) {
            *cls = classify_no_centre(conic, tol);
        } else if (conic_centre(&cc) == 0) {
            st = SBR_ERR_RANGE; /* linear or constant terms beyond the products' reach */
        } else {
            /* det(C) = det(C22) f0: f0 counts as zero relative to the terms it is summed
               from (both sides times |det(C22)|); a + c > 0 in the scaled conic, so a
               real ellipse has f0 < 0, i.e. det(C) < 0 */
            int zero = 0;
            if ((fabsf(cc.det) <= (tol * cc.terms22)) || (cc.terms22 <= 0.0f)) {
                zero = 1;
            }
            if (cc.d22 > 0.0f) {
                if (zero != 0) {
                    *cls = SBR_CONIC_POINT_ELLIPSE;
                } else if (cc.det < 0.0f) {
                    *cls = SBR_CONIC_REAL_ELLIPSE;
                } else {
                    *cls = SBR_CONIC_IMAGINARY_ELLIPSE;
                }
            } else {
                *cls = (zero != 0) ? SBR_CONIC_INTERSECTING_LINES : SBR_CONIC_HYPERBOLA;
            }
        }
    }
    return st;
}

/* ---------------------------------------------------------------- ellipse geometry */

/* Geometry of a conic known to be finite; 0 if it is not a real ellipse. */
int sbr_conic_priv_ellipse_of(const sbr_conic_t *q0, sbr_ellipse_t *el)
{
    const float m = fmaxf(fabsf(q0->a), fmaxf(fabsf(q0->b), fabsf(q0->c)));
    int ok = 0;
    conic_centre_t cc;
    float qs = 0.0f;
    (void)memset(&cc, 0, sizeof cc);
    if (m > 0.0f) {
        conic_scaled(q0, &cc);
        qs = fmaxf(fabsf(cc.q.a), fmaxf(fabsf(cc.q.b), fabsf(cc.q.c)));
    }
    /* quadratic part scaled to [0.5, 1), a + c > 0 */
    if ((m > 0.0f) && (cc.d22 > (SBR_CONIC_ZERO_TOL * 1e-2f * qs * qs)) && (conic_centre(&cc) != 0) &&
        (cc.det < 0.0f)) {
        const sbr_conic_t *q = &cc.q;
        const float f0 = cc.det / cc.d22; /* the value at the centre, accurate */
        const float h = 0.5f * (q->a - q->c);
        const float r = sqrtf((h * h) + (q->b * q->b));
        const float lmax = (0.5f * (q->a + q->c)) + r;
        const float lmin = cc.d22 / lmax; /* the major axis's; no cancellation */
        float vx;
        float vy;
        float ang;
        /* eigenvector of lmin: (b, lmin - a) or (lmin - c, b), the longer one */
        const float ax = q->b;
        const float ay = lmin - q->a;
        const float bx = lmin - q->c;
        const float by = q->b;
        if (((ax * ax) + (ay * ay)) >= ((bx * bx) + (by * by))) {
            vx = ax;
            vy = ay;
        } else {
            vx = bx;
            vy = by;
        }
        if (((vx * vx) + (vy * vy)) <= 0.0f) {
            vx = 1.0f; /* a circle */
            vy = 0.0f;
        }
        ang = atan2f(vy, vx);
        if (ang <= (-0.5f * SBR_PI_F)) {
            ang += SBR_PI_F;
        } else if (ang > (0.5f * SBR_PI_F)) {
            ang -= SBR_PI_F;
        } else {
            /* in range */
        }
        el->cx = cc.xnum / cc.d22;
        el->cy = cc.ynum / cc.d22;
        el->semi_major = sqrtf(-f0 / lmin);
        el->semi_minor = sqrtf(-f0 / lmax);
        el->angle = ang;
        if ((lmin > 0.0f) && (isfinite(el->semi_major) != 0) && (el->semi_minor > 0.0f) &&
            (isfinite(el->cx) != 0) && (isfinite(el->cy) != 0)) {
            ok = 1;
        }
    }
    return ok;
}

/* The conic of an ellipse, unchecked. */
sbr_conic_t sbr_conic_priv_of_ellipse(const sbr_ellipse_t *el)
{
    const float cs = cosf(el->angle);
    const float sn = sinf(el->angle);
    const float ia = 1.0f / (el->semi_major * el->semi_major);
    const float ib = 1.0f / (el->semi_minor * el->semi_minor);
    const float a = (cs * cs * ia) + (sn * sn * ib);
    const float b = cs * sn * (ia - ib);
    const float c = (sn * sn * ia) + (cs * cs * ib);
    const float x = el->cx;
    const float y = el->cy;
    sbr_conic_t q;
    q.a = a;
    q.b = b;
    q.c = c;
    q.d = -((a * x) + (b * y));
    q.e = -((b * x) + (c * y));
    q.f = ((a * x * x) + (2.0f * b * x * y) + (c * y * y)) - 1.0f;
    return q;
}

/* Largest relative change of a semi-axis, and of the centre in units of the semi-major
   axis, between an ellipse and the exact geometry of its float32 conic. */
#define CONIC_GEOMETRY_TOL 1e-2f

/* 1 when the finite conic q is, computed exactly (float-float f0), a real ellipse with
   el's centre and semi-axes within CONIC_GEOMETRY_TOL. */
int sbr_conic_priv_is_ellipse(const sbr_conic_t *q, const sbr_ellipse_t *el)
{
    sbr_ellipse_t back;
    return ((sbr_conic_priv_ellipse_of(q, &back) != 0) &&
            (fabsf(back.semi_major - el->semi_major) <= (CONIC_GEOMETRY_TOL * el->semi_major)) &&
            (fabsf(back.semi_minor - el->semi_minor) <= (CONIC_GEOMETRY_TOL * el->semi_minor)) &&
            (fabsf(back.cx - el->cx) <= (CONIC_GEOMETRY_TOL * el->semi_major)) &&
            (fabsf(back.cy - el->cy) <= (CONIC_GEOMETRY_TOL * el->semi_major)))
               ? 1
               : 0;
}

/* An ellipse in the documented domain whose float32 conic is finite and has, computed
   exactly (float-float f0), this ellipse's centre and semi-axes within
   CONIC_GEOMETRY_TOL: SBR_OK and the conic, else SBR_ERR_RANGE. */
sbr_status_t sbr_conic_priv_ellipse_checked(const sbr_ellipse_t *el, sbr_conic_t *out)
{
    sbr_status_t st = SBR_OK;
    if ((isfinite(el->cx) == 0) || (isfinite(el->cy) == 0) || (isfinite(el->angle) == 0) ||
        (isfinite(el->semi_major) == 0) || (isfinite(el->semi_minor) == 0) ||
        (fabsf(el->cx) > SBR_CONIC_MAX_COORD) || (fabsf(el->cy) > SBR_CONIC_MAX_COORD) ||
        (el->semi_minor < SBR_CONIC_MIN_AXIS) || (el->semi_minor > el->semi_major) ||
        (el->semi_major > SBR_CONIC_MAX_COORD)) {
        st = SBR_ERR_RANGE;
    } else {
        const sbr_conic_t q = sbr_conic_priv_of_ellipse(el);
        /* float32 cannot hold every such conic (a thin ellipse far from the origin loses
           its constant term): refuse one that is not finite, is no real ellipse, or is
           another ellipse */
        if ((sbr_conic_priv_finite(&q) == 0) || (sbr_conic_priv_is_ellipse(&q, el) == 0)) {
            st = SBR_ERR_RANGE;
        } else {
            *out = q;
        }
    }
    return st;
}

sbr_status_t sbr_conic_to_ellipse(const sbr_conic_t *conic, sbr_ellipse_t *ellipse)
{
    sbr_status_t st = SBR_OK;
    sbr_conic_class_t cls = SBR_CONIC_REAL_ELLIPSE;
    if ((conic == NULL) || (ellipse == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        sbr_ellipse_t el = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        st = sbr_conic_classify(conic, SBR_CONIC_ZERO_TOL, &cls);
        if ((st == SBR_OK) && (cls != SBR_CONIC_REAL_ELLIPSE)) {
            st = SBR_ERR_DEGENERATE;
        } else if ((st == SBR_OK) && (sbr_conic_priv_ellipse_of(conic, &el) == 0)) {
            st = SBR_ERR_RANGE; /* a real ellipse whose centre or axes float32 cannot hold */
        } else {
            /* st as classified */
        }
        if (st == SBR_OK) {
            sbr_conic_t back;
            /* the geometry must be one that sbr_ellipse_to_conic() takes back */
            if (sbr_conic_priv_ellipse_checked(&el, &back) != SBR_OK) {
                st = SBR_ERR_RANGE;
            } else {
                *ellipse = el;
            }
        }
    }
    return st;
}

sbr_status_t sbr_ellipse_to_conic(const sbr_ellipse_t *ellipse, sbr_conic_t *conic)
{
    sbr_status_t st = SBR_OK;
    if ((ellipse == NULL) || (conic == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        st = sbr_conic_priv_ellipse_checked(ellipse, conic);
    }
    return st;
}

/* ---------------------------------------------------------------- Sampson distance */

/* Sampson distance of (x, y) to the conic. */
float sbr_conic_priv_sampson(const sbr_conic_t *q, float x, float y)
{
    const float gx = (q->a * x) + (q->b * y) + q->d;
    const float gy = (q->b * x) + (q->c * y) + q->e;
    const float val = (x * gx) + (y * gy) + (q->d * x) + (q->e * y) + q->f;
    const float g = 2.0f * sqrtf((gx * gx) + (gy * gy));
    return (g > 0.0f) ? (fabsf(val) / g) : INFINITY;
}

/* ---------------------------------------------------------------- residual, coverage */

/* Finite points within +-SBR_CONIC_MAX_COORD. */
int sbr_conic_priv_points_finite(const sbr_pointf_t *p, uint32_t n)
{
    uint32_t i;
    int ok = 1;
    for (i = 0u; (i < n) && (ok != 0); ++i) {
        if ((isfinite(p[i].x) == 0) || (isfinite(p[i].y) == 0) ||
            (fabsf(p[i].x) > SBR_CONIC_MAX_COORD) || (fabsf(p[i].y) > SBR_CONIC_MAX_COORD)) {
            ok = 0;
        }
    }
    return ok;
}

sbr_status_t sbr_conic_residual(const sbr_conic_t *conic, const sbr_pointf_t *points,
                                uint32_t n, float *rms, float *max_abs)
{
    sbr_status_t st = SBR_OK;
    if ((conic == NULL) || (points == NULL) || (rms == NULL)) {
        st = SBR_ERR_NULL;
    } else if (n == 0u) {
        st = SBR_ERR_SIZE;
    } else if ((sbr_conic_priv_finite(conic) == 0) || (sbr_conic_priv_points_finite(points, n) == 0)) {
        st = SBR_ERR_RANGE;
    } else {
        /* evaluate around the points' first point to limit cancellation */
        const float ox = points[0].x;
        const float oy = points[0].y;
        sbr_conic_t q = *conic;
        float acc = 0.0f;
        float mx = 0.0f;
        uint32_t i;
        q.d = (conic->a * ox) + (conic->b * oy) + conic->d;
        q.e = (conic->b * ox) + (conic->c * oy) + conic->e;
        q.f = (conic->a * ox * ox) + (2.0f * conic->b * ox * oy) + (conic->c * oy * oy) +
              (2.0f * conic->d * ox) + (2.0f * conic->e * oy) + conic->f;
        for (i = 0u; i < n; ++i) {
            const float dd = sbr_conic_priv_sampson(&q, points[i].x - ox, points[i].y - oy);
            acc += dd * dd;
            mx = fmaxf(mx, dd);
        }
        /* a NaN or infinite distance makes the sum non-finite, whatever fmaxf kept */
        if (isfinite(acc) == 0) {
            st = SBR_ERR_RANGE; /* a conic whose values overflow float32 at these points */
        } else {
            *rms = sqrtf(acc / (float)n);
            if (max_abs != NULL) {
                *max_abs = mx;
            }
        }
    }
    return st;
}

sbr_status_t sbr_ellipse_coverage(const sbr_conic_t *conic, const sbr_pointf_t *points,
                                  uint32_t n, float tol, float *coverage)
{
    sbr_status_t st = SBR_OK;
    sbr_ellipse_t el = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    if ((conic == NULL) || (points == NULL) || (coverage == NULL)) {
        st = SBR_ERR_NULL;
    } else if (n == 0u) {
        st = SBR_ERR_SIZE;
    } else if ((sbr_conic_priv_finite(conic) == 0) || (sbr_conic_priv_points_finite(points, n) == 0) ||
               (isfinite(tol) == 0) || (tol <= 0.0f)) {
        st = SBR_ERR_RANGE;
    } else {
        st = sbr_conic_to_ellipse(conic, &el);
    }
    if (st == SBR_OK) {
        sbr_conic_t q; /* the same ellipse, centred at its centre */
        uint32_t hit[2] = {0u, 0u};
        uint32_t filled = 0u;
        uint32_t i;
        const float cs = cosf(el.angle);
        const float sn = sinf(el.angle);
        /* el passed sbr_conic_to_ellipse()'s checks, so its axes give a finite conic at
           the origin: no second check */
        const sbr_ellipse_t centred = {0.0f, 0.0f, el.semi_major, el.semi_minor, el.angle};
        q = sbr_conic_priv_of_ellipse(&centred);
        for (i = 0u; i < n; ++i) {
            const float dx = points[i].x - el.cx;
            const float dy = points[i].y - el.cy;
            if (sbr_conic_priv_sampson(&q, dx, dy) <= tol) {
                const float u = ((dx * cs) + (dy * sn)) / el.semi_major;
                const float v = ((dy * cs) - (dx * sn)) / el.semi_minor;
                const float t = atan2f(v, u) + SBR_PI_F;
                const float fsec = (t / (2.0f * SBR_PI_F)) * (float)COVERAGE_SECTORS;
                uint32_t sec = (uint32_t)fsec;
                if (sec >= COVERAGE_SECTORS) {
                    sec = COVERAGE_SECTORS - 1u;
                }
                hit[sec / 32u] |= (uint32_t)1u << (sec % 32u);
            }
        }
        for (i = 0u; i < COVERAGE_SECTORS; ++i) {
            if ((hit[i / 32u] & ((uint32_t)1u << (i % 32u))) != 0u) {
                ++filled;
            }
        }
        *coverage = (float)filled / (float)COVERAGE_SECTORS;
    }
    return st;
}
