#include "sbr/map.h"

#include "../common/sbr_util.h"

/* One map value from mean channel values. */
static uint8_t map_value(sbr_map_kind_t kind, uint32_t r, uint32_t g, uint32_t b)
{
    uint32_t v;
    switch (kind) {
    case SBR_MAP_RED:
        v = ((512u + (2u * r)) - (g + b)) / 4u;
        break;
    case SBR_MAP_BLUE:
        v = ((512u + (2u * b)) - (r + g)) / 4u;
        break;
    case SBR_MAP_YELLOW:
        v = ((512u + r + g) - (2u * b)) / 4u;
        break;
    default:
        v = (r + g + b + 1u) / 3u;
        break;
    }
    return (uint8_t)v;
}

/* One row at subsample 1: map_value() of each pixel, without the block means' divisions. */
static void map_row(sbr_map_kind_t kind, const uint8_t *row, uint32_t bpp, uint32_t ri,
                    uint32_t bi, uint32_t n, uint8_t *dst)
{
    uint32_t x;
    if (bpp == 1u) {
        for (x = 0u; x < n; x++) {
            dst[x] = row[x];
        }
    } else {
        for (x = 0u; x < n; x++) {
            const uint8_t *px = &row[x * 3u];
            dst[x] = map_value(kind, px[ri], px[1], px[bi]);
        }
    }
}

sbr_status_t sbr_map_make(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                          uint8_t *out, uint32_t out_stride, size_t out_size,
                          sbr_image_t *out_view)
{
    sbr_status_t st;
    uint32_t ow;
    uint32_t oh;
    uint32_t bpp;
    uint32_t ri;
    uint32_t bi;
    uint32_t x;
    uint32_t y;
    uint32_t n2;
    size_t src_bytes;
    size_t out_bytes;

    if ((src == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_image_check(src);
    if (st != SBR_OK) {
        return st;
    }
    if (((uint32_t)kind > (uint32_t)SBR_MAP_YELLOW) || (subsample == 0u) ||
        (subsample > SBR_MAP_MAX_SUBSAMPLE) || (subsample > src->width) ||
        (subsample > src->height)) {
        return SBR_ERR_RANGE;
    }
    if ((src->format == SBR_PIXEL_GRAY8) && (kind != SBR_MAP_INTENSITY)) {
        return SBR_ERR_RANGE;
    }
    ow = src->width / subsample;
    oh = src->height / subsample;
    out_bytes = ((size_t)oh - 1u) * (size_t)out_stride;
    out_bytes += (size_t)ow;
    if ((out_stride < ow) || (out_size < out_bytes)) {
        return SBR_ERR_ALIGN;
    }
    bpp = sbr_image_bytes_per_pixel(src->format);
    src_bytes = ((size_t)src->height - 1u) * (size_t)src->stride;
    src_bytes += (size_t)src->width * (size_t)bpp;
    if (sbr_util_overlap(src->data, src_bytes, out, out_bytes) != 0) {
        return SBR_ERR_OVERLAP;
    }
    ri = 0u;
    bi = 2u;
    if (src->format == SBR_PIXEL_BGR888) {
        ri = 2u;
        bi = 0u;
    }
    n2 = subsample * subsample;
    for (y = 0u; (y < oh) && (subsample == 1u); y++) {
        map_row(kind, &src->data[(size_t)y * src->stride], bpp, ri, bi, ow,
                &out[(size_t)y * out_stride]);
    }
    for (y = 0u; (y < oh) && (subsample > 1u); y++) {
        uint8_t *dst = &out[(size_t)y * out_stride];
        for (x = 0u; x < ow; x++) {
            uint32_t sr = 0u;
            uint32_t sg = 0u;
            uint32_t sb = 0u;
            uint32_t by;
            uint32_t bx;
            for (by = 0u; by < subsample; by++) {
                const uint8_t *row =
                    &src->data[(((size_t)y * subsample) + by) * src->stride];
                for (bx = 0u; bx < subsample; bx++) {
                    const uint8_t *px = &row[(((size_t)x * subsample) + bx) * bpp];
                    if (bpp == 1u) {
                        sr += px[0];
                        sg += px[0];
                        sb += px[0];
                    } else {
                        sr += px[ri];
                        sg += px[1];
                        sb += px[bi];
                    }
                }
            }
            dst[x] = map_value(kind, (sr + (n2 / 2u)) / n2, (sg + (n2 / 2u)) / n2,
                               (sb + (n2 / 2u)) / n2);
        }
    }
    if (out_view != NULL) {
        out_view->width = ow;
        out_view->height = oh;
        out_view->stride = out_stride;
        out_view->format = SBR_PIXEL_GRAY8;
        out_view->data = out;
    }
    return SBR_OK;
}
