/* SPDX-License-Identifier: MIT */
/* Fourier-descriptor matching (include/sbr/fd.h): the correlation of a query with a
   prototype (checks, products, peak search and its refinement, the screening), pair by
   pair through the FFT; the per-lane steps of the table matcher (peaks, gathering) that
   share these helpers. The table matcher itself is in fd_table.c. */
#include "sbr/fd.h"
#include "fd_match.h"

#include <math.h>

#include "../common/sbr_util.h"

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
sbr_status_t sbr_fd_priv_check_match_args(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
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
   query's M (sbr_fd_priv_check_proto() adds the coefficients). */
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
sbr_status_t sbr_fd_priv_check_proto(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    const sbr_status_t st = sbr_fd_check(proto, NULL);
    if (st != SBR_OK) {
        return st;
    }
    return check_proto_header(query, proto);
}

/* A prototype of a prepared table (sbr_fd_table_init() checked it; its scales and the
   query's are in SBR_FD_TABLE_MIN_SCALE .. SBR_FD_TABLE_MAX_SCALE, so their ratio is
   finite): only its M against the query's. */
sbr_status_t sbr_fd_priv_check_trusted(const sbr_fd_t *query, const sbr_fd_t *proto)
{
    return (proto->m == query->m) ? SBR_OK : SBR_ERR_SIZE;
}

/* Where conj(Q(n)) C(n), n = -M..M (k = n + M), goes: element `scale * place(n mod P)` of
   the re/im arrays, place = bit reversal (lane buffers) or identity (bitrev NULL). */
void sbr_fd_priv_product_positions(uint32_t m, uint32_t size, const uint16_t *bitrev,
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
void sbr_fd_priv_write_products(const sbr_fd_t *query, const sbr_fd_t *proto, const uint32_t *pos,
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

int sbr_fd_priv_mode_invariant(const sbr_fd_match_config_t *cfg)
{
    int inv = 0;
    if (cfg->mode == SBR_FD_ROTATION_INVARIANT) {
        inv = 1;
    }
    return inv;
}

/* cos of the rotation bound, or -2 (no bound) */
float sbr_fd_priv_rotation_cos_bound(const sbr_fd_match_config_t *cfg)
{
    float cb = -2.0f;
    if ((cfg->mode == SBR_FD_ROTATION_COVARIANT) && (cfg->max_rotation < SBR_PI_F)) {
        cb = cosf(cfg->max_rotation);
    }
    return cb;
}

/* Whether a pair is refined (an admissible grid peak, refine on, the parabola through r at
   best - 1, best, best + 1 concave) and the refined lag's offset d from best, |d| <= 1/2
   (0 when not refined). */
int sbr_fd_priv_refine_offset(const sbr_fd_match_config_t *cfg, int found,
                              const sbr_complex_t around[3], float *d)
{
    int refined = 0;
    *d = 0.0f;
    if ((found != 0) && (cfg->refine != 0)) {
        const float val = objective(cfg->mode, around[1]);
        const float fa = objective(cfg->mode, around[0]);
        const float fb = objective(cfg->mode, around[2]);
        const float den = fa - (2.0f * val) + fb;
        if (den < 0.0f) {
            float x = 0.5f * (fa - fb) / den;
            if (x > 0.5f) {
                x = 0.5f;
            }
            if (x < -0.5f) {
                x = -0.5f;
            }
            *d = x;
            refined = 1;
        }
    }
    return refined;
}

/* Refinement and the result, given the grid peak `best` (found = 0: no admissible peak),
   r at best - 1, best, best + 1, and r at the refined lag when the caller has it (`at_d`,
   corr_at() of best + d, d from sbr_fd_priv_refine_offset(); NULL: found here). */
void sbr_fd_priv_finish_match(uint32_t size, const sbr_fd_match_config_t *cfg,
                              const sbr_fd_t *query, const sbr_fd_t *proto, int found,
                              uint32_t best, const sbr_complex_t around[3],
                              const sbr_complex_t *at_d, sbr_fd_match_t *result)
{
    int bounded = 0;
    sbr_complex_t r;
    float lag;
    float val;
    float rot;
    float level;
    float d;

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
    level = sbr_fd_priv_screen_level(cfg);
    if (sbr_fd_priv_refine_offset(cfg, found, around, &d) != 0) {
        const sbr_complex_t rr = (at_d != NULL) ? *at_d : corr_at(query, proto, (float)best + d, size);
        const float vv = objective(cfg->mode, rr);
        rot = sbr_util_atan2f(rr.im, rr.re);
        if ((vv >= val) && ((bounded == 0) || (fabsf(rot) <= cfg->max_rotation))) {
            r = rr;
            val = vv;
            lag = (float)best + d;
        }
    }
    if ((level > 0.0f) && (val < level)) {
        /* below the screening's level (max_error > 0): the error is above max_error by more
           than the margin, so the pair gets the no-match result, as the screening before
           the transform gives it (the rotation and shift need not be found) */
        result->error = 4.0f;
        result->rotation = 0.0f;
        result->shift = 0.0f;
        return;
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
float sbr_fd_priv_screen_level(const sbr_fd_match_config_t *cfg)
{
    float level = -1.0f;
    if ((cfg->max_error > 0.0f) && (cfg->max_error < 2.0f)) {
        level = (1.0f - (0.5f * cfg->max_error)) - FD_SCREEN_MARGIN;
    }
    return level;
}

/* |Q(n)| of the query's 2M + 1 coefficients. */
void sbr_fd_priv_magnitudes(const sbr_fd_t *query, float *qmag)
{
    const uint32_t n = (2u * query->m) + 1u;
    uint32_t k;
    for (k = 0u; k < n; k++) {
        const sbr_complex_t q = query->c[k];
        qmag[k] = sqrtf((q.re * q.re) + (q.im * q.im));
    }
}

/* screened_out() with the prototype's magnitudes given (pmag, sbr_fd_priv_magnitudes() of it):
   the same sum, term by term. */
static int screened_out_mag(const float *qmag, const float *pmag, uint32_t m, float level)
{
    const uint32_t n = (2u * m) + 1u;
    const uint32_t n4 = n - (n % 4u);
    float sum = 0.0f;
    uint32_t k = 0u;
    int out = 0;
    /* The level tested every four terms: the partial sums are the same, and a sum that
       reached the level stays there (the terms are >= 0; a NaN term keeps the pair in,
       as before), so the verdict is the same as with a test after every term. */
    while ((k < n4) && (!(sum >= level))) {
        sum += qmag[k] * pmag[k];
        sum += qmag[k + 1u] * pmag[k + 1u];
        sum += qmag[k + 2u] * pmag[k + 2u];
        sum += qmag[k + 3u] * pmag[k + 3u];
        k += 4u;
    }
    while ((k < n) && (!(sum >= level))) {
        sum += qmag[k] * pmag[k];
        k++;
    }
    if (sum < level) {
        out = 1;
    }
    return out;
}

/* Is the pair certainly worse than max_error? (level from sbr_fd_priv_screen_level(), > 0) */
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

/* The result of a pair that was not correlated (as sbr_fd_priv_finish_match() without a peak). */
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
        sbr_fd_priv_product_positions(query->m, size, NULL, 2u, pos);
        sbr_fd_priv_write_products(query, proto, pos, f, &f[1]);
    }
    /* The instance was checked by the caller, so this cannot fail. The inverse is scaled
       by 1/P, so r = P * work. */
    (void)sbr_fft_inverse(fft, work, work);
    {
        const int inv = sbr_fd_priv_mode_invariant(cfg);
        const float cb = sbr_fd_priv_rotation_cos_bound(cfg);
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
        sbr_fd_priv_finish_match(size, cfg, query, proto, (best_val > FD_OUTSIDE) ? 1 : 0, best, around,
                                 NULL, result);
    }
    return SBR_OK;
}

/* match_core() after the screening (checked arguments). */
sbr_status_t sbr_fd_priv_match_screened(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                        const sbr_fd_t *query, const sbr_fd_t *proto,
                                        sbr_complex_t *work, sbr_fd_match_t *result)
{
    const float level = sbr_fd_priv_screen_level(cfg);
    int skip = 0;
    sbr_status_t st = SBR_OK;
    if (level > 0.0f) {
        float qmag[(2u * SBR_FD_MAX_M) + 1u];
        sbr_fd_priv_magnitudes(query, qmag);
        skip = screened_out(qmag, proto, level);
    }
    if (skip != 0) {
        no_match(query, proto, result);
    } else {
        st = match_core(fft, cfg, query, proto, work, result);
    }
    return st;
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
void sbr_fd_priv_lanes_peaks(uint32_t size, int inv, float cb, const float *re, const float *im,
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
                /* peak_value_fast() is xr or FD_OUTSIDE (the start value), so only a lag
                   whose xr beats the best so far can change the best: the bound's square
                   root is taken for those alone (a NaN xr beats nothing, as before) */
                if ((xr > bv[b]) && (peak_value_fast(cb, xr, im[(l * FD_LANES) + b]) > bv[b])) {
                    bv[b] = xr;
                    bl[b] = fl;
                }
            }
        }
        sbr_fd_priv_lanes_energy(size, re, im, check);
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

/* Was the lane's peak admissible (a value above FD_OUTSIDE)? */
int sbr_fd_priv_found_any(int inv, float cb, sbr_complex_t at_best)
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

/* The next (up to) four prototypes from *i that pass the header check and the screening,
   in table order (the screened ones get their no-match result); the walk stops at the
   first bad header, whose status goes to *header. */
void sbr_fd_priv_lanes_gather(const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                              const float *qmag, float level, const fd_table_t *tb, uint32_t *i,
                              lane_batch_t *bt, sbr_fd_match_t *results, sbr_status_t *header)
{
    const int trusted = tb->trusted;
    bt->valid = 0u;
    while ((bt->valid < FD_LANES) && (*i < count) && (*header == SBR_OK)) {
        /* a trusted table (sbr_fd_table_init() checked it) gets the per-pair checks
           only: its M and the scale ratio */
        *header = (trusted != 0) ? sbr_fd_priv_check_trusted(query, &protos[*i]) : sbr_fd_priv_check_proto(query, &protos[*i]);
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

sbr_status_t sbr_fd_match(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                          const sbr_fd_t *query, const sbr_fd_t *proto, sbr_complex_t *work,
                          uint32_t work_len, sbr_fd_match_t *result)
{
    sbr_status_t st = sbr_fd_priv_check_match_args(fft, cfg, query, work, work_len, result);

    if (st == SBR_OK) {
        st = sbr_fd_priv_check_proto(query, proto);
    }
    if (st == SBR_OK) {
        st = sbr_fd_priv_match_screened(fft, cfg, query, proto, work, result);
    }
    return st;
}
