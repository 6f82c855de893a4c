/* SPDX-License-Identifier: MIT */
/* Channel representation (include/sbr/channel.h): cos^2 channel encoding, soft 1-D and
   2-D histograms and their mode decoding. */
#include "sbr/channel.h"

#include <math.h>

#include "../common/sbr_util.h"

/* Slack (in channels) on both ends of a window's valid interval. Without it, a value on
   the boundary between two windows can be rounded out of both and lost; with it, both
   windows may accept it, and the near-identical estimates are merged (see insert_*). */
#define SBR_CHANNEL_VALID_EPS 1e-3f
/* Estimates closer than this (in channels) are one mode. */
#define SBR_CHANNEL_SAME_MODE 4e-3f

static int is_finite_f(float v)
{
    return (isfinite(v) != 0) ? 1 : 0;
}

void sbr_channel_config_default(sbr_channel_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->first_centre = 1.0f;
        cfg->spacing = 1.0f;
        cfg->count = 10u;
        cfg->overlap = 3u;
    }
}

void sbr_channel2d_config_default(sbr_channel2d_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_channel_config_default(&cfg->x);
        sbr_channel_config_default(&cfg->y);
    }
}

sbr_status_t sbr_channel_config_check(const sbr_channel_config_t *cfg)
{
    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    if ((is_finite_f(cfg->first_centre) == 0) || (is_finite_f(cfg->spacing) == 0) ||
        (cfg->spacing <= 0.0f) || (cfg->overlap < SBR_CHANNEL_MIN_OVERLAP) ||
        (cfg->overlap > SBR_CHANNEL_MAX_OVERLAP)) {
        return SBR_ERR_RANGE;
    }
    if ((cfg->count < cfg->overlap) || (cfg->count > SBR_CHANNEL_MAX_COUNT)) {
        return SBR_ERR_SIZE;
    }
    /* every value a window can decode to, a whole kernel beyond either end, stays finite */
    {
        const uint32_t reach = cfg->count + cfg->overlap;
        if ((is_finite_f(cfg->first_centre + (cfg->spacing * (float)reach)) == 0) ||
            (is_finite_f(cfg->first_centre - (cfg->spacing * (float)cfg->overlap)) == 0)) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

/* A valid channel value: finite, >= 0, at most SBR_CHANNEL_MAX_VALUE. */
static int value_ok(float h)
{
    return ((is_finite_f(h) != 0) && (h >= 0.0f) && (h <= SBR_CHANNEL_MAX_VALUE)) ? 1 : 0;
}

/* Representable interval in channel coordinates u = (x - first_centre) / spacing. */
static void range_u(const sbr_channel_config_t *cfg, float *lo, float *hi)
{
    const float half_m = 0.5f * (float)cfg->overlap;
    const uint32_t last = cfg->count - 1u;
    *lo = half_m - 1.0f;
    *hi = (float)last - (half_m - 1.0f);
}

sbr_status_t sbr_channel_range(const sbr_channel_config_t *cfg, float *lo, float *hi)
{
    const sbr_status_t st = sbr_channel_config_check(cfg);
    float ulo;
    float uhi;

    if (st != SBR_OK) {
        return st;
    }
    if ((lo == NULL) || (hi == NULL)) {
        return SBR_ERR_NULL;
    }
    range_u(cfg, &ulo, &uhi);
    *lo = cfg->first_centre + (ulo * cfg->spacing);
    *hi = cfg->first_centre + (uhi * cfg->spacing);
    return SBR_OK;
}

/* Validates and converts x to channel coordinates; gives the first active channel and
   the kernel values of the (at most M) channels from there on. */
static sbr_status_t encode_prepare(const sbr_channel_config_t *cfg, float x, float weight,
                                   const float *buf, uint32_t len, uint32_t *first,
                                   float vals[SBR_CHANNEL_MAX_OVERLAP], uint32_t *nvals)
{
    const sbr_status_t st = sbr_channel_config_check(cfg);
    float u;
    float ulo;
    float uhi;
    float start;
    float scale;
    uint32_t k;
    uint32_t m;

    if (st != SBR_OK) {
        return st;
    }
    if (buf == NULL) {
        return SBR_ERR_NULL;
    }
    if (len < cfg->count) {
        return SBR_ERR_SIZE;
    }
    if ((is_finite_f(x) == 0) || (is_finite_f(weight) == 0) || (weight <= 0.0f) ||
        (weight > SBR_CHANNEL_MAX_VALUE)) {
        return SBR_ERR_RANGE;
    }
    u = (x - cfg->first_centre) / cfg->spacing;
    range_u(cfg, &ulo, &uhi);
    if ((u < ulo) || (u >= uhi)) {
        return SBR_ERR_RANGE;
    }
    m = cfg->overlap;
    /* Active channels k satisfy |u - k| < M/2. */
    start = ceilf(u - (0.5f * (float)m));
    if (start < 0.0f) {
        start = 0.0f;
    }
    *first = (uint32_t)start;
    scale = SBR_PI_F / (float)m;
    *nvals = 0u;
    for (k = *first; (k < cfg->count) && (*nvals < m); k++) {
        const float d = u - (float)k;
        if (fabsf(d) < (0.5f * (float)m)) {
            const float c = cosf(scale * d);
            vals[*nvals] = weight * c * c;
        } else {
            vals[*nvals] = 0.0f;
        }
        (*nvals)++;
    }
    return SBR_OK;
}

sbr_status_t sbr_channel_encode(const sbr_channel_config_t *cfg, float x, float weight,
                                float *out, uint32_t len)
{
    float vals[SBR_CHANNEL_MAX_OVERLAP];
    uint32_t first = 0u;
    uint32_t nvals = 0u;
    uint32_t k;
    const sbr_status_t st = encode_prepare(cfg, x, weight, out, len, &first, vals, &nvals);

    if (st != SBR_OK) {
        return st;
    }
    for (k = 0u; k < cfg->count; k++) {
        out[k] = 0.0f;
    }
    for (k = 0u; k < nvals; k++) {
        out[first + k] = vals[k];
    }
    return SBR_OK;
}

sbr_status_t sbr_channel_accumulate(const sbr_channel_config_t *cfg, float x, float weight,
                                    float *hist, uint32_t len)
{
    float vals[SBR_CHANNEL_MAX_OVERLAP];
    uint32_t first = 0u;
    uint32_t nvals = 0u;
    uint32_t k;
    const sbr_status_t st = encode_prepare(cfg, x, weight, hist, len, &first, vals, &nvals);

    if (st != SBR_OK) {
        return st;
    }
    /* every channel stays a valid histogram value (finite, >= 0, at most
       SBR_CHANNEL_MAX_VALUE), or nothing is added */
    for (k = 0u; k < nvals; k++) {
        const float h = hist[first + k];
        if ((value_ok(h) == 0) || (value_ok(h + vals[k]) == 0)) {
            return SBR_ERR_RANGE;
        }
    }
    for (k = 0u; k < nvals; k++) {
        hist[first + k] += vals[k];
    }
    return SBR_OK;
}

/* Unit phasors e^{i 2 pi k / M}, k = 0..M-1 (M <= 8, computed per call: no tables). */
static void window_phasors(uint32_t m, float re[SBR_CHANNEL_MAX_OVERLAP],
                           float im[SBR_CHANNEL_MAX_OVERLAP])
{
    uint32_t k;
    for (k = 0u; k < m; k++) {
        const float a = (2.0f * SBR_PI_F * (float)k) / (float)m;
        re[k] = cosf(a);
        im[k] = sinf(a);
    }
}

/* Offset within a window (in channels) decoded from a phasor sum; validity of it. */
static float window_offset(uint32_t m, float sre, float sim, int *valid)
{
    const float mid = 0.5f * ((float)m - 1.0f);
    float off;

    if ((sre == 0.0f) && (sim == 0.0f)) {
        /* arg(0) taken as 0, as in the thesis's table; never valid. */
        *valid = 0;
        return 0.0f;
    }
    off = ((float)m / (2.0f * SBR_PI_F)) * atan2f(sim, sre);
    if ((off >= (mid - 0.5f - SBR_CHANNEL_VALID_EPS)) &&
        (off < (mid + 0.5f + SBR_CHANNEL_VALID_EPS))) {
        *valid = 1;
    } else {
        *valid = 0;
    }
    return off;
}

static sbr_status_t check_hist(const sbr_channel_config_t *cfg, const float *hist,
                               uint32_t len)
{
    const sbr_status_t st = sbr_channel_config_check(cfg);
    uint32_t k;

    if (st != SBR_OK) {
        return st;
    }
    if (hist == NULL) {
        return SBR_ERR_NULL;
    }
    if (len < cfg->count) {
        return SBR_ERR_SIZE;
    }
    for (k = 0u; k < cfg->count; k++) {
        if (value_ok(hist[k]) == 0) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

static void decode_one(const sbr_channel_config_t *cfg, const float *hist, uint32_t window,
                       const float *pre, const float *pim, float *value, float *certainty,
                       int *valid)
{
    float sre = 0.0f;
    float sim = 0.0f;
    float sum = 0.0f;
    uint32_t k;

    for (k = 0u; k < cfg->overlap; k++) {
        const float c = hist[window + k];
        sre += c * pre[k];
        sim += c * pim[k];
        sum += c;
    }
    *value = cfg->first_centre +
             (cfg->spacing * ((float)window + window_offset(cfg->overlap, sre, sim, valid)));
    *certainty = sum;
}

sbr_status_t sbr_channel_decode_window(const sbr_channel_config_t *cfg, const float *hist,
                                       uint32_t len, uint32_t window, float *value,
                                       float *certainty, int *valid)
{
    float pre[SBR_CHANNEL_MAX_OVERLAP];
    float pim[SBR_CHANNEL_MAX_OVERLAP];
    const sbr_status_t st = check_hist(cfg, hist, len);

    if (st != SBR_OK) {
        return st;
    }
    if ((value == NULL) || (certainty == NULL) || (valid == NULL)) {
        return SBR_ERR_NULL;
    }
    if (window > (cfg->count - cfg->overlap)) {
        return SBR_ERR_RANGE;
    }
    window_phasors(cfg->overlap, pre, pim);
    decode_one(cfg, hist, window, pre, pim, value, certainty, valid);
    return SBR_OK;
}

/* Adds a mode to a list sorted by decreasing certainty (ties keep scan order), holding
   at most `capacity`. A mode within `same` of one already listed is the same mode seen
   by two windows: the stronger of the two is kept. Returns 1 if a distinct mode did not
   fit (the list then holds the strongest `capacity`). */
static int insert_1d(sbr_channel_mode_t *modes, uint32_t capacity, uint32_t *n,
                     float value, float certainty, float same)
{
    uint32_t i;
    uint32_t pos;
    uint32_t dup;

    dup = *n;
    for (i = 0u; i < *n; i++) {
        if ((dup == *n) && (fabsf(modes[i].value - value) <= same)) {
            dup = i;
        }
    }
    if (dup < *n) {
        if (modes[dup].certainty >= certainty) {
            return 0;
        }
        for (i = dup; (i + 1u) < *n; i++) {
            modes[i] = modes[i + 1u];
        }
        (*n)--;
    }
    pos = *n;
    while ((pos > 0u) && (modes[pos - 1u].certainty < certainty)) {
        pos--;
    }
    if (pos >= capacity) {
        return 1;
    }
    i = (*n < capacity) ? *n : (capacity - 1u);
    while (i > pos) {
        modes[i] = modes[i - 1u];
        i--;
    }
    modes[pos].value = value;
    modes[pos].certainty = certainty;
    if (*n < capacity) {
        (*n)++;
        return 0;
    }
    return 1;
}

static int insert_2d(sbr_channel_mode2d_t *modes, uint32_t capacity, uint32_t *n, float x,
                     float y, float certainty, float same_x, float same_y)
{
    uint32_t i;
    uint32_t pos;
    uint32_t dup;

    dup = *n;
    for (i = 0u; i < *n; i++) {
        if ((dup == *n) && ((fabsf(modes[i].x - x) <= same_x) && (fabsf(modes[i].y - y) <= same_y))) {
            dup = i;
        }
    }
    if (dup < *n) {
        if (modes[dup].certainty >= certainty) {
            return 0;
        }
        for (i = dup; (i + 1u) < *n; i++) {
            modes[i] = modes[i + 1u];
        }
        (*n)--;
    }
    pos = *n;
    while ((pos > 0u) && (modes[pos - 1u].certainty < certainty)) {
        pos--;
    }
    if (pos >= capacity) {
        return 1;
    }
    i = (*n < capacity) ? *n : (capacity - 1u);
    while (i > pos) {
        modes[i] = modes[i - 1u];
        i--;
    }
    modes[pos].x = x;
    modes[pos].y = y;
    modes[pos].certainty = certainty;
    if (*n < capacity) {
        (*n)++;
        return 0;
    }
    return 1;
}

static sbr_status_t check_outputs(const void *modes, uint32_t capacity, const uint32_t *count,
                                  float min_certainty)
{
    if (count == NULL) {
        return SBR_ERR_NULL;
    }
    if ((modes == NULL) && (capacity != 0u)) {
        return SBR_ERR_NULL;
    }
    if ((is_finite_f(min_certainty) == 0) || (min_certainty < 0.0f)) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

sbr_status_t sbr_channel_decode(const sbr_channel_config_t *cfg, const float *hist,
                                uint32_t len, float min_certainty, sbr_channel_mode_t *modes,
                                uint32_t capacity, uint32_t *count)
{
    float pre[SBR_CHANNEL_MAX_OVERLAP];
    float pim[SBR_CHANNEL_MAX_OVERLAP];
    sbr_status_t st = check_hist(cfg, hist, len);
    uint32_t n = 0u;
    uint32_t w;
    int overflow = 0;

    if (st == SBR_OK) {
        st = check_outputs(modes, capacity, count, min_certainty);
    }
    if (st != SBR_OK) {
        if (count != NULL) {
            *count = 0u;
        }
        return st;
    }
    window_phasors(cfg->overlap, pre, pim);
    for (w = 0u; w <= (cfg->count - cfg->overlap); w++) {
        float value;
        float cert;
        int valid;
        decode_one(cfg, hist, w, pre, pim, &value, &cert, &valid);
        if ((valid != 0) && (cert > min_certainty)) {
            if (insert_1d(modes, capacity, &n, value, cert,
                          SBR_CHANNEL_SAME_MODE * cfg->spacing) != 0) {
                overflow = 1;
            }
        }
    }
    *count = n;
    return (overflow != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}

sbr_status_t sbr_channel2d_config_check(const sbr_channel2d_config_t *cfg)
{
    sbr_status_t st;

    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    st = sbr_channel_config_check(&cfg->x);
    if (st == SBR_OK) {
        st = sbr_channel_config_check(&cfg->y);
    }
    return st;
}

uint32_t sbr_channel2d_grid_len(const sbr_channel2d_config_t *cfg)
{
    return (sbr_channel2d_config_check(cfg) == SBR_OK) ? (cfg->x.count * cfg->y.count) : 0u;
}

sbr_status_t sbr_channel2d_accumulate(const sbr_channel2d_config_t *cfg, float x, float y,
                                      float weight, float *grid, uint32_t len)
{
    float vx[SBR_CHANNEL_MAX_OVERLAP];
    float vy[SBR_CHANNEL_MAX_OVERLAP];
    uint32_t fx = 0u;
    uint32_t fy = 0u;
    uint32_t nx = 0u;
    uint32_t ny = 0u;
    uint32_t i;
    uint32_t j;
    sbr_status_t st = sbr_channel2d_config_check(cfg);

    if (st != SBR_OK) {
        return st;
    }
    if (grid == NULL) {
        return SBR_ERR_NULL;
    }
    if (len < (cfg->x.count * cfg->y.count)) {
        return SBR_ERR_SIZE;
    }
    /* Each axis is validated as a 1-D encoding of its own length. */
    st = encode_prepare(&cfg->x, x, weight, grid, cfg->x.count, &fx, vx, &nx);
    if (st == SBR_OK) {
        st = encode_prepare(&cfg->y, y, 1.0f, grid, cfg->y.count, &fy, vy, &ny);
    }
    if (st != SBR_OK) {
        return st;
    }
    for (j = 0u; j < ny; j++) {
        const float *row = &grid[(fy + j) * cfg->x.count];
        for (i = 0u; i < nx; i++) {
            const float h = row[fx + i];
            if ((value_ok(h) == 0) || (value_ok(h + (vy[j] * vx[i])) == 0)) {
                return SBR_ERR_RANGE;
            }
        }
    }
    for (j = 0u; j < ny; j++) {
        float *row = &grid[(fy + j) * cfg->x.count];
        for (i = 0u; i < nx; i++) {
            row[fx + i] += vy[j] * vx[i];
        }
    }
    return SBR_OK;
}

/* The arguments of sbr_channel2d_decode(): configuration, outputs, a grid of finite,
   non-negative values. */
static sbr_status_t decode2d_check(const sbr_channel2d_config_t *cfg, const float *grid,
                                   uint32_t len, float min_certainty,
                                   const sbr_channel_mode2d_t *modes, uint32_t capacity,
                                   const uint32_t *count)
{
    sbr_status_t st = sbr_channel2d_config_check(cfg);
    if (st == SBR_OK) {
        st = check_outputs(modes, capacity, count, min_certainty);
    }
    if ((st == SBR_OK) && (grid == NULL)) {
        st = SBR_ERR_NULL;
    }
    if (st == SBR_OK) {
        const uint32_t total = cfg->x.count * cfg->y.count;
        uint32_t k;
        if (len < total) {
            st = SBR_ERR_SIZE;
        }
        for (k = 0u; (st == SBR_OK) && (k < total); k++) {
            if (value_ok(grid[k]) == 0) {
                st = SBR_ERR_RANGE;
            }
        }
    }
    return st;
}

/* The decoding window's phasors along x (p) and y (q). */
typedef struct window2d_s {
    float pre[SBR_CHANNEL_MAX_OVERLAP];
    float pim[SBR_CHANNEL_MAX_OVERLAP];
    float qre[SBR_CHANNEL_MAX_OVERLAP];
    float qim[SBR_CHANNEL_MAX_OVERLAP];
} window2d_t;

/* The window at (wx, wy): its sum, and its phasor sums along x and y (re, im each). */
static float window2d_sums(const sbr_channel2d_config_t *cfg, const float *grid,
                           const window2d_t *w, uint32_t wx, uint32_t wy, float xs[2],
                           float ys[2])
{
    float sum = 0.0f;
    uint32_t ky;
    uint32_t kx;
    xs[0] = 0.0f;
    xs[1] = 0.0f;
    ys[0] = 0.0f;
    ys[1] = 0.0f;
    for (ky = 0u; ky < cfg->y.overlap; ky++) {
        const float *row = &grid[((wy + ky) * cfg->x.count) + wx];
        float rowsum = 0.0f;
        for (kx = 0u; kx < cfg->x.overlap; kx++) {
            xs[0] += row[kx] * w->pre[kx];
            xs[1] += row[kx] * w->pim[kx];
            rowsum += row[kx];
        }
        ys[0] += rowsum * w->qre[ky];
        ys[1] += rowsum * w->qim[ky];
        sum += rowsum;
    }
    return sum;
}

sbr_status_t sbr_channel2d_decode(const sbr_channel2d_config_t *cfg, const float *grid,
                                  uint32_t len, float min_certainty,
                                  sbr_channel_mode2d_t *modes, uint32_t capacity,
                                  uint32_t *count)
{
    window2d_t w;
    uint32_t n = 0u;
    uint32_t wx;
    uint32_t wy;
    int overflow = 0;
    const sbr_status_t st =
        decode2d_check(cfg, grid, len, min_certainty, modes, capacity, count);

    if (st != SBR_OK) {
        if (count != NULL) {
            *count = 0u;
        }
        return st;
    }
    window_phasors(cfg->x.overlap, w.pre, w.pim);
    window_phasors(cfg->y.overlap, w.qre, w.qim);
    for (wy = 0u; wy <= (cfg->y.count - cfg->y.overlap); wy++) {
        for (wx = 0u; wx <= (cfg->x.count - cfg->x.overlap); wx++) {
            float xs[2];
            float ys[2];
            int vx = 0;
            int vy = 0;
            const float sum = window2d_sums(cfg, grid, &w, wx, wy, xs, ys);
            float ox = 0.0f;
            float oy = 0.0f;
            if (sum > min_certainty) {
                ox = window_offset(cfg->x.overlap, xs[0], xs[1], &vx);
                oy = window_offset(cfg->y.overlap, ys[0], ys[1], &vy);
            }
            if ((vx != 0) && (vy != 0) &&
                (insert_2d(modes, capacity, &n,
                           cfg->x.first_centre + (cfg->x.spacing * ((float)wx + ox)),
                           cfg->y.first_centre + (cfg->y.spacing * ((float)wy + oy)), sum,
                           SBR_CHANNEL_SAME_MODE * cfg->x.spacing,
                           SBR_CHANNEL_SAME_MODE * cfg->y.spacing) != 0)) {
                overflow = 1;
            }
        }
    }
    *count = n;
    return (overflow != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}
