/* SPDX-License-Identifier: MIT */
/* Fourier descriptors (include/sbr/fd.h): descriptors of contours, and their matching by
   correlation, pair by pair and over a prototype table (four lanes at a time). */
#include "sbr/fd.h"
#include "fd_internal.h"

#include <math.h>

#include "../common/sbr_util.h"


/* Reads point i of whichever array is given (integer or float points). */
static void get_point(const sbr_point_t *pi, const sbr_pointf_t *pf, uint32_t i, float *x,
                      float *y)
{
    if (pi != NULL) {
        *x = (float)pi[i].x;
        *y = (float)pi[i].y;
    } else {
        *x = pf[i].x;
        *y = pf[i].y;
    }
}

/* Index of the point after i on a closed contour. */
static uint32_t next_index(uint32_t i, uint32_t count)
{
    uint32_t j = i + 1u;
    if (j >= count) {
        j = 0u;
    }
    return j;
}

/* Validate the points and measure the outline's length and twice its signed area
   (relative to the first point, which keeps the shoelace sum accurate for contours far
   from the origin). */
static sbr_status_t fd_measure(const sbr_point_t *pi, const sbr_pointf_t *pf, uint32_t count,
                               float *length, float *area2)
{
    float x0;
    float y0;
    uint32_t i;
    *length = 0.0f;
    *area2 = 0.0f;
    get_point(pi, pf, 0u, &x0, &y0);
    for (i = 0u; i < count; i++) {
        float xa;
        float ya;
        float xb;
        float yb;
        get_point(pi, pf, i, &xa, &ya);
        if ((isfinite(xa) == 0) || (isfinite(ya) == 0) || (fabsf(xa) > SBR_FD_MAX_COORD) ||
            (fabsf(ya) > SBR_FD_MAX_COORD)) {
            return SBR_ERR_RANGE;
        }
        get_point(pi, pf, next_index(i, count), &xb, &yb);
        *length += hypotf(xb - xa, yb - ya);
        *area2 += ((xa - x0) * (yb - y0)) - ((xb - x0) * (ya - y0));
    }
    return SBR_OK;
}

/* Arc-length resampling of the closed outline (of the given length) at n equally spaced
   positions, starting at point 0, into work[0..n). */
static void fd_resample(const sbr_point_t *pi, const sbr_pointf_t *pf, uint32_t count,
                        uint32_t n, float length, sbr_complex_t *work)
{
    const float step = length / (float)n;
    float acc = 0.0f; /* arc length at the start of segment i */
    uint32_t i = 0u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const float t = step * (float)k;
        float xa;
        float ya;
        float xb;
        float yb;
        float seg;
        get_point(pi, pf, i, &xa, &ya);
        get_point(pi, pf, next_index(i, count), &xb, &yb);
        seg = hypotf(xb - xa, yb - ya);
        while ((i + 1u) < count) {
            if ((acc + seg) >= t) {
                break;
            }
            acc += seg;
            i++;
            xa = xb;
            ya = yb;
            get_point(pi, pf, next_index(i, count), &xb, &yb);
            seg = hypotf(xb - xa, yb - ya);
        }
        if (seg > 0.0f) {
            float u = (t - acc) / seg;
            if (u > 1.0f) {
                u = 1.0f;
            }
            work[k].re = xa + (u * (xb - xa));
            work[k].im = ya + (u * (yb - ya));
        } else {
            work[k].re = xa;
            work[k].im = ya;
        }
    }
}

/* The descriptor from the n-point spectrum in work: centroid, scale (the energy of the
   coefficients +-1..m) and the 2m + 1 coefficients at unit energy. */
static sbr_status_t fd_coefficients(const sbr_complex_t *work, uint32_t n, uint32_t m,
                                    sbr_fd_t *out)
{
    const float inv_n = 1.0f / (float)n;
    float energy = 0.0f;
    float inv_scale;
    uint32_t k;
    for (k = 1u; k <= m; k++) {
        const sbr_complex_t a = work[k];
        const sbr_complex_t b = work[n - k];
        energy += (a.re * a.re) + (a.im * a.im) + (b.re * b.re) + (b.im * b.im);
    }
    energy *= inv_n * inv_n;
    if ((energy <= 0.0f) || (isfinite(energy) == 0)) {
        return SBR_ERR_DEGENERATE;
    }
    out->m = m;
    out->scale = sqrtf(energy);
    out->cx = work[0].re * inv_n;
    out->cy = work[0].im * inv_n;
    inv_scale = inv_n / out->scale;
    out->c[m].re = 0.0f;
    out->c[m].im = 0.0f;
    for (k = 1u; k <= m; k++) {
        out->c[m + k].re = work[k].re * inv_scale;
        out->c[m + k].im = work[k].im * inv_scale;
        out->c[m - k].re = work[n - k].re * inv_scale;
        out->c[m - k].im = work[n - k].im * inv_scale;
    }
    return SBR_OK;
}

static sbr_status_t fd_compute(const sbr_fft_t *fft, const sbr_point_t *pi,
                               const sbr_pointf_t *pf, uint32_t count, uint32_t m,
                               sbr_complex_t *work, uint32_t work_len, sbr_fd_t *out)
{
    sbr_status_t st = sbr_fft_check(fft);
    float length;
    float area2;
    uint32_t n;

    if (st != SBR_OK) {
        return st;
    }
    if ((out == NULL) || (work == NULL)) {
        return SBR_ERR_NULL;
    }
    n = fft->n;
    if ((count == 0u) || (m == 0u) || (m > SBR_FD_MAX_M) || ((2u * m) >= n) || (work_len < n)) {
        return SBR_ERR_SIZE;
    }
    if (count < 3u) {
        return SBR_ERR_DEGENERATE;
    }
    st = fd_measure(pi, pf, count, &length, &area2);
    if (st != SBR_OK) {
        return st;
    }
    if ((length <= 0.0f) || (fabsf(area2) <= (1e-6f * length * length))) {
        return SBR_ERR_DEGENERATE;
    }
    fd_resample(pi, pf, count, n, length, work);
    st = sbr_fft_forward(fft, work, work);
    if (st != SBR_OK) {
        return st;
    }
    return fd_coefficients(work, n, m, out);
}

