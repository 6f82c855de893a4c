/* SPDX-License-Identifier: MIT */
/* The class stage's features of a candidate box (picto.h): the box resampled to a
   SBR_PICTO_SIZE patch (separable bilinear taps with supersampling), orientation
   histograms, a grey thumbnail and colour cells (sbr_picto_features(),
   sbr_picto_features_outline()). */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

/* picto_internal.h */
const float sbr_picto_priv_u8f[256] = {
    0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f,
    12.0f, 13.0f, 14.0f, 15.0f, 16.0f, 17.0f, 18.0f, 19.0f, 20.0f, 21.0f, 22.0f, 23.0f,
    24.0f, 25.0f, 26.0f, 27.0f, 28.0f, 29.0f, 30.0f, 31.0f, 32.0f, 33.0f, 34.0f, 35.0f,
    36.0f, 37.0f, 38.0f, 39.0f, 40.0f, 41.0f, 42.0f, 43.0f, 44.0f, 45.0f, 46.0f, 47.0f,
    48.0f, 49.0f, 50.0f, 51.0f, 52.0f, 53.0f, 54.0f, 55.0f, 56.0f, 57.0f, 58.0f, 59.0f,
    60.0f, 61.0f, 62.0f, 63.0f, 64.0f, 65.0f, 66.0f, 67.0f, 68.0f, 69.0f, 70.0f, 71.0f,
    72.0f, 73.0f, 74.0f, 75.0f, 76.0f, 77.0f, 78.0f, 79.0f, 80.0f, 81.0f, 82.0f, 83.0f,
    84.0f, 85.0f, 86.0f, 87.0f, 88.0f, 89.0f, 90.0f, 91.0f, 92.0f, 93.0f, 94.0f, 95.0f,
    96.0f, 97.0f, 98.0f, 99.0f, 100.0f, 101.0f, 102.0f, 103.0f, 104.0f, 105.0f, 106.0f, 107.0f,
    108.0f, 109.0f, 110.0f, 111.0f, 112.0f, 113.0f, 114.0f, 115.0f, 116.0f, 117.0f, 118.0f, 119.0f,
    120.0f, 121.0f, 122.0f, 123.0f, 124.0f, 125.0f, 126.0f, 127.0f, 128.0f, 129.0f, 130.0f, 131.0f,
    132.0f, 133.0f, 134.0f, 135.0f, 136.0f, 137.0f, 138.0f, 139.0f, 140.0f, 141.0f, 142.0f, 143.0f,
    144.0f, 145.0f, 146.0f, 147.0f, 148.0f, 149.0f, 150.0f, 151.0f, 152.0f, 153.0f, 154.0f, 155.0f,
    156.0f, 157.0f, 158.0f, 159.0f, 160.0f, 161.0f, 162.0f, 163.0f, 164.0f, 165.0f, 166.0f, 167.0f,
    168.0f, 169.0f, 170.0f, 171.0f, 172.0f, 173.0f, 174.0f, 175.0f, 176.0f, 177.0f, 178.0f, 179.0f,
    180.0f, 181.0f, 182.0f, 183.0f, 184.0f, 185.0f, 186.0f, 187.0f, 188.0f, 189.0f, 190.0f, 191.0f,
    192.0f, 193.0f, 194.0f, 195.0f, 196.0f, 197.0f, 198.0f, 199.0f, 200.0f, 201.0f, 202.0f, 203.0f,
    204.0f, 205.0f, 206.0f, 207.0f, 208.0f, 209.0f, 210.0f, 211.0f, 212.0f, 213.0f, 214.0f, 215.0f,
    216.0f, 217.0f, 218.0f, 219.0f, 220.0f, 221.0f, 222.0f, 223.0f, 224.0f, 225.0f, 226.0f, 227.0f,
    228.0f, 229.0f, 230.0f, 231.0f, 232.0f, 233.0f, 234.0f, 235.0f, 236.0f, 237.0f, 238.0f, 239.0f,
    240.0f, 241.0f, 242.0f, 243.0f, 244.0f, 245.0f, 246.0f, 247.0f, 248.0f, 249.0f, 250.0f, 251.0f,
    252.0f, 253.0f, 254.0f, 255.0f
};

