/* Conics: classification, ellipse geometry, direct least-squares fit (Halir-Flusser),
   residual, coverage, torchlight pose, ellipse detection. See include/sbr/conic.h. */
#include "sbr/conic.h"

#include <math.h>

#include "../common/sbr_util.h"

#define CONIC_PI 3.14159265358979f
#define COVERAGE_SECTORS 64u
/* largest rms Sampson distance of a fit, relative to the points' mean distance from
   their centroid */
/* Torchlight least squares: weight of the quadratic entries (11, 12, 22: the ellipse's
   elongation, poorly conditioned for distant planes) against the linear and constant
   ones (13, 23, 33: its centre and size). */
#define TORCH_WQ 0.1f
#define FIT_MAX_MISS 0.5f

/* ---------------------------------------------------------------- small linear algebra */

static float max_abs_entry(const sbr_conic_t *q)
{
    float m = fabsf(q->a);
    const float v[5] = {q->b, q->c, q->d, q->e, q->f};
    uint32_t i;
    for (i = 0u; i < 5u; ++i) {
        m = fmaxf(m, fabsf(v[i]));
    }
    return m;
}

static int conic_finite(const sbr_conic_t *q)
{
    return (isfinite(q->a) != 0) && (isfinite(q->b) != 0) && (isfinite(q->c) != 0) &&
           (isfinite(q->d) != 0) && (isfinite(q->e) != 0) && (isfinite(q->f) != 0);
}

/* The conic q divided by k (a division per entry: correctly rounded, which matters for
   conics far from the origin, whose constant term cancels against the others). */
static sbr_conic_t conic_div(const sbr_conic_t *q, float k)
{
    const sbr_conic_t r = {q->a / k, q->b / k, q->c / k, q->d / k, q->e / k, q->f / k};
    return r;
}

static float det3(const float m[9])
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
static int solve_small(float *a, float *b, uint32_t n, float tiny)
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

/* ---------------------------------------------------------------- classification */

