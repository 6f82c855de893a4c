/* SPDX-License-Identifier: MIT */
/* The recogniser's class stage: features of a candidate box and their classifier
   (picto.h). */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

#define PS SBR_PICTO_SIZE
#define CELLS SBR_PICTO_CELLS
#define CELL (PS / CELLS)
#define ORIENT 8u
#define THUMB SBR_PICTO_THUMB
#define THUMB_CELL (PS / THUMB)
#define CCELLS 4u
#define CCELL (PS / CCELLS)
#define F_HOG 0u
#define F_THUMB (CELLS * CELLS * ORIENT)
#define F_COLOUR (F_THUMB + (THUMB * THUMB))
#define F_CENTRE (F_COLOUR + (2u * CCELLS * CCELLS))
/* The middle half of the patch, [PS / 4, 3 PS / 4), in cells of CENTRE_CELL pixels. */
#define CENTRE_CELLS SBR_PICTO_CENTRE_CELLS
#define CENTRE_LO (PS / 4u)
#define CENTRE_CELL ((PS / 2u) / CENTRE_CELLS)

/* Pixel counts of a thumbnail cell and a colour cell. */
#define THUMB_AREA ((float)SBR_PICTO_SIZE * (float)SBR_PICTO_SIZE / \
                    ((float)SBR_PICTO_THUMB * (float)SBR_PICTO_THUMB))
#define CCELL_AREA ((float)SBR_PICTO_SIZE * (float)SBR_PICTO_SIZE / ((float)CCELLS * (float)CCELLS))

/* One over the square root of two: the diagonal axes. */
#define DIAG 0.70710678f

static int finite4(const float b[4])
{
    int ok = 1;
    uint32_t i;
    for (i = 0u; i < 4u; i++) {
        if (isfinite(b[i]) == 0) {
            ok = 0;
        }
    }
    return ok;
}

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

/* Version, sizes and tables present (what every call needs; the weights' finiteness is
   sbr_picto_check()'s, once per model). */
static int header_ok(const sbr_picto_model_t *model)
{
    int ok = 0;
    if ((model->version == SBR_PICTO_VERSION) && (model->features == SBR_PICTO_FEATURES) &&
        (model->hidden <= SBR_PICTO_HIDDEN_MAX) && (model->classes >= 1u) &&
        (model->classes <= SBR_PICTO_MAX_CLASSES) && (model->w2 != NULL) &&
        ((model->hidden == 0u) || (model->w1 != NULL))) {
        ok = 1;
    }
    return ok;
}

/* Inputs of the last layers (without the bias), and their row length with it. */
static size_t last_inputs_n(const sbr_picto_model_t *model)
{
    return (size_t)((model->hidden > 0u) ? model->hidden : SBR_PICTO_FEATURES);
}

static size_t last_cols(const sbr_picto_model_t *model)
{
    return last_inputs_n(model) + 1u;
}

static int all_finite(const float *w, size_t n)
{
    int ok = 1;
    size_t i;
    for (i = 0u; (i < n) && (ok != 0); i++) {
        if (isfinite(w[i]) == 0) {
            ok = 0;
        }
    }
    return ok;
}

/* The colour check tables: both absent, or both present with outlines in range and
   finite floors in [-2, 2]. */
static int rim_tables_ok(const sbr_picto_model_t *model)
{
    int ok = 1;
    if ((model->rim_shape == NULL) || (model->rim_floor == NULL)) {
        if ((model->rim_shape != NULL) || (model->rim_floor != NULL)) {
            ok = 0;
        }
    } else {
        uint32_t c;
        for (c = 0u; (c < model->classes) && (ok != 0); c++) {
            const float f = model->rim_floor[c];
            if ((model->rim_shape[c] > (uint8_t)SBR_PICTO_RIM_TRIANGLE_DOWN) ||
                (isfinite(f) == 0) || (f < -2.0f) || (f > 2.0f)) {
                ok = 0;
            }
        }
    }
    return ok;
}

