/* SPDX-License-Identifier: MIT */
/**
 * @file mser.h
 * @brief Maximally stable extremal regions (MSER) of a u8 map, both polarities, in linear
 *        time with bounded memory.
 *
 * An extremal region at level t is a 4-connected component of the pixels whose value is
 * <= t (dark regions, ::SBR_MSER_DARK) or >= 255 - t' (bright regions, ::SBR_MSER_BRIGHT,
 * the same on the inverted map). The components of all levels form a tree; sbr builds it
 * with one flood fill per polarity that visits every pixel a bounded number of times
 * (Nistér and Stewénius, "Linear time maximally stable extremal regions", ECCV 2008: a
 * boundary heap with one stack per grey level and a stack of growing components). No
 * recursion, no sorting.
 *
 * Stability of the tree node R at level t, with delta = config.delta:
 *   variation(R) = (|R(t + delta)| - |R(t - delta)|) / |R|
 * where R(t + delta) is R's ancestor at level t + delta (the root when the tree ends
 * below) and R(t - delta) is the first node at or above level t - delta on R's main
 * chain (the chain of largest children). A node is reported when
 *   - min_area <= |R| <= max_area and variation(R) <= max_variation,
 *   - no child (of area >= min_area) has a smaller variation, and
 *   - its parent's variation is larger (or R's variation is 0),
 * and, when min_diversity > 0, it is not a near-duplicate of the nearest reported region
 * that contains it ((|Q| - |R|) / |Q| < min_diversity): of such a pair the less stable one
 * is dropped. These are the definitions of OpenCV's `cv::MSER` for grey images (which
 * ignores min_diversity), so both give the same regions for the same parameters; the
 * host test `host_mser_equals_opencv` measures the agreement on GTSDB scenes.
 *
 * As in OpenCV, the outermost row and column on each side of the map are not part of any
 * region (they bound the flood fill); a map must be at least 3 x 3.
 *
 * A region is returned compactly (level, polarity, area, bounding box, one seed pixel);
 * sbr_mser_region_mask() rebuilds its pixels from the map as a mask of its bounding box,
 * ready for sbr_contour_find_external().
 *
 * Memory: sbr_mser_workspace_size() bytes, 4-byte aligned: 2 bytes per pixel (the
 * map's level with a "reached" bit), ::SBR_MSER_NODE_BYTES per tree node of area >=
 * min_area, and the boundary heap, 4 bytes per pixel waiting in it (a pixel waiting
 * carries the next neighbour to look at in its entry) in chunks of ::SBR_MSER_HEAP_CHUNK
 * words. Two bounds size it:
 * - config.max_nodes: the number of nodes is at most the number of interior pixels;
 *   natural scenes have far fewer (the host tool `sbr_mser` prints the count);
 * - config.max_heap: the pixels waiting in the heap at once, at most every interior
 *   pixel; on natural scenes under a third of them (most of a bright or dark flood's
 *   pixels are taken as soon as they are reached).
 * 0 reserves the worst case (never runs out); a smaller bound saves RAM, and when a frame
 * needs more the call still completes and returns ::SBR_ERR_CAPACITY: nodes beyond the
 * bound are not kept (regions may be missed); when the heap's bound is reached the flood
 * in progress stops there and the pixels it has not taken stay unflooded (regions through
 * them are smaller or missing; every region reported is still part of its extremal
 * component).
 */
#ifndef SBR_MSER_H
#define SBR_MSER_H

#include "sbr/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest supported delta (the history of each growing component is delta + 1 long). */
#define SBR_MSER_MAX_DELTA 32u

/** Bytes per component-tree node in the workspace. */
#define SBR_MSER_NODE_BYTES 32u

/** @name Blocks of the MSER workspace (for ::SBR_MSER_WORKSPACE_SIZE) @{ */
/** The boundary heap's header: for each of the 256 levels the place of its top entry. */
#define SBR_MSER_HEAP_HEADER_BYTES 1024u
/** Words of one chunk of the boundary heap (a power of two): ::SBR_MSER_HEAP_CHUNK - 1
    entries and the link to the level's chunk below (or to the next free chunk). */