/* Neighbours of a patch row or column, repeated at the patch border. */
static uint32_t nb_lo(uint32_t i)
{
    uint32_t r = i;
    if (i > 0u) {
        r = i - 1u;
    }
    return r;
}

static uint32_t nb_hi(uint32_t i)
{
    uint32_t r = i;
    if ((i + 1u) < PS) {
        r = i + 1u;
    }
    return r;
}


/* The taps of `count` output pixels with n sub-samples each along one axis: sub-sample i
   of pixel u sits at start + step (u + (i + 0.5) / n) - 0.5 in pixel-centre coordinates,
   clamped to [0, size - 1]. */
void sbr_picto_priv_taps(float start, float step, uint32_t n, uint32_t size, uint32_t count,
                       picto_tap_t *t)
{
    const float cmax = (float)size - 1.0f;
    uint32_t u;
    for (u = 0u; u < count; u++) {
        uint32_t i;
        for (i = 0u; i < n; i++) {
            const float c = sbr_util_clampf(
                start + (step * ((float)u + (((float)i + 0.5f) / (float)n))) - 0.5f, 0.0f, cmax);
            picto_tap_t *tp = &t[(u * n) + i];
            uint32_t c0 = (uint32_t)c;
            uint32_t c1;
            if (c0 >= (size - 1u)) {
                c0 = size - 1u;
            }
            c1 = c0;
            if ((c0 + 1u) < size) {
                c1 = c0 + 1u;
            }
            tp->lo = c0;
            tp->hi = c1;
            tp->f = c - (float)c0;
        }
    }
}

/* Horizontal sub-samples of the resampling: per source row, the bilinear value along x
   of each of the PS nx sub-sample columns in each channel (what the vertical step mixes).
   Two rows are kept, so that consecutive sub-rows (which share their rows) compute each
   source row once. */
#define ROW_SAMPLES (PS * 4u)
#define ROW_FLOATS (3u * ROW_SAMPLES)

typedef struct picto_rows_s {
    float *h[2];     /* [ROW_FLOATS] each: channel c, sub-sample i of pixel u at
                        c ROW_SAMPLES + i PS + u */
    uint32_t tag[2]; /* the source row held, or PICTO_NO_ROW */
} picto_rows_t;

#define PICTO_NO_ROW 0xFFFFFFFFu

/* The patches, the taps' block and the two rows fit the workspace. */
typedef char picto_ws_fits[((((4u * PS * PS) + (2u * ROW_FLOATS)) * sizeof(float)) <=
                            SBR_PICTO_WORKSPACE_SIZE) ? 1 : -1];

/* The slot holding source row r (filled if need be, never slot `keep`); tx: the x taps
   as byte offsets in a row. */
static const float *picto_row(const sbr_image_t *img, const picto_tap_t *tx, uint32_t n,
                              const picto_px_t *px, uint32_t r, uint32_t keep,
                              picto_rows_t *rows, uint32_t *slot)
{
    uint32_t k = 0u;
    if (rows->tag[0] == r) {
        k = 0u;
    } else if (rows->tag[1] == r) {
        k = 1u;
    } else {
        const uint8_t *src = &img->data[(size_t)r * img->stride];
        const uint32_t c0 = px->ch[0];
        const uint32_t c1 = px->ch[1];
        const uint32_t c2 = px->ch[2];
        uint32_t i;
        if (keep == 0u) {
            k = 1u;
        }
        for (i = 0u; i < n; i++) {
            /* sub-sample column i of the three channels */
            float *h0 = &rows->h[k][i * PS];
            float *h1 = &h0[ROW_SAMPLES];
            float *h2 = &h1[ROW_SAMPLES];
            uint32_t u;
            for (u = 0u; u < PS; u++) {
                const picto_tap_t *xt = &tx[(u * n) + i];
                const uint8_t *pa = &src[xt->lo];
                const uint8_t *pb = &src[xt->hi];
                const float f = xt->f;
                float a = sbr_picto_priv_u8f[pa[c0]];
                float b = sbr_picto_priv_u8f[pb[c0]];
                h0[u] = a + (f * (b - a));
                a = sbr_picto_priv_u8f[pa[c1]];
                b = sbr_picto_priv_u8f[pb[c1]];
                h1[u] = a + (f * (b - a));
                a = sbr_picto_priv_u8f[pa[c2]];
                b = sbr_picto_priv_u8f[pb[c2]];
                h2[u] = a + (f * (b - a));
            }
        }
        rows->tag[k] = r;
    }
    *slot = k;
    return rows->h[k];
}

