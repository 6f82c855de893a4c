/* SPDX-License-Identifier: MIT */
/**
 * @file parts.h
 * @brief The front half of the recogniser: channel maps -> MSER regions -> outer contours
 *        -> Fourier descriptors ("parts"), for a whole frame or a region of interest.
 *
 * For every map kind selected in the configuration (intensity, red, blue, yellow; see
 * map.h) the frame is turned into a u8 map (optionally subsampled), its maximally stable
 * extremal regions are extracted (both polarities, mser.h), regions failing the shape
 * filters are skipped, and each remaining region's outer boundary is traced (contour.h)
 * and described by its Fourier descriptor (fd.h). Coordinates of the results (boxes,
 * centroids, descriptor scale) are in pixels of the input view, whatever the subsampling.
 *
 * Region filters (cheap, before tracing): bounding box at least `min_side` and at most
 * `max_side` map pixels on each side, aspect ratio (long side / short side) at most
 * `max_aspect`, fill ratio (area / box area) at least `min_fill`. Contours longer than
 * `max_contour` points are skipped. Every skip is counted in ::sbr_parts_stats_t.
 */
#ifndef SBR_PARTS_H
#define SBR_PARTS_H

#include "sbr/fd.h"
#include "sbr/map.h"
#include "sbr/mser.h"

#ifdef __cplusplus
extern "C" {
#endif

/** One part: a region and its descriptor. */
typedef struct sbr_part_s {
    sbr_fd_t fd;       /**< descriptor; fd.cx, fd.cy = centroid, fd.scale = size (input px) */
    sbr_rect_t bbox;   /**< bounding box in input pixels */
    uint32_t area;     /**< region area in map pixels */
    uint8_t map;       /**< ::sbr_map_kind_t the region came from */
    uint8_t polarity;  /**< ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT */
    uint8_t level;     /**< MSER level in map values */
    uint8_t pad;
} sbr_part_t;

/** @name Defaults that size the workspace (sbr_parts_config_default()) @{ */
#define SBR_PARTS_DEFAULT_MAX_NODES 68000u  /**< mser.max_nodes */
#define SBR_PARTS_DEFAULT_MAX_HEAP 384000u  /**< mser.max_heap */
#define SBR_PARTS_DEFAULT_MAX_REGIONS 2048u /**< max_regions */
#define SBR_PARTS_DEFAULT_MAX_SIDE 160u     /**< max_side */
#define SBR_PARTS_DEFAULT_MAX_CONTOUR 2048u /**< max_contour */
#define SBR_PARTS_DEFAULT_FD_N 128u         /**< fd_n */
#define SBR_PARTS_DEFAULT_FD_M 12u          /**< fd_m */
/** @} */

/** Configuration. Start from sbr_parts_config_default(). */
typedef struct sbr_parts_config_s {
    /** Bit mask of map kinds: bit k selects ::sbr_map_kind_t k. Default: intensity, red and
        blue (0x7). */
    uint32_t maps;
    /** Map subsampling, 1..::SBR_MAP_MAX_SUBSAMPLE. 2 quarters the memory and the time and
        loses signs below about twice the MSER min_area. Default 1. */
    uint32_t subsample;
    /** Further subsampling of one map kind (index ::sbr_map_kind_t): map k is made with
        blocks of subsample x map_subsample[k] pixels, at most ::SBR_MAP_MAX_SUBSAMPLE
        (region filters and MSER areas stay in that map's pixels). A map whose objects are
        large enough anyway costs a quarter of the time at 2. Default 1 for every kind.
        The map and MSER buffers of the workspace are sized by the finest selected map
        (the smallest subsample x map_subsample[k] over the kinds in `maps`). */
    uint32_t map_subsample[SBR_MAP_KINDS];
    /** Smallest MSER region of one map kind (index ::sbr_map_kind_t), in that map's pixels;
        0 = mser.min_area. A subsampled map's signs have a quarter of the area, so a smaller
        bound keeps its small ones (more regions to describe). Otherwise in
        [1, mser.max_area]. Default 0 for every kind. */
    uint32_t map_min_area[SBR_MAP_KINDS];
    /** Polarities of one map kind's regions (index ::sbr_map_kind_t): 0 = mser.polarity,
        otherwise an ::sbr_mser_polarity_t mask. A map whose signs all have one polarity
        there needs one flood instead of two. Default 0 for every kind. */
    uint32_t map_polarity[SBR_MAP_KINDS];
    /** Level limits of one map kind's regions (index ::sbr_map_kind_t; mser.h dark_max and
        bright_min): bright regions only from map_bright_min[k] up, 0 = mser.bright_min;
        dark regions only up to map_dark_max[k], 0 = mser.dark_max. The pixels beyond a
        limit are not flooded: a colour map whose signs are far from grey (red rims are
        above 136 in the red map, where under 2 % of a scene's pixels are) costs a few per
        cent of a full flood. Default 0 for every kind. */
    uint32_t map_bright_min[SBR_MAP_KINDS];
    uint32_t map_dark_max[SBR_MAP_KINDS];
    /** Region extraction. Defaults: delta 5, area 60..14400, variation 0.25, diversity 0.2,
        both polarities, max_nodes 68000 (a sixteenth of a 1360 x 800 map, measured
        sufficient on GTSDB scenes; stats.capacity_hit says when a frame needed more). */
    sbr_mser_config_t mser;
    /** Regions kept per map before filtering (bounds the workspace). Default 2048. */
    uint32_t max_regions;
    /** Box side limits in map pixels. Defaults 6 and 160. */
    uint32_t min_side;
    uint32_t max_side;
    /** Largest long/short side ratio. Default 3. */
    float max_aspect;
    /** Smallest area / box area. Default 0.2. */
    float min_fill;
    /** Longest contour traced, in points. Default 2048. */
    uint32_t max_contour;
    /** Descriptor: resampling size N (the FFT instance's length) and kept coefficients M
        (2M < N). Defaults 128 and 12. */
    uint32_t fd_n;
    uint32_t fd_m;
} sbr_parts_config_t;

/** What one call did. */
typedef struct sbr_parts_stats_s {
    uint32_t regions;          /**< MSER regions, all maps */
    uint32_t skipped_shape;    /**< failed a region filter */
    uint32_t skipped_contour;  /**< contour too long, or degenerate descriptor */
    uint32_t capacity_hit;     /**< 1 if MSER ran out of nodes or regions on some map */
} sbr_parts_stats_t;

/**
 * @brief Defaults as documented. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_parts_config_default(sbr_parts_config_t *cfg);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK, ::SBR_ERR_NULL, ::SBR_ERR_RANGE.
 */
sbr_status_t sbr_parts_config_check(const sbr_parts_config_t *cfg);

/**
 * @brief Workspace bytes for views up to width x height; 0 for a bad configuration or
 *        size (the map must be at least 3 x 3 after subsampling).
 * @param[in] cfg the configuration
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 */
size_t sbr_parts_workspace_size(const sbr_parts_config_t *cfg, uint32_t width, uint32_t height);

/**
 * @brief sbr_parts_workspace_size() as a constant expression: `map_w` x `map_h` the finest
 *        selected map (the view divided by the smallest subsample x map_subsample[k]),
 *        `delta`, `nodes` and `heap` the configuration's mser.delta, mser.max_nodes and
 *        mser.max_heap (0: the worst case),
 *        the other arguments the configuration's fields of those names. Blocks in
 *        order: MSER (which holds each map too), the regions, a region's mask, its fill
 *        and trace scratch, its contour as integer and float points, the descriptor's
 *        transform.
 */
#define SBR_PARTS_WORKSPACE_SIZE(map_w, map_h, delta, nodes, heap, max_regions, max_side,    \
                                 max_contour, fd_n)                                          \
    (SBR_WS_ALIGN8(SBR_MSER_WORKSPACE_SIZE(map_w, map_h, delta, nodes, heap)) +              \
     SBR_WS_ALIGN8((size_t)(max_regions) * sizeof(sbr_mser_region_t)) +                      \
     SBR_WS_ALIGN8((size_t)(max_side) * (size_t)(max_side)) +                                \
     SBR_WS_ALIGN8(SBR_MSER_MASK_WORKSPACE_SIZE(max_side, max_side)) +                       \
     SBR_WS_ALIGN8(SBR_CONTOUR_WORKSPACE_SIZE(max_side, max_side)) +                         \
     SBR_WS_ALIGN8((size_t)(max_contour) * sizeof(sbr_point_t)) +                            \
     SBR_WS_ALIGN8((size_t)(max_contour) * sizeof(sbr_pointf_t)) +                           \
     SBR_WS_ALIGN8((size_t)(fd_n) * sizeof(sbr_complex_t)))

