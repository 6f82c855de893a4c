/* SPDX-License-Identifier: MIT */
/* Fourier descriptors (include/sbr/fd.h): descriptors of contours (resampling, FFT,
   normalisation), their check, mirror and smoothing. Matching: fd_match.c, fd_table.c. */
#include "sbr/fd.h"

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
    float xa;
    float ya;
    float xb;
    float yb;
    float seg; /* segment i: from (xa, ya) to (xb, yb), its length */
    get_point(pi, pf, 0u, &xa, &ya);
    get_point(pi, pf, next_index(0u, count), &xb, &yb);
    seg = hypotf(xb - xa, yb - ya);
    for (k = 0u; k < n; k++) {
        const float t = step * (float)k;
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