/* One source sub-row's samples into the patch row's sums: per channel and horizontal
   sub-sample, the vertical interpolation between rows h0 and h1 (weight fy of h1). */
static void picto_accumulate(const float *h0, const float *h1, float fy, uint32_t nx, float acc[3][PS])
{
    uint32_t c;
    for (c = 0u; c < 3u; c++) {
        uint32_t i;
        for (i = 0u; i < nx; i++) {
            const float *t0 = &h0[(c * ROW_SAMPLES) + (i * PS)];
            const float *t1 = &h1[(c * ROW_SAMPLES) + (i * PS)];
            float *ac = &acc[c][0];
            uint32_t u;
            for (u = 0u; u < PS; u++) {
                ac[u] += t0[u] + (fy * (t1[u] - t0[u]));
            }
        }
    }
}

/* Resample the box into grey (g) and chromaticity (cr, cb) patches: each patch pixel is
   the mean of nx x ny bilinear samples (nx, ny = the box's scale, 1..4), the
   taps in `taps` (2 PS 4 entries) and `rows` as scratch. The sums run over the
   sub-samples in the same order as a pixel-by-pixel loop would (per patch pixel: source
   sub-row by sub-row, each left to right). */
static void picto_resample(const sbr_image_t *img, const float box[4], picto_tap_t *taps,
                           picto_rows_t *rows, float *g, float *cr, float *cb)
{
    float acc[3][PS]; /* local arrays: the compiler knows the rows do not alias them */
    float out[3][PS];
    const float sx = (box[2] - box[0]) / (float)PS;
    const float sy = (box[3] - box[1]) / (float)PS;
    const uint32_t nx = (uint32_t)sbr_util_clampf(ceilf(sx), 1.0f, 4.0f);
    const uint32_t ny = (uint32_t)sbr_util_clampf(ceilf(sy), 1.0f, 4.0f);
    const float inv = 1.0f / ((float)nx * (float)ny);
    const picto_tap_t *tx = taps;
    const picto_tap_t *ty = &taps[PS * 4u];
    picto_px_t px;
    uint32_t v;
    sbr_picto_priv_colour_channels(img, &px);
    sbr_picto_priv_taps(box[0], sx, nx, img->width, PS, &taps[0]);
    sbr_picto_priv_taps(box[1], sy, ny, img->height, PS, &taps[PS * 4u]);
    for (v = 0u; v < (PS * nx); v++) {
        /* the x taps as byte offsets in a row (what picto_row() reads) */
        taps[v].lo *= px.bpp;
        taps[v].hi *= px.bpp;
    }
    rows->tag[0] = PICTO_NO_ROW;
    rows->tag[1] = PICTO_NO_ROW;
    for (v = 0u; v < PS; v++) {
        uint32_t u;
        uint32_t j;
        for (u = 0u; u < PS; u++) {
            acc[0][u] = 0.0f;
            acc[1][u] = 0.0f;
            acc[2][u] = 0.0f;
        }
        for (j = 0u; j < ny; j++) {
            const picto_tap_t *yt = &ty[(v * ny) + j];
            const float fy = yt->f;
            uint32_t s0;
            uint32_t s1;
            const float *h0 = picto_row(img, tx, nx, &px, yt->lo, 2u, rows, &s0);
            const float *h1 = picto_row(img, tx, nx, &px, yt->hi, s0, rows, &s1);
            picto_accumulate(h0, h1, fy, nx, acc);
        }
        for (u = 0u; u < PS; u++) {
            const float a0 = acc[0][u] * inv;
            const float a1 = acc[1][u] * inv;
            const float a2 = acc[2][u] * inv;
            const float sum = a0 + a1 + a2;
            out[0][u] = sum * (1.0f / 3.0f);
            out[1][u] = a0 / (sum + 30.0f);
            out[2][u] = a2 / (sum + 30.0f);
        }
        (void)memcpy(&g[v * PS], out[0], sizeof(out[0]));
        (void)memcpy(&cr[v * PS], out[1], sizeof(out[1]));
        (void)memcpy(&cb[v * PS], out[2], sizeof(out[2]));
    }
}

