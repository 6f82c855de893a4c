/* SPDX-License-Identifier: MIT */
/* The class stage's gate (picto.h): cheap features of a candidate box (a grey grid, colour
   and edge cells; sbr_picto_gate_features()) and the small network that decides whether
   the full class stage looks at it (sbr_picto_gate()). */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

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

/* The bilinear value of one channel between bytes a, b (weight fx of b) of the top row
   and d, e of the bottom row (weight fy of the bottom). */
static inline float gate_bilinear(uint8_t a, uint8_t b, uint8_t d, uint8_t e, float fx, float fy)
{
    const float fa = sbr_picto_priv_u8f[a];
    const float fd = sbr_picto_priv_u8f[d];
    const float top = fa + (fx * (sbr_picto_priv_u8f[b] - fa));
    const float bot = fd + (fx * (sbr_picto_priv_u8f[e] - fd));
    return top + (fy * (bot - top));
}

/* Grid row v's cells: per cell the mean of the image over its 2 x 2 bilinear samples, per
   channel (r, g, b order); tx, ty the taps of the grid's sub-samples
   (sbr_picto_priv_taps(), 2 per cell). Each cell sums its samples sub-row by sub-row, each
   left to right; a sub-row's two source rows and every sub-column's byte offsets are
   found once. */
static void gate_row(const sbr_image_t *img, const picto_tap_t *tx, const picto_tap_t *ty,
                     uint32_t v, const picto_px_t *px, float cells[GG][3])
{
    const uint32_t c0 = px->ch[0];
    const uint32_t c1 = px->ch[1];
    const uint32_t c2 = px->ch[2];
    const uint32_t bpp = px->bpp;
    uint32_t j;
    uint32_t s;
    for (s = 0u; s < GG; s++) {
        cells[s][0] = 0.0f;
        cells[s][1] = 0.0f;
        cells[s][2] = 0.0f;
    }
    for (j = 0u; j < 2u; j++) {
        const picto_tap_t *yt = &ty[(v * 2u) + j];
        const uint8_t *r0 = &img->data[(size_t)yt->lo * img->stride];
        const uint8_t *r1 = &img->data[(size_t)yt->hi * img->stride];
        const float fy = yt->f;
        for (s = 0u; s < (2u * GG); s++) {
            const picto_tap_t *xt = &tx[s];
            const uint8_t *a = &r0[xt->lo * bpp];
            const uint8_t *b = &r0[xt->hi * bpp];
            const uint8_t *d = &r1[xt->lo * bpp];
            const uint8_t *e = &r1[xt->hi * bpp];
            const float fx = xt->f;
            float *cell = cells[s / 2u];
            cell[0] += 0.25f * gate_bilinear(a[c0], b[c0], d[c0], e[c0], fx, fy);
            cell[1] += 0.25f * gate_bilinear(a[c1], b[c1], d[c1], e[c1], fx, fy);
            cell[2] += 0.25f * gate_bilinear(a[c2], b[c2], d[c2], e[c2], fx, fy);
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
    sbr_picto_priv_unit_norm(&feat[G_EDGES], 72u);
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
    uint32_t v;
    sbr_status_t st;
    if (feat == NULL) {
        return SBR_ERR_NULL;
    }
    st = sbr_picto_priv_colour_box_check(img, box, 1);
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
    sbr_picto_priv_colour_channels(img, &px);
    g = (float *)workspace;
    tx = (picto_tap_t *)(void *)&g[GG * GG];
    ty = &tx[GG * 2u];
    sbr_picto_priv_taps(box[0], (box[2] - box[0]) / (float)GG, 2u, img->width, GG, tx);
    sbr_picto_priv_taps(box[1], (box[3] - box[1]) / (float)GG, 2u, img->height, GG, ty);
    for (i = 0u; i < 32u; i++) {
        feat[G_COLOUR + i] = 0.0f;
    }
    for (v = 0u; v < GG; v++) {
        float cells[GG][3];
        uint32_t u;
        gate_row(img, tx, ty, v, &px, cells);
        for (u = 0u; u < GG; u++) {
            const float *c = cells[u];
            const float sum = (c[0] + c[1]) + c[2];
            float *col = &feat[G_COLOUR + ((((v / 3u) * 4u) + (u / 3u)) * 2u)];
            i = (v * GG) + u;
            g[i] = sum * (1.0f / 3.0f);
            mean += g[i];
            col[0] += (c[0] / (sum + 30.0f)) * (1.0f / 9.0f);
            col[1] += (c[2] / (sum + 30.0f)) * (1.0f / 9.0f);
        }
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
        sbr_picto_priv_affine(model->gate, feat, SBR_PICTO_GATE_FEATURES, model->gate_hidden, a);
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
