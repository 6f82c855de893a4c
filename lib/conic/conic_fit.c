/* SPDX-License-Identifier: MIT */
/* Conics: the direct least-squares ellipse fit (Halir-Flusser). See include/sbr/conic.h. */
#include "conic_internal.h"

#include <math.h>

/* largest rms Sampson distance of a fit, relative to the points' mean distance from
   their centroid */
#define FIT_MAX_MISS 0.5f

/* Real roots of the characteristic polynomial of a 3 x 3 matrix; returns their count. */
static uint32_t eig3_real(const float m[9], float roots[3])
{
    /* lambda^3 + p2 lambda^2 + p1 lambda + p0 = 0 */
    const float tr = m[0] + m[4] + m[8];
    const float c2 = ((m[0] * m[4]) - (m[1] * m[3])) + ((m[0] * m[8]) - (m[2] * m[6])) +
                     ((m[4] * m[8]) - (m[5] * m[7]));
    const float p2 = -tr;
    const float p1 = c2;
    const float p0 = -sbr_conic_priv_det3(m);
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
                roots[k] = (2.0f * r * cosf((phi - (2.0f * SBR_PI_F * (float)k)) / 3.0f)) - sh;
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
            if (sbr_conic_priv_solve(b, x, 3u, 1e-30f) != 0) {
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
static float normalised_miss(const sbr_conic_t *q, const sbr_pointf_t *points, uint32_t n,
                             float mx, float my, float s)
{
    float acc = 0.0f;
    uint32_t i;
    for (i = 0u; i < n; ++i) {
        const float dd = sbr_conic_priv_sampson(q, (points[i].x - mx) * s, (points[i].y - my) * s);
        acc += dd * dd;
    }
    return sqrtf(acc / (float)n);
}

/* Do the points lie on a hyperbola? The unconstrained least-squares conic (the smallest
   eigenvector of the symmetric reduced scatter M) is a hyperbola that misses the points
   by less than a quarter of the ellipse fit's miss (noisy arcs of an ellipse give
   comparable misses; points of a hyperbola fit it almost exactly). */
static int hyperbola_fits_better(const float mm[9], const float t[9], const sbr_pointf_t *points,
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

/* The points of a fit: finite, within +-SBR_CONIC_MAX_COORD, at least five distinct. */
static sbr_status_t fit_points_check(const sbr_pointf_t *points, uint32_t n)
{
    sbr_status_t st = SBR_OK;
    sbr_pointf_t seen[5] = {{0.0f, 0.0f}, {0.0f, 0.0f}, {0.0f, 0.0f}, {0.0f, 0.0f}, {0.0f, 0.0f}};
    uint32_t distinct = 0u;
    uint32_t i;
    if (n < 5u) {
        st = SBR_ERR_SIZE;
    } else if (sbr_conic_priv_points_finite(points, n) == 0) {
        st = SBR_ERR_RANGE;
    } else {
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
    return st;
}

/* The fit's normalisation x' = s (x - mx): the centroid and the inverse mean distance
   from it (s = 0 when the points coincide). */
typedef struct fit_frame_s {
    float mx;
    float my;
    float s;
} fit_frame_t;

static void fit_frame(const sbr_pointf_t *points, uint32_t n, fit_frame_t *fr)
{
    const float fn = (float)n;
    float md = 0.0f;
    uint32_t i;
    fr->mx = 0.0f;
    fr->my = 0.0f;
    for (i = 0u; i < n; ++i) {
        fr->mx += points[i].x;
        fr->my += points[i].y;
    }
    fr->mx /= fn;
    fr->my /= fn;
    for (i = 0u; i < n; ++i) {
        const float dx = points[i].x - fr->mx;
        const float dy = points[i].y - fr->my;
        md += sqrtf((dx * dx) + (dy * dy));
    }
    md /= fn;
    fr->s = 0.0f;
    if (md > 0.0f) {
        fr->s = 1.0f / md;
    }
}

/* Scatter matrices of D1 = [x^2, xy, y^2] and D2 = [x, y, 1] in the normalised frame (all
   zero when the points coincide, s = 0). */
static void fit_scatter(const sbr_pointf_t *points, uint32_t n, const fit_frame_t *fr,
                        float s1[9], float s2[9], float s3[9])
{
    uint32_t i;
    for (i = 0u; i < 9u; ++i) {
        s1[i] = 0.0f;
        s2[i] = 0.0f;
        s3[i] = 0.0f;
    }
    for (i = 0u; i < n; ++i) {
        const float x = (points[i].x - fr->mx) * fr->s;
        const float y = (points[i].y - fr->my) * fr->s;
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
}

/* T = -S3^-1 S2^T, column by column, and M = S1 + S2 T. Returns 0 if S3 is singular. */
static int fit_reduce(const float s1[9], const float s2[9], const float s3[9], float t[9],
                      float mm[9])
{
    uint32_t c;
    uint32_t k;
    uint32_t r;
    int ok = 1;
    for (c = 0u; (c < 3u) && (ok != 0); ++c) {
        float a3[9];
        float col[3] = {-s2[(c * 3u) + 0u], -s2[(c * 3u) + 1u], -s2[(c * 3u) + 2u]};
        for (k = 0u; k < 9u; ++k) {
            a3[k] = s3[k];
        }
        if (sbr_conic_priv_solve(a3, col, 3u, 1e-20f) == 0) {
            ok = 0;
        } else {
            t[0u + c] = col[0];
            t[3u + c] = col[1];
            t[6u + c] = col[2];
        }
    }
    for (r = 0u; (r < 3u) && (ok != 0); ++r) {
        for (c = 0u; c < 3u; ++c) {
            float acc = s1[(r * 3u) + c];
            for (k = 0u; k < 3u; ++k) {
                acc += s2[(r * 3u) + k] * t[(k * 3u) + c];
            }
            mm[(r * 3u) + c] = acc;
        }
    }
    return ok;
}

/* The ellipse solution of the reduced problem C1^-1 M (rows M3/2, -M2, M1/2): of the
   eigenvectors with 4ac - b^2 > 0, the one of the smallest |eigenvalue|. Returns 0 if
   there is none. */
static int fit_eigen(const float mm[9], float best_v[3])
{
    float red[9];
    float roots[3];
    float scale = 0.0f;
    float best_l = 0.0f;
    int found = 0;
    uint32_t nr;
    uint32_t c;
    uint32_t k;
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
    return found;
}

/* The conic and ellipse of the normalised solution qn (geometry en) in image
   coordinates, x' = s (x - mx) undone. */
static sbr_status_t fit_denormalise(const sbr_conic_t *qn, const sbr_ellipse_t *en,
                                    const fit_frame_t *fr, sbr_conic_t *conic,
                                    sbr_ellipse_t *ellipse)
{
    const float s = fr->s;
    const float mx = fr->mx;
    const float my = fr->my;
    const float ss = s * s;
    const float a = qn->a * ss;
    const float b = qn->b * ss;
    const float c2 = qn->c * ss;
    const float d = (qn->d * s) - (a * mx) - (b * my);
    const float e = (qn->e * s) - (b * mx) - (c2 * my);
    const float f = (a * mx * mx) + (2.0f * b * mx * my) + (c2 * my * my) -
                    (2.0f * qn->d * s * mx) - (2.0f * qn->e * s * my) + qn->f;
    const sbr_conic_t q = {a, b, c2, d, e, f};
    const float m = sbr_conic_priv_max_abs(&q);
    sbr_status_t st = SBR_OK;
    sbr_ellipse_t el;
    sbr_conic_t back;
    el.cx = (en->cx / s) + mx;
    el.cy = (en->cy / s) + my;
    el.semi_major = en->semi_major / s;
    el.semi_minor = en->semi_minor / s;
    el.angle = en->angle;
    if ((m <= 0.0f) || (isfinite(m) == 0) ||
        (sbr_conic_priv_ellipse_checked(&el, &back) != SBR_OK)) {
        st = SBR_ERR_DEGENERATE;
    } else {
        const sbr_conic_t qm = sbr_conic_priv_div(&q, m);
        /* the returned conic itself must be that ellipse: moved back from the centroid,
           the constant term of points far from the origin can cancel until it is not */
        if (sbr_conic_priv_is_ellipse(&qm, &el) == 0) {
            st = SBR_ERR_DEGENERATE;
        } else {
            *conic = qm;
            if (ellipse != NULL) {
                *ellipse = el;
            }
        }
    }
    return st;
}

sbr_status_t sbr_ellipse_fit(const sbr_pointf_t *points, uint32_t n, sbr_conic_t *conic,
                             sbr_ellipse_t *ellipse)
{
    sbr_status_t st;
    fit_frame_t fr;
    float s1[9];
    float s2[9];
    float s3[9];
    float t[9];
    float mm[9];
    float best_v[3] = {0.0f, 0.0f, 0.0f};
    if ((points == NULL) || (conic == NULL)) {
        return SBR_ERR_NULL;
    }
    st = fit_points_check(points, n);
    if (st != SBR_OK) {
        return st;
    }
    fit_frame(points, n, &fr);
    fit_scatter(points, n, &fr, s1, s2, s3);
    if ((fr.s <= 0.0f) ||
        (fabsf(sbr_conic_priv_det3(s3)) <= (1e-6f * (float)n * (float)n * (float)n)) ||
        (fit_reduce(s1, s2, s3, t, mm) == 0) || (fit_eigen(mm, best_v) == 0)) {
        st = SBR_ERR_DEGENERATE; /* all points equal, or collinear */
    } else {
        /* conic in normalised coordinates, then back: x' = s (x - mx) */
        const sbr_conic_t qn = conic_from_reduced(t, best_v);
        const float miss = normalised_miss(&qn, points, n, fr.mx, fr.my, fr.s);
        sbr_ellipse_t en = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        if ((sbr_conic_priv_ellipse_of(&qn, &en) == 0) || (miss > FIT_MAX_MISS) ||
            (isfinite(miss) == 0) ||
            (hyperbola_fits_better(mm, t, points, n, fr.mx, fr.my, fr.s, miss) != 0)) {
            st = SBR_ERR_DEGENERATE; /* e.g. the points of a hyperbola */
        } else {
            st = fit_denormalise(&qn, &en, &fr, conic, ellipse);
        }
    }
    return st;
}
