/* SPDX-License-Identifier: MIT */
/**
 * @file recog.h
 * @brief Traffic-sign recognition from the shapes of regions (thesis paper D): parts
 *        (parts.h) are matched against a prototype library, vote for a sign's centre and
 *        size, are verified by each class's cascade, and the class stage (picto.h) names
 *        and scores what survives. docs/architecture.md describes the stages; the
 *        configuration's fields, their ranges and defaults are one table
 *        (sbr_recog_field_at(), docs/usage/configuration.md).
 *
 * Use: sbr_recog_init() once (it checks the configuration, the library and the class
 * stage, against each other, and keeps the caller's workspace), then sbr_recog_detect()
 * per frame. No heap, no statics; the models' tables are only read.
 *
 *     sbr_recog_config_t cfg;  sbr_model_t model;  sbr_picto_model_t picto;  sbr_recog_t rec;
 *     static uint64_t ws[SBR_RECOG_WORKSPACE_DEFAULT_SIZE(1360u, 800u, 1u) / 8u];
 *     sbr_recog_config_default(&cfg);
 *     (void)sbr_model_gtsdb(&model);   (void)sbr_picto_gtsdb(&picto);   (sbr/models.h)
 *     st = sbr_recog_init(&rec, &cfg, &model, &picto, ws, sizeof ws);
 *     ... per frame: st = sbr_recog_detect(&rec, &frame, NULL, dets, 64u, &n, &stats);
 */
#ifndef SBR_RECOG_H
#define SBR_RECOG_H

#include "sbr/parts.h"
#include "sbr/part_model.h"
#include "sbr/picto.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest sbr_recog_config_t::views. */
#define SBR_RECOG_MAX_VIEWS 5u
/** Shift of the extra views, as a fraction of the box's width or height. */
#define SBR_RECOG_VIEW_SHIFT 0.06f
/** Largest sbr_recog_config_t::refine_steps. */
#define SBR_RECOG_MAX_REFINE 4u

/** Options. Start from sbr_recog_config_default(). Each field's range, default and meaning
    is in the table (sbr_recog_field_at(); docs/usage/configuration.md), which the check,
    the host tools' options and the Python keywords are made from; why the defaults are
    what they are: docs/results/. */
typedef struct sbr_recog_config_s {
    /** Part extraction (parts.h): maps, regions, contours, descriptors. fd_n and fd_m
        must equal the model's. On a GRAY8 frame only the intensity map is used. */
    sbr_parts_config_t parts;
    uint32_t grey_polarity;    /**< intensity map's polarities on a GRAY8 frame */
    uint32_t match_p;          /**< correlation size P (FFT size >= 2 fd_m + 1) */
    uint32_t max_parts;        /**< parts per frame (workspace bound) */
    uint32_t max_votes;        /**< votes per frame (workspace bound) */
    uint32_t max_hypotheses;   /**< hypotheses per frame (workspace bound) */
    uint32_t max_model_protos; /**< largest library the workspace serves */
    float vote_error;          /**< vote threshold on the match error; 0: the model's */
    float verify_error;        /**< the cascade's threshold (looser: the place is known) */
    float max_rotation;        /**< radians a part may turn against its prototype */
    float min_size;            /**< smallest predicted sign, pixels */
    float max_size;            /**< largest predicted sign, pixels */
    float centre_tol;          /**< a hypothesis's votes: centres within this x size */
    float size_tol;            /**< ... and sizes within a factor 1 + size_tol */
    uint32_t cascade_depth;    /**< cascade prototypes looked for (0: none) */
    uint32_t min_parts;        /**< distinct prototypes a hypothesis needs */
    float candidate_score;     /**< part-score floor of a class-stage candidate */
    uint32_t max_candidates;   /**< class-stage candidates per frame (::SBR_RECOG_HIT_CANDIDATES) */
    uint32_t refine_steps;     /**< box refinements by the class stage's regression (when
                                    and how far: the class stage's looks, picto.h) */
    uint32_t views;            /**< shifted views averaged (::SBR_RECOG_VIEW_SHIFT) */
    uint32_t triangle_view;    /**< 1: a danger candidate's inner triangle looked at again */
    uint32_t max_extra_looks;  /**< looks per frame beyond each candidate's first
                                    (::SBR_RECOG_HIT_LOOKS) */
    float min_score;           /**< score floor of a reported detection */
    float nms_iou;             /**< suppression IoU on the final scores */
    float candidate_iou;       /**< suppression IoU before the class stage (1: none) */
    uint32_t gate;             /**< 1: the class stage's gate screens candidates first */
    uint32_t outline_maps;     /**< map kinds whose sign-shaped regions are candidates too */
    uint32_t max_outline_candidates; /**< such candidates per frame (::SBR_RECOG_HIT_OUTLINES) */
    /** Optional tick source for per-stage profiling (a cycle counter, a monotonic clock);
        NULL: none. Not a field of the table. */
    uint32_t (*clock)(void *clock_ctx);
    void *clock_ctx;           /**< passed to `clock` */
} sbr_recog_config_t;