#define SBR_MSER_HEAP_CHUNK 32u
/** Depth of the component stack: every grey level, a sentinel and the root. */
#define SBR_MSER_STACK 258u
/** Bytes of one stack entry, without its history. */
#define SBR_MSER_COMP_BYTES 24u
/** Bytes of one history entry of a stack entry (size and level; delta + 1 of them). */
#define SBR_MSER_HISTORY_BYTES 8u
/** Bytes per pixel: the map's level or "reached". */
#define SBR_MSER_PIXEL_BYTES 2u
/** Slack at the end of the workspace. */
#define SBR_MSER_TAIL_BYTES 8u
/** @} */

/** Polarities (bit mask). */
typedef enum sbr_mser_polarity_e {
    SBR_MSER_DARK = 1,   /**< regions darker than their surroundings (pixels <= level) */
    SBR_MSER_BRIGHT = 2, /**< regions brighter than their surroundings (pixels >= level) */
    SBR_MSER_BOTH = 3    /**< both, dark ones first */
} sbr_mser_polarity_t;

/** Parameters. Start from sbr_mser_config_default(). */
typedef struct sbr_mser_config_s {
    /** Grey-level step over which the area change is measured, 1..::SBR_MSER_MAX_DELTA.
        Larger: fewer, more contrasted regions. Default 5. */
    uint32_t delta;
    /** Smallest region area in pixels, >= 1. Default 60. */
    uint32_t min_area;
    /** Largest region area in pixels, >= min_area. Default 14400. */
    uint32_t max_area;
    /** Largest accepted variation, > 0 and at most 1e30 (no bound in practice).
        Larger: more, less stable regions. Default 0.25. */
    float max_variation;
    /** Nested regions whose areas differ by less than this fraction of the larger one are
        reported once (the more stable one), in [0, 1); 0 keeps both. Default 0.2. */
    float min_diversity;
    /** Which polarities to extract (::sbr_mser_polarity_t). Default ::SBR_MSER_BOTH. */
    uint32_t polarity;
    /** Bound on tree nodes of area >= min_area per polarity; 0 = the worst case for the
        map size. Default 0. */
    uint32_t max_nodes;
    /** Dark regions only up to this level, 0..255: pixels above it are never flooded (they
        bound the fill like the map's border), and regions of levels above dark_max -
        delta are not reported (their variation would need levels beyond the limit).
        Regions further inside are the unrestricted flood's, except that the stability
        and diversity tests see no ancestor beyond the limit. Default 255 (no limit). A
        map whose wanted dark regions are all dark (the blue map's yellow signs) floods a
        few per cent of its pixels instead of all. */
    uint32_t dark_max;
    /** Bright regions only down to this level, 0..255: the same for the bright pass (pixels
        below it are never flooded, regions below bright_min + delta not reported). Default
        0 (no limit). */
    uint32_t bright_min;
    /** Bound on pixels waiting in the boundary heap at once (per pass); 0 = the worst case
        (every interior pixel, ::SBR_MSER_HEAP). When it is reached the flood in progress
        stops (what it has not taken stays unflooded) and the call returns
        ::SBR_ERR_CAPACITY. Default 0. */
    uint32_t max_heap;
} sbr_mser_config_t;

/** One region. Its pixels: the 4-connected component of pixels of the map that pass the
    level test (<= level for dark, >= level for bright) and contains the seed. */
typedef struct sbr_mser_region_s {
    sbr_rect_t bbox;    /**< bounding box of its pixels */
    uint32_t area;      /**< number of pixels */
    float variation;    /**< stability (smaller is more stable) */
    uint16_t seed_x;    /**< a pixel of the region */
    uint16_t seed_y;
    uint8_t level;      /**< threshold in map values */
    uint8_t polarity;   /**< ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT */
} sbr_mser_region_t;

/** Worst-case node count for a width x height map (its interior pixels). */
#define SBR_MSER_WORST_NODES(width, height) \
    ((((size_t)(width)) - 2u) * (((size_t)(height)) - 2u))

/** The nodes the workspace holds for a width x height map and config.max_nodes: the
    worst case when max_nodes is 0 or larger. */