sbr_status_t sbr_picto_check(const sbr_picto_model_t *model)
{
    if (model == NULL) {
        return SBR_ERR_NULL;
    }
    if ((header_ok(model) == 0) || (model->threshold <= 0.0f) ||
        (model->threshold >= 1.0f) || (isfinite(model->threshold) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if ((all_finite(model->w1, (size_t)model->hidden * (SBR_PICTO_FEATURES + 1u)) == 0) ||
        (all_finite(model->w2, (size_t)(model->classes + 1u) * last_cols(model)) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if ((model->w3 != NULL) &&
        (all_finite(model->w3, (size_t)SBR_PICTO_BOX_OUTPUTS * last_cols(model)) == 0)) {
        return SBR_ERR_CORRUPT;
    }
    if (rim_tables_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if ((model->gate != NULL) &&
        ((model->gate_hidden > SBR_PICTO_GATE_HIDDEN_MAX) ||
         (all_finite(model->gate, (size_t)SBR_PICTO_GATE_WEIGHTS(model->gate_hidden)) == 0) ||
         (isfinite(model->gate_threshold) == 0))) {
        return SBR_ERR_CORRUPT;
    }
    return SBR_OK;
}

/* One bilinear tap along an axis: the two neighbouring sample coordinates and the weight
   of the second. */
typedef struct picto_tap_s {
    uint32_t lo;
    uint32_t hi;
    float f;
} picto_tap_t;

/* The taps of both axes live in the workspace's fourth patch-sized block. */
typedef char picto_tap_fits[((sizeof(picto_tap_t) * 2u * PS * 4u) <= (PS * PS * sizeof(float)))
                                ? 1 : -1];

/* Where a pixel's red, green and blue bytes are, and its size in bytes: RGB888, BGR888,
   or GRAY8 (one byte read as all three: a grey frame is an image with R = G = B). */
typedef struct picto_px_s {
    uint32_t ch[3];
    uint32_t bpp;
} picto_px_t;

static void colour_channels(const sbr_image_t *img, picto_px_t *px)
{
    px->ch[0] = 0u;
    px->ch[1] = 1u;
    px->ch[2] = 2u;
    px->bpp = 3u;
    if (img->format == SBR_PIXEL_BGR888) {
        px->ch[0] = 2u;
        px->ch[2] = 0u;
    } else if (img->format == SBR_PIXEL_GRAY8) {
        px->ch[1] = 0u;
        px->ch[2] = 0u;
        px->bpp = 1u;
    } else {
        /* RGB888 */
    }
}

/* 1 for the formats the class stage's features read (RGB888, BGR888, GRAY8). */
static int picto_format_ok(const sbr_image_t *img)
{
    return ((img->format == SBR_PIXEL_RGB888) || (img->format == SBR_PIXEL_BGR888) ||
            (img->format == SBR_PIXEL_GRAY8)) ? 1 : 0;
}

/* The taps of `count` output pixels with n sub-samples each along one axis: sub-sample i
   of pixel u sits at start + step (u + (i + 0.5) / n) - 0.5 in pixel-centre coordinates,
   clamped to [0, size - 1]. */
static void picto_taps(float start, float step, uint32_t n, uint32_t size, uint32_t count,
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

/* The slot holding source row r (filled if need be, never slot `keep`). */
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
        const uint32_t bpp = px->bpp;
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
                const uint8_t *pa = &src[xt->lo * bpp];
                const uint8_t *pb = &src[xt->hi * bpp];
                const float f = xt->f;
                float a = (float)pa[c0];
                float b = (float)pb[c0];
                h0[u] = a + (f * (b - a));
                a = (float)pa[c1];
                b = (float)pb[c1];
                h1[u] = a + (f * (b - a));
                a = (float)pa[c2];
                b = (float)pb[c2];
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
    float acc[3][PS]; /* a local array: the compiler knows the rows do not alias it */
    const float sx = (box[2] - box[0]) / (float)PS;
    const float sy = (box[3] - box[1]) / (float)PS;
    const uint32_t nx = (uint32_t)sbr_util_clampf(ceilf(sx), 1.0f, 4.0f);
    const uint32_t ny = (uint32_t)sbr_util_clampf(ceilf(sy), 1.0f, 4.0f);
    const float inv = 1.0f / ((float)nx * (float)ny);
    const picto_tap_t *tx = taps;
    const picto_tap_t *ty = &taps[PS * 4u];
    picto_px_t px;
    uint32_t v;
    colour_channels(img, &px);
    picto_taps(box[0], sx, nx, img->width, PS, &taps[0]);
    picto_taps(box[1], sy, ny, img->height, PS, &taps[PS * 4u]);
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
            g[(v * PS) + u] = sum * (1.0f / 3.0f);
            cr[(v * PS) + u] = a0 / (sum + 30.0f);
            cb[(v * PS) + u] = a2 / (sum + 30.0f);
        }
    }
}

/* Normalise a vector segment to unit L2 norm (left alone when it is all zero). */
static void unit_norm(float *f, uint32_t n)
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
    if (picto_format_ok(img) == 0) {
        return SBR_ERR_RANGE;
    }
    if (len < SBR_PICTO_FEATURES) {
        return SBR_ERR_SIZE;
    }
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    if ((finite4(box) == 0) || (outline > (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE)) {
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

/* The eight orientation bins of pixel (u, v)'s gradient: its projections on 0, 45, 90 and
   135 degrees, direction k getting a positive projection, k + 4 a negative one (negated);
   the other bin gets +0, which leaves every sum as it was, so all eight bins are updated
   without a data-dependent branch or index. */
static void orient_bins(const float *g, uint32_t u, uint32_t v, float add8[ORIENT])
{
    const float gx = g[(v * PS) + nb_hi(u)] - g[(v * PS) + nb_lo(u)];
    const float gy = g[(nb_hi(v) * PS) + u] - g[(nb_lo(v) * PS) + u];
    float proj[4];
    uint32_t k;
    proj[0] = gx;
    proj[1] = DIAG * (gx + gy);
    proj[2] = gy;
    proj[3] = DIAG * (gy - gx);
    for (k = 0u; k < 4u; k++) {
        float pos = 0.0f;
        float neg = -proj[k];
        if (proj[k] > 0.0f) {
            pos = proj[k];
            neg = 0.0f;
        }
        add8[k] = pos;
        add8[k + 4u] = neg;
    }
}

/* Orientation histograms of the normalised grey patch: per cell, and per cell of the
   finer centre grid; each unit-normalised. */
static void orient_features(const float *g, float *feat)
{
    uint32_t u;
    uint32_t v;
    for (v = 0u; v < PS; v++) {
        for (u = 0u; u < PS; u++) {
            float add8[ORIENT];
            float *cell = &feat[F_HOG + ((((v / CELL) * CELLS) + (u / CELL)) * ORIENT)];
            uint32_t k;
            orient_bins(g, u, v, add8);
            for (k = 0u; k < ORIENT; k++) {
                cell[k] += add8[k];
            }
            if ((u >= CENTRE_LO) && (v >= CENTRE_LO) && (u < (PS - CENTRE_LO)) &&
                (v < (PS - CENTRE_LO))) {
                float *fine = &feat[F_CENTRE + ((((((v - CENTRE_LO) / CENTRE_CELL) * CENTRE_CELLS) +
                                                  ((u - CENTRE_LO) / CENTRE_CELL))) * ORIENT)];
                for (k = 0u; k < ORIENT; k++) {
                    fine[k] += add8[k];
                }
            }
        }
    }
    unit_norm(&feat[F_HOG], CELLS * CELLS * ORIENT);
    unit_norm(&feat[F_CENTRE], CENTRE_CELLS * CENTRE_CELLS * ORIENT);
}

/* The grey thumbnail and the chromaticity per colour cell (means). */
static void thumb_colour_features(const float *g, const float *cr, const float *cb, float *feat)
{
    uint32_t i;
    uint32_t u;
    uint32_t v;
    for (v = 0u; v < PS; v++) {
        for (u = 0u; u < PS; u++) {
            const uint32_t p = (v * PS) + u;
            const uint32_t c = ((v / CCELL) * CCELLS) + (u / CCELL);
            feat[F_THUMB + (((v / THUMB_CELL) * THUMB) + (u / THUMB_CELL))] += g[p];
            feat[F_COLOUR + (2u * c)] += cr[p];
            feat[F_COLOUR + (2u * c) + 1u] += cb[p];
        }
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

/* Checks shared by sbr_picto_classify() and sbr_picto_refine(). */
static sbr_status_t run_check(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                              const void *workspace, size_t workspace_size)
{
    uint32_t i;
    if (len < SBR_PICTO_FEATURES) {
        return SBR_ERR_SIZE;
    }
    if (header_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    for (i = 0u; i < SBR_PICTO_FEATURES; i++) {
        if (isfinite(feat[i]) == 0) {
            return SBR_ERR_RANGE;
        }
    }
    return SBR_OK;
}

/* sbr_util_dot() of four rows (w, w + stride, ...) with the same b at once: each row's sum
   is the same sequence of operations as sbr_util_dot()'s (bit for bit), but the four rows'
   additions are independent, so the FPU overlaps them instead of waiting on one chain. */
static void dot4(const float *w, size_t stride, const float *b, size_t n, float out[4])
{
    /* four partial sums per row, as sbr_util_dot(); each row's four are one group of
       lanes (one vector on SIMD hosts) */
    const float *w0 = w;
    const float *w1 = &w[stride];
    const float *w2 = &w[2u * stride];
    const float *w3 = &w[3u * stride];
    float s0[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s1[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s2[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float s3[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    size_t k;
    for (k = 0u; (k + 4u) <= n; k += 4u) {
        uint32_t l;
        for (l = 0u; l < 4u; l++) {
            s0[l] += w0[k + l] * b[k + l];
        }
        for (l = 0u; l < 4u; l++) {
            s1[l] += w1[k + l] * b[k + l];
        }
        for (l = 0u; l < 4u; l++) {
            s2[l] += w2[k + l] * b[k + l];
        }
        for (l = 0u; l < 4u; l++) {
            s3[l] += w3[k + l] * b[k + l];
        }
    }
    while (k < n) {
        s0[0] += w0[k] * b[k];
        s1[0] += w1[k] * b[k];
        s2[0] += w2[k] * b[k];
        s3[0] += w3[k] * b[k];
        k++;
    }
    out[0] = (s0[0] + s0[1]) + (s0[2] + s0[3]);
    out[1] = (s1[0] + s1[1]) + (s1[2] + s1[3]);
    out[2] = (s2[0] + s2[1]) + (s2[2] + s2[3]);
    out[3] = (s3[0] + s3[1]) + (s3[2] + s3[3]);
}

/* out[r] = sbr_util_dot(row r of w, b) for `rows` rows `stride` apart, four rows at a
   time. */
static void rows_dot(const float *w, size_t stride, uint32_t rows, const float *b, size_t n,
                     float *out)
{
    uint32_t r = 0u;
    while ((r + 4u) <= rows) {
        dot4(&w[(size_t)r * stride], stride, b, n, &out[r]);
        r += 4u;
    }
    while (r < rows) {
        out[r] = sbr_util_dot(&w[(size_t)r * stride], b, n);
        r++;
    }
}

/* out[r] = w[r] . [in; 1] for `rows` rows of `n_in` inputs and a bias (row stride
   n_in + 1). */
static void affine(const float *w, const float *in, size_t n_in, uint32_t rows, float *out)
{
    const size_t cols = n_in + 1u;
    uint32_t r;
    rows_dot(w, cols, rows, in, n_in, out);
    for (r = 0u; r < rows; r++) {
        out[r] = w[((size_t)r * cols) + n_in] + out[r];
    }
}

/* The last layer's inputs: the rectified hidden units (in the workspace), or the features
   themselves without a hidden layer. */
static const float *last_inputs(const sbr_picto_model_t *model, const float *feat, float *a)
{
    const float *in = feat;
    if (model->hidden > 0u) {
        const size_t n_feat = SBR_PICTO_FEATURES;
        uint32_t i;
        affine(model->w1, feat, n_feat, model->hidden, a);
        for (i = 0u; i < model->hidden; i++) {
            a[i] = (a[i] > 0.0f) ? a[i] : 0.0f;
        }
        in = a;
    }
    return in;
}

sbr_status_t sbr_picto_classify(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                                float *prob, uint32_t nprob, void *workspace,
                                size_t workspace_size)
{
    float mx;
    float sum = 0.0f;
    uint32_t i;
    uint32_t outputs;
    sbr_status_t st;

    if ((model == NULL) || (feat == NULL) || (prob == NULL)) {
        return SBR_ERR_NULL;
    }
    st = run_check(model, feat, len, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    outputs = model->classes + 1u;
    if (nprob < outputs) {
        return SBR_ERR_SIZE;
    }
    affine(model->w2, last_inputs(model, feat, (float *)workspace), last_inputs_n(model),
           outputs, prob);
    if (all_finite(prob, outputs) == 0) {
        return SBR_ERR_RANGE; /* features so large that the logits overflow */
    }
    mx = prob[0];
    for (i = 1u; i < outputs; i++) {
        if (prob[i] > mx) {
            mx = prob[i];
        }
    }
    for (i = 0u; i < outputs; i++) {
        prob[i] = expf(prob[i] - mx);
        sum += prob[i];
    }
    for (i = 0u; i < outputs; i++) {
        prob[i] /= sum;
    }
    return SBR_OK;
}

/* A box sbr_picto_refine() and sbr_picto_rim_contrast() take: finite, each |coordinate|
   <= SBR_PICTO_MAX_COORD, at least SBR_PICTO_MIN_BOX wide and high. */
static int box_in_domain(const float box[4])
{
    int ok = 0;
    if ((finite4(box) != 0) && (fabsf(box[0]) <= SBR_PICTO_MAX_COORD) &&
        (fabsf(box[1]) <= SBR_PICTO_MAX_COORD) && (fabsf(box[2]) <= SBR_PICTO_MAX_COORD) &&
        (fabsf(box[3]) <= SBR_PICTO_MAX_COORD) && ((box[2] - box[0]) >= SBR_PICTO_MIN_BOX) &&
        ((box[3] - box[1]) >= SBR_PICTO_MIN_BOX)) {
        ok = 1;
    }
    return ok;
}

/* Whether the point (u, v) of the unit box lies inside the rim outline `shape` shrunk to
   k of its size about its centroid. */
static int in_outline(uint32_t shape, float u, float v, float k)
{
    int in = 0;
    const float x = 0.5f + ((u - 0.5f) / k);
    if (shape == (uint32_t)SBR_PICTO_RIM_DISC) {
        const float y = 0.5f + ((v - 0.5f) / k);
        if ((((x - 0.5f) * (x - 0.5f)) + ((y - 0.5f) * (y - 0.5f))) <= 0.25f) {
            in = 1;
        }
    } else if (shape == (uint32_t)SBR_PICTO_RIM_TRIANGLE) {
        const float y = (2.0f / 3.0f) + ((v - (2.0f / 3.0f)) / k);
        if ((y <= 1.0f) && (fabsf(x - 0.5f) <= (0.5f * y))) {
            in = 1;
        }
    } else {
        const float y = (1.0f / 3.0f) + ((v - (1.0f / 3.0f)) / k);
        if ((y >= 0.0f) && (fabsf(x - 0.5f) <= (0.5f * (1.0f - y)))) {
            in = 1;
        }
    }
    return in;
}

/* Nearest pixel index of coordinate p along an axis of n pixels, the border repeated. */
static uint32_t clamp_index(float p, uint32_t n)
{
    uint32_t i = 0u;
    if (p >= (float)n) {
        i = n - 1u;
    } else if (p > 0.0f) {
        i = (uint32_t)p;
    } else {
        i = 0u;
    }
    return i;
}

/* What sbr_picto_rim_contrast() and sbr_picto_gate_features() check of their image and
   box: ::SBR_ERR_NULL, sbr_image_check()'s errors, ::SBR_ERR_RANGE for a box outside
   box_in_domain() or a grey image unless `grey` is 1. */
static sbr_status_t colour_box_check(const sbr_image_t *img, const float box[4], int grey)
{
    sbr_status_t st;
    if ((img == NULL) || (box == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_image_check(img);
    if (st != SBR_OK) {
        return st;
    }
    if ((picto_format_ok(img) == 0) || ((grey == 0) && (img->format == SBR_PIXEL_GRAY8)) ||
        (box_in_domain(box) == 0)) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

sbr_status_t sbr_picto_rim_contrast(const sbr_image_t *img, const float box[4], uint32_t shape,
                                    float *contrast)
{
    sbr_status_t st;
    float bw;
    float bh;
    float rim = 0.0f;
    float mid = 0.0f;
    uint32_t n_rim = 0u;
    uint32_t n_mid = 0u;
    uint32_t i;
    uint32_t j;
    picto_px_t px;
    float k_in;
    float k_mid;
    if (contrast == NULL) {
        return SBR_ERR_NULL;
    }
    st = colour_box_check(img, box, 0);
    if (st != SBR_OK) {
        return st;
    }
    if ((shape < (uint32_t)SBR_PICTO_RIM_DISC) || (shape > (uint32_t)SBR_PICTO_RIM_TRIANGLE_DOWN)) {
        return SBR_ERR_RANGE;
    }
    bw = box[2] - box[0];
    bh = box[3] - box[1];
    colour_channels(img, &px);
    k_in = (shape == (uint32_t)SBR_PICTO_RIM_DISC) ? 0.75f : 0.6f;
    k_mid = (shape == (uint32_t)SBR_PICTO_RIM_DISC) ? 0.6f : 0.45f;
    for (j = 0u; j < SBR_PICTO_RIM_GRID; j++) {
        const float v = ((float)j + 0.5f) / (float)SBR_PICTO_RIM_GRID;
        const uint8_t *row = &img->data[(size_t)clamp_index(box[1] + (v * bh), img->height) *
                                        img->stride];
        for (i = 0u; i < SBR_PICTO_RIM_GRID; i++) {
            const float u = ((float)i + 0.5f) / (float)SBR_PICTO_RIM_GRID;
            if (in_outline(shape, u, v, 1.0f) != 0) {
                const uint8_t *p = &row[(size_t)clamp_index(box[0] + (u * bw), img->width) * 3u];
                const float r = (float)p[px.ch[0]];
                const float g = (float)p[px.ch[1]];
                const float b = (float)p[px.ch[2]];
                const float red = (r - ((g > b) ? g : b)) / (r + g + b + 3.0f);
                if (in_outline(shape, u, v, k_in) == 0) {
                    rim += red;
                    n_rim++;
                } else if (in_outline(shape, u, v, k_mid) != 0) {
                    mid += red;
                    n_mid++;
                } else {
                    /* between rim and middle: neither */
                }
            }
        }
    }
    if ((n_rim == 0u) || (n_mid == 0u)) {
        return SBR_ERR_RANGE; /* not reached: a 32 x 32 grid holds both of every outline */
    }
    *contrast = (rim / (float)n_rim) - (mid / (float)n_mid);
    return SBR_OK;
}

sbr_status_t sbr_picto_refine(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                              const float box[4], float refined[4], void *workspace,
                              size_t workspace_size)
{
    const float *in;
    sbr_status_t st;

    if ((model == NULL) || (feat == NULL) || (box == NULL) || (refined == NULL)) {
        return SBR_ERR_NULL;
    }
    st = run_check(model, feat, len, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    if (box_in_domain(box) == 0) {
        return SBR_ERR_RANGE;
    }
    in = feat;
    if (model->w3 != NULL) {
        in = last_inputs(model, feat, (float *)workspace);
    }
    return sbr_picto_priv_refine_from(model, in, box, refined);
}

sbr_status_t sbr_picto_priv_refine_from(const sbr_picto_model_t *model, const float *in,
                                        const float box[4], float refined[4])
{
    float cx;
    float cy;
    float hw;
    float hh;
    if (header_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    if (box_in_domain(box) == 0) {
        return SBR_ERR_RANGE;
    }
    cx = 0.5f * (box[0] + box[2]);
    cy = 0.5f * (box[1] + box[3]);
    hw = 0.5f * (box[2] - box[0]);
    hh = 0.5f * (box[3] - box[1]);
    if (model->w3 != NULL) {
        float d[SBR_PICTO_BOX_OUTPUTS];
        affine(model->w3, in, last_inputs_n(model), SBR_PICTO_BOX_OUTPUTS, d);
        if (all_finite(d, SBR_PICTO_BOX_OUTPUTS) == 0) {
            return SBR_ERR_RANGE; /* features so large that the regression overflows */
        }
        cx += 2.0f * hw * sbr_util_clampf(d[0], -SBR_PICTO_MAX_SHIFT, SBR_PICTO_MAX_SHIFT);
        cy += 2.0f * hh * sbr_util_clampf(d[1], -SBR_PICTO_MAX_SHIFT, SBR_PICTO_MAX_SHIFT);
        hw *= expf(sbr_util_clampf(d[2], -SBR_PICTO_MAX_LOG_SCALE, SBR_PICTO_MAX_LOG_SCALE));
        hh *= expf(sbr_util_clampf(d[3], -SBR_PICTO_MAX_LOG_SCALE, SBR_PICTO_MAX_LOG_SCALE));
    }
    refined[0] = cx - hw;
    refined[1] = cy - hh;
    refined[2] = cx + hw;
    refined[3] = cy + hh;
    return SBR_OK;
}

/* ---- the gate (sbr_picto_gate_features(), sbr_picto_gate()) ---------------------------- */

#define GG SBR_PICTO_GATE_GRID
#define GG_CELLS ((float)SBR_PICTO_GATE_GRID * (float)SBR_PICTO_GATE_GRID)
#define G_GREY 0u
#define G_COLOUR (GG * GG)
#define G_EDGES (G_COLOUR + 32u)

/* The grey grid and both axes' taps fit SBR_PICTO_GATE_WORKSPACE_SIZE. */
typedef char gate_ws_fits[(((GG * GG * sizeof(float)) + (4u * GG * sizeof(picto_tap_t))) <=
                           SBR_PICTO_GATE_WORKSPACE_SIZE) ? 1 : -1];

/* i + 1, or i at the last of n. */
static uint32_t gate_next(uint32_t i, uint32_t n)
{
    uint32_t r = i;
    if ((i + 1u) < n) {
        r = i + 1u;
    }
    return r;
}

/* i - 1, or 0 at 0. */
static uint32_t gate_prev(uint32_t i)
{
    uint32_t r = 0u;
    if (i > 0u) {
        r = i - 1u;
    }
    return r;
}

/* Mean of the image over the 2 x 2 bilinear samples of grid cell (u, v), per channel (r,
   g, b order): tx, ty the taps of the grid's sub-samples (picto_taps(), 2 per cell). */
static void gate_cell(const sbr_image_t *img, const picto_tap_t *tx, const picto_tap_t *ty,
                      uint32_t u, uint32_t v, const picto_px_t *px, float out[3])
{
    uint32_t i;
    uint32_t j;
    out[0] = 0.0f;
    out[1] = 0.0f;
    out[2] = 0.0f;
    for (j = 0u; j < 2u; j++) {
        const picto_tap_t *yt = &ty[(v * 2u) + j];
        const uint8_t *r0 = &img->data[(size_t)yt->lo * img->stride];
        const uint8_t *r1 = &img->data[(size_t)yt->hi * img->stride];
        for (i = 0u; i < 2u; i++) {
            const picto_tap_t *xt = &tx[(u * 2u) + i];
            uint32_t c;
            for (c = 0u; c < 3u; c++) {
                const float a = (float)r0[(xt->lo * px->bpp) + px->ch[c]];
                const float b = (float)r0[(xt->hi * px->bpp) + px->ch[c]];
                const float d = (float)r1[(xt->lo * px->bpp) + px->ch[c]];
                const float e = (float)r1[(xt->hi * px->bpp) + px->ch[c]];
                const float top = a + (xt->f * (b - a));
                const float bot = d + (xt->f * (e - d));
                out[c] += 0.25f * (top + (yt->f * (bot - top)));
            }
        }
    }
}

/* Signed orientation histograms (8 bins) of the grey grid in 3 x 3 cells of 4 x 4. */
static void gate_edges(const float *g, float *feat)
{
    uint32_t u;
    uint32_t v;
    for (u = 0u; u < 72u; u++) {
        feat[G_EDGES + u] = 0.0f;
    }
    for (v = 0u; v < GG; v++) {
        const uint32_t vm = gate_prev(v);
        const uint32_t vp = gate_next(v, GG);
        for (u = 0u; u < GG; u++) {
            const uint32_t um = gate_prev(u);
            const uint32_t up = gate_next(u, GG);
            const float gx = g[(v * GG) + up] - g[(v * GG) + um];
            const float gy = g[(vp * GG) + u] - g[(vm * GG) + u];
            const float p[4] = {gx, gy, DIAG * (gx + gy), DIAG * (gx - gy)};
            float *bin = &feat[G_EDGES + ((((v / 4u) * 3u) + (u / 4u)) * 8u)];
            uint32_t k;
            for (k = 0u; k < 4u; k++) {
                bin[2u * k] += (p[k] > 0.0f) ? p[k] : 0.0f;
                bin[(2u * k) + 1u] += (p[k] < 0.0f) ? -p[k] : 0.0f;
            }
        }
    }
    unit_norm(&feat[G_EDGES], 72u);
}

sbr_status_t sbr_picto_gate_features(const sbr_image_t *img, const float box[4], float *feat,
                                     uint32_t len, void *workspace, size_t workspace_size)
{
    float *g;
    picto_tap_t *tx;
    picto_tap_t *ty;
    float mean = 0.0f;
    float var = 0.0f;
    float sd;
    picto_px_t px;
    uint32_t i;
    sbr_status_t st;
    if (feat == NULL) {
        return SBR_ERR_NULL;
    }
    st = colour_box_check(img, box, 1);
    if (st != SBR_OK) {
        return st;
    }
    if (len < SBR_PICTO_GATE_FEATURES) {
        return SBR_ERR_SIZE;
    }
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_GATE_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    colour_channels(img, &px);
    g = (float *)workspace;
    tx = (picto_tap_t *)(void *)&g[GG * GG];
    ty = &tx[GG * 2u];
    picto_taps(box[0], (box[2] - box[0]) / (float)GG, 2u, img->width, GG, tx);
    picto_taps(box[1], (box[3] - box[1]) / (float)GG, 2u, img->height, GG, ty);
    for (i = 0u; i < 32u; i++) {
        feat[G_COLOUR + i] = 0.0f;
    }
    for (i = 0u; i < (GG * GG); i++) {
        const uint32_t u = i % GG;
        const uint32_t v = i / GG;
        float c[3];
        float sum;
        float *col = &feat[G_COLOUR + ((((v / 3u) * 4u) + (u / 3u)) * 2u)];
        gate_cell(img, tx, ty, u, v, &px, c);
        sum = (c[0] + c[1]) + c[2];
        g[i] = sum * (1.0f / 3.0f);
        mean += g[i];
        col[0] += (c[0] / (sum + 30.0f)) * (1.0f / 9.0f);
        col[1] += (c[2] / (sum + 30.0f)) * (1.0f / 9.0f);
    }
    mean *= 1.0f / GG_CELLS;
    for (i = 0u; i < (GG * GG); i++) {
        const float d = g[i] - mean;
        var += d * d;
    }
    sd = sqrtf(var * (1.0f / GG_CELLS)) + 1.0f;
    for (i = 0u; i < (GG * GG); i++) {
        g[i] = (g[i] - mean) / sd;
        feat[G_GREY + i] = g[i];
    }
    gate_edges(g, feat);
    return SBR_OK;
}

sbr_status_t sbr_picto_gate(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                            float *score)
{
    float v;
    uint32_t i;
    if ((model == NULL) || (feat == NULL) || (score == NULL) || (model->gate == NULL)) {
        return SBR_ERR_NULL;
    }
    if (len < SBR_PICTO_GATE_FEATURES) {
        return SBR_ERR_SIZE;
    }
    for (i = 0u; i < SBR_PICTO_GATE_FEATURES; i++) {
        if (isfinite(feat[i]) == 0) {
            return SBR_ERR_RANGE;
        }
    }
    if (model->gate_hidden > SBR_PICTO_GATE_HIDDEN_MAX) {
        return SBR_ERR_CORRUPT;
    }
    if (model->gate_hidden == 0u) {
        v = model->gate[SBR_PICTO_GATE_FEATURES] +
            sbr_util_dot(model->gate, feat, SBR_PICTO_GATE_FEATURES);
    } else {
        float a[SBR_PICTO_GATE_HIDDEN_MAX];
        const float *w2 = &model->gate[(size_t)model->gate_hidden * (SBR_PICTO_GATE_FEATURES + 1u)];
        affine(model->gate, feat, SBR_PICTO_GATE_FEATURES, model->gate_hidden, a);
        for (i = 0u; i < model->gate_hidden; i++) {
            a[i] = (a[i] > 0.0f) ? a[i] : 0.0f;
        }
        v = w2[model->gate_hidden] + sbr_util_dot(w2, a, model->gate_hidden);
    }
    if (isfinite(v) == 0) {
        return SBR_ERR_RANGE;
    }
    *score = v;
    return SBR_OK;
}