/**
 * @brief Fields in the configuration's table.
 * @return the count (every field of sbr_recog_config_t but the clock).
 */
uint32_t sbr_recog_field_count(void);

/**
 * @brief One field of the table.
 * @param[in]  index 0 .. sbr_recog_field_count() - 1
 * @param[out] out   the field (name and help point into const tables)
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE beyond the table.
 */
sbr_status_t sbr_recog_field_at(uint32_t index, sbr_field_t *out);

/**
 * @brief A field's index by name.
 * @param[in] name the field's name (sbr_field_t::name)
 * @return its index; ::SBR_FIELD_NONE for an unknown name or NULL.
 */
uint32_t sbr_recog_field_find(const char *name);

/**
 * @brief Which field of a configuration fails its check: every range first, then the
 *        rules between fields (::SBR_FIELD_LINKED), in table order.
 * @param[in] cfg the configuration
 * @return the failing field's index; ::SBR_FIELD_NONE when all pass or `cfg` is NULL.
 */
uint32_t sbr_recog_config_check_field(const sbr_recog_config_t *cfg);

/** Stages timed when a clock is configured. */
typedef enum sbr_recog_stage_e {
    SBR_RECOG_STAGE_PARTS = 0,  /**< maps, MSER, masks, contours, descriptors */
    SBR_RECOG_STAGE_VOTES = 1,  /**< prototype matching and voting */
    SBR_RECOG_STAGE_GROUP = 2,  /**< sorting and grouping votes into hypotheses */
    SBR_RECOG_STAGE_VERIFY = 3, /**< class evidence and cascade verification */
    SBR_RECOG_STAGE_NMS = 4,    /**< non-maximum suppression on part evidence */
    SBR_RECOG_STAGE_CLASS = 5,  /**< class stage (pictograms), suppression, output */
    SBR_RECOG_STAGES = 6
} sbr_recog_stage_t;

/** One detection. */
typedef struct sbr_detection_s {
    sbr_rect_t box;     /**< in pixels of the full image (a ROI's offset added back) */
    float score;        /**< 0..1 */
    float class_share;  /**< the class's share of the hypothesis's evidence, 0..1 */
    uint16_t class_id;  /**< 0 .. the model's class_count - 1 */
    uint16_t parts;     /**< distinct prototypes that supported it (0: an outline
                             candidate, sbr_recog_config_t::outline_maps) */
} sbr_detection_t;

/** @name Bits of sbr_recog_stats_t::capacity_hit: the internal bounds that ran full @{ */
#define SBR_RECOG_HIT_PARTS 1u       /**< max_parts */
#define SBR_RECOG_HIT_VOTES 2u       /**< max_votes */
#define SBR_RECOG_HIT_HYPOTHESES 4u  /**< max_hypotheses */
#define SBR_RECOG_HIT_MSER 8u        /**< the part stage's MSER nodes or regions */
#define SBR_RECOG_HIT_CANDIDATES 16u /**< max_candidates */
#define SBR_RECOG_HIT_LOOKS 32u      /**< max_extra_looks */
#define SBR_RECOG_HIT_OUTLINES 64u   /**< max_outline_candidates, or no room among the
                                          max_hypotheses for them */
/** The bounds whose reaching loses results: all but ::SBR_RECOG_HIT_CANDIDATES, which
    ranks by design (the best max_candidates are classified). The ECU's status frame
    reports these (ecu.h). */
#define SBR_RECOG_HIT_LOSSES                                                                      \
    (SBR_RECOG_HIT_PARTS | SBR_RECOG_HIT_VOTES | SBR_RECOG_HIT_HYPOTHESES | SBR_RECOG_HIT_MSER | \
     SBR_RECOG_HIT_LOOKS | SBR_RECOG_HIT_OUTLINES)