#define SBR_MSER_NODES(width, height, max_nodes)                                    \
    ((((max_nodes) == 0u) || ((size_t)(max_nodes) > SBR_MSER_WORST_NODES(width, height))) \
         ? SBR_MSER_WORST_NODES(width, height)                                      \
         : (size_t)(max_nodes))

/** The pixels the boundary heap holds at once for a width x height map and
    config.max_heap: the worst case (every interior pixel) when max_heap is 0 or larger. */
#define SBR_MSER_HEAP(width, height, max_heap)                                    \
    ((((size_t)(max_heap) - 1u) >= SBR_MSER_WORST_NODES(width, height)) /* 0 wraps */ \
         ? SBR_MSER_WORST_NODES(width, height)                                    \
         : (size_t)(max_heap))

/** Chunks of the boundary heap for `entries` (::SBR_MSER_HEAP) pixels waiting at once:
    every level but one chunk full, one partly filled chunk per level. */
#define SBR_MSER_HEAP_CHUNKS(entries) \
    ((((size_t)(entries) + (SBR_MSER_HEAP_CHUNK - 2u)) / (SBR_MSER_HEAP_CHUNK - 1u)) + 256u)

/**
 * @brief Workspace bytes for a width x height map (>= 3 x 3), a delta and the bounds:
 *        `nodes` is config.max_nodes and `heap` config.max_heap (0 or more than the worst
 *        case: the worst case, ::SBR_MSER_NODES, ::SBR_MSER_HEAP), so the value equals
 *        sbr_mser_workspace_size() of that configuration.
 */
#define SBR_MSER_WORKSPACE_SIZE(width, height, delta, nodes, heap)                         \
    ((size_t)SBR_MSER_HEAP_HEADER_BYTES +                                                   \
     ((size_t)SBR_MSER_STACK *                                                              \
      (SBR_MSER_COMP_BYTES + ((((size_t)(delta)) + 1u) * SBR_MSER_HISTORY_BYTES))) +        \
     (SBR_MSER_NODES(width, height, nodes) * SBR_MSER_NODE_BYTES) +                         \
     (SBR_MSER_HEAP_CHUNKS(SBR_MSER_HEAP(width, height, heap)) * SBR_MSER_HEAP_CHUNK * 4u) + \
     ((((size_t)(width)) * ((size_t)(height))) * SBR_MSER_PIXEL_BYTES) + SBR_MSER_TAIL_BYTES)

/**
 * @brief Fill a configuration with the defaults documented above. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_mser_config_default(sbr_mser_config_t *cfg);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for any field outside its range.
 */
sbr_status_t sbr_mser_config_check(const sbr_mser_config_t *cfg);

/**
 * @brief Workspace bytes sbr_mser_detect() needs for maps up to width x height with this
 *        configuration; 0 for an invalid configuration or a size below 3 x 3 or above
 *        ::SBR_IMAGE_MAX_DIM.
 * @param[in] cfg the configuration
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 */
size_t sbr_mser_workspace_size(const sbr_mser_config_t *cfg, uint32_t width, uint32_t height);

/**
 * @brief Extract the maximally stable extremal regions of a map.
 *
 * @param[in]  map            GRAY8 view, at least 3 x 3; not modified.
 * @param[in]  cfg            parameters (sbr_mser_config_check()).
 * @param[in,out] workspace      sbr_mser_workspace_size() bytes, 4-byte aligned.
 * @param[in]     workspace_size its size.
 * @param[out] regions        results: dark regions first, each polarity in the order its
 *                            tree nodes were completed (smaller before containing ones).
 * @param[in]  capacity       length of `regions`.
 * @param[out] count          regions written.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a format other than GRAY8 or a bad
 *         configuration; ::SBR_ERR_SIZE for a map below 3 x 3 or a capacity of 0 (and
 *         errors of sbr_image_check()); ::SBR_ERR_WORKSPACE if the workspace is too small or not
 *         4-byte aligned; ::SBR_ERR_CAPACITY if more regions were found than `capacity`
 *         (the first `capacity` are written), the node bound was reached (regions may
 *         be missing; the others are exact) or the heap bound was (pixels left unflooded:
 *         regions through them smaller or split).
 */
sbr_status_t sbr_mser_detect(const sbr_image_t *map, const sbr_mser_config_t *cfg,
                             void *workspace, size_t workspace_size,
                             sbr_mser_region_t *regions, uint32_t capacity, uint32_t *count);