/* Normalise a vector segment to unit L2 norm (left alone when it is all zero). */
void sbr_picto_priv_unit_norm(float *f, uint32_t n)
{
    float ss = 0.0f;
    uint32_t i;
    for (i = 0u; i < n; i++) {
        ss += f[i] * f[i];
    }
    if (ss > 1e-12f) {
        const float s = 1.0f / sqrtf(ss);
        for (i = 0u; i < n; i++) {
            f[i] *= s;
        }
    }
}

/* The columns [*u0, *u1) of patch row v that lie inside the upward triangle inscribed in
   the patch, grown by one patch pixel (picto.h SBR_PICTO_OUTLINE_TRIANGLE): apex at
   (PS / 2, -1), base from (-1, PS + 1) to (PS + 1, PS + 1), pixel centres tested. At row
   v's centre the triangle is (v + 1.5) / 2 wide on either side of the middle, a quarter
   pixel off every pixel centre, so rounding cannot move a pixel in or out. */
static void triangle_row(uint32_t v, uint32_t *u0, uint32_t *u1)
{
    const float half = 0.5f * ((float)v + 1.5f);
    const float mid = (0.5f * (float)PS) - 0.5f; /* the middle, in pixel-centre columns */
    const float lo = ceilf(mid - half);
    const float hi = floorf(mid + half); /* the last column inside */
    *u0 = (lo > 0.0f) ? (uint32_t)lo : 0u;
    *u1 = (hi >= ((float)PS - 1.0f)) ? PS : ((uint32_t)hi + 1u);
}

/* Replace the patch pixels outside the triangle by half the inside's mean grey, with the
   chromaticity picto_resample() gives a grey pixel of that value. */
static void picto_mask_triangle(float *g, float *cr, float *cb)
{
    float sum = 0.0f;
    float fill;
    float chroma;
    uint32_t u;
    uint32_t v;
    uint32_t u0;
    uint32_t u1;
    uint32_t inside = 0u;
    for (v = 0u; v < PS; v++) {
        triangle_row(v, &u0, &u1);
        for (u = u0; u < u1; u++) {
            sum += g[(v * PS) + u];
        }
        inside += u1 - u0;
    }
    fill = (0.5f * sum) / (float)inside; /* inside > 0: the triangle holds half the patch */
    chroma = fill / ((3.0f * fill) + 30.0f);
    for (v = 0u; v < PS; v++) {
        triangle_row(v, &u0, &u1);
        for (u = 0u; u < PS; u++) {
            if ((u < u0) || (u >= u1)) {
                g[(v * PS) + u] = fill;
                cr[(v * PS) + u] = chroma;
                cb[(v * PS) + u] = chroma;
            }
        }
    }
}

sbr_status_t sbr_picto_features(const sbr_image_t *img, const float box[4], float *feat,
                                uint32_t len, void *workspace, size_t workspace_size)
{
    return sbr_picto_features_outline(img, box, (uint32_t)SBR_PICTO_OUTLINE_BOX, feat, len,
                                      workspace, workspace_size);
}