/** @} */

/** What one call did. */
typedef struct sbr_recog_stats_s {
    sbr_parts_stats_t parts_stats; /**< part extraction counters */
    uint32_t parts;           /**< parts extracted */
    uint32_t matches;         /**< part-prototype correlations computed */
    uint32_t votes;           /**< votes cast */
    uint32_t hypotheses;      /**< hypotheses formed */
    uint32_t verified;        /**< parts found by cascade verification */
    uint32_t rejected;        /**< hypotheses below min_parts or a score floor */
    uint32_t classified;      /**< candidates the class stage examined */
    uint32_t refined;         /**< box refinements the class stage applied */
    uint32_t views;           /**< extra views the class stage classified (config.views) */
    uint32_t extra_looks;     /**< looks beyond each candidate's first (refinements, extra
                                   views, triangle views; config.max_extra_looks) */
    uint32_t rim_rejected;    /**< candidates dropped by the class stage's colour check
                                   (sbr_picto_model_t::rim_floor) */
    uint32_t gated;           /**< candidates the class stage's gate rejected (config.gate) */
    uint32_t outlines;        /**< outline candidates made (config.outline_maps; counted in
                                   `classified` too) */
    uint32_t capacity_hit;    /**< the bounds that ran full: ::SBR_RECOG_HIT_PARTS, ... */
    uint32_t stage_ticks[SBR_RECOG_STAGES]; /**< clock ticks per ::sbr_recog_stage_t
                                                 (0 without a clock) */
} sbr_recog_stats_t;

/**
 * @brief Defaults as documented. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_recog_config_default(sbr_recog_config_t *cfg);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK, ::SBR_ERR_NULL, ::SBR_ERR_RANGE.
 */
sbr_status_t sbr_recog_config_check(const sbr_recog_config_t *cfg);

/**
 * @brief Workspace bytes for frames (or ROIs) up to width x height; 0 for a bad
 *        configuration or size.
 * @param[in] cfg the configuration
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 */
size_t sbr_recog_workspace_size(const sbr_recog_config_t *cfg, uint32_t width, uint32_t height);

/** @name Defaults that size the workspace (sbr_recog_config_default()) @{ */
#define SBR_RECOG_DEFAULT_DELTA 3u               /**< parts.mser.delta */
#define SBR_RECOG_DEFAULT_MATCH_P 32u            /**< match_p */
#define SBR_RECOG_DEFAULT_MAX_PARTS 3072u        /**< max_parts */
#define SBR_RECOG_DEFAULT_MAX_VOTES 16384u       /**< max_votes */
#define SBR_RECOG_DEFAULT_MAX_HYPOTHESES 4096u   /**< max_hypotheses */
#define SBR_RECOG_DEFAULT_MAX_MODEL_PROTOS 1024u /**< max_model_protos */
#define SBR_RECOG_DEFAULT_MAX_EXTRA_LOOKS 256u   /**< max_extra_looks */
#define SBR_RECOG_DEFAULT_MAX_OUTLINES 64u       /**< max_outline_candidates */
/** @} */

/** @name Outline candidates (sbr_recog_config_t::outline_maps) @{ */
#define SBR_RECOG_OUTLINE_ASPECT 1.5f /**< longest box side / shortest side, at most */
#define SBR_RECOG_OUTLINE_IOU 0.85f   /**< IoU above which a nested region's box counts once */
/** @} */

/** @name Per-entry bytes of the recogniser's workspace arrays @{ */
#define SBR_RECOG_INDEX_BYTES 12u /**< the part index, per part */
#define SBR_RECOG_VOTE_BYTES 32u  /**< per vote */
#define SBR_RECOG_HYP_BYTES 52u   /**< per hypothesis */
/** The class stage's block: its looks' workspace (picto.h), then the class
    probabilities of a box and their mean over views. */
#define SBR_RECOG_CLASS_BYTES \
    (SBR_WS_ALIGN8(SBR_PICTO_LOOK_WORKSPACE_SIZE) + \
     SBR_WS_ALIGN8((size_t)2u * SBR_PICTO_MAX_OUTPUTS * sizeof(float)))
/** @} */

