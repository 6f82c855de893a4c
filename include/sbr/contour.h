/* SPDX-License-Identifier: MIT */
/**
 * @file contour.h
 * @brief Closed outer boundaries of binary blobs (8-connected), traced iteratively.
 *
 * sbr_contour_find_external() finds the outer boundary of every top-level blob of a
 * binary mask, with the semantics of OpenCV's `findContours(RETR_EXTERNAL,
 * CHAIN_APPROX_NONE)`: Suzuki–Abe border following, 8-connected foreground, each
 * boundary starting at the blob's first pixel in raster order and listing every boundary
 * pixel in order (a pixel on a one-pixel-wide part appears once per pass). Blobs inside
 * holes of other blobs are not reported. Pixels on the image border are handled as if the
 * image were surrounded by background.
 *
 * Orientation: seen on the screen (x right, y down), an outer boundary runs
 * counter-clockwise, i.e. its shoelace area sum is negative in image coordinates; the
 * same for every contour, as the Fourier descriptors need.
 *
 * Work: each pixel is visited a bounded number of times (O(width * height)); no recursion.
 */
#ifndef SBR_CONTOUR_H
#define SBR_CONTOUR_H

#include "sbr/image.h"

#ifdef __cplusplus
extern "C" {
#endif


/** One traced contour: its points are `points[first .. first + length)`. */
typedef struct sbr_contour_s {
    uint32_t first;  /**< index of its first point in the caller's point array */
    uint32_t length; /**< number of points (>= 1) */
    sbr_rect_t bbox; /**< bounding box of the points */
} sbr_contour_t;

/**
 * @brief Workspace bytes for masks up to `width` x `height` (a padded label map).
 */
#define SBR_CONTOUR_WORKSPACE_SIZE(width, height) \
    (((size_t)(width) + 2u) * ((size_t)(height) + 2u))

/**
 * @brief Workspace bytes for masks up to `width` x `height`; 0 if a size is 0 or above
 *        ::SBR_IMAGE_MAX_DIM.
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 */
size_t sbr_contour_workspace_size(uint32_t width, uint32_t height);

/**
 * @brief Outer boundaries of all top-level blobs of a mask (GRAY8, non-zero = foreground).
 *
 * @param[in]  mask           GRAY8 view; not modified.
 * @param[in,out] workspace      at least sbr_contour_workspace_size(width, height) bytes, any
 *                            alignment; its contents are overwritten.
 * @param[in]     workspace_size its size.
 * @param[out] points         point storage shared by all contours.
 * @param[in]  point_capacity length of `points`.
 * @param[out] contours       one entry per contour, in raster order of their first pixel.
 * @param[in]  contour_capacity length of `contours`.
 * @param[out] contour_count  contours written.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a format other than GRAY8; errors of
 *         sbr_image_check(); ::SBR_ERR_WORKSPACE if the workspace is too small;
 *         ::SBR_ERR_CAPACITY if a contour did not fit in `points` or `contours`: such a
 *         contour is left out whole (never truncated), the others are complete.
 */
sbr_status_t sbr_contour_find_external(const sbr_image_t *mask, void *workspace,
                                       size_t workspace_size, sbr_point_t *points,
                                       uint32_t point_capacity, sbr_contour_t *contours,
                                       uint32_t contour_capacity, uint32_t *contour_count);

/**
 * @brief Twice the signed area of a closed polygon (shoelace sum, image coordinates).
 *        Outer boundaries traced by sbr give negative values.
 * @param[in] points the points
 * @param[in] count number of entries
 * @param[out] area2 twice the signed area, pixels squared.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE for 0 points.
 */
sbr_status_t sbr_contour_area2(const sbr_point_t *points, uint32_t count, int64_t *area2);

#ifdef __cplusplus
}
#endif

#endif /* SBR_CONTOUR_H */
