/* SPDX-License-Identifier: MIT */
/* What every file of the class stage checks with (picto_internal.h): finite boxes, the
   box domain, the image formats and their colour channels. A leaf: it uses no other file
   of the module. */
#include "sbr/picto.h"

#include "picto_internal.h"

#include <math.h>

/* 1 when the four values are finite. */
int sbr_picto_priv_finite4(const float b[4])
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

/* A box sbr_picto_refine() and sbr_picto_rim_contrast() take: finite, each |coordinate|
   <= SBR_PICTO_MAX_COORD, at least SBR_PICTO_MIN_BOX wide and high. */
int sbr_picto_priv_box_in_domain(const float box[4])
{
    int ok = 0;
    if ((sbr_picto_priv_finite4(box) != 0) && (fabsf(box[0]) <= SBR_PICTO_MAX_COORD) &&
        (fabsf(box[1]) <= SBR_PICTO_MAX_COORD) && (fabsf(box[2]) <= SBR_PICTO_MAX_COORD) &&
        (fabsf(box[3]) <= SBR_PICTO_MAX_COORD) && ((box[2] - box[0]) >= SBR_PICTO_MIN_BOX) &&
        ((box[3] - box[1]) >= SBR_PICTO_MIN_BOX)) {
        ok = 1;
    }
    return ok;
}

/* 1 for the formats the class stage's features read (RGB888, BGR888, GRAY8). */
int sbr_picto_priv_format_ok(const sbr_image_t *img)
{
    return ((img->format == SBR_PIXEL_RGB888) || (img->format == SBR_PIXEL_BGR888) ||
            (img->format == SBR_PIXEL_GRAY8)) ? 1 : 0;
}

/* The channel order of an image's pixels (R, G, B; one channel for GRAY8). */
void sbr_picto_priv_colour_channels(const sbr_image_t *img, picto_px_t *px)
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
