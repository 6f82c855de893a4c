/* SPDX-License-Identifier: MIT */
/**
 * @file image.h
 * @brief Borrowed image views with explicit stride, and regions of interest.
 *
 * A view never owns its pixels: `data` points at the caller's buffer (a camera frame, an
 * OpenCV `cv::Mat`'s `data` with `stride = step`), which must outlive every call that
 * uses the view. Rows are `stride` bytes apart; the pixel (x, y) of channel c is
 * `data[y * stride + x * channels + c]`.
 */
#ifndef SBR_IMAGE_H
#define SBR_IMAGE_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest supported width or height (coordinates fit in int16_t with a margin). */
#define SBR_IMAGE_MAX_DIM 16384u
/** Largest supported stride in bytes (4 bytes x the largest width): row offsets of any
    valid view fit in 32 bits, so a corrupted stride cannot wrap address arithmetic. */
#define SBR_IMAGE_MAX_STRIDE (4u * SBR_IMAGE_MAX_DIM)

/** Pixel formats. */
typedef enum sbr_pixel_format_e {
    SBR_PIXEL_GRAY8 = 1,  /**< one byte per pixel */
    SBR_PIXEL_RGB888 = 3, /**< three bytes per pixel, R G B (OpenCV's BGR: see swap_rb) */
    SBR_PIXEL_BGR888 = 4  /**< three bytes per pixel, B G R (OpenCV's default order) */
} sbr_pixel_format_t;

/** A borrowed image view. */
typedef struct sbr_image_s {
    uint32_t width;            /**< pixels per row, 1 .. ::SBR_IMAGE_MAX_DIM */
    uint32_t height;           /**< rows, 1 .. ::SBR_IMAGE_MAX_DIM */
    uint32_t stride;           /**< bytes from one row to the next, >= width * bytes/pixel,
                                    <= ::SBR_IMAGE_MAX_STRIDE */
    sbr_pixel_format_t format; /**< pixel format */
    const uint8_t *data;       /**< first pixel (borrowed, not owned) */
} sbr_image_t;

/** An axis-aligned rectangle in pixels. */
typedef struct sbr_rect_s {
    uint32_t x;      /**< left column */
    uint32_t y;      /**< top row */
    uint32_t width;  /**< columns */
    uint32_t height; /**< rows */
} sbr_rect_t;

/**
 * @brief Bytes per pixel of a format (0 for an unknown format).
 * @param[in] format a pixel format
 */
uint32_t sbr_image_bytes_per_pixel(sbr_pixel_format_t format);

/**
 * @brief Validate a view.
 * @param[in] img the frame
 * @return ::SBR_OK; ::SBR_ERR_NULL (view or data NULL); ::SBR_ERR_SIZE (zero or too large
 *         width/height); ::SBR_ERR_RANGE (unknown format); ::SBR_ERR_ALIGN (stride above
 *         ::SBR_IMAGE_MAX_STRIDE or smaller
 *         than a row).
 */
sbr_status_t sbr_image_check(const sbr_image_t *img);

/**
 * @brief A view of a rectangle inside a view (no copy).
 * @param[in]  img view to cut from.
 * @param[in]  roi rectangle; must lie completely inside `img` and be non-empty.
 * @param[out] out the sub-view.
 * @return as sbr_image_check(); ::SBR_ERR_RANGE if the ROI is empty or leaves the image.
 */
sbr_status_t sbr_image_roi(const sbr_image_t *img, const sbr_rect_t *roi, sbr_image_t *out);

#ifdef __cplusplus
}
#endif

#endif /* SBR_IMAGE_H */
