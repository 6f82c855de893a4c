/* SPDX-License-Identifier: MIT */
/**
 * @file map.h
 * @brief u8 channel maps from camera images: intensity and colour (chromaticity) maps, with
 *        optional block subsampling (the input of region extraction).
 *
 * Each output pixel first averages an s x s block of the source (s = subsample, rounded
 * to nearest), giving mean channel values R, G, B in 0..255 (a GRAY8 source gives the
 * same value for all three). With integer arithmetic (division truncates towards zero):
 *
 *   ::SBR_MAP_INTENSITY  (T(R) + T(G) + T(B) + 1) / 3
 *   ::SBR_MAP_RED        C(2R - G - B)      red vs. green and blue
 *   ::SBR_MAP_BLUE       C(2B - R - G)      blue vs. red and green
 *   ::SBR_MAP_YELLOW     C(R + G - 2B)      yellow vs. blue
 *
 * The intensity map passes each mean c through the tone curve T(c) = round(sqrt(255 c))
 * (a table: T(0) = 0, T(16) = 64, T(64) = 128, T(255) = 255). The curve stretches the
 * dark end: a sign in shadow under a bright sky, whose pixels a camera exposed for the
 * sky records in 10..60, spans about twice as many grey levels, enough for MSER's
 * stability test (measured: docs/results/recognition.md).
 *
 * The colour maps are chromaticities: C(d) = 128 + 128 d / (R + G + B + 60), clamped to
 * 0..255. They are 128 for grey pixels of any brightness, rise towards 255 for saturated
 * red, blue or yellow and fall towards 0 for the opposite hue (cyan for red, yellow for
 * blue, blue for yellow). Dividing by the brightness makes a colour's value about the
 * same in shadow and in sunlight; the 60 keeps the near-black pixels, whose hue is
 * mostly noise, near 128. Red sign rims are bright regions of the red map, blue
 * mandatory signs bright regions of the blue map, and the white or black inner parts
 * extremal regions of the intensity map (why these maps: docs/results/recognition.md).
 *
 * Output size: floor(width / s) x floor(height / s). Work: one pass over the source.
 */
#ifndef SBR_MAP_H
#define SBR_MAP_H

#include "sbr/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest subsampling factor. */
#define SBR_MAP_MAX_SUBSAMPLE 8u

/** Number of map kinds (::sbr_map_kind_t values 0 .. SBR_MAP_KINDS - 1). */
#define SBR_MAP_KINDS 4u

/** Map kinds. */
typedef enum sbr_map_kind_e {
    SBR_MAP_INTENSITY = 0,
    SBR_MAP_RED = 1,
    SBR_MAP_BLUE = 2,
    SBR_MAP_YELLOW = 3
} sbr_map_kind_t;

/**
 * @brief Make one map.
 * @param[in]  src        RGB888, BGR888 or (intensity only) GRAY8 view.
 * @param[in]  kind       which map.
 * @param[in]  subsample  block size s, 1..::SBR_MAP_MAX_SUBSAMPLE, at most the source's
 *                        width and height.
 * @param[out] out        floor(height / s) rows of `out_stride` bytes.
 * @param[in]  out_stride bytes per output row, >= floor(width / s).
 * @param[in]  out_size   bytes available at `out`.
 * @param[out] out_view   (may be NULL) a GRAY8 view of the result.
 * @return ::SBR_OK; ::SBR_ERR_NULL; errors of sbr_image_check(); ::SBR_ERR_RANGE for an
 *         unknown kind, a colour map of a GRAY8 source, or a subsample outside its range;
 *         ::SBR_ERR_ALIGN for a stride below the output width or an output too small;
 *         ::SBR_ERR_OVERLAP if the output overlaps the source.
 */
sbr_status_t sbr_map_make(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                          uint8_t *out, uint32_t out_stride, size_t out_size,
                          sbr_image_t *out_view);

/**
 * @brief sbr_map_make() for a map whose only MSER pass is bright with a level floor above
 *        128 (the part stage's red map, sbr_parts_config_t::map_bright_min): such a pass
 *        treats every value up to 128 as a wall, so those values need not be exact. A
 *        pixel of the red map at subsample 1 whose colour difference (2R - G - B) is not
 *        positive gets 128 without the division; every other pixel, and every pixel of the
 *        other kinds and subsamples, gets sbr_map_make()'s value.
 * @param[in]  src        as sbr_map_make().
 * @param[in]  kind       as sbr_map_make().
 * @param[in]  subsample  as sbr_map_make().
 * @param[out] out        as sbr_map_make().
 * @param[in]  out_stride as sbr_map_make().
 * @param[in]  out_size   as sbr_map_make().
 * @param[out] out_view   as sbr_map_make().
 * @return the statuses of sbr_map_make().
 */
sbr_status_t sbr_map_make_bright(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                                 uint8_t *out, uint32_t out_stride, size_t out_size,
                                 sbr_image_t *out_view);

#ifdef __cplusplus
}
#endif

#endif /* SBR_MAP_H */