sbr_status_t sbr_fd_from_points(const sbr_fft_t *fft, const sbr_point_t *points,
                                uint32_t count, uint32_t m, sbr_complex_t *work,
                                uint32_t work_len, sbr_fd_t *out)
{
    if (points == NULL) {
        return SBR_ERR_NULL;
    }
    return fd_compute(fft, points, NULL, count, m, work, work_len, out);
}

sbr_status_t sbr_fd_from_pointsf(const sbr_fft_t *fft, const sbr_pointf_t *points,
                                 uint32_t count, uint32_t m, sbr_complex_t *work,
                                 uint32_t work_len, sbr_fd_t *out)
{
    if (points == NULL) {
        return SBR_ERR_NULL;
    }
    return fd_compute(fft, NULL, points, count, m, work, work_len, out);
}

/* Sum of squares of a descriptor's coefficients (sbr_util_dot's four partial sums); not
   finite iff a coefficient is not finite. */
static float coeff_energy(const sbr_fd_t *p)
{
    const float *f = (const float *)(const void *)p->c; /* 2(2M+1) floats */
    const uint32_t n = 2u * ((2u * p->m) + 1u);
    return sbr_util_dot(f, f, (size_t)n);
}

sbr_status_t sbr_fd_check(const sbr_fd_t *fd, float *energy)
{
    float e;
    if (fd == NULL) {
        return SBR_ERR_NULL;
    }
    if ((fd->m == 0u) || (fd->m > SBR_FD_MAX_M) || (isfinite(fd->scale) == 0) ||
        (fd->scale <= 0.0f) || (isfinite(fd->cx) == 0) || (isfinite(fd->cy) == 0)) {
        return SBR_ERR_RANGE;
    }
    e = coeff_energy(fd); /* finite iff every coefficient is */
    if (isfinite(e) == 0) {
        return SBR_ERR_RANGE;
    }
    if (energy != NULL) {
        *energy = e;
    }
    return SBR_OK;
}

sbr_status_t sbr_fd_mirror(const sbr_fd_t *in, sbr_fd_t *out)
{
    const sbr_status_t st = sbr_fd_check(in, NULL);
    uint32_t k;
    uint32_t m;

    if (st != SBR_OK) {
        return st;
    }
    if (out == NULL) {
        return SBR_ERR_NULL;
    }
    m = in->m;
    out->m = m;
    out->scale = in->scale;
    out->cx = -in->cx;
    out->cy = in->cy;
    for (k = 0u; k <= (2u * m); k++) {
        const sbr_complex_t v = in->c[k];
        out->c[k].re = -v.re;
        out->c[k].im = v.im;
    }
    return SBR_OK;
}

sbr_status_t sbr_fd_smooth(const sbr_fd_t *in, float sigma, sbr_fd_t *out)
{
    const sbr_status_t st = sbr_fd_check(in, NULL);
    const float g = 2.0f * SBR_PI_F * SBR_PI_F * sigma * sigma;
    float energy = 0.0f;
    float inv;
    uint32_t m;
    uint32_t k;
    sbr_fd_t r;

    if (st != SBR_OK) {
        return st;
    }
    if (out == NULL) {
        return SBR_ERR_NULL;
    }
    if ((isfinite(sigma) == 0) || (sigma < 0.0f) || (sigma > 0.5f)) {
        return SBR_ERR_RANGE;
    }
    m = in->m;
    r = *in;
    for (k = 1u; k <= m; k++) {
        const float fk = (float)k;
        const float w = expf(-g * fk * fk);
        r.c[m + k].re *= w;
        r.c[m + k].im *= w;
        r.c[m - k].re *= w;
        r.c[m - k].im *= w;
        energy += (r.c[m + k].re * r.c[m + k].re) + (r.c[m + k].im * r.c[m + k].im) +
                  (r.c[m - k].re * r.c[m - k].re) + (r.c[m - k].im * r.c[m - k].im);
    }
    if ((energy <= 0.0f) || (isfinite(energy) == 0)) {
        return SBR_ERR_RANGE;
    }
    inv = 1.0f / sqrtf(energy);
    for (k = 0u; k <= (2u * m); k++) {
        r.c[k].re *= inv;
        r.c[k].im *= inv;
    }
    /* a damaged input (a DC term far from 0, coefficients near the float limits) can
       leave no finite unit-energy result: refused, `out` untouched */
    if (isfinite(coeff_energy(&r)) == 0) {
        return SBR_ERR_RANGE;
    }
    *out = r;
    return SBR_OK;
}

void sbr_fd_match_config_default(sbr_fd_match_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->mode = SBR_FD_ROTATION_COVARIANT;
        cfg->max_rotation = SBR_PI_F;
        cfg->refine = 1;
        cfg->max_error = 0.0f;
    }
}

sbr_status_t sbr_fd_match_config_check(const sbr_fd_match_config_t *cfg)
{
    sbr_status_t st = SBR_OK;
    if (cfg == NULL) {
        st = SBR_ERR_NULL;
    } else if (((cfg->mode != SBR_FD_ROTATION_INVARIANT) &&
                (cfg->mode != SBR_FD_ROTATION_COVARIANT)) ||
               (isfinite(cfg->max_rotation) == 0) || (cfg->max_rotation < 0.0f) ||
               (!(cfg->max_error >= 0.0f))) {
        st = SBR_ERR_RANGE;
    } else {
        /* valid */
    }
    return st;
}

