#include "sbr/fd.h"

#include <math.h>

#define SBR_PI_F 3.14159265f
#define SBR_TWO_PI_F 6.28318531f

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

static sbr_status_t fd_compute(const sbr_fft_t *fft, const sbr_point_t *pi,
                               const sbr_pointf_t *pf, uint32_t count, uint32_t m,
                               sbr_complex_t *work, uint32_t work_len, sbr_fd_t *out)
{
    sbr_status_t st = sbr_fft_check(fft);
    float length = 0.0f;
    float area2 = 0.0f;
    float x0;
    float y0;
    float step;
    float acc;
    float energy;
    float inv_n;
    float inv_scale;
    uint32_t n;
    uint32_t i;
    uint32_t j;
    uint32_t k;

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
    /* Validate, measure the length and the area (relative to the first point, which keeps
       the shoelace sum accurate for contours far from the origin). */
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
        j = next_index(i, count);
        get_point(pi, pf, j, &xb, &yb);
        length += hypotf(xb - xa, yb - ya);
        area2 += ((xa - x0) * (yb - y0)) - ((xb - x0) * (ya - y0));
    }
    if ((length <= 0.0f) || (fabsf(area2) <= (1e-6f * length * length))) {
        return SBR_ERR_DEGENERATE;
    }

    /* Arc-length resampling at N equally spaced positions, starting at point 0. */
    step = length / (float)n;
    acc = 0.0f; /* arc length at the start of segment i */
    i = 0u;
    for (k = 0u; k < n; k++) {
        const float t = step * (float)k;
        float xa;
        float ya;
        float xb;
        float yb;
        float seg;
        get_point(pi, pf, i, &xa, &ya);
        j = next_index(i, count);
        get_point(pi, pf, j, &xb, &yb);
        seg = hypotf(xb - xa, yb - ya);
        while ((i + 1u) < count) {
            if ((acc + seg) >= t) {
                break;
            }
            acc += seg;
            i++;
            xa = xb;
            ya = yb;
            j = next_index(i, count);
            get_point(pi, pf, j, &xb, &yb);
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
    st = sbr_fft_forward(fft, work, work);
    if (st != SBR_OK) {
        return st;
    }
    inv_n = 1.0f / (float)n;
    energy = 0.0f;
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

static sbr_status_t check_fd(const sbr_fd_t *fd)
{
    uint32_t k;
    if (fd == NULL) {
        return SBR_ERR_NULL;
    }
    if ((fd->m == 0u) || (fd->m > SBR_FD_MAX_M) || (isfinite(fd->scale) == 0) ||
        (fd->scale <= 0.0f)) {
        return SBR_ERR_RANGE;
    }
    for (k = 0u; k <= (2u * fd->m); k++) {
        if ((isfinite(fd->c[k].re) == 0) || (isfinite(fd->c[k].im) == 0)) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

sbr_status_t sbr_fd_mirror(const sbr_fd_t *in, sbr_fd_t *out)
{
    const sbr_status_t st = check_fd(in);
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
    const sbr_status_t st = check_fd(in);
    const float g = 2.0f * SBR_PI_F * SBR_PI_F * sigma * sigma;
    float energy = 0.0f;
    float inv;
    uint32_t m;
    uint32_t k;

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
    *out = *in;
    for (k = 1u; k <= m; k++) {
        const float fk = (float)k;
        const float w = expf(-g * fk * fk);
        out->c[m + k].re *= w;
        out->c[m + k].im *= w;
        out->c[m - k].re *= w;
        out->c[m - k].im *= w;
        energy += (out->c[m + k].re * out->c[m + k].re) + (out->c[m + k].im * out->c[m + k].im) +
                  (out->c[m - k].re * out->c[m - k].re) + (out->c[m - k].im * out->c[m - k].im);
    }
    if (energy <= 0.0f) {
        return SBR_ERR_RANGE;
    }
    inv = 1.0f / sqrtf(energy);
    for (k = 0u; k <= (2u * m); k++) {
        out->c[k].re *= inv;
        out->c[k].im *= inv;
    }
    return SBR_OK;
}

sbr_status_t sbr_fd_match_config_default(sbr_fd_match_config_t *cfg)
{
    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    cfg->mode = SBR_FD_ROTATION_COVARIANT;
    cfg->max_rotation = SBR_PI_F;
    cfg->refine = 1;
    return SBR_OK;
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
    return (mode == SBR_FD_ROTATION_INVARIANT) ? hypotf(r.re, r.im) : r.re;
}

/* Everything a match needs except the prototype: checked once per call of
   sbr_fd_match() and once per table in sbr_fd_match_table(). */
static sbr_status_t check_match_args(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                     const sbr_fd_t *query, const sbr_complex_t *work,
                                     uint32_t work_len, const void *result)
{
    sbr_status_t st = sbr_fft_check(fft);

    if (st == SBR_OK) {
        st = check_fd(query);
    }
    if (st != SBR_OK) {
        return st;
    }
    if ((cfg == NULL) || (work == NULL) || (result == NULL)) {
        return SBR_ERR_NULL;
    }
    if (((cfg->mode != SBR_FD_ROTATION_INVARIANT) && (cfg->mode != SBR_FD_ROTATION_COVARIANT)) ||
        (isfinite(cfg->max_rotation) == 0) || (cfg->max_rotation < 0.0f)) {
        return SBR_ERR_RANGE;
    }
    if ((fft->n < ((2u * query->m) + 1u)) || (work_len < fft->n)) {
        return SBR_ERR_SIZE;
    }
    return SBR_OK;
}

/* A prototype must be a valid descriptor with the query's M. */
static sbr_status_t check_proto(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    const sbr_status_t st = check_fd(proto);

    if (st != SBR_OK) {
        return st;
    }
    return (proto->m != query->m) ? SBR_ERR_SIZE : SBR_OK;
}

/* The match itself, on arguments already checked. */
static void match_core(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                       const sbr_fd_t *query, const sbr_fd_t *proto, sbr_complex_t *work,
                       sbr_fd_match_t *result)
{
    const uint32_t size = fft->n;
    const uint32_t m = query->m;
    uint32_t k;
    uint32_t l;
    uint32_t best = 0u;
    float best_val = -1.0f;
    float cos_bound = -1.0f;
    int found = 0;
    int bounded;
    sbr_complex_t r;
    float lag;
    float val;
    float rot;

    /* conj(Q) C at n mod P: indices 0..M and P-M..P-1; the gap between is zero. */
    for (k = m + 1u; k < (size - m); k++) {
        work[k].re = 0.0f;
        work[k].im = 0.0f;
    }
    for (k = 0u; k <= (2u * m); k++) {
        const sbr_complex_t q = query->c[k];
        const sbr_complex_t c = proto->c[k];
        uint32_t at = k - m;
        if (k < m) {
            at = (size + k) - m;
        }
        work[at].re = (q.re * c.re) + (q.im * c.im);
        work[at].im = (q.re * c.im) - (q.im * c.re);
    }
    /* The instance was checked by the caller, so this cannot fail. */
    (void)sbr_fft_inverse(fft, work, work);
    /* The inverse is scaled by 1/P; r = P * work. Only comparisons follow, so the scale
       is applied to the peak only. */
    bounded = 0;
    if ((cfg->mode == SBR_FD_ROTATION_COVARIANT) && (cfg->max_rotation < SBR_PI_F)) {
        bounded = 1;
        cos_bound = cosf(cfg->max_rotation);
    }
    for (l = 0u; l < size; l++) {
        const sbr_complex_t v = work[l];
        if (cfg->mode == SBR_FD_ROTATION_INVARIANT) {
            val = (v.re * v.re) + (v.im * v.im);
        } else {
            val = v.re;
            if ((bounded != 0) && (v.re < (cos_bound * hypotf(v.re, v.im)))) {
                continue;
            }
        }
        if ((found == 0) || (val > best_val)) {
            best_val = val;
            best = l;
            found = 1;
        }
    }
    if (found == 0) {
        result->error = 4.0f;
        result->rotation = 0.0f;
        result->shift = 0.0f;
        result->scale_ratio = query->scale / proto->scale;
        return;
    }
    r.re = work[best].re * (float)size;
    r.im = work[best].im * (float)size;
    lag = (float)best;
    val = objective(cfg->mode, r);
    if (cfg->refine != 0) {
        const uint32_t lm = (best + size - 1u) % size;
        const uint32_t lp = (best + 1u) % size;
        sbr_complex_t a = work[lm];
        sbr_complex_t b = work[lp];
        float fa;
        float fb;
        float den;
        a.re *= (float)size;
        a.im *= (float)size;
        b.re *= (float)size;
        b.im *= (float)size;
        fa = objective(cfg->mode, a);
        fb = objective(cfg->mode, b);
        den = fa - (2.0f * val) + fb;
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
            rot = atan2f(rr.im, rr.re);
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
    rot = -atan2f(r.im, r.re);
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
    result->scale_ratio = query->scale / proto->scale;
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
        match_core(fft, cfg, query, proto, work, result);
    }
    return st;
}

sbr_status_t sbr_fd_match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                sbr_complex_t *work, uint32_t work_len, sbr_fd_match_t *results,
                                uint32_t *best)
{
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
    for (i = 0u; i < count; i++) {
        st = check_proto(query, &protos[i]);
        if (st != SBR_OK) {
            return st;
        }
        match_core(fft, cfg, query, &protos[i], work, &results[i]);
        if (results[i].error < results[b].error) {
            b = i;
        }
    }
    *best = b;
    return SBR_OK;
}