sbr_status_t sbr_conic_classify(const sbr_conic_t *conic, float tol, sbr_conic_class_t *cls)
{
    sbr_status_t st = SBR_OK;
    if ((conic == NULL) || (cls == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((conic_finite(conic) == 0) || (isfinite(tol) == 0) || (tol < 0.0f) ||
               (tol >= 1.0f)) {
        st = SBR_ERR_RANGE;
    } else if (max_abs_entry(conic) <= 0.0f) {
        st = SBR_ERR_DEGENERATE;
    } else {
        const float m = max_abs_entry(conic);
        const float qa = fmaxf(fabsf(conic->a), fmaxf(fabsf(conic->b), fabsf(conic->c)));
        float c[9];
        float d22 = 0.0f;
        conic_matrix(conic, 1.0f / m, c);
        if (qa > 0.0f) {
            /* det(C22) relative to the quadratic part's own scale */
            const float a = conic->a / qa;
            const float b = conic->b / qa;
            const float cc = conic->c / qa;
            d22 = (a * cc) - (b * b);
            if (fabsf(d22) <= tol) {
                d22 = 0.0f;
            }
        }
        if (d22 != 0.0f) {
            /* a centre exists: det(C) = det(C22) * f0 with f0 the value at the centre;
               f0 counts as zero relative to the terms it is summed from */
            const float det = (conic->a * conic->c) - (conic->b * conic->b);
            const float xc = ((conic->b * conic->e) - (conic->c * conic->d)) / det;
            const float yc = ((conic->b * conic->d) - (conic->a * conic->e)) / det;
            const float f0 = (conic->d * xc) + (conic->e * yc) + conic->f;
            const float terms = fabsf(conic->d * xc) + fabsf(conic->e * yc) + fabsf(conic->f);
            int zero = 0;
            if ((fabsf(f0) <= (tol * terms)) || (terms <= 0.0f)) {
                zero = 1;
            }
            if (d22 > 0.0f) {
                if (zero != 0) {
                    *cls = SBR_CONIC_POINT_ELLIPSE;
                } else if (((conic->a + conic->c) * f0) < 0.0f) {
                    *cls = SBR_CONIC_REAL_ELLIPSE;
                } else {
                    *cls = SBR_CONIC_IMAGINARY_ELLIPSE;
                }
            } else {
                *cls = (zero != 0) ? SBR_CONIC_INTERSECTING_LINES : SBR_CONIC_HYPERBOLA;
            }
        } else {
            /* no centre: det(C) relative to the product of the row norms (Hadamard) */
            const float n0 = sqrtf((c[0] * c[0]) + (c[1] * c[1]) + (c[2] * c[2]));
            const float n1 = sqrtf((c[3] * c[3]) + (c[4] * c[4]) + (c[5] * c[5]));
            const float n2 = sqrtf((c[6] * c[6]) + (c[7] * c[7]) + (c[8] * c[8]));
            const float d33 = det3(c);
            if (fabsf(d33) > (tol * n0 * n1 * n2)) {
                *cls = SBR_CONIC_PARABOLA;
            } else {
                /* rank 1 when every 2 x 2 minor vanishes */
                const float minors[6] = {(c[0] * c[4]) - (c[1] * c[3]), (c[0] * c[5]) - (c[2] * c[3]),
                                         (c[0] * c[8]) - (c[2] * c[6]), (c[4] * c[8]) - (c[5] * c[7]),
                                         (c[1] * c[5]) - (c[2] * c[4]), (c[3] * c[7]) - (c[4] * c[6])};
                float mm = 0.0f;
                uint32_t i;
                for (i = 0u; i < 6u; ++i) {
                    mm = fmaxf(mm, fabsf(minors[i]));
                }
                if (mm <= tol) {
                    *cls = SBR_CONIC_DOUBLE_LINE;
                } else {
                    /* cofactor sum < 0: two real parallel lines, > 0: imaginary */
                    const float cof = ((c[4] * c[8]) - (c[5] * c[5])) + ((c[0] * c[8]) - (c[2] * c[2]));
                    *cls = (cof < 0.0f) ? SBR_CONIC_PARALLEL_LINES
                                        : SBR_CONIC_IMAGINARY_PARALLEL_LINES;
                }
            }
        }
    }
    return st;
}

/* ---------------------------------------------------------------- ellipse geometry */

/* Geometry of a conic known to be finite; 0 if it is not a real ellipse. */
static int ellipse_of(const sbr_conic_t *q0, sbr_ellipse_t *el)
{
    const float m = fmaxf(fabsf(q0->a), fmaxf(fabsf(q0->b), fabsf(q0->c)));
    int ok = 0;
    if (m > 0.0f) {
        /* quadratic part at unit scale, a + c > 0 */
        const float k = ((q0->a + q0->c) < 0.0f) ? -m : m;
        const sbr_conic_t q = conic_div(q0, k);
        const float d22 = (q.a * q.c) - (q.b * q.b);
        if (d22 > (SBR_CONIC_ZERO_TOL * 1e-2f)) {
            const float xc = ((q.b * q.e) - (q.c * q.d)) / d22;
            const float yc = ((q.b * q.d) - (q.a * q.e)) / d22;
            const float f0 = (q.d * xc) + (q.e * yc) + q.f;
            const float h = 0.5f * (q.a - q.c);
            const float r = sqrtf((h * h) + (q.b * q.b));
            const float lmin = (0.5f * (q.a + q.c)) - r; /* major axis */
            const float lmax = (0.5f * (q.a + q.c)) + r;
            if ((f0 < 0.0f) && (lmin > 0.0f) && (isfinite(xc) != 0) && (isfinite(yc) != 0)) {
                float vx;
                float vy;
                float ang;
                /* eigenvector of lmin: (b, lmin - a) or (lmin - c, b), the longer one */
                const float ax = q.b;
                const float ay = lmin - q.a;
                const float bx = lmin - q.c;
                const float by = q.b;
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
                if (ang <= (-0.5f * CONIC_PI)) {
                    ang += CONIC_PI;
                } else if (ang > (0.5f * CONIC_PI)) {
                    ang -= CONIC_PI;
                } else {
                    /* in range */
                }
                el->cx = xc;
                el->cy = yc;
                el->semi_major = sqrtf(-f0 / lmin);
                el->semi_minor = sqrtf(-f0 / lmax);
                el->angle = ang;
                if (isfinite(el->semi_major) != 0) {
                    ok = 1;
                }
            }
        }
    }
    return ok;
}

/* The conic of an ellipse, unchecked. */
static sbr_conic_t conic_of(const sbr_ellipse_t *el)
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

/* An ellipse in the documented domain whose conic is finite and still has an ellipse's
   geometry (centre, axes): SBR_OK and the conic, else SBR_ERR_RANGE. */
static sbr_status_t ellipse_conic_checked(const sbr_ellipse_t *el, sbr_conic_t *out)
{
    sbr_status_t st = SBR_OK;
    if ((isfinite(el->cx) == 0) || (isfinite(el->cy) == 0) || (isfinite(el->angle) == 0) ||
        (isfinite(el->semi_major) == 0) || (isfinite(el->semi_minor) == 0) ||
        (fabsf(el->cx) > SBR_CONIC_MAX_COORD) || (fabsf(el->cy) > SBR_CONIC_MAX_COORD) ||
        (el->semi_minor < SBR_CONIC_MIN_AXIS) || (el->semi_minor > el->semi_major) ||
        (el->semi_major > SBR_CONIC_MAX_COORD)) {
        st = SBR_ERR_RANGE;
    } else {
        const sbr_conic_t q = conic_of(el);
        sbr_ellipse_t back;
        /* float32 cannot hold every such conic (a very thin ellipse far from the origin
           loses its centre term): refuse one that is not finite or has no ellipse's
           geometry any more */
        if ((conic_finite(&q) == 0) || (ellipse_of(&q, &back) == 0)) {
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
        if ((st == SBR_OK) && ((cls != SBR_CONIC_REAL_ELLIPSE) || (ellipse_of(conic, &el) == 0))) {
            st = SBR_ERR_DEGENERATE;
        }
        if (st == SBR_OK) {
            sbr_conic_t back;
            /* the geometry must be one that sbr_ellipse_to_conic() takes back */
            if (ellipse_conic_checked(&el, &back) != SBR_OK) {
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
        st = ellipse_conic_checked(ellipse, conic);
    }
    return st;
}

/* ---------------------------------------------------------------- direct fit */

/* Sampson distance of (x, y) to the conic. */
static float sampson(const sbr_conic_t *q, float x, float y)
{
    const float gx = (q->a * x) + (q->b * y) + q->d;
    const float gy = (q->b * x) + (q->c * y) + q->e;
    const float val = (x * gx) + (y * gy) + (q->d * x) + (q->e * y) + q->f;
    const float g = 2.0f * sqrtf((gx * gx) + (gy * gy));
    return (g > 0.0f) ? (fabsf(val) / g) : INFINITY;
}



/* Real roots of the characteristic polynomial of a 3 x 3 matrix; returns their count. */
static uint32_t eig3_real(const float m[9], float roots[3])
{
    /* lambda^3 + p2 lambda^2 + p1 lambda + p0 = 0 */
    const float tr = m[0] + m[4] + m[8];
    const float c2 = ((m[0] * m[4]) - (m[1] * m[3])) + ((m[0] * m[8]) - (m[2] * m[6])) +
                     ((m[4] * m[8]) - (m[5] * m[7]));
    const float p2 = -tr;
    const float p1 = c2;
    const float p0 = -det3(m);
    const float sh = p2 / 3.0f; /* lambda = t - sh */
    const float p = p1 - ((p2 * p2) / 3.0f);
    const float q = ((2.0f * p2 * p2 * p2) / 27.0f) - ((p2 * p1) / 3.0f) + p0;
    const float disc = ((q * q) / 4.0f) + ((p * p * p) / 27.0f);
    uint32_t n;
    if ((p < 0.0f) && (disc <= 0.0f)) {
        const float r = sqrtf(-p / 3.0f);
        float arg = (-q / 2.0f) / (r * r * r);
        arg = fminf(1.0f, fmaxf(-1.0f, arg));
        {
            const float phi = acosf(arg);
            uint32_t k;
            for (k = 0u; k < 3u; ++k) {
                roots[k] = (2.0f * r * cosf((phi - (2.0f * CONIC_PI * (float)k)) / 3.0f)) - sh;
            }
        }
        n = 3u;
    } else {
        const float sd = sqrtf(fmaxf(disc, 0.0f));
        roots[0] = (cbrtf((-q / 2.0f) + sd) + cbrtf((-q / 2.0f) - sd)) - sh;
        n = 1u;
    }
    return n;
}

/* Eigenvector of m for eigenvalue lambda: the longest cross product of two rows of
   (m - lambda I), refined by inverse iteration. Returns 0 when none is found. */
static int eigvec3(const float m[9], float lambda, float scale, float v[3])
{
    float a[9];
    float best = 0.0f;
    uint32_t i;
    int ok = 0;
    for (i = 0u; i < 9u; ++i) {
        a[i] = m[i];
    }
    a[0] -= lambda;
    a[4] -= lambda;
    a[8] -= lambda;
    for (i = 0u; i < 3u; ++i) {
        const float *r0 = &a[((i + 1u) % 3u) * 3u];
        const float *r1 = &a[((i + 2u) % 3u) * 3u];
        const float cx = (r0[1] * r1[2]) - (r0[2] * r1[1]);
        const float cy = (r0[2] * r1[0]) - (r0[0] * r1[2]);
        const float cz = (r0[0] * r1[1]) - (r0[1] * r1[0]);
        const float n2 = (cx * cx) + (cy * cy) + (cz * cz);
        if (n2 > best) {
            best = n2;
            v[0] = cx;
            v[1] = cy;
            v[2] = cz;
        }
    }
    if ((best > 0.0f) && (isfinite(best) != 0)) {
        uint32_t it;
        ok = 1;
        /* two steps of inverse iteration with a small shift */
        for (it = 0u; it < 2u; ++it) {
            float b[9];
            float x[3] = {v[0], v[1], v[2]};
            for (i = 0u; i < 9u; ++i) {
                b[i] = a[i];
            }
            b[0] += 1e-4f * scale;
            b[4] += 1e-4f * scale;
            b[8] += 1e-4f * scale;
            if (solve_small(b, x, 3u, 1e-30f) != 0) {
                const float nrm = sqrtf((x[0] * x[0]) + (x[1] * x[1]) + (x[2] * x[2]));
                if ((nrm > 0.0f) && (isfinite(nrm) != 0)) {
                    v[0] = x[0] / nrm;
                    v[1] = x[1] / nrm;
                    v[2] = x[2] / nrm;
                }
            }
        }
    }
    return ok;
}

/* The conic of a solution of the reduced problem: a1 = (a, 2b, c) and a2 = T a1 =
   (2d, 2e, f). */
static sbr_conic_t conic_from_reduced(const float t[9], const float v[3])
{
    const float a2[3] = {(t[0] * v[0]) + (t[1] * v[1]) + (t[2] * v[2]),
                         (t[3] * v[0]) + (t[4] * v[1]) + (t[5] * v[2]),
                         (t[6] * v[0]) + (t[7] * v[1]) + (t[8] * v[2])};
    const sbr_conic_t q = {v[0], 0.5f * v[1], v[2], 0.5f * a2[0], 0.5f * a2[1], a2[2]};
    return q;
}

/* Rms Sampson distance of the points in the fit's normalised frame x' = s (x - mx). */
static float normalised_miss(const sbr_conic_t *q, const sbr_point2f_t *points, uint32_t n,
                             float mx, float my, float s)
{
    float acc = 0.0f;
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        const float dd = sampson(q, (points[i].x - mx) * s, (points[i].y - my) * s);
        acc += dd * dd;
    }
    return sqrtf(acc / (float)n);
}

/* Do the points lie on a hyperbola? The unconstrained least-squares conic (the smallest
   eigenvector of the symmetric reduced scatter M) is a hyperbola that misses the points
   by less than a quarter of the ellipse fit's miss (noisy arcs of an ellipse give
   comparable misses; points of a hyperbola fit it almost exactly). */
static int hyperbola_fits_better(const float mm[9], const float t[9], const sbr_point2f_t *points,
                                 uint32_t n, float mx, float my, float s, float ellipse_miss)
{
    float roots[3];
    float scale = 0.0f;
    float lmin;
    float v[3] = {0.0f, 0.0f, 0.0f};
    uint32_t k;
    uint32_t nr;
    int hyp = 0;
    for (k = 0u; k < 9u; ++k) {
        scale = fmaxf(scale, fabsf(mm[k]));
    }
    nr = eig3_real(mm, roots);
    lmin = roots[0];
    for (k = 1u; k < nr; ++k) {
        lmin = fminf(lmin, roots[k]);
    }
    if ((eigvec3(mm, lmin, scale, v) != 0) && (((4.0f * v[0] * v[2]) - (v[1] * v[1])) < 0.0f)) {
        const sbr_conic_t qg = conic_from_reduced(t, v);
        if (normalised_miss(&qg, points, n, mx, my, s) < (0.25f * ellipse_miss)) {
            hyp = 1;
        }
    }
    return hyp;
}

sbr_status_t sbr_ellipse_fit(const sbr_point2f_t *points, uint32_t n, sbr_conic_t *conic,
                             sbr_ellipse_t *ellipse)
{
    sbr_status_t st = SBR_OK;
    uint32_t i;
    if ((points == NULL) || (conic == NULL)) {
        st = SBR_ERR_NULL;
    } else if (n < 5u) {
        st = SBR_ERR_SIZE;
    } else {
        for (i = 0u; (i < n) && (st == SBR_OK); ++i) {
            if ((isfinite(points[i].x) == 0) || (isfinite(points[i].y) == 0) ||
                (fabsf(points[i].x) > SBR_CONIC_MAX_COORD) || (fabsf(points[i].y) > SBR_CONIC_MAX_COORD)) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    if (st == SBR_OK) {
        /* at least five distinct points */
        sbr_point2f_t seen[5];
        uint32_t distinct = 0u;
        for (i = 0u; (i < n) && (distinct < 5u); ++i) {
            uint32_t k;
            int fresh = 1;
            for (k = 0u; k < distinct; ++k) {
                if ((seen[k].x == points[i].x) && (seen[k].y == points[i].y)) {
                    fresh = 0;
                }
            }
            if (fresh != 0) {
                seen[distinct] = points[i];
                ++distinct;
            }
        }
        if (distinct < 5u) {
            st = SBR_ERR_DEGENERATE;
        }
    }
    if (st == SBR_OK) {
        float mx = 0.0f;
        float my = 0.0f;
        float md = 0.0f;
        float s;
        float s1[9] = {0};
        float s2[9] = {0};
        float s3[9] = {0};
        const float fn = (float)n;
        for (i = 0u; i < n; ++i) {
            mx += points[i].x;
            my += points[i].y;
        }
        mx /= fn;
        my /= fn;
        for (i = 0u; i < n; ++i) {
            const float dx = points[i].x - mx;
            const float dy = points[i].y - my;
            md += sqrtf((dx * dx) + (dy * dy));
        }
        md /= fn;
        s = 0.0f;
        if (md > 0.0f) {
            s = 1.0f / md;
        }
        /* scatter matrices of D1 = [x^2, xy, y^2] and D2 = [x, y, 1] (all zero when the
           points coincide, s = 0) */
        for (i = 0u; i < n; ++i) {
            const float x = (points[i].x - mx) * s;
            const float y = (points[i].y - my) * s;
            const float d1[3] = {x * x, x * y, y * y};
            const float d2[3] = {x, y, 1.0f};
            uint32_t r;
            uint32_t c;
            for (r = 0u; r < 3u; ++r) {
                for (c = 0u; c < 3u; ++c) {
                    s1[(r * 3u) + c] += d1[r] * d1[c];
                    s2[(r * 3u) + c] += d1[r] * d2[c];
                    s3[(r * 3u) + c] += d2[r] * d2[c];
                }
            }
        }
        if ((s <= 0.0f) || (fabsf(det3(s3)) <= (1e-6f * fn * fn * fn))) {
            st = SBR_ERR_DEGENERATE; /* all points equal, or collinear */
        } else {
            float t[9];
            float mm_keep[9];
            float best_v[3] = {0.0f, 0.0f, 0.0f};
            uint32_t c;
            uint32_t k;
            /* T = -S3^-1 S2^T, column by column */
            for (c = 0u; (c < 3u) && (st == SBR_OK); ++c) {
                float a3[9];
                float col[3] = {-s2[(c * 3u) + 0u], -s2[(c * 3u) + 1u], -s2[(c * 3u) + 2u]};
                for (k = 0u; k < 9u; ++k) {
                    a3[k] = s3[k];
                }
                if (solve_small(a3, col, 3u, 1e-20f) == 0) {
                    st = SBR_ERR_DEGENERATE;
                } else {
                    t[0u + c] = col[0];
                    t[3u + c] = col[1];
                    t[6u + c] = col[2];
                }
            }
            if (st == SBR_OK) {
                float scale = 0.0f;
                float mm[9];
                float red[9];
                float roots[3];
                float best_l = 0.0f;
                int found = 0;
                uint32_t nr;
                uint32_t r;
                /* M = S1 + S2 T; reduced M = C1^-1 M: rows M3/2, -M2, M1/2 */
                for (r = 0u; r < 3u; ++r) {
                    for (c = 0u; c < 3u; ++c) {
                        float acc = s1[(r * 3u) + c];
                        for (k = 0u; k < 3u; ++k) {
                            acc += s2[(r * 3u) + k] * t[(k * 3u) + c];
                        }
                        mm[(r * 3u) + c] = acc;
                    }
                }
                for (k = 0u; k < 9u; ++k) {
                    mm_keep[k] = mm[k];
                }
                for (c = 0u; c < 3u; ++c) {
                    red[0u + c] = 0.5f * mm[6u + c];
                    red[3u + c] = -mm[3u + c];
                    red[6u + c] = 0.5f * mm[0u + c];
                }
                for (k = 0u; k < 9u; ++k) {
                    scale = fmaxf(scale, fabsf(red[k]));
                }
                nr = eig3_real(red, roots);
                for (k = 0u; k < nr; ++k) {
                    float v[3] = {0.0f, 0.0f, 0.0f};
                    if (eigvec3(red, roots[k], scale, v) != 0) {
                        const float cond = (4.0f * v[0] * v[2]) - (v[1] * v[1]);
                        if ((cond > 0.0f) && ((found == 0) || (fabsf(roots[k]) < fabsf(best_l)))) {
                            best_l = roots[k];
                            best_v[0] = v[0];
                            best_v[1] = v[1];
                            best_v[2] = v[2];
                            found = 1;
                        }
                    }
                }
                if (found == 0) {
                    st = SBR_ERR_DEGENERATE;
                }
            }
            if (st == SBR_OK) {
                /* conic in normalised coordinates, then back: x' = s (x - mx) */
                const sbr_conic_t qn = conic_from_reduced(t, best_v);
                const float miss = normalised_miss(&qn, points, n, mx, my, s);
                sbr_ellipse_t en = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
                if ((ellipse_of(&qn, &en) == 0) || (miss > FIT_MAX_MISS) || (isfinite(miss) == 0) ||
                    (hyperbola_fits_better(mm_keep, t, points, n, mx, my, s, miss) != 0)) {
                    st = SBR_ERR_DEGENERATE; /* e.g. the points of a hyperbola */
                } else {
                    const float ss = s * s;
                    const float a = qn.a * ss;
                    const float b = qn.b * ss;
                    const float c2 = qn.c * ss;
                    const float d = (qn.d * s) - (a * mx) - (b * my);
                    const float e = (qn.e * s) - (b * mx) - (c2 * my);
                    const float f = (a * mx * mx) + (2.0f * b * mx * my) + (c2 * my * my) -
                                    (2.0f * qn.d * s * mx) - (2.0f * qn.e * s * my) + qn.f;
                    const sbr_conic_t q = {a, b, c2, d, e, f};
                    const float m = max_abs_entry(&q);
                    sbr_ellipse_t el;
                    sbr_conic_t back;
                    el.cx = (en.cx / s) + mx;
                    el.cy = (en.cy / s) + my;
                    el.semi_major = en.semi_major / s;
                    el.semi_minor = en.semi_minor / s;
                    el.angle = en.angle;
                    if ((m <= 0.0f) || (isfinite(m) == 0) ||
                        (ellipse_conic_checked(&el, &back) != SBR_OK)) {
                        st = SBR_ERR_DEGENERATE;
                    } else {
                        *conic = conic_div(&q, m);
                        if (ellipse != NULL) {
                            *ellipse = el;
                        }
                    }
                }
            }
        }
    }
    return st;
}

/* ---------------------------------------------------------------- residual, coverage */

/* Finite points within +-SBR_CONIC_MAX_COORD. */
static int points_finite(const sbr_point2f_t *p, uint32_t n)
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

sbr_status_t sbr_conic_residual(const sbr_conic_t *conic, const sbr_point2f_t *points,
                                uint32_t n, float *rms, float *max_abs)
{
    sbr_status_t st = SBR_OK;
    if ((conic == NULL) || (points == NULL) || (rms == NULL)) {
        st = SBR_ERR_NULL;
    } else if (n == 0u) {
        st = SBR_ERR_SIZE;
    } else if ((conic_finite(conic) == 0) || (points_finite(points, n) == 0)) {
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
            const float dd = sampson(&q, points[i].x - ox, points[i].y - oy);
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

sbr_status_t sbr_ellipse_coverage(const sbr_conic_t *conic, const sbr_point2f_t *points,
                                  uint32_t n, float tol, float *coverage)
{
    sbr_status_t st = SBR_OK;
    sbr_ellipse_t el = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    if ((conic == NULL) || (points == NULL) || (coverage == NULL)) {
        st = SBR_ERR_NULL;
    } else if (n == 0u) {
        st = SBR_ERR_SIZE;
    } else if ((conic_finite(conic) == 0) || (points_finite(points, n) == 0) ||
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
        q = conic_of(&centred);
        for (i = 0u; i < n; ++i) {
            const float dx = points[i].x - el.cx;
            const float dy = points[i].y - el.cy;
            if (sampson(&q, dx, dy) <= tol) {
                const float u = ((dx * cs) + (dy * sn)) / el.semi_major;
                const float v = ((dy * cs) - (dx * sn)) / el.semi_minor;
                const float t = atan2f(v, u) + CONIC_PI;
                const float fsec = (t / (2.0f * CONIC_PI)) * (float)COVERAGE_SECTORS;
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

/* ---------------------------------------------------------------- torchlight pose */

/* Residuals (weighted: off-diagonal entries count twice, as in the Frobenius norm) of
   mu * M(n1, n2, k) against the normalised conic g[6] = {11, 12, 22, 13, 23, 33}, and the
   Jacobian rows (d/dmu, d/dn1, d/dn2, d/dk). */
static float torch_residuals(const float p[4], const float g[6], float r[6], float jac[24])
{
    const float mu = p[0];
    const float n1 = p[1];
    const float n2 = p[2];
    const float k = p[3];
    const float w = 1.41421356f;
    const float model[6] = {k - (n1 * n1), -n1 * n2, k - (n2 * n2), n1, n2, -1.0f};
    const float wt[6] = {TORCH_WQ, TORCH_WQ * w, TORCH_WQ, w, w, 1.0f};
    const float jr[24] = {model[0], -2.0f * mu * n1, 0.0f, mu,
                          model[1], -mu * n2, -mu * n1, 0.0f,
                          model[2], 0.0f, -2.0f * mu * n2, mu,
                          model[3], mu, 0.0f, 0.0f,
                          model[4], 0.0f, mu, 0.0f,
                          model[5], 0.0f, 0.0f, 0.0f};
    float acc = 0.0f;
    uint32_t i;
    uint32_t j;
    for (i = 0u; i < 6u; ++i) {
        r[i] = wt[i] * ((mu * model[i]) - g[i]);
        acc += r[i] * r[i];
        for (j = 0u; j < 4u; ++j) {
            jac[(i * 4u) + j] = wt[i] * jr[(i * 4u) + j];
        }
    }
    return acc;
}

/* Unweighted rms misfit of mu * M(n1, n2, k) against g (the consistency measure). */
static float torch_misfit(const float p[4], const float g[6])
{
    const float model[6] = {p[3] - (p[1] * p[1]), -p[1] * p[2], p[3] - (p[2] * p[2]), p[1], p[2], -1.0f};
    const float wt[6] = {1.0f, 2.0f, 1.0f, 2.0f, 2.0f, 1.0f}; /* off-diagonal entries twice */
    float acc = 0.0f;
    uint32_t i;
    for (i = 0u; i < 6u; ++i) {
        const float d = (p[0] * model[i]) - g[i];
        acc += wt[i] * d * d;
    }
    return sqrtf(acc / 9.0f);
}

sbr_status_t sbr_torch_pose(const sbr_conic_t *conic, float focal, float max_residual,
                            sbr_torch_pose_t *pose)
{
    sbr_status_t st = SBR_OK;
    sbr_conic_class_t cls = SBR_CONIC_REAL_ELLIPSE;
    if ((conic == NULL) || (pose == NULL)) {
        st = SBR_ERR_NULL;
    } else if ((conic_finite(conic) == 0) || (isfinite(focal) == 0) || (focal <= 0.0f) ||
               (isfinite(max_residual) == 0) || (max_residual <= 0.0f)) {
        st = SBR_ERR_RANGE;
    } else {
        st = sbr_conic_classify(conic, SBR_CONIC_ZERO_TOL, &cls);
        if ((st == SBR_OK) && (cls != SBR_CONIC_REAL_ELLIPSE)) {
            st = SBR_ERR_DEGENERATE;
        }
    }
    if (st == SBR_OK) {
        /* normalised image coordinates x = f x^: C^ = diag(f, f, 1) C diag(f, f, 1) */
        const float f2 = focal * focal;
        float g[6] = {conic->a * f2, conic->b * f2, conic->c * f2, conic->d * focal,
                      conic->e * focal, conic->f};
        float nrm = 0.0f;
        float p[4];
        uint32_t i;
        for (i = 0u; i < 6u; ++i) {
            const float w = ((i == 1u) || (i == 3u) || (i == 4u)) ? 2.0f : 1.0f;
            nrm += w * g[i] * g[i];
        }
        nrm = sqrtf(nrm);
        for (i = 0u; i < 6u; ++i) {
            g[i] /= nrm;
        }
        /* closed form: mu from C33, n from C13 and C23, k from both diagonal entries */
        p[0] = -g[5];
        if (fabsf(p[0]) <= 1e-12f) {
            st = SBR_ERR_DEGENERATE;
        } else {
            float r[6];
            float jac[24];
            float cost;
            uint32_t it;
            int go = 1;
            p[1] = g[3] / p[0];
            p[2] = g[4] / p[0];
            p[3] = 0.5f * (((g[0] + g[2]) / p[0]) + (p[1] * p[1]) + (p[2] * p[2]));
            cost = torch_residuals(p, g, r, jac);
            /* Gauss-Newton over all six entries, while the cost decreases */
            for (it = 0u; (it < 20u) && (go != 0); ++it) {
                float jtj[16] = {0};
                float jtr[4] = {0};
                uint32_t a;
                uint32_t b;
                for (i = 0u; i < 6u; ++i) {
                    for (a = 0u; a < 4u; ++a) {
                        jtr[a] -= jac[(i * 4u) + a] * r[i];
                        for (b = 0u; b < 4u; ++b) {
                            jtj[(a * 4u) + b] += jac[(i * 4u) + a] * jac[(i * 4u) + b];
                        }
                    }
                }
                if (solve_small(jtj, jtr, 4u, 1e-20f) == 0) {
                    go = 0;
                } else {
                    float q[4];
                    float r2[6];
                    float jac2[24];
                    float cost2;
                    for (a = 0u; a < 4u; ++a) {
                        q[a] = p[a] + jtr[a];
                    }
                    cost2 = torch_residuals(q, g, r2, jac2);
                    if ((isfinite(cost2) == 0) || (cost2 >= cost)) {
                        go = 0;
                    } else {
                        for (a = 0u; a < 4u; ++a) {
                            p[a] = q[a];
                        }
                        for (a = 0u; a < 6u; ++a) {
                            r[a] = r2[a];
                        }
                        for (a = 0u; a < 24u; ++a) {
                            jac[a] = jac2[a];
                        }
                        cost = cost2;
                    }
                }
            }
            pose->n1 = p[1];
            pose->n2 = p[2];
            pose->z0_over_r = (p[3] > 0.0f) ? sqrtf(p[3]) : 0.0f;
            pose->residual = torch_misfit(p, g);
            if ((p[3] <= 0.0f) || (pose->residual > max_residual) ||
                (isfinite(pose->residual) == 0)) {
                st = SBR_ERR_DEGENERATE;
            }
        }
    }
    return st;
}

/* ---------------------------------------------------------------- detection */

#define DET_MAX_CONTOURS 4u

void sbr_ellipse_detect_config_default(sbr_ellipse_detect_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_mser_config_default(&cfg->mser);
        cfg->mser.delta = 5u;
        cfg->mser.min_area = 40u;
        cfg->mser.max_area = 200000u;
        cfg->mser.max_variation = 0.5f;
        cfg->mser.min_diversity = 0.2f;
        cfg->mser.polarity = (uint32_t)SBR_MSER_BOTH;
        cfg->max_residual = 1.0f;
        cfg->min_coverage = 0.9f;
        cfg->min_semi_minor = 4.0f;
        cfg->min_axis_ratio = 0.1f;
        cfg->edge_offset = 0.5f;
        cfg->max_regions = 1024u;
        cfg->max_contour_points = 4096u;
    }
}

sbr_status_t sbr_ellipse_detect_config_check(const sbr_ellipse_detect_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if (sbr_mser_config_check(&cfg->mser) != SBR_OK) {
        st = SBR_ERR_RANGE;
    } else if ((isfinite(cfg->max_residual) == 0) || (cfg->max_residual <= 0.0f) ||
               (isfinite(cfg->min_coverage) == 0) || (cfg->min_coverage <= 0.0f) ||
               (cfg->min_coverage > 1.0f) || (isfinite(cfg->min_semi_minor) == 0) ||
               (cfg->min_semi_minor <= 0.0f) || (isfinite(cfg->min_axis_ratio) == 0) ||
               (cfg->min_axis_ratio <= 0.0f) || (cfg->min_axis_ratio > 1.0f) ||
               (isfinite(cfg->edge_offset) == 0) || (cfg->edge_offset < 0.0f) ||
               (cfg->edge_offset > 1.0f) || (cfg->max_regions == 0u) ||
               (cfg->max_regions > 1000000u) || (cfg->max_contour_points < 5u) ||
               (cfg->max_contour_points > 1000000u)) {
        st = SBR_ERR_RANGE;
    } else {
        /* valid */
    }
    return st;
}

static size_t round8(size_t v)
{
    return (v + 7u) & ~(size_t)7u;
}

/* Bytes of the per-region stage (mask workspace, mask, contour workspace, points). */
static size_t region_stage_size(uint32_t width, uint32_t height, uint32_t max_points)
{
    const size_t wh = (size_t)width * (size_t)height;
    return round8(SBR_MSER_MASK_WORKSPACE_SIZE(width, height)) + round8(wh) +
           round8(SBR_CONTOUR_WORKSPACE_SIZE(width, height)) +
           round8((size_t)max_points * sizeof(sbr_point_t)) +
           round8((size_t)DET_MAX_CONTOURS * sizeof(sbr_contour_t)) +
           round8((size_t)max_points * sizeof(sbr_point2f_t));
}

size_t sbr_ellipse_detect_workspace_size(uint32_t width, uint32_t height,
                                         const sbr_ellipse_detect_config_t *cfg)
{
    size_t total = 0u;
    if ((sbr_ellipse_detect_config_check(cfg) == SBR_OK) && (width >= 3u) && (height >= 3u) &&
        (width <= SBR_IMAGE_MAX_DIM) && (height <= SBR_IMAGE_MAX_DIM)) {
        const size_t mser = sbr_mser_workspace_size(width, height, &cfg->mser);
        const size_t stage = region_stage_size(width, height, cfg->max_contour_points);
        if (mser > 0u) {
            total = round8((size_t)cfg->max_regions * sizeof(sbr_mser_region_t)) +
                    ((mser > stage) ? round8(mser) : stage);
        }
    }
    return total;
}

/* Contour points as floats, moved `offset` pixels along the outward normal. The outward
   side follows from the contour's orientation (the sign of its shoelace area). */
static void edge_points(const sbr_point_t *pts, uint32_t n, float offset, sbr_point2f_t *out)
{
    int64_t area2 = 0;
    float side = 1.0f; /* normal (ty, -tx) * side points outward */
    uint32_t i;
    if ((sbr_contour_area2(pts, n, &area2) == SBR_OK) && (area2 < 0)) {
        side = -1.0f;
    }
    for (i = 0u; i < n; ++i) {
        const sbr_point_t *pa = &pts[(i + n - 2u) % n];
        const sbr_point_t *pb = &pts[(i + 2u) % n];
        const float tx = (float)pb->x - (float)pa->x;
        const float ty = (float)pb->y - (float)pa->y;
        const float len = sqrtf((tx * tx) + (ty * ty));
        out[i].x = (float)pts[i].x;
        out[i].y = (float)pts[i].y;
        if (len > 0.0f) {
            out[i].x += (offset * side * ty) / len;
            out[i].y -= (offset * side * tx) / len;
        }
    }
}

/* Index of a detection that is the same ellipse as `el` (a nested level set of the same
   edge: centres within 1 px, axes within 1.5 px or 3 %), or count when there is none. */
static uint32_t same_ellipse(const sbr_ellipse_det_t *dets, uint32_t count, const sbr_ellipse_t *el)
{
    uint32_t i;
    uint32_t found = count;
    for (i = 0u; (i < count) && (found == count); ++i) {
        const sbr_ellipse_t *o = &dets[i].ellipse;
        const float dx = o->cx - el->cx;
        const float dy = o->cy - el->cy;
        const float ta = fmaxf(1.5f, 0.03f * o->semi_major);
        const float tb = fmaxf(1.5f, 0.03f * o->semi_minor);
        if ((((dx * dx) + (dy * dy)) <= 1.0f) && (fabsf(o->semi_major - el->semi_major) <= ta) &&
            (fabsf(o->semi_minor - el->semi_minor) <= tb)) {
            found = i;
        }
    }
    return found;
}

/* Scale a conic to a + c = 1 (positive for an ellipse). */
static void unit_trace(sbr_conic_t *q)
{
    const float tr = q->a + q->c;
    if (tr != 0.0f) {
        *q = conic_div(q, tr);
    }
}

/* Merge `det` into `into`: the running mean of their conics (each scaled to a + c = 1;
   nested level sets of one edge have nearly equal conics, so the mean is well defined
   even for near-circles, whose angles are not), the geometry recomputed from it. */
static void merge_into(sbr_ellipse_det_t *into, const sbr_ellipse_det_t *det)
{
    const float w = 1.0f / ((float)into->merged + 1.0f);
    sbr_conic_t *o = &into->conic;
    sbr_ellipse_t el;
    o->a += w * (det->conic.a - o->a);
    o->b += w * (det->conic.b - o->b);
    o->c += w * (det->conic.c - o->c);
    o->d += w * (det->conic.d - o->d);
    o->e += w * (det->conic.e - o->e);
    o->f += w * (det->conic.f - o->f);
    if (ellipse_of(o, &el) != 0) {
        into->ellipse = el;
    }
    into->residual += w * (det->residual - into->residual);
    into->coverage += w * (det->coverage - into->coverage);
    into->merged += 1u;
}

sbr_status_t sbr_ellipse_detect(const sbr_image_t *image, const sbr_ellipse_detect_config_t *cfg,
                                void *workspace, size_t workspace_size, sbr_ellipse_det_t *out,
                                uint32_t capacity, uint32_t *count)
{
    sbr_status_t st = SBR_OK;
    if ((image == NULL) || (cfg == NULL) || (out == NULL) || (count == NULL)) {
        st = SBR_ERR_NULL;
    } else {
        *count = 0u;
        st = sbr_image_check(image);
        if ((st == SBR_OK) && ((image->format != SBR_PIXEL_GRAY8) ||
                               (sbr_ellipse_detect_config_check(cfg) != SBR_OK))) {
            st = SBR_ERR_RANGE;
        }
        if ((st == SBR_OK) && ((image->width < 3u) || (image->height < 3u))) {
            st = SBR_ERR_SIZE;
        }
    }
    if (st == SBR_OK) {
        const size_t need = sbr_ellipse_detect_workspace_size(image->width, image->height, cfg);
        if ((workspace == NULL) || (need == 0u) || (workspace_size < need) ||
            (sbr_util_aligned(workspace, 8u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        } else if (capacity == 0u) {
            st = SBR_ERR_CAPACITY;
        } else {
            /* valid */
        }
    }
    if (st == SBR_OK) {
        uint8_t *base = (uint8_t *)workspace;
        sbr_mser_region_t *regions = (sbr_mser_region_t *)workspace;
        const size_t region_bytes = round8((size_t)cfg->max_regions * sizeof(sbr_mser_region_t));
        uint8_t *shared = &base[region_bytes];
        const size_t shared_size = workspace_size - region_bytes;
        uint32_t nreg = 0u;
        uint32_t r;
        int capacity_hit = 0;
        const sbr_status_t ms = sbr_mser_detect(image, &cfg->mser, shared, shared_size, regions,
                                                cfg->max_regions, &nreg);
        if (ms == SBR_ERR_CAPACITY) {
            capacity_hit = 1;
        } else if (ms != SBR_OK) {
            st = ms;
            nreg = 0u;
        } else {
            /* all regions */
        }
        for (r = 0u; (r < nreg) && (st == SBR_OK); ++r) {
            const sbr_mser_region_t *reg = &regions[r];
            const uint32_t bw = reg->bbox.width;
            const uint32_t bh = reg->bbox.height;
            const size_t off_mask = round8(SBR_MSER_MASK_WORKSPACE_SIZE(bw, bh));
            const size_t off_cws = off_mask + round8((size_t)bw * bh);
            const size_t off_pts = off_cws + round8(SBR_CONTOUR_WORKSPACE_SIZE(bw, bh));
            const size_t off_cons = off_pts + round8((size_t)cfg->max_contour_points * sizeof(sbr_point_t));
            const size_t off_fp = off_cons + round8((size_t)DET_MAX_CONTOURS * sizeof(sbr_contour_t));
            uint8_t *mws = shared;
            uint8_t *mask = &shared[off_mask];
            uint8_t *cws = &shared[off_cws];
            sbr_point_t *pts = (sbr_point_t *)(void *)&shared[off_pts];
            sbr_contour_t *cons = (sbr_contour_t *)(void *)&shared[off_cons];
            sbr_point2f_t *fp = (sbr_point2f_t *)(void *)&shared[off_fp];
            const sbr_image_t mview = {bw, bh, bw, SBR_PIXEL_GRAY8, mask};
            uint32_t ncon = 0u;
            sbr_status_t cs;
            if ((2.0f * cfg->min_semi_minor) > (float)((bw < bh) ? bw : bh)) {
                continue; /* too small to pass the axis test */
            }
            if (sbr_mser_region_mask(image, reg, mws, SBR_MSER_MASK_WORKSPACE_SIZE(bw, bh), mask, bw,
                                     (size_t)bw * bh) != SBR_OK) {
                continue;
            }
            cs = sbr_contour_find_external(&mview, cws, SBR_CONTOUR_WORKSPACE_SIZE(bw, bh), pts,
                                           cfg->max_contour_points, cons, DET_MAX_CONTOURS, &ncon);
            if (cs == SBR_ERR_CAPACITY) {
                capacity_hit = 1;
            } else if (cs != SBR_OK) {
                ncon = 0u;
            } else {
                /* traced */
            }
            if (ncon > 0u) {
                uint32_t best = 0u;
                uint32_t k;
                uint32_t np;
                for (k = 1u; k < ncon; ++k) {
                    if (cons[k].length > cons[best].length) {
                        best = k;
                    }
                }
                np = cons[best].length;
                if (np >= 8u) {
                    sbr_ellipse_det_t det;
                    uint32_t i;
                    edge_points(&pts[cons[best].first], np, cfg->edge_offset, fp);
                    for (i = 0u; i < np; ++i) {
                        fp[i].x += (float)reg->bbox.x;
                        fp[i].y += (float)reg->bbox.y;
                    }
                    if ((sbr_ellipse_fit(fp, np, &det.conic, &det.ellipse) == SBR_OK) &&
                        (sbr_conic_residual(&det.conic, fp, np, &det.residual, NULL) == SBR_OK) &&
                        (det.residual <= cfg->max_residual) &&
                        (det.ellipse.semi_minor >= cfg->min_semi_minor) &&
                        (det.ellipse.semi_minor >= (cfg->min_axis_ratio * det.ellipse.semi_major)) &&
                        (sbr_ellipse_coverage(&det.conic, fp, np, 2.0f * cfg->max_residual,
                                              &det.coverage) == SBR_OK) &&
                        (det.coverage >= cfg->min_coverage)) {
                        const uint32_t same = same_ellipse(out, *count, &det.ellipse);
                        det.area = reg->area;
                        det.polarity = reg->polarity;
                        det.merged = 1u;
                        unit_trace(&det.conic);
                        if (same < *count) {
                            merge_into(&out[same], &det);
                        } else if (*count < capacity) {
                            out[*count] = det;
                            *count += 1u;
                        } else {
                            capacity_hit = 1;
                        }
                    }
                }
            }
        }
        if ((st == SBR_OK) && (capacity_hit != 0)) {
            st = SBR_ERR_CAPACITY;
        }
    }
    return st;
}