/**
 * @brief Extract the parts of a frame.
 * @param[in]  img       RGB888 / BGR888 view (GRAY8 with maps = intensity only).
 * @param[in]  cfg       configuration.
 * @param[in]  fft       FFT instance of length cfg->fd_n.
 * @param[in,out] workspace sbr_parts_workspace_size() bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @param[out] parts     results, map by map (in the order of the kinds), each in MSER order.
 * @param[in]  capacity  length of `parts`.
 * @param[out] count     parts written.
 * @param[out] stats     (may be NULL) counters of this call.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (bad configuration, format/map mismatch);
 *         ::SBR_ERR_SIZE (view too small after subsampling); ::SBR_ERR_STATE (FFT instance
 *         invalid or not of length fd_n); ::SBR_ERR_WORKSPACE; ::SBR_ERR_CAPACITY when
 *         `parts` ran full (the first `capacity` are written).
 */
sbr_status_t sbr_parts_extract(const sbr_image_t *img, const sbr_parts_config_t *cfg,
                               const sbr_fft_t *fft, void *workspace, size_t workspace_size,
                               sbr_part_t *parts, uint32_t capacity, uint32_t *count,
                               sbr_parts_stats_t *stats);

#ifdef __cplusplus
}
#endif

#endif /* SBR_PARTS_H */
