/* SPDX-License-Identifier: MIT */
/* The class stage's rim check (picto.h): the colour contrast between a candidate's rim and
   its middle (sbr_picto_rim_contrast()), and the box domain the refinement shares. */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

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
   sbr_picto_priv_box_in_domain() or a grey image unless `grey` is 1. */
sbr_status_t sbr_picto_priv_colour_box_check(const sbr_image_t *img, const float box[4], int grey)
{
    sbr_status_t st;
    if ((img == NULL) || (box == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_image_check(img);
    if (st != SBR_OK) {
        return st;
    }
    if ((sbr_picto_priv_format_ok(img) == 0) || ((grey == 0) && (img->format == SBR_PIXEL_GRAY8)) ||
        (sbr_picto_priv_box_in_domain(box) == 0)) {
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
    st = sbr_picto_priv_colour_box_check(img, box, 0);
    if (st != SBR_OK) {
        return st;
    }
    if ((shape < (uint32_t)SBR_PICTO_RIM_DISC) || (shape > (uint32_t)SBR_PICTO_RIM_TRIANGLE_DOWN)) {
        return SBR_ERR_RANGE;
    }
    bw = box[2] - box[0];
    bh = box[3] - box[1];
    sbr_picto_priv_colour_channels(img, &px);
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