/* The arguments of sbr_picto_features_outline(), in its documented order of checks. */
static sbr_status_t features_check(const sbr_image_t *img, const float box[4], uint32_t outline,
                                   uint32_t len, const void *workspace, size_t workspace_size)
{
    sbr_status_t st = sbr_image_check(img);
    float bw;
    float bh;
    if (st != SBR_OK) {
        return st;
    }
    if (sbr_picto_priv_format_ok(img) == 0) {
        return SBR_ERR_RANGE;
    }
    if (len < SBR_PICTO_FEATURES) {
        return SBR_ERR_SIZE;
    }
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    if ((sbr_picto_priv_finite4(box) == 0) || (outline > (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE)) {
        return SBR_ERR_RANGE;
    }
    bw = box[2] - box[0];
    bh = box[3] - box[1];
    if ((bw < SBR_PICTO_MIN_BOX) || (bh < SBR_PICTO_MIN_BOX) || (box[0] < -bw) || (box[1] < -bh) ||
        (box[2] > ((float)img->width + bw)) || (box[3] > ((float)img->height + bh))) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

/* The grey patch contrast-normalised in place: zero mean, unit deviation (plus a floor
   of 4 grey levels squared in the variance). */
static void grey_normalise(float *g)
{
    float mean = 0.0f;
    float var = 0.0f;
    float inv_sd;
    uint32_t i;
    for (i = 0u; i < (PS * PS); i++) {
        mean += g[i];
    }
    mean /= ((float)PS * (float)PS);
    for (i = 0u; i < (PS * PS); i++) {
        const float d = g[i] - mean;
        var += d * d;
    }
    var /= ((float)PS * (float)PS);
    inv_sd = 1.0f / sqrtf(var + 4.0f);
    for (i = 0u; i < (PS * PS); i++) {
        g[i] = (g[i] - mean) * inv_sd;
    }
}

/* One pixel's projections p into a cell's eight sums: bin k gets max(p[k], 0), bin k + 4
   max(p[k], 0) - p[k]. */
static inline void orient_add(float acc[ORIENT], const float p[4])
{
#if SBR_UTIL_SCALAR_CORE == 0
    /* SIMD hosts: whole-lane steps (one vector operation each) */
    float q[4];
    uint32_t k;
    for (k = 0u; k < 4u; k++) {
        q[k] = (p[k] > 0.0f) ? p[k] : 0.0f;
    }
    for (k = 0u; k < 4u; k++) {
        acc[k] += q[k];
    }
    for (k = 0u; k < 4u; k++) {
        acc[k + 4u] += q[k] - p[k];
    }
#else
    /* M-profile cores: straight-line code, the sums kept in FPU registers */
    const float q0 = (p[0] > 0.0f) ? p[0] : 0.0f;
    const float q1 = (p[1] > 0.0f) ? p[1] : 0.0f;
    const float q2 = (p[2] > 0.0f) ? p[2] : 0.0f;
    const float q3 = (p[3] > 0.0f) ? p[3] : 0.0f;
    acc[0] += q0;
    acc[1] += q1;
    acc[2] += q2;
    acc[3] += q3;
    acc[4] += q0 - p[0];
    acc[5] += q1 - p[1];
    acc[6] += q2 - p[2];
    acc[7] += q3 - p[3];
#endif
}

/* Patch row v's pixels [u0, u0 + n * width) into n cells of `width` pixels (cells: n x 8
   bins), each cell's pixels added left to right in local sums. A pixel's gradient
   projections p on 0, 45, 90 and 135 degrees: bin k gets max(p, 0) and bin k + 4
   max(p, 0) - p (which is -p or exactly 0), so a positive projection counts in direction
   k, a negative one (negated) in k + 4, without a branch on the sign (a desktop CPU
   mispredicts half of them; orient_add()). */
static void orient_cells(const float *g, uint32_t v, uint32_t u0, uint32_t n, uint32_t width,
                         float *cells)
{
    const float *row = &g[v * PS];
    const float *up = &g[nb_lo(v) * PS];
    const float *down = &g[nb_hi(v) * PS];
    uint32_t c;
    for (c = 0u; c < n; c++) {
        float *cell = &cells[c * ORIENT];
        float acc[ORIENT]; /* the cell's sums: a local array the rows cannot alias */
        uint32_t t;
        uint32_t k;
        for (k = 0u; k < ORIENT; k++) {
            acc[k] = cell[k];
        }
        for (t = 0u; t < width; t++) {
            const uint32_t u = u0 + (c * width) + t;
            const float gx = row[nb_hi(u)] - row[nb_lo(u)];
            const float gy = down[u] - up[u];
            const float p[4] = {gx, DIAG * (gx + gy), gy, DIAG * (gy - gx)};
            orient_add(acc, p);
        }
        for (k = 0u; k < ORIENT; k++) {
            cell[k] = acc[k];
        }
    }
}

/* Orientation histograms of the normalised grey patch: per cell, and per cell of the
   finer centre grid; each unit-normalised. Every bin sums its pixels in raster order (row
   by row, each row's pixels left to right). */
static void orient_features(const float *g, float *feat)
{
    uint32_t v;
    for (v = 0u; v < PS; v++) {
        orient_cells(g, v, 0u, CELLS, CELL, &feat[F_HOG + ((v / CELL) * CELLS * ORIENT)]);
        if ((v >= CENTRE_LO) && (v < (PS - CENTRE_LO))) {
            orient_cells(g, v, CENTRE_LO, CENTRE_CELLS, CENTRE_CELL,
                         &feat[F_CENTRE + (((v - CENTRE_LO) / CENTRE_CELL) * CENTRE_CELLS * ORIENT)]);
        }
    }
    sbr_picto_priv_unit_norm(&feat[F_HOG], CELLS * CELLS * ORIENT);
    sbr_picto_priv_unit_norm(&feat[F_CENTRE], CENTRE_CELLS * CENTRE_CELLS * ORIENT);
}

/* One patch row's pixels into n cells of `width` pixels (sums[c * step] the sum of cell
   c), each cell's pixels added left to right. */
static void row_cell_sums(const float *row, uint32_t n, uint32_t width, float *sums, uint32_t step)
{
    uint32_t c;
    for (c = 0u; c < n; c++) {
        float acc = sums[c * step];
        uint32_t t;
        for (t = 0u; t < width; t++) {
            acc += row[(c * width) + t];
        }
        sums[c * step] = acc;
    }
}

/* The grey thumbnail and the chromaticity per colour cell (means); every cell sums its
   pixels in raster order. */
static void thumb_colour_features(const float *g, const float *cr, const float *cb, float *feat)
{
    uint32_t i;
    uint32_t v;
    for (v = 0u; v < PS; v++) {
        float *colour = &feat[F_COLOUR + (2u * (v / CCELL) * CCELLS)];
        row_cell_sums(&g[v * PS], THUMB, THUMB_CELL, &feat[F_THUMB + ((v / THUMB_CELL) * THUMB)], 1u);
        row_cell_sums(&cr[v * PS], CCELLS, CCELL, colour, 2u);
        row_cell_sums(&cb[v * PS], CCELLS, CCELL, &colour[1], 2u);
    }
    for (i = 0u; i < (THUMB * THUMB); i++) {
        feat[F_THUMB + i] *= 1.0f / (THUMB_AREA);
    }
    for (i = 0u; i < (2u * CCELLS * CCELLS); i++) {
        feat[F_COLOUR + i] *= 1.0f / (CCELL_AREA);
    }
}

sbr_status_t sbr_picto_features_outline(const sbr_image_t *img, const float box[4],
                                        uint32_t outline, float *feat, uint32_t len,
                                        void *workspace, size_t workspace_size)
{
    float *g;
    float *cr;
    float *cb;
    sbr_status_t st;

    if ((img == NULL) || (box == NULL) || (feat == NULL)) {
        return SBR_ERR_NULL;
    }
    st = features_check(img, box, outline, len, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    g = (float *)workspace;
    cr = &g[PS * PS];
    cb = &cr[PS * PS];
    {
        /* after the three patches: the taps (one patch-sized block), the two rows */
        float *after_taps = &cb[2u * PS * PS];
        picto_rows_t rows;
        rows.h[0] = after_taps;
        rows.h[1] = &after_taps[ROW_FLOATS];
        picto_resample(img, box, (picto_tap_t *)(void *)&cb[PS * PS], &rows, g, cr, cb);
    }
    if (outline == (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE) {
        picto_mask_triangle(g, cr, cb);
    }
    grey_normalise(g);
    (void)memset(feat, 0, SBR_PICTO_FEATURES * sizeof(float));
    orient_features(g, feat);
    thumb_colour_features(g, cr, cb, feat);
    return SBR_OK;
}
