/* SPDX-License-Identifier: MIT */
/* Image views (include/sbr/image.h): pixel formats, checks of a view, regions of
   interest. */
#include "sbr/image.h"

uint32_t sbr_image_bytes_per_pixel(sbr_pixel_format_t format)
{
    uint32_t bpp;

    switch (format) {
    case SBR_PIXEL_GRAY8:
        bpp = 1u;
        break;
    case SBR_PIXEL_RGB888:
    case SBR_PIXEL_BGR888:
        bpp = 3u;
        break;
    default:
        bpp = 0u;
        break;
    }
    return bpp;
}

sbr_status_t sbr_image_check(const sbr_image_t *img)
{
    uint32_t bpp;

    if ((img == NULL) || (img->data == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((img->width == 0u) || (img->height == 0u) || (img->width > SBR_IMAGE_MAX_DIM) ||
        (img->height > SBR_IMAGE_MAX_DIM)) {
        return SBR_ERR_SIZE;
    }
    bpp = sbr_image_bytes_per_pixel(img->format);
    if (bpp == 0u) {
        return SBR_ERR_RANGE;
    }
    if ((img->stride < (img->width * bpp)) || (img->stride > SBR_IMAGE_MAX_STRIDE)) {
        return SBR_ERR_ALIGN;
    }
    return SBR_OK;
}

sbr_status_t sbr_image_roi(const sbr_image_t *img, const sbr_rect_t *roi, sbr_image_t *out)
{
    const sbr_status_t st = sbr_image_check(img);
    uint32_t bpp;

    if (st != SBR_OK) {
        return st;
    }
    if ((roi == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((roi->width == 0u) || (roi->height == 0u) || (roi->x >= img->width) ||
        (roi->y >= img->height) || (roi->width > (img->width - roi->x)) ||
        (roi->height > (img->height - roi->y))) {
        return SBR_ERR_RANGE;
    }
    bpp = sbr_image_bytes_per_pixel(img->format);
    out->width = roi->width;
    out->height = roi->height;
    out->stride = img->stride;
    out->format = img->format;
    out->data = &img->data[((size_t)roi->y * img->stride) + ((size_t)roi->x * bpp)];
    return SBR_OK;
}