/* r at a fractional lag l (in samples of P), evaluated directly from the coefficients. */
static sbr_complex_t corr_at(const sbr_fd_t *q, const sbr_fd_t *p, float lag, uint32_t size)
{
    const uint32_t m = q->m;
    const float a = (SBR_TWO_PI_F * lag) / (float)size;
    const sbr_complex_t w = {cosf(a), sinf(a)};
    sbr_complex_t wn = w; /* w^n */
    sbr_complex_t r = {0.0f, 0.0f};
    uint32_t n;

    for (n = 1u; n <= m; n++) {
        const sbr_complex_t qp = q->c[m + n];
        const sbr_complex_t cp = p->c[m + n];
        const sbr_complex_t qn = q->c[m - n];
        const sbr_complex_t cn = p->c[m - n];
        /* conj(Q) C for +n and -n */
        const float pr = (qp.re * cp.re) + (qp.im * cp.im);
        const float pim = (qp.re * cp.im) - (qp.im * cp.re);
        const float nr = (qn.re * cn.re) + (qn.im * cn.im);
        const float nim = (qn.re * cn.im) - (qn.im * cn.re);
        float t;
        r.re += ((pr * wn.re) - (pim * wn.im)) + ((nr * wn.re) + (nim * wn.im));
        r.im += ((pr * wn.im) + (pim * wn.re)) + ((nim * wn.re) - (nr * wn.im));
        t = (wn.re * w.re) - (wn.im * w.im);
        wn.im = (wn.re * w.im) + (wn.im * w.re);
        wn.re = t;
    }
    return r;
}

/* Objective of a correlation value in the given mode (|r|^2 is avoided: the parabola
   fit needs the objective itself). */
static float objective(sbr_fd_mode_t mode, sbr_complex_t r)
{
    float v = r.re;
    if (mode == SBR_FD_ROTATION_INVARIANT) {
        v = sqrtf((r.re * r.re) + (r.im * r.im)); /* |r| <= 1: no overflow */
    }
    return v;
}

/* Everything a match needs except the prototype: checked once per call of
   sbr_fd_match() and once per table in sbr_fd_match_table(). */
