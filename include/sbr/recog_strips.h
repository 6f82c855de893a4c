/* SPDX-License-Identifier: MIT */
/**
 * @file recog_strips.h
 * @brief The strip configuration: the recogniser over a frame in bands of full rows, for
 *        RAM that does not hold a whole frame's workspace (recog.h).
 */
#ifndef SBR_RECOG_STRIPS_H
#define SBR_RECOG_STRIPS_H

#include "sbr/recog.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @name The strip configuration (sbr_recog_config_strips(), sbr_recog_detect_strips()):
    the frame in bands of full rows, for RAM that does not hold a whole frame's workspace.
    Measured on GTSDB (docs/results/realtime.md): the bands' bounds are each reached on
    under a tenth of the bands, and the cross-validation finds within 2 signs per
    superclass of the whole-frame default at the same precision. @{ */
#define SBR_RECOG_STRIP_ROWS 256u            /**< rows of a band */
#define SBR_RECOG_STRIP_OVERLAP 128u         /**< rows neighbouring bands share: the
                                                  tallest sign always found (GTSDB's
                                                  tallest at 1360 x 800: 128) */
#define SBR_RECOG_STRIP_MAX_NODES 10000u     /**< parts.mser.max_nodes of a band */
#define SBR_RECOG_STRIP_MAX_HEAP 70000u      /**< parts.mser.max_heap of a band */
#define SBR_RECOG_STRIP_MAX_PARTS 1024u      /**< max_parts of a band */
#define SBR_RECOG_STRIP_MAX_CANDIDATES 96u   /**< max_candidates of a band */
#define SBR_RECOG_STRIP_MAX_OUTLINES 32u     /**< max_outline_candidates of a band */
#define SBR_RECOG_STRIP_BAND_DETECTIONS 128u /**< detections kept of one band (its best;
                                                  more are flagged by ::SBR_ERR_CAPACITY) */
/** @} */

/**
 * sbr_recog_strip_workspace_size() of the strip configuration (sbr_recog_config_strips())
 * for frames `width` wide in bands of ::SBR_RECOG_STRIP_ROWS rows, as a constant
 * expression: 1,942,760 bytes at 1360 (checked by the unit tests).
 */
#define SBR_RECOG_WORKSPACE_STRIP_SIZE(width)                                                  \
    (SBR_RECOG_WORKSPACE_BOUNDS_SIZE(width, SBR_RECOG_STRIP_ROWS, 1u, SBR_RECOG_STRIP_MAX_NODES, \
                                     SBR_RECOG_STRIP_MAX_HEAP, SBR_RECOG_STRIP_MAX_PARTS) +      \
     SBR_WS_ALIGN8((size_t)SBR_RECOG_STRIP_BAND_DETECTIONS * sizeof(sbr_detection_t)))

/**
 * @brief The strip configuration: the defaults with the bounds of one band
 *        (::SBR_RECOG_STRIP_MAX_NODES, ::SBR_RECOG_STRIP_MAX_HEAP,
 *        ::SBR_RECOG_STRIP_MAX_PARTS, ::SBR_RECOG_STRIP_MAX_CANDIDATES,
 *        ::SBR_RECOG_STRIP_MAX_OUTLINES), for
 *        sbr_recog_detect_strips() with ::SBR_RECOG_STRIP_ROWS and
 *        ::SBR_RECOG_STRIP_OVERLAP. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_recog_config_strips(sbr_recog_config_t *cfg);

/**
 * @brief Workspace bytes of a recogniser that sees a width x height frame in bands of
 *        `rows` rows (sbr_recog_detect_strips()): sbr_recog_workspace_size() of one band
 *        (of the frame when it is no taller) and room for a band's detections
 *        (::SBR_RECOG_STRIP_BAND_DETECTIONS).
 * @param[in] cfg    the configuration (e.g. sbr_recog_config_strips()).
 * @param[in] width  frame width.
 * @param[in] height frame height.
 * @param[in] rows   rows of a band.
 * @return the bytes; 0 for a bad configuration or size, or `rows` 0.
 */
size_t sbr_recog_strip_workspace_size(const sbr_recog_config_t *cfg, uint32_t width,
                                      uint32_t height, uint32_t rows);

/**
 * @brief Detect signs in a frame seen in bands of full rows (the strip configuration):
 *        for RAM that does not hold the workspace of a whole frame.
 *
 * Band k covers rows [t_k, t_k + rows), t_k = min(k (rows - overlap), height - rows)
 * (one band when the frame is no taller than `rows`); each is recognised as a region of
 * interest (sbr_recog_detect()), so the recogniser's workspace needs only one band's
 * (sbr_recog_strip_workspace_size()) and its bounds (parts, votes, hypotheses, MSER nodes,
 * candidates) apply per band. Each band keeps the detections whose centre row lies in its
 * core: from half the overlap below its top to half the overlap above its bottom (the
 * first core from row 0, the last to the frame's bottom); the cores tile the frame, so no
 * sign is reported twice, and a sign at most `overlap` tall is always found in a band that
 * holds all of it. The work is that of the bands: about rows x bands / height times a
 * whole frame's part stage.
 *
 * @param[in,out] rec  a recogniser from sbr_recog_init() with a workspace of at least
 *                     sbr_recog_strip_workspace_size() bytes.
 * @param[in]  img     the frame (as sbr_recog_detect()).
 * @param[in]  rows    rows of a band, > overlap (::SBR_RECOG_STRIP_ROWS).
 * @param[in]  overlap rows shared by neighbouring bands: at least the tallest sign to be
 *                     found (::SBR_RECOG_STRIP_OVERLAP).
 * @param[out] dets    detections, highest score first.
 * @param[in]  capacity length of `dets`, >= 1.
 * @param[out] count   detections written.
 * @param[out] stats   the bands' counters summed (capacity_hit: any band's); may be NULL.
 *                     Zeroed first; all zero after a status other than ::SBR_OK and
 *                     ::SBR_ERR_CAPACITY.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (`rec` not initialised, or changed
 *         since); the frame's status (sbr_image_check()); ::SBR_ERR_RANGE for rows 0 or
 *         overlap >= rows; ::SBR_ERR_SIZE for a capacity of 0; the
 *         statuses of sbr_recog_detect() for a band, `count` 0 then; ::SBR_ERR_SIZE also
 *         for a frame too small for the maps; ::SBR_ERR_WORKSPACE when the recogniser's
 *         workspace is below sbr_recog_strip_workspace_size(); ::SBR_ERR_CAPACITY when a
 *         detection did not fit: `dets` ran full (the best `capacity` of all bands are
 *         written) or a band had more than ::SBR_RECOG_STRIP_BAND_DETECTIONS (its best
 *         are kept). Every band is processed either way.
 */
sbr_status_t sbr_recog_detect_strips(sbr_recog_t *rec, const sbr_image_t *img, uint32_t rows,
                                     uint32_t overlap, sbr_detection_t *dets, uint32_t capacity,
                                     uint32_t *count, sbr_recog_stats_t *stats);

#ifdef __cplusplus
}
#endif

#endif /* SBR_RECOG_STRIPS_H */
