/* SPDX-License-Identifier: MIT */
/* Private to the core: the part stage's map (parts.c). */
#ifndef SBR_MAP_INTERNAL_H
#define SBR_MAP_INTERNAL_H

#include "sbr/map.h"

/* sbr_map_make() for a map whose only MSER pass is bright with a floor above 128 (the
   part stage's red map, parts.map_bright_min): every pixel whose value is at most 128 is
   a wall of that pass, so its value is not needed: a pixel of the red map at subsample 1
   whose colour difference (2R - G - B) is not positive gets 128 without the division.
   Every other pixel, and every pixel of other maps and subsamples, gets sbr_map_make()'s
   value; statuses as sbr_map_make(). */
sbr_status_t sbr_map_priv_make_bright(const sbr_image_t *src, sbr_map_kind_t kind,
                                      uint32_t subsample, uint8_t *out, uint32_t out_stride,
                                      size_t out_size, sbr_image_t *out_view);

#endif /* SBR_MAP_INTERNAL_H */