static sbr_status_t check_match_args(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                     const sbr_fd_t *query, const sbr_complex_t *work,
                                     uint32_t work_len, const void *result)
{
    sbr_status_t st = sbr_fft_check(fft);

    if (st == SBR_OK) {
        st = sbr_fd_check(query, NULL);
    }
    if (st != SBR_OK) {
        return st;
    }
    if ((cfg == NULL) || (work == NULL) || (result == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_fd_match_config_check(cfg);
    if (st != SBR_OK) {
        return st;
    }
    if ((fft->n < ((2u * query->m) + 1u)) || (work_len < fft->n)) {
        return SBR_ERR_SIZE;
    }
    return SBR_OK;
}

/* The header of a prototype: sbr_fd_check()'s M, scale and centre conditions, and the
   query's M (check_proto() adds the coefficients). */
static sbr_status_t check_proto_header(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    if ((proto->m == 0u) || (proto->m > SBR_FD_MAX_M) || (isfinite(proto->scale) == 0) ||
        (proto->scale <= 0.0f) || (isfinite(proto->cx) == 0) || (isfinite(proto->cy) == 0)) {
        return SBR_ERR_RANGE;
    }
    if (proto->m != query->m) {
        return SBR_ERR_SIZE;
    }
    {
        /* the result's scale ratio must be a float32 value (fd.h) */
        const float ratio = query->scale / proto->scale;
        if ((isfinite(ratio) == 0) || (ratio <= 0.0f)) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

/* A prototype must be a valid descriptor with the query's M. */
static sbr_status_t check_proto(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    const sbr_status_t st = sbr_fd_check(proto, NULL);
    if (st != SBR_OK) {
        return st;
    }
    return check_proto_header(query, proto);
}

/* A prototype of a trusted table (fd_internal.h: checked by its owner, its scale ratio to
   any query of the owner's finite): only its M against the query's. */
static sbr_status_t check_trusted(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    return (proto->m == query->m) ? SBR_OK : SBR_ERR_SIZE;
}

/* Where conj(Q(n)) C(n), n = -M..M (k = n + M), goes: element `scale * place(n mod P)` of
   the re/im arrays, place = bit reversal (lane buffers) or identity (bitrev NULL). */
static void product_positions(uint32_t m, uint32_t size, const uint16_t *bitrev,
                              uint32_t scale, uint32_t *pos)
{
    uint32_t k;
    for (k = 0u; k <= (2u * m); k++) {
        uint32_t at = k - m;
        if (k < m) {
            at = (size + k) - m;
        }
        if (bitrev != NULL) {
            at = (uint32_t)bitrev[at];
        }
        pos[k] = at * scale;
    }
}

/* conj(Q(n)) C(n) at the given positions. */
static void write_products(const sbr_fd_t *query, const sbr_fd_t *proto, const uint32_t *pos,
                           float *re, float *im)
{
    const uint32_t n = (2u * query->m) + 1u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const sbr_complex_t q = query->c[k];
        const sbr_complex_t c = proto->c[k];
        re[pos[k]] = (q.re * c.re) + (q.im * c.im);
        im[pos[k]] = (q.re * c.im) - (q.im * c.re);
    }
}

/* Objective value used by the peak search: |r|^2 (invariant), Re r (covariant), or
   FD_OUTSIDE for a covariant value whose rotation exceeds the bound. */
#define FD_OUTSIDE (-8.0f)
/* Below this |r|^2, the rotation test scales r first: its square would lose the direction
   to underflow. A covariant peak search is redone with that test only where a lag the
   fast one misjudged can matter (rescan()). */
#define FD_TINY_SQ 1e-30f
#define FD_TINY_VALUE 1e-15f

/* The covariant objective as the hot loops test it: one square root a lag, exact unless
   |r|^2 underflows, which only a lag of |Re r| < FD_TINY_VALUE can suffer. */
static float peak_value_fast(float cos_bound, float re, float im)
{
    float v = re;
    if (re < (cos_bound * sqrtf((re * re) + (im * im)))) {
        v = FD_OUTSIDE;
    }
    return v;
}

/* Whether a covariant peak search must be redone with the careful test: the fast one can
   admit a tiny lag whose direction it cannot see (then the best is below FD_TINY_VALUE),
   or reject one for a bound beyond pi / 2 (cos < 0), which matters only if no lag
   qualified. Without a bound (cos <= -1) it misjudges nothing. */
static int rescan(float best_val, float cos_bound)
{
    int again = 0;
    if ((cos_bound > -1.0f) && (((best_val > FD_OUTSIDE) && (best_val < FD_TINY_VALUE)) ||
                                ((best_val <= FD_OUTSIDE) && (cos_bound < 0.0f)))) {
        again = 1;
    }
    return again;
}

static float peak_value(int invariant, float cos_bound, float re, float im)
{
    float v;
    if (invariant != 0) {
        v = (re * re) + (im * im);
    } else if (((re * re) + (im * im)) >= FD_TINY_SQ) {
        v = peak_value_fast(cos_bound, re, im);
    } else {
        /* |r|^2 underflows (a query or prototype of tiny energy): the direction of r
           scaled to a largest part of 1; r = 0 has none */
        const float m = fmaxf(fabsf(re), fabsf(im));
        v = re;
        if (m <= 0.0f) {
            if (cos_bound > -1.0f) {
                v = FD_OUTSIDE;
            }
        } else if (peak_value_fast(cos_bound, re / m, im / m) <= FD_OUTSIDE) {
            v = FD_OUTSIDE;
        } else {
            /* within the bound */
        }
    }
    return v;
}

static int mode_invariant(const sbr_fd_match_config_t *cfg)
{
    int inv = 0;
    if (cfg->mode == SBR_FD_ROTATION_INVARIANT) {
        inv = 1;
    }
    return inv;
}

/* cos of the rotation bound, or -2 (no bound) */
static float rotation_cos_bound(const sbr_fd_match_config_t *cfg)
{
    float cb = -2.0f;
    if ((cfg->mode == SBR_FD_ROTATION_COVARIANT) && (cfg->max_rotation < SBR_PI_F)) {
        cb = cosf(cfg->max_rotation);
    }
    return cb;
}

/* Refinement and the result, given the grid peak `best` (found = 0: no admissible peak)
   and r at best - 1, best, best + 1. */
static void finish_match(uint32_t size, const sbr_fd_match_config_t *cfg,
                         const sbr_fd_t *query, const sbr_fd_t *proto, int found,
                         uint32_t best, const sbr_complex_t around[3], sbr_fd_match_t *result)
{
    int bounded = 0;
    sbr_complex_t r;
    float lag;
    float val;
    float rot;

    if ((cfg->mode == SBR_FD_ROTATION_COVARIANT) && (cfg->max_rotation < SBR_PI_F)) {
        bounded = 1;
    }
    result->scale_ratio = query->scale / proto->scale;
    if (found == 0) {
        result->error = 4.0f;
        result->rotation = 0.0f;
        result->shift = 0.0f;
        return;
    }
    r = around[1];
    lag = (float)best;
    val = objective(cfg->mode, r);
    if (cfg->refine != 0) {
        const float fa = objective(cfg->mode, around[0]);
        const float fb = objective(cfg->mode, around[2]);
        const float den = fa - (2.0f * val) + fb;
        if (den < 0.0f) {
            float d = 0.5f * (fa - fb) / den;
            sbr_complex_t rr;
            float vv;
            if (d > 0.5f) {
                d = 0.5f;
            }
            if (d < -0.5f) {
                d = -0.5f;
            }
            rr = corr_at(query, proto, (float)best + d, size);
            vv = objective(cfg->mode, rr);
            rot = sbr_util_atan2f(rr.im, rr.re);
            if ((vv >= val) && ((bounded == 0) || (fabsf(rot) <= cfg->max_rotation))) {
                r = rr;
                val = vv;
                lag = (float)best + d;
            }
        }
    }
    result->error = 2.0f - (2.0f * val);
    if (result->error < 0.0f) {
        result->error = 0.0f;
    }
    if (result->error > 4.0f) {
        result->error = 4.0f;
    }
    rot = -sbr_util_atan2f(r.im, r.re);
    if (rot <= -SBR_PI_F) {
        rot += SBR_TWO_PI_F;
    }
    result->rotation = rot;
    lag = lag / (float)size;
    if (lag < 0.0f) {
        lag += 1.0f;
    }
    if (lag >= 1.0f) {
        lag -= 1.0f;
    }
    result->shift = lag;
}

/* Screening (sbr_fd_match_config_t::max_error): |r| <= sum |Q(n)| |C(n)| at every lag,
   integer or not, and every mode's objective is at most |r|, so e >= 2 - 2 sum. A pair is
   skipped when that sum is below 1 - max_error / 2 by more than FD_SCREEN_MARGIN (far more
   than the rounding of a correlation of unit-energy descriptors). A non-finite
   coefficient makes the sum non-finite, which never passes the test: such a prototype is
   correlated and reported as before. */
#define FD_SCREEN_MARGIN 1.0e-4f

/* The level the magnitude sum must reach, or a negative value when nothing is screened
   (max_error 0: off; 2 or more: no pair could be ruled out). */
static float screen_level(const sbr_fd_match_config_t *cfg)
{
    float level = -1.0f;
    if ((cfg->max_error > 0.0f) && (cfg->max_error < 2.0f)) {
        level = (1.0f - (0.5f * cfg->max_error)) - FD_SCREEN_MARGIN;
    }
    return level;
}

/* |Q(n)| of the query's 2M + 1 coefficients. */
static void query_magnitudes(const sbr_fd_t *query, float *qmag)
{
    const uint32_t n = (2u * query->m) + 1u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const sbr_complex_t q = query->c[k];
        qmag[k] = sqrtf((q.re * q.re) + (q.im * q.im));
    }
}

/* screened_out() with the prototype's magnitudes given (pmag, query_magnitudes() of it):
   the same sum, term by term. */
static int screened_out_mag(const float *qmag, const float *pmag, uint32_t m, float level)
{
    const uint32_t n = (2u * m) + 1u;
    float sum = 0.0f;
    uint32_t k = 0u;
    int out = 0;
    while ((k < n) && (!(sum >= level))) {
        sum += qmag[k] * pmag[k];
        k++;
    }
    if (sum < level) {
        out = 1;
    }
    return out;
}

/* Is the pair certainly worse than max_error? (level from screen_level(), > 0) */
static int screened_out(const float *qmag, const sbr_fd_t *proto, float level)
{
    const uint32_t n = (2u * proto->m) + 1u;
    float sum = 0.0f;
    uint32_t k = 0u;
    int out = 0;
    /* The terms are >= 0 (or NaN), so a partial sum that reached the level stays there:
       the pair is not screened out, and the rest of the sum is not needed. */
    while ((k < n) && (!(sum >= level))) {
        const sbr_complex_t c = proto->c[k];
        sum += qmag[k] * sqrtf((c.re * c.re) + (c.im * c.im));
        k++;
    }
    if (sum < level) {
        out = 1;
    }
    return out;
}

/* The result of a pair that was not correlated (as finish_match() without a peak). */
static void no_match(const sbr_fd_t *query, const sbr_fd_t *proto, sbr_fd_match_t *result)
{
    result->scale_ratio = query->scale / proto->scale;
    result->error = 4.0f;
    result->rotation = 0.0f;
    result->shift = 0.0f;
}

/* One match through the FFT instance, on checked arguments (prototype included):
   SBR_OK, or SBR_ERR_RANGE (result untouched) when the correlation overflows float32 as
   the four-lane path finds it (descriptors of far more than unit energy). */
static sbr_status_t match_core(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                               const sbr_fd_t *query, const sbr_fd_t *proto, sbr_complex_t *work,
                               sbr_fd_match_t *result)
{
    const uint32_t size = fft->n;
    uint32_t k;

    /* indices 0..M and P-M..P-1 are filled; the gap between is zero */
    for (k = query->m + 1u; k < (size - query->m); k++) {
        work[k].re = 0.0f;
        work[k].im = 0.0f;
    }
    {
        uint32_t pos[(2u * SBR_FD_MAX_M) + 1u];
        /* the complex array seen as interleaved floats (re, im, re, im, ...) */
        float *f = (float *)(void *)work;
        product_positions(query->m, size, NULL, 2u, pos);
        write_products(query, proto, pos, f, &f[1]);
    }
    /* The instance was checked by the caller, so this cannot fail. The inverse is scaled
       by 1/P, so r = P * work. */
    (void)sbr_fft_inverse(fft, work, work);
    {
        const int inv = mode_invariant(cfg);
        const float cb = rotation_cos_bound(cfg);
        const float scale = (float)size;
        float best_val = FD_OUTSIDE;
        float check = (inv != 0) ? FD_OUTSIDE : 0.0f;
        uint32_t best = 0u;
        uint32_t l;
        sbr_complex_t around[3];
        for (l = 0u; l < size; l++) {
            const float v = (inv != 0) ? peak_value(1, cb, work[l].re, work[l].im)
                                       : peak_value_fast(cb, work[l].re, work[l].im);
            const float rr = work[l].re * scale;
            const float ri = work[l].im * scale;
            if (v > best_val) {
                best_val = v;
                best = l;
            }
            /* the four-lane path's overflow check, in r = P * work: the largest |r|^2
               (rotation invariant) or their sum */
            if (inv != 0) {
                const float v2 = (rr * rr) + (ri * ri);
                check = (v2 > check) ? v2 : check;
            } else {
                check += (rr * rr) + (ri * ri);
            }
        }
        if ((isfinite(check) == 0) || (check < 0.0f)) {
            return SBR_ERR_RANGE;
        }
        float best_r = best_val; /* in r = P * work */
        if (best_val > FD_OUTSIDE) {
            best_r = best_val * scale;
        }
        if ((inv == 0) && (rescan(best_r, cb) != 0)) {
            /* rare: the careful test, on r = P * work */
            best_val = FD_OUTSIDE;
            best = 0u;
            for (l = 0u; l < size; l++) {
                const float v = peak_value(0, cb, work[l].re * scale, work[l].im * scale);
                if (v > best_val) {
                    best_val = v;
                    best = l;
                }
            }
        }
        around[0] = work[(best + size - 1u) % size];
        around[1] = work[best];
        around[2] = work[(best + 1u) % size];
        for (l = 0u; l < 3u; l++) {
            around[l].re *= scale;
            around[l].im *= scale;
        }
        finish_match(size, cfg, query, proto, (best_val > FD_OUTSIDE) ? 1 : 0, best, around,
                     result);
    }
    return SBR_OK;
}

/* match_core() after the screening (checked arguments). */
static sbr_status_t match_screened(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                   const sbr_fd_t *query, const sbr_fd_t *proto,
                                   sbr_complex_t *work, sbr_fd_match_t *result)
{
    const float level = screen_level(cfg);
    int skip = 0;
    sbr_status_t st = SBR_OK;
    if (level > 0.0f) {
        float qmag[(2u * SBR_FD_MAX_M) + 1u];
        query_magnitudes(query, qmag);
        skip = screened_out(qmag, proto, level);
    }
    if (skip != 0) {
        no_match(query, proto, result);
    } else {
        st = match_core(fft, cfg, query, proto, work, result);
    }
    return st;
}

/* ---- table matching, FD_LANES prototypes at a time ----------------------------------
   The same correlation through a radix-2 transform whose butterflies work on FD_LANES
   independent transforms side by side (lane-interleaved arrays): the innermost loop has
   a fixed trip count over contiguous floats, which compilers map to SIMD registers on
   hosts that have them; on a scalar ECU core it costs the same as one transform after
   another. Layout of `work` (as floats): re[4P], im[4P], P / 2 complex twiddles, then
   P floats for the screening's query magnitudes (SBR_FD_TABLE_WORK_LEN = 5P complex). */
#define FD_LANES 4u

/* One radix-2 butterfly on FD_LANES transforms: all loads before all stores, so that the
   four lanes form straight-line groups a compiler can keep in one vector register. */
static void lanes_butterfly(float *ar, float *ai, float *br, float *bi, sbr_complex_t w)
{
    float xr[FD_LANES];
    float xi[FD_LANES];
    float yr[FD_LANES];
    float yi[FD_LANES];
    float tr[FD_LANES];
    float ti[FD_LANES];
    uint32_t b;

    for (b = 0u; b < FD_LANES; b++) {
        xr[b] = ar[b];
        xi[b] = ai[b];
        yr[b] = br[b];
        yi[b] = bi[b];
    }
    for (b = 0u; b < FD_LANES; b++) {
        tr[b] = (yr[b] * w.re) - (yi[b] * w.im);
        ti[b] = (yr[b] * w.im) + (yi[b] * w.re);
    }
    /* one store group per array: the groups stay in program order */
    for (b = 0u; b < FD_LANES; b++) {
        ar[b] = xr[b] + tr[b];
    }
    for (b = 0u; b < FD_LANES; b++) {
        ai[b] = xi[b] + ti[b];
    }
    for (b = 0u; b < FD_LANES; b++) {
        br[b] = xr[b] - tr[b];
    }
    for (b = 0u; b < FD_LANES; b++) {
        bi[b] = xi[b] - ti[b];
    }
}

/* The first two radix-2 stages of the decimation-in-time transform on each group of four:
   their twiddles are 1 and i (the inverse transform's e^{+i pi / 2}), so no multiplies.
   Written as whole-lane groups (loads, sums, differences, stores) that compilers keep in
   vector registers. */
static void lanes_first_stages(uint32_t size, float *re, float *im)
{
    uint32_t g;

    for (g = 0u; g < size; g += 4u) {
        float *r = &re[g * FD_LANES];
        float *m = &im[g * FD_LANES];
        float ar[FD_LANES];
        float ai[FD_LANES];
        float br[FD_LANES];
        float bi[FD_LANES];
        float cr[FD_LANES];
        float ci[FD_LANES];
        float dr[FD_LANES];
        float di[FD_LANES];
        uint32_t b;
        /* stage 1: (x0 +- x1), (x2 +- x3) */
        for (b = 0u; b < FD_LANES; b++) {
            ar[b] = r[b] + r[FD_LANES + b];
            ai[b] = m[b] + m[FD_LANES + b];
            br[b] = r[b] - r[FD_LANES + b];
            bi[b] = m[b] - m[FD_LANES + b];
            cr[b] = r[(2u * FD_LANES) + b] + r[(3u * FD_LANES) + b];
            ci[b] = m[(2u * FD_LANES) + b] + m[(3u * FD_LANES) + b];
            dr[b] = r[(2u * FD_LANES) + b] - r[(3u * FD_LANES) + b];
            di[b] = m[(2u * FD_LANES) + b] - m[(3u * FD_LANES) + b];
        }
        /* stage 2: a +- c, b +- i d */
        for (b = 0u; b < FD_LANES; b++) {
            r[b] = ar[b] + cr[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[b] = ai[b] + ci[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            r[FD_LANES + b] = br[b] - di[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[FD_LANES + b] = bi[b] + dr[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            r[(2u * FD_LANES) + b] = ar[b] - cr[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[(2u * FD_LANES) + b] = ai[b] - ci[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            r[(3u * FD_LANES) + b] = br[b] + di[b];
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[(3u * FD_LANES) + b] = bi[b] - dr[b];
        }
    }
}

/* In-place inverse transform (unscaled) of FD_LANES bit-reversed inputs, size >= 4: the
   first two stages without multiplies, then radix-2 stages. (Fusing pairs of the later
   stages into radix-4 steps was measured slower on x86-64: the compiler spills them.) */
static void lanes_transform(uint32_t size, const sbr_complex_t *tw, float *re, float *im)
{
    uint32_t half;

    lanes_first_stages(size, re, im);
    for (half = 4u; half < size; half *= 2u) {
        const uint32_t tstep = size / (2u * half);
        uint32_t j;
        for (j = 0u; j < half; j++) {
            const sbr_complex_t w = tw[j * tstep];
            uint32_t i;
            for (i = j; i < size; i += 2u * half) {
                lanes_butterfly(&re[i * FD_LANES], &im[i * FD_LANES], &re[(i + half) * FD_LANES],
                                &im[(i + half) * FD_LANES], w);
            }
        }
    }
}

/* One pass over the transformed lanes: the grid peak of each lane (first lag of the
   largest objective value, as the scalar search) and a check value that is finite and
   >= 0 iff the lane's prototype coefficients are finite. IEEE arithmetic never turns an
   infinity or a NaN back into a finite value and every output of the transform depends
   on every input, so one non-finite coefficient makes every |r|^2 non-finite: in the
   invariant mode the largest |r|^2 is the check (infinite, or never above its start value
   when all are NaN); in the covariant mode the sum of |r|^2 over the lags. (The query is
   finite with unit energy, so a prototype of finite energy cannot overflow either.)
   The invariant search is whole-lane compare-and-select steps, which map to SIMD. */
static void lanes_peaks(uint32_t size, int inv, float cb, const float *re, const float *im,
                        uint32_t best[FD_LANES], float check[FD_LANES])
{
    float bv[FD_LANES];
    float bl[FD_LANES];
    uint32_t l;
    uint32_t b;

    for (b = 0u; b < FD_LANES; b++) {
        bv[b] = FD_OUTSIDE;
        bl[b] = 0.0f;
        check[b] = 0.0f;
    }
    if (inv != 0) {
        for (l = 0u; l < size; l++) {
            const float *lr = &re[l * FD_LANES];
            const float *li = &im[l * FD_LANES];
            const float fl = (float)l;
            float v[FD_LANES];
            /* separate whole-lane steps: each maps to one vector operation */
            for (b = 0u; b < FD_LANES; b++) {
                v[b] = (lr[b] * lr[b]) + (li[b] * li[b]);
            }
            for (b = 0u; b < FD_LANES; b++) {
                bl[b] = (v[b] > bv[b]) ? fl : bl[b];
            }
            for (b = 0u; b < FD_LANES; b++) {
                bv[b] = (v[b] > bv[b]) ? v[b] : bv[b];
            }
        }
        for (b = 0u; b < FD_LANES; b++) {
            check[b] = bv[b];
        }
    } else {
        for (l = 0u; l < size; l++) {
            const float fl = (float)l;
            for (b = 0u; b < FD_LANES; b++) {
                const float xr = re[(l * FD_LANES) + b];
                const float xi = im[(l * FD_LANES) + b];
                const float v = peak_value_fast(cb, xr, xi);
                if (v > bv[b]) {
                    bv[b] = v;
                    bl[b] = fl;
                }
                check[b] += (xr * xr) + (xi * xi);
            }
        }
        for (b = 0u; b < FD_LANES; b++) {
            if (rescan(bv[b], cb) != 0) {
                /* rare: the careful test */
                bv[b] = FD_OUTSIDE;
                for (l = 0u; l < size; l++) {
                    const float v = peak_value(0, cb, re[(l * FD_LANES) + b], im[(l * FD_LANES) + b]);
                    if (v > bv[b]) {
                        bv[b] = v;
                        bl[b] = (float)l;
                    }
                }
            }
        }
    }
    for (b = 0u; b < FD_LANES; b++) {
        best[b] = (uint32_t)bl[b];
    }
}

/* conj(Q(n)) C(n) of four consecutive prototypes (FD_LANES = 4): per coefficient, the
   four prototypes' values are loaded one by one (straight-line code, which compilers pack
   into one vector on SIMD hosts) and the products are stored as whole-lane groups,
   instead of 2 x 4 scattered single stores. */
static void lanes_products(const sbr_fd_t *query, const sbr_fd_t *const protos[FD_LANES],
                           const uint32_t *pos, float *re, float *im)
{
    const uint32_t n = (2u * query->m) + 1u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const float qr = query->c[k].re;
        const float qi = query->c[k].im;
        const sbr_complex_t c0 = protos[0]->c[k];
        const sbr_complex_t c1 = protos[1]->c[k];
        const sbr_complex_t c2 = protos[2]->c[k];
        const sbr_complex_t c3 = protos[3]->c[k];
        const float cr[FD_LANES] = {c0.re, c1.re, c2.re, c3.re};
        const float ci[FD_LANES] = {c0.im, c1.im, c2.im, c3.im};
        float *r = &re[pos[k]];
        float *m = &im[pos[k]];
        uint32_t b;
        for (b = 0u; b < FD_LANES; b++) {
            r[b] = (qr * cr[b]) + (qi * ci[b]);
        }
        for (b = 0u; b < FD_LANES; b++) {
            m[b] = (qr * ci[b]) - (qi * cr[b]);
        }
    }
}

/* Was the lane's peak admissible (a value above FD_OUTSIDE)? */
static int found_any(int inv, float cb, sbr_complex_t at_best)
{
    int f = 0;
    float v;
    if (inv != 0) {
        v = peak_value(1, cb, at_best.re, at_best.im);
    } else if (fabsf(at_best.re) < FD_TINY_VALUE) {
        v = peak_value(0, cb, at_best.re, at_best.im); /* as the rescan judged it */
    } else {
        v = peak_value_fast(cb, at_best.re, at_best.im);
    }
    if (v > FD_OUTSIDE) {
        f = 1;
    }
    return f;
}

/* The four-lane batch of match_table_lanes(): up to four prototypes and their indices. */
typedef struct lane_batch_s {
    const sbr_fd_t *lane[FD_LANES];
    uint32_t idx[FD_LANES];
    uint32_t valid;
} lane_batch_t;

/* How a table is matched: trusted (its owner checked every entry, fd_internal.h) or not,
   and its entries' coefficient magnitudes when the owner computed them (NULL: computed
   per pair by the screening). */
typedef struct fd_table_s {
    int trusted;
    const float *pmag; /* per entry 2M + 1 values, query_magnitudes() of it */
} fd_table_t;

/* The next (up to) four prototypes from *i that pass the header check and the screening,
   in table order (the screened ones get their no-match result); the walk stops at the
   first bad header, whose status goes to *header. */
static void lanes_gather(const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                         const float *qmag, float level, const fd_table_t *tb, uint32_t *i,
                         lane_batch_t *bt, sbr_fd_match_t *results, sbr_status_t *header)
{
    const int trusted = tb->trusted;
    bt->valid = 0u;
    while ((bt->valid < FD_LANES) && (*i < count) && (*header == SBR_OK)) {
        /* a trusted table (checked by its owner, fd_internal.h) gets the per-pair checks
           only: its M and the scale ratio */
        *header = (trusted != 0) ? check_trusted(query, &protos[*i]) : check_proto(query, &protos[*i]);
        if (*header == SBR_OK) {
            int out = 0;
            if (level > 0.0f) {
                out = (tb->pmag != NULL)
                          ? screened_out_mag(qmag, &tb->pmag[*i * ((2u * query->m) + 1u)], query->m, level)
                          : screened_out(qmag, &protos[*i], level);
            }
            if (out != 0) {
                no_match(query, &protos[*i], &results[*i]);
            } else {
                bt->lane[bt->valid] = &protos[*i];
                bt->idx[bt->valid] = *i;
                bt->valid++;
            }
            *i += 1u;
        }
    }
}

/* The lanes' inputs: the products of the query with each prototype at their bit-reversed
   positions, zero elsewhere (only the gap n = M+1 .. P-M-1 needs clearing after the
   products are placed; unused lanes get zero input, their results are discarded). */
static void lanes_fill(const sbr_fft_t *fft, const sbr_fd_t *query, const lane_batch_t *bt,
                       const uint32_t *pos, float *re, float *im)
{
    const uint32_t size = fft->n;
    uint32_t b;
    uint32_t k;
    for (k = query->m + 1u; k < (size - query->m); k++) {
        const uint32_t at = (uint32_t)fft->bitrev[k] * FD_LANES;
        for (b = 0u; b < FD_LANES; b++) {
            re[at + b] = 0.0f;
            im[at + b] = 0.0f;
        }
    }
    for (b = bt->valid; b < FD_LANES; b++) {
        for (k = 0u; k < size; k++) {
            re[(k * FD_LANES) + b] = 0.0f;
            im[(k * FD_LANES) + b] = 0.0f;
        }
    }
    if (bt->valid == FD_LANES) {
        lanes_products(query, bt->lane, pos, re, im);
    } else {
        for (b = 0u; b < bt->valid; b++) {
            write_products(query, bt->lane[b], pos, &re[b], &im[b]);
        }
    }
}

/* The results of a transformed batch from each lane's correlation peak and its two
   neighbours. */
static void lanes_finish(uint32_t size, const sbr_fd_match_config_t *cfg, const sbr_fd_t *query,
                         const lane_batch_t *bt, int inv, float cb, const float *re,
                         const float *im, const uint32_t *best, sbr_fd_match_t *results)
{
    uint32_t b;
    uint32_t k;
    for (b = 0u; b < bt->valid; b++) {
        sbr_complex_t around[3];
        /* size is a power of two (a valid FFT instance) */
        const uint32_t at[3] = {(best[b] + size - 1u) & (size - 1u), best[b],
                                (best[b] + 1u) & (size - 1u)};
        for (k = 0u; k < 3u; k++) {
            around[k].re = re[(at[k] * FD_LANES) + b];
            around[k].im = im[(at[k] * FD_LANES) + b];
        }
        finish_match(size, cfg, query, bt->lane[b], found_any(inv, cb, around[1]), best[b],
                     around, &results[bt->idx[b]]);
    }
}

static sbr_status_t match_table_lanes(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                      const sbr_fd_t *query, const sbr_fd_t *protos,
                                      uint32_t count, const fd_table_t *tb, sbr_complex_t *work,
                                      sbr_fd_match_t *results)
{
    const uint32_t size = fft->n;
    /* lane buffers: the first 4P complex values of `work` seen as 8P floats */
    float *re = (float *)(void *)work;
    float *im = &re[size * FD_LANES];
    sbr_complex_t *tw = &work[size * FD_LANES];       /* P / 2 twiddles after re, im */
    /* the query's magnitudes in the last P floats (2M + 1 <= P) */
    float *qmag = (float *)(void *)&work[(size * FD_LANES) + (size / 2u)];
    const int inv = mode_invariant(cfg);
    const float cb = rotation_cos_bound(cfg);
    const float level = screen_level(cfg);
    uint32_t best[FD_LANES];
    float check[FD_LANES];
    uint32_t pos[(2u * SBR_FD_MAX_M) + 1u];
    uint32_t j;
    uint32_t i = 0u;
    sbr_status_t header = SBR_OK;

    product_positions(query->m, size, fft->bitrev, FD_LANES, pos);
    for (j = 0u; j < (size / 2u); j++) {
        const float a = (SBR_TWO_PI_F * (float)j) / (float)size;
        tw[j].re = cosf(a);
        tw[j].im = sinf(a);
    }
    if (level > 0.0f) {
        query_magnitudes(query, qmag);
    }
    while ((i < count) && (header == SBR_OK)) {
        /* each prototype is checked as sbr_fd_check() does when it is gathered; a bad
           one's status is returned after the batch gathered before it is transformed
           (whose correlations are checked for overflow), so the first bad prototype in
           table order decides the status */
        lane_batch_t bt;
        lanes_gather(query, protos, count, qmag, level, tb, &i, &bt, results, &header);
        if (bt.valid > 0u) {
            uint32_t b;
            lanes_fill(fft, query, &bt, pos, re, im);
            lanes_transform(size, tw, re, im);
            lanes_peaks(size, inv, cb, re, im, best, check);
            for (b = 0u; b < bt.valid; b++) {
                if ((isfinite(check[b]) == 0) || (check[b] < 0.0f)) {
                    return SBR_ERR_RANGE;
                }
            }
            lanes_finish(size, cfg, query, &bt, inv, cb, re, im, best, results);
        }
    }
    return header;
}

sbr_status_t sbr_fd_match(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                          const sbr_fd_t *query, const sbr_fd_t *proto, sbr_complex_t *work,
                          uint32_t work_len, sbr_fd_match_t *result)
{
    sbr_status_t st = check_match_args(fft, cfg, query, work, work_len, result);

    if (st == SBR_OK) {
        st = check_proto(query, proto);
    }
    if (st == SBR_OK) {
        st = match_screened(fft, cfg, query, proto, work, result);
    }
    return st;
}

/* sbr_fd_match_table(); trusted: the prototypes were checked by sbr_fd_check() before
   (fd_internal.h), so only the per-pair conditions are checked here. */
static sbr_status_t match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                const fd_table_t *tb, sbr_complex_t *work, uint32_t work_len,
                                sbr_fd_match_t *results, uint32_t *best)
{
    const int trusted = tb->trusted;
    sbr_status_t st = check_match_args(fft, cfg, query, work, work_len, results);
    uint32_t i;
    uint32_t b = 0u;

    if (st != SBR_OK) {
        return st;
    }
    if ((protos == NULL) || (best == NULL)) {
        return SBR_ERR_NULL;
    }
    if (count == 0u) {
        return SBR_ERR_SIZE;
    }
    if (work_len >= SBR_FD_TABLE_WORK_LEN(fft->n)) {
        st = match_table_lanes(fft, cfg, query, protos, count, tb, work, results);
        if (st != SBR_OK) {
            return st;
        }
    } else {
        for (i = 0u; i < count; i++) {
            st = (trusted != 0) ? check_trusted(query, &protos[i]) : check_proto(query, &protos[i]);
            if (st != SBR_OK) {
                return st;
            }
            st = match_screened(fft, cfg, query, &protos[i], work, &results[i]);
            if (st != SBR_OK) {
                return st;
            }
        }
    }
    for (i = 1u; i < count; i++) {
        if (results[i].error < results[b].error) {
            b = i;
        }
    }
    *best = b;
    return SBR_OK;
}

sbr_status_t sbr_fd_match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                sbr_complex_t *work, uint32_t work_len, sbr_fd_match_t *results,
                                uint32_t *best)
{
    const fd_table_t tb = {0, NULL};
    return match_table(fft, cfg, query, protos, count, &tb, work, work_len, results, best);
}

sbr_status_t sbr_fd_priv_match_checked_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                             const sbr_fd_t *query, const sbr_fd_t *protos,
                                             const float *proto_mag, uint32_t count,
                                             sbr_complex_t *work, uint32_t work_len,
                                             sbr_fd_match_t *results, uint32_t *best)
{
    const fd_table_t tb = {1, proto_mag};
    return match_table(fft, cfg, query, protos, count, &tb, work, work_len, results, best);
}

void sbr_fd_priv_magnitudes(const sbr_fd_t *fd, float *mag)
{
    query_magnitudes(fd, mag);
}