/**
 * sbr_recog_workspace_size() of the default configuration (sbr_recog_config_default())
 * with parts.subsample = `s` (1..8), for frames up to width x height, as a constant
 * expression for static allocation on an ECU (equal to the function; checked by the unit
 * tests). Three blocks: the part stage's (::SBR_PARTS_WORKSPACE_SIZE of the finest map,
 * intensity at `s`), which after that stage holds everything the later stages use but the
 * parts and is at least that large (::SBR_RECOG_AFTER_PARTS_SIZE); the parts; the class
 * stage's.
 */
#define SBR_RECOG_WORKSPACE_DEFAULT_SIZE(width, height, s)                                     \
    SBR_RECOG_WORKSPACE_BOUNDS_SIZE(width, height, s, SBR_PARTS_DEFAULT_MAX_NODES,              \
                                    SBR_PARTS_DEFAULT_MAX_HEAP, SBR_RECOG_DEFAULT_MAX_PARTS)

/**
 * sbr_recog_workspace_size() of the default configuration with parts.subsample = `s` and
 * the MSER's and the part stage's bounds `nodes` (parts.mser.max_nodes), `heap`
 * (parts.mser.max_heap) and `parts` (max_parts) for a width x height frame or band
 * (::SBR_RECOG_WORKSPACE_DEFAULT_SIZE, ::SBR_RECOG_WORKSPACE_STRIP_SIZE).
 */
#define SBR_RECOG_WORKSPACE_BOUNDS_SIZE(width, height, s, nodes, heap, parts)                  \
    (SBR_WS_MAX(SBR_WS_ALIGN8(SBR_PARTS_WORKSPACE_SIZE((width) / (s), (height) / (s),           \
                                            SBR_RECOG_DEFAULT_DELTA, nodes, heap,                \
                                            SBR_PARTS_DEFAULT_MAX_REGIONS,                       \
                                            SBR_PARTS_DEFAULT_MAX_SIDE,                          \
                                            SBR_PARTS_DEFAULT_MAX_CONTOUR,                       \
                                            SBR_PARTS_DEFAULT_FD_N)),                            \
                SBR_RECOG_AFTER_PARTS_SIZE(width, SBR_RECOG_DEFAULT_MAX_MODEL_PROTOS, parts,     \
                                           SBR_RECOG_DEFAULT_MAX_VOTES,                          \
                                           SBR_RECOG_DEFAULT_MAX_HYPOTHESES)) +                  \
     SBR_WS_ALIGN8((size_t)(parts) * sizeof(sbr_part_t)) + SBR_RECOG_CLASS_BYTES)

/**
 * What the part stage's block holds after that stage, in bytes (default fd_m and
 * match_p): the prototypes' coefficient magnitudes for the matcher's screening (2 fd_m + 1
 * floats per prototype), the vote grouping's index of hypotheses by column (width / 16 +
 * 2 + 2 hypotheses words), the part index, the match results, the matcher's scratch, the
 * votes and the hypotheses.
 */
#define SBR_RECOG_AFTER_PARTS_SIZE(width, protos, parts, votes, hypotheses)                   \
    (SBR_WS_ALIGN8((size_t)(protos) * ((2u * SBR_PARTS_DEFAULT_FD_M) + 1u) * sizeof(float)) + \
     SBR_WS_ALIGN8((((size_t)(width) / 16u) + 2u + (2u * (size_t)(hypotheses))) *             \
                   sizeof(uint32_t)) +                                                         \
     SBR_WS_ALIGN8((size_t)(parts) * SBR_RECOG_INDEX_BYTES) +                                  \
     SBR_WS_ALIGN8((size_t)(protos) * sizeof(sbr_fd_match_t)) +                                \
     SBR_WS_ALIGN8((size_t)SBR_FD_TABLE_WORK_LEN(SBR_RECOG_DEFAULT_MATCH_P) *                  \
                   sizeof(sbr_complex_t)) +                                                    \
     SBR_WS_ALIGN8((size_t)(votes) * SBR_RECOG_VOTE_BYTES) +                                   \
     SBR_WS_ALIGN8((size_t)(hypotheses) * SBR_RECOG_HYP_BYTES))

/** A recogniser: the configuration, the library and the class stage it was initialised
    with, checked, and the caller's workspace. Fields are private; use the functions. The
    model's and the class stage's tables, the workspace and cfg.clock_ctx are borrowed and
    must outlive it. One recogniser runs one frame at a time (its workspace). */