/** Workspace bytes sbr_mser_region_mask() needs for a bounding box of w x h pixels. */
#define SBR_MSER_MASK_WORKSPACE_SIZE(w, h) (((size_t)(w)) * ((size_t)(h)) * 4u)

/**
 * @brief The pixels of a region as a mask of its bounding box (255 inside, 0 outside).
 *
 * @param[in]  map            the map the region was extracted from.
 * @param[in]  region         a region of that map.
 * @param[in,out] workspace      SBR_MSER_MASK_WORKSPACE_SIZE(bbox.width, bbox.height) bytes,
 *                            4-byte aligned.
 * @param[in]     workspace_size its size.
 * @param[out] mask           bbox.height rows of `mask_stride` bytes; pixel (x, y) of the
 *                            map is mask[(y - bbox.y) * mask_stride + (x - bbox.x)].
 * @param[in]  mask_stride    >= bbox.width.
 * @param[in]  mask_size      bytes available at `mask`.
 * @return ::SBR_OK; ::SBR_ERR_NULL; errors of sbr_image_check(); ::SBR_ERR_RANGE for a
 *         format other than GRAY8 or a region that does not lie in the map's interior
 *         (bad box, seed outside the box, unknown polarity); ::SBR_ERR_ALIGN for a stride
 *         below bbox.width or a mask too small; ::SBR_ERR_WORKSPACE; ::SBR_ERR_CORRUPT if
 *         the map does not hold this region (seed fails the level test, or the filled
 *         area differs from region->area: a different or modified map).
 */
sbr_status_t sbr_mser_region_mask(const sbr_image_t *map, const sbr_mser_region_t *region,
                                  void *workspace, size_t workspace_size, uint8_t *mask,
                                  uint32_t mask_stride, size_t mask_size);

/**
 * @brief Where a width x height map (stride = width) goes for sbr_mser_detect_in_place():
 *        inside the MSER's workspace (the second half of its pixel words), so that a
 *        caller that makes the map itself needs no map buffer of its own (the part stage).
 * @param[in] cfg            parameters (sbr_mser_config_check()).
 * @param[in] width          map width, >= 3.
 * @param[in] height         map height, >= 3.
 * @param[in] workspace      sbr_mser_workspace_size(cfg, width, height) bytes, 4-byte aligned.
 * @param[in] workspace_size its size.
 * @return width x height writable bytes inside `workspace`; NULL for a NULL or bad
 *         configuration, a size below 3 x 3, or a workspace that is NULL, too small or
 *         misaligned.
 */
uint8_t *sbr_mser_map_slot(const sbr_mser_config_t *cfg, uint32_t width, uint32_t height,
                           void *workspace, size_t workspace_size);

/**
 * @brief sbr_mser_detect() of the map the caller wrote at sbr_mser_map_slot() of the same
 *        configuration, size and workspace. The workspace's copy of the map is consumed;
 *        `map` is then the same map at the start of the workspace's pixel words, valid
 *        until the workspace is used again.
 * @param[in]  width          map width, >= 3.
 * @param[in]  height         map height, >= 3.
 * @param[in]  cfg            parameters (sbr_mser_config_check()).
 * @param[in,out] workspace   as sbr_mser_detect(), holding the map at sbr_mser_map_slot().
 * @param[in]  workspace_size its size.
 * @param[out] regions        results, as sbr_mser_detect().
 * @param[in]  capacity       length of `regions`.
 * @param[out] count          regions written.
 * @param[out] map            the map's view after the call (on ::SBR_OK and
 *                            ::SBR_ERR_CAPACITY).
 * @return the statuses of sbr_mser_detect(); ::SBR_ERR_NULL also for a NULL `map`.
 */
sbr_status_t sbr_mser_detect_in_place(uint32_t width, uint32_t height, const sbr_mser_config_t *cfg,
                                      void *workspace, size_t workspace_size,
                                      sbr_mser_region_t *regions, uint32_t capacity,
                                      uint32_t *count, sbr_image_t *map);

#ifdef __cplusplus
}
#endif

#endif /* SBR_MSER_H */