typedef struct sbr_recog_s {
    sbr_recog_config_t cfg;
    sbr_model_t model;
    sbr_picto_model_t picto; /* version 0: no class stage */
    sbr_fft_t fft_n;         /* the descriptors' FFT (parts.fd_n), set up once */
    sbr_fft_t fft_p;         /* the correlation's FFT (match_p), set up once */
    void *workspace;
    size_t workspace_size;
    float vote_error;        /* cfg.vote_error, or the model's */
    uint32_t magic;
    uint32_t check;          /* integrity word over everything before it */
} sbr_recog_t;

/**
 * @brief Set up a recogniser: check the configuration (sbr_recog_config_check()), the
 *        prototype library (sbr_model_check()) and the class stage (sbr_picto_check())
 *        once, and against each other, and keep the workspace. On any status other than
 *        ::SBR_OK `rec` is left uninitialised (sbr_recog_detect() refuses it).
 * @param[out] rec       the recogniser.
 * @param[in]  cfg       options (copied).
 * @param[in]  model     prototype library, e.g. sbr_model_gtsdb() (the struct is copied,
 *                       its tables borrowed).
 * @param[in]  picto     class stage, e.g. sbr_picto_gtsdb() (copied, tables borrowed);
 *                       NULL or version 0: none (detections are scored and classified by
 *                       part evidence alone).
 * @param[in]  workspace sbr_recog_workspace_size() bytes for the largest frame or ROI it
 *                       will see, 8-byte aligned; borrowed.
 * @param[in]  workspace_size bytes available at `workspace`.
 * @return ::SBR_OK; ::SBR_ERR_NULL (rec, cfg or model); ::SBR_ERR_RANGE (bad configuration,
 *         or model and configuration disagree on fd_n/fd_m, or the model exceeds
 *         max_model_protos); ::SBR_ERR_CORRUPT (the model fails sbr_model_check(), the
 *         class stage sbr_picto_check(), or their class counts differ);
 *         ::SBR_ERR_WORKSPACE (NULL, size 0 or misaligned).
 */
sbr_status_t sbr_recog_init(sbr_recog_t *rec, const sbr_recog_config_t *cfg,
                            const sbr_model_t *model, const sbr_picto_model_t *picto,
                            void *workspace, size_t workspace_size);

/**
 * @brief Detect signs in a frame (or a region of it).
 * @param[in,out] rec    a recogniser from sbr_recog_init() (its workspace is used).
 * @param[in]  img       RGB888, BGR888 or GRAY8 frame. A GRAY8 frame (a monochrome camera)
 *                       gives parts from the intensity map alone, the class stage reads
 *                       it as an image with R = G = B, and the colour check
 *                       (sbr_picto_model_t::rim_floor) is skipped; the built-in models are
 *                       trained on colour, so grey frames find fewer signs
 *                       (docs/results/recognition.md).
 * @param[in]  roi       region of interest (NULL: the whole frame); boxes are reported in
 *                       frame pixels.
 * @param[out] dets      detections, highest score first.
 * @param[in]  capacity  length of `dets`, >= 1.
 * @param[out] count     detections written.
 * @param[out] stats     counters (may be NULL). Zeroed first; written on ::SBR_OK and
 *                       ::SBR_ERR_CAPACITY, all zero after any other status.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (`rec` not initialised, or its
 *         contents changed since); ::SBR_ERR_SIZE / ::SBR_ERR_ALIGN (bad view: size, or a
 *         stride; a frame or ROI too small for the maps; SIZE also for a capacity of 0);
 *         ::SBR_ERR_RANGE for a ROI that is empty or leaves the frame, and for a GRAY8
 *         frame when parts.maps has no intensity map;
 *         ::SBR_ERR_WORKSPACE (the frame or ROI needs more than the recogniser's workspace,
 *         sbr_recog_workspace_size());
 *         ::SBR_ERR_CAPACITY when `dets` ran full (the best `capacity` are written).
 *         Internal bounds (parts, votes, hypotheses, MSER nodes) that run full do not fail
 *         the call: they are flagged in stats->capacity_hit.
 */
sbr_status_t sbr_recog_detect(sbr_recog_t *rec, const sbr_image_t *img, const sbr_rect_t *roi,
                              sbr_detection_t *dets, uint32_t capacity, uint32_t *count,
                              sbr_recog_stats_t *stats);

#ifdef __cplusplus
}
#endif

#endif /* SBR_RECOG_H */
