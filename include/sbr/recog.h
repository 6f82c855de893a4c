/* SPDX-License-Identifier: MIT */
/**
 * @file recog.h
 * @brief Traffic-sign recognition from the shapes of regions (thesis paper D): channel
 *        maps -> MSER regions -> outer contours -> Fourier descriptors ("parts") ->
 *        matching against a prototype library -> star-model votes for the sign centre and
 *        size -> cascaded verification of the class's other parts -> non-maximum
 *        suppression -> detections.
 *
 * ## The model (prototype library)
 * A prototype is a part that recurs across training instances of signs: its descriptor,
 * the map and polarity it is found on, the offset from the part's centroid to the sign's
 * centre and the sign's width and height, all in units of the part's scale
 * (sbr_fd_t::scale, a length), and the classes whose signs contain it (a ring is shared by
 * every prohibitory sign, a "5" only by some speed limits). Each prototype carries a vote
 * weight, its precision on training backgrounds, so parts that also match clutter count
 * less. Per class, the cascade lists the class's prototypes, most reliable first.
 * Prototypes are grouped by map and polarity so a part is only matched against the
 * prototypes of its own group. The library is built by the host tool `sbr_train`, which
 * writes a const C table (lib/models/, the default, sbr_model_gtsdb()) and a file form
 * for host tools.
 *
 * ## Recognition
 * 1. Parts of the frame or ROI (parts.h), at most `max_parts`.
 * 2. Every part is matched (covariant mode, rotation bounded by `max_rotation`) against
 *    the prototypes of its group; each match with error e <= `vote_error` that predicts a
 *    sign of `min_size` .. `max_size` pixels casts a vote: centre = part centroid + offset
 *    x part scale, size = prototype size x part scale, weight = prototype weight x
 *    (1 - e / vote_error). At most `max_votes` votes.
 * 3. Votes, strongest first, are grouped into hypotheses: a vote joins the first
 *    hypothesis whose centre is within `centre_tol` of its size and whose size is within a
 *    factor 1 + `size_tol`, else starts one (at most `max_hypotheses`).
 * 4. A hypothesis's evidence for class c is the sum over its distinct prototypes of the
 *    strongest vote times the prototype's share of class c. The best class is verified by
 *    its cascade: the class's prototypes that did not vote (at most `cascade_depth`) are
 *    looked for among the parts where the model predicts them (centre within `centre_tol`,
 *    scale within a factor 1 + `size_tol`, same group) with the looser `verify_error`;
 *    each one found adds its weight. A hypothesis needs `min_parts` distinct supporting
 *    prototypes. (The parts are indexed by group and centre x once per frame, so a check
 *    looks only at the parts in the x range; matching in steps 2 and 4 screens out
 *    prototypes whose error is certainly above the threshold, fd.h `max_error`. Neither
 *    changes a result.)
 * 5. Part score = 1 - prod(1 - w) over the supporting weights w (0..1). Hypotheses below
 *    the part-score floor are dropped; overlapping ones are suppressed, the higher score
 *    kept: IoU > `nms_iou` without a class stage, IoU > `candidate_iou` with one (default
 *    1: none, since the part score says little about where exactly the sign is: a box
 *    the part evidence placed well is often weaker than an overlapping one it placed
 *    badly, and suppressing on part scores dropped it before the class stage saw it).
 * 6. Class stage (when the recogniser has one, sbr_recog_init()'s `picto`): the surviving hypotheses
 *    (at most `max_candidates`, best part score first) are the candidates; the pictogram
 *    classifier (picto.h) looks at each box and gives the class (its most probable
 *    sign class) and the score (that probability; "no sign" takes the rest). When the
 *    classifier has a box regression, a candidate is moved to the box the regression
 *    predicts and classified again there (`refine_steps` times at most: the first move
 *    when the candidate is at least `refine_first_score` likely a sign, each further one
 *    while it is at least `refine_score` likely); box is the last one. A candidate still at least
 *    `view_score` likely is then classified at `views` slightly shifted copies of its
 *    box and class and score come from the mean probabilities (fewer confident false
 *    detections; views = 1 keeps the last classification). With `triangle_view`, the
 *    final box is classified once more with only the inside of a danger sign's triangle
 *    in view (for candidates at least `triangle_score` likely a danger sign at first),
 *    and a danger class more probable there is taken. Detections
 *    below `min_score` are dropped and suppression runs again on the new scores.
 *    After the part model's candidates the class stage looks at the outline candidates
 *    (`outline_maps`, at most `max_outline_candidates`): the sign-shaped bright regions
 *    of those maps, each at its own bounding box, classified the same way.
 *    Without a class stage the part score and part evidence's class are reported.
 *
 * ## Use
 * The recogniser is an object (sbr_recog_t): sbr_recog_init() checks the configuration,
 * the prototype library and the class stage once, against each other, and keeps the
 * caller's workspace; sbr_recog_detect() then runs on frame after frame without checking
 * them again:
 *
 *     sbr_recog_config_t cfg;  sbr_model_t model;  sbr_picto_model_t picto;  sbr_recog_t rec;
 *     static uint64_t ws[SBR_RECOG_WORKSPACE_DEFAULT_SIZE(1360u, 800u, 1u) / 8u];
 *     sbr_recog_config_default(&cfg);
 *     (void)sbr_model_gtsdb(&model);
 *     (void)sbr_picto_gtsdb(&picto);
 *     st = sbr_recog_init(&rec, &cfg, &model, &picto, ws, sizeof ws);
 *     ... per frame: st = sbr_recog_detect(&rec, &frame, NULL, dets, 64u, &n, &stats);
 *
 * Everything lives in the caller's workspace (sbr_recog_workspace_size()); the model's
 * tables are only read. No heap, no statics.
 */
#ifndef SBR_RECOG_H
#define SBR_RECOG_H

#include "sbr/parts.h"
#include "sbr/picto.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of sign classes of a model (sbr_model_t::class_count); a bound of the
    core, not of a dataset (GTSDB has 43). */
#define SBR_RECOG_MAX_CLASSES SBR_PICTO_MAX_CLASSES
/** Largest sbr_recog_config_t::views. */
#define SBR_RECOG_MAX_VIEWS 5u
/** Shift of the extra views, as a fraction of the box's width or height. */
#define SBR_RECOG_VIEW_SHIFT 0.06f
/** Largest sbr_recog_config_t::refine_steps. */
#define SBR_RECOG_MAX_REFINE 4u
/** Classes a prototype can be shared by. */
#define SBR_MODEL_PROTO_CLASSES 4u
/** "No class" in sbr_model_proto_t::class_id. */
#define SBR_MODEL_NO_CLASS 255u
/** Groups: map kind (0..3) x polarity (dark, bright). */
#define SBR_MODEL_GROUPS 8u
/** Model format version of the generated table and the file form (the class count and
    the classes' outlines are the model's). */
#define SBR_MODEL_VERSION 4u

/** One prototype part (see the file comment). */
typedef struct sbr_model_proto_s {
    float dx;        /**< sign centre x - part centroid x, in part scales */
    float dy;        /**< sign centre y - part centroid y, in part scales */
    float w;         /**< sign width in part scales, > 0 */
    float h;         /**< sign height in part scales, > 0 */
    float weight;    /**< vote weight (precision on training backgrounds), (0, 1] */
    uint16_t support; /**< training signs the part recurred in */
    uint8_t map;     /**< ::sbr_map_kind_t */
    uint8_t polarity; /**< ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT */
    uint8_t class_id[SBR_MODEL_PROTO_CLASSES]; /**< classes, most frequent first;
                                                   ::SBR_MODEL_NO_CLASS pads */
    float class_p[SBR_MODEL_PROTO_CLASSES];     /**< share of each class, sum <= 1 */
} sbr_model_proto_t;

/** A prototype library. All arrays are borrowed (const tables or host memory). */
typedef struct sbr_model_s {
    uint32_t version;          /**< ::SBR_MODEL_VERSION */
    uint32_t fd_n;             /**< descriptor resampling size it was trained with */
    uint32_t fd_m;             /**< descriptor M */
    uint32_t proto_count;      /**< prototypes */
    /** Sign classes of the dataset the model was trained on, 1 .. ::SBR_RECOG_MAX_CLASSES;
        class ids are 0 .. class_count - 1 (GTSDB: 43). */
    uint32_t class_count;
    /** Outline of each class's sign (::sbr_picto_rim_t; ::SBR_PICTO_RIM_NONE: another or
        unknown outline), class_count entries used: the class stage's triangle view
        (sbr_recog_config_t::triangle_view) is for the classes with
        ::SBR_PICTO_RIM_TRIANGLE (GTSDB's danger signs). */
    uint8_t class_outline[SBR_RECOG_MAX_CLASSES];
    const sbr_fd_t *fds;       /**< proto_count descriptors, sorted by group */
    const sbr_model_proto_t *protos; /**< proto_count prototypes, same order */
    /** Group g = map * 2 + (polarity - 1) holds prototypes group_first[g] ..
        group_first[g + 1] - 1. */
    uint16_t group_first[SBR_MODEL_GROUPS + 1u];
    /** Class c's cascade is cascade[class_first[c] .. class_first[c + 1] - 1]
        (prototype indices, most reliable first). */
    uint16_t class_first[SBR_RECOG_MAX_CLASSES + 1u];
    const uint16_t *cascade;   /**< class_first[class_count] entries */
    float vote_error;          /**< vote threshold it was trained with */
    float score_threshold;     /**< operating point of part evidence alone (without a class
                                    stage), chosen on the training images */
} sbr_model_t;

/** Range of a model descriptor's scale (sbr_fd_t::scale, pixels of the training region),
    so that a region's scale over it stays a float32 value. */
#define SBR_MODEL_MIN_SCALE 1e-10f
#define SBR_MODEL_MAX_SCALE 1e10f

/**
 * @brief Check a model: version, sizes, group and cascade indices, finite positive
 *        geometry, weights in (0, 1], class count in 1 .. ::SBR_RECOG_MAX_CLASSES and
 *        class ids below it, outlines in range, valid descriptors of unit energy with
 *        scales in ::SBR_MODEL_MIN_SCALE .. ::SBR_MODEL_MAX_SCALE. (The class stage is
 *        checked by sbr_picto_check(), and against the library by sbr_recog_init().)
 * @param[in] model the model
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_CORRUPT for any inconsistency.
 */
sbr_status_t sbr_model_check(const sbr_model_t *model);

/**
 * @brief The prototype group of a part's map and polarity (sbr_model_t::group_first):
 *        map * 2 + (polarity - 1).
 * @param[in] map      the part's map (::sbr_map_kind_t)
 * @param[in] polarity ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT
 * @return the group, 0 .. ::SBR_MODEL_GROUPS - 1; ::SBR_MODEL_GROUPS for a map or polarity
 *         out of range.
 */
uint32_t sbr_model_group(uint8_t map, uint8_t polarity);

/**
 * @brief The library trained on GTSDB images 00000-00599 (lib/models/sbr_model_gtsdb.c,
 *        generated by sbr_train): fills `out` with pointers to const tables in flash (the
 *        struct itself is the caller's, so the core keeps no relocated data). The class
 *        stage trained with it is sbr_picto_gtsdb().
 * @param[out] out the result
 * @return ::SBR_OK; ::SBR_ERR_NULL.
 */
sbr_status_t sbr_model_gtsdb(sbr_model_t *out);

/** Options. Start from sbr_recog_config_default(); every field is documented there. */
typedef struct sbr_recog_config_s {
    /** Part extraction (parts.h). fd_n and fd_m must equal the model's. Default:
        sbr_parts_config_default() with MSER delta 3, max_variation 0.5, and each map
        flooded where its signs are: the intensity map's bright regions
        (map_polarity[SBR_MAP_INTENSITY] = SBR_MSER_BRIGHT); the red map's bright regions
        from level 136 up (map_polarity[SBR_MAP_RED] = SBR_MSER_BRIGHT,
        map_bright_min[SBR_MAP_RED] = 136: red rims and discs, under 2 % of a scene's
        pixels); the blue map at half resolution (map_subsample[SBR_MAP_BLUE] = 2) with
        regions from 20 of its pixels (map_min_area[SBR_MAP_BLUE] = 20, signs from about
        11 px), bright ones and dark ones up to level 120 (map_dark_max[SBR_MAP_BLUE] =
        120: yellow). Trade-off: maps and subsample set most of the time and memory;
        subsample 2 quarters both and loses signs below about 24 px. On a GRAY8 frame only
        the intensity map of `maps` is used (the colour kinds are skipped), with the
        polarities of `grey_polarity`. Why these: docs/results/realtime.md (2026-12-05)
        and docs/results/recognition.md. */
    sbr_parts_config_t parts;
    /** Polarities of the intensity map on a GRAY8 frame (its only map): 0 = parts.mser's,
        otherwise an ::sbr_mser_polarity_t mask; replaces map_polarity[SBR_MAP_INTENSITY]
        there. Default 0 (both: in grey a red ring on a bright ground is a dark region, the
        only region a sign's rim gives). */
    uint32_t grey_polarity;
    /** Correlation size P (a supported FFT size, >= 2M + 1). Default 32. Larger P locates
        the peak on a finer grid before refinement; the cost grows with P log P. */
    uint32_t match_p;
    /** Parts kept per frame (bounds the workspace: each part's record and its 12-byte
        entry in the cascade's index of parts by group and x). Default 3072 (GTSDB frames
        have at most 2,699 with the default maps; frames of random colour blocks reach it). */
    uint32_t max_parts;
    /** Votes kept per frame. Default 16384. */
    uint32_t max_votes;
    /** Hypotheses kept per frame. Default 4096. */
    uint32_t max_hypotheses;
    /** Largest prototype count of a model this workspace can serve. Default 1024. */
    uint32_t max_model_protos;
    /** Vote threshold on the match error, (0, 4]; 0 = the model's. Default 0 (the model's).
        Larger: more votes, more recall on distorted parts, more clutter. */
    float vote_error;
    /** Cascade verification threshold, (0, 4]. Default 0.25 (looser than voting: the
        location is already known). */
    float verify_error;
    /** Largest rotation of a part against its prototype, radians (0, pi]. Default 0.35
        (signs stand upright; keeps a "6" from matching a "9"). */
    float max_rotation;
    /** Predicted sign size (max of width and height) limits, pixels. Defaults 12 and 200. */
    float min_size;
    float max_size;
    /** Centre tolerance as a fraction of the sign size. Default 0.2. */
    float centre_tol;
    /** Size tolerance: factor 1 + size_tol either way. Default 0.3. */
    float size_tol;
    /** Cascade prototypes checked per hypothesis. Default 8; 0 = no verification. */
    uint32_t cascade_depth;
    /** Distinct prototypes a hypothesis needs (votes and verified parts). Default 1 (the
        class stage rejects clutter; without a class stage, 2 gives far fewer false
        detections at the cost of single-contour signs). */
    uint32_t min_parts;
    /** With a class stage: the part-score floor of a candidate, [0, 1). Default 0 (every
        hypothesis is a candidate). Larger: less class-stage work, lower recall. */
    float candidate_score;
    /** With a class stage: candidates classified per frame, best part score first
        (bounds its work: each costs one pictogram, see picto.h). Default 256; a
        1360 x 800 street frame has several hundred hypotheses, so the bound is usually
        reached: that is its purpose, and ::SBR_RECOG_HIT_CANDIDATES says so. Larger: more
        recall on signs with weak part evidence, more time. */
    uint32_t max_candidates;
    /** With a class stage whose classifier has a box regression (sbr_picto_model_t::w3):
        how often a candidate's box is moved to where the classifier places the sign and
        classified again, 0 .. ::SBR_RECOG_MAX_REFINE. Default 2. 0: boxes stay where the
        part model put them. Each step costs one more pictogram and the regression. */
    uint32_t refine_steps;
    /** The first refinement needs the sign classes together to be at least this probable
        at the part model's box, [0, 1], on a colour frame. Default 0.01: the candidates
        the classifier finds at least that sign-like are refined (the others, most of the
        background, are not moved; 0: every candidate is refined once, for boxes a fifth of
        a sign's size off that it calls "no sign" yet whose regression still points at the
        sign). Each refinement costs one pictogram; higher: less work, fewer badly placed
        signs recovered (docs/results/realtime.md, 2026-12-05, seventh part). */
    float refine_first_score;
    /** refine_first_score on a grey (::SBR_PIXEL_GRAY8) frame, [0, 1]. Default 0.0003:
        without colour the class stage's first look at a sign is often far less sure, and
        only the refined box finds it. */
    float grey_refine_first_score;
    /** Further refinements (steps 2 .. refine_steps) only while the sign classes together
        are at least this probable, [0, 1]. Default 0.001 (after one move, a box near a
        sign is seldom less likely than that; background stays below it and is not moved
        again). Lower: more work. */
    float refine_score;
    /** With a class stage: a candidate that is still at least view_score likely after
        its refinement is classified at this many views of its final box, 1 ..
        ::SBR_RECOG_MAX_VIEWS, and the class probabilities are averaged: the box itself,
        then shifted by ::SBR_RECOG_VIEW_SHIFT of its size right, left, down, up. Default
        5. 1: the box alone. Each view costs one more pictogram. */
    uint32_t views;
    /** Classify at several views only while the sign classes together are at least this
        probable after refinement, [0, 1]. Default 0.1. Lower: more work (most candidates
        are background). */
    float view_score;
    /** With a class stage: 1 (default) classifies every candidate once more at its final
        box with only the inside of a danger sign's triangle (sbr_picto_features_outline(),
        ::SBR_PICTO_OUTLINE_TRIANGLE); when that view's most probable sign class is a
        danger sign (GTSDB class 11 or 18..31) and more probable than the candidate's
        score, it becomes the candidate's class and score (clutter in the box's top
        corners otherwise hides danger signs). 0: off. Costs one more pictogram per
        candidate that passes triangle_score. */
    uint32_t triangle_view;
    /** With triangle_view: only candidates whose first classification (at the box the
        part model placed) gives the danger classes together at least this probability
        get the triangle view, [0, 1]. Default 0.001: skips most candidates (about half
        the class stage's time) with the same detections at the usual operating point.
        0: every candidate. Higher: less work, fewer danger signs recovered. */
    float triangle_score;
    /** With a class stage: the looks a frame may spend beyond each candidate's first
        (refinement steps, extra views, triangle views), 0 .. 1000000. The candidates are
        classified in order of part score; once the budget is spent, further extra looks
        are skipped and a candidate keeps the box, class and score of its last look
        (::SBR_RECOG_HIT_LOOKS in the statistics). Bounds the class stage's work on frames full of
        sign-like shapes (a grid of rings: about 1,000 extra looks) to a known multiple of
        a scene's; GTSDB frames spend at most a few dozen (docs/results/realtime.md).
        Default 256. */
    uint32_t max_extra_looks;
    /** Score floor of reported detections, [0, 1): the class stage's probability, or the
        part score without one. Default 0.3 (below the usual operating point, so
        evaluations can draw precision-recall curves). */
    float min_score;
    /** Non-maximum suppression IoU, (0, 1]. Default 0.3. */
    float nms_iou;
    /** With a class stage: the suppression IoU among the candidates before it, on part
        scores, (0, 1]. Default 1: every hypothesis above the floor is a candidate (up to
        max_candidates, best part score first) and suppression runs once, on the class
        scores (nms_iou). Lower values classify fewer boxes and lose signs whose best box
        had a weaker part score (measured: docs/results/recognition.md). */
    float candidate_iou;
    /** With a class stage whose classifier has a gate (sbr_picto_model_t::gate): 1
        (default) looks at each candidate with the gate first (sbr_picto_gate_features(),
        about a tenth of a pictogram's work) and classifies only the candidates that pass
        it; 0: every candidate goes to the full classifier. The candidate bound
        (max_candidates) counts the candidates looked at, passed or not. */
    uint32_t gate;
    /** With a class stage: outline candidates. Every part of these map kinds (bit k = map
        kind k, map.h) whose region is bright there, of `min_size` .. `max_size` pixels
        (its box's larger side) and at most ::SBR_RECOG_OUTLINE_ASPECT times as long as
        it is wide, also becomes a candidate at its own bounding box, without part
        evidence (a region that traces a sign's outline is a sign's box; the part model's
        votes place small or blurred signs too large when their outline matches no
        prototype). Nested regions of nearly one box (IoU > ::SBR_RECOG_OUTLINE_IOU with
        an earlier outline candidate) count once. They are classified after the part
        model's candidates, from the same look budget (max_extra_looks), and report
        `parts` 0. Default: the red and blue maps (red rims and discs, blue discs: the
        prohibitory, danger and mandatory signs). 0: none. Measured:
        docs/results/crossval.md (2026-12-06, outline candidates). */
    uint32_t outline_maps;
    /** With a class stage: outline candidates per frame at most, 0 .. 1000000, in the
        order of the parts (::SBR_RECOG_HIT_OUTLINES when more qualify). Default 64
        (GTSDB frames have about 33). Each costs a gate look (config.gate) and, when it
        passes, a classification. */
    uint32_t max_outline_candidates;
    /** Optional time source for per-stage profiling (e.g. the DWT cycle counter on a
        Cortex-M, a monotonic clock on a host): returns a free-running tick count; the
        stats report differences modulo 2^32. NULL (default): no profiling. */
    uint32_t (*clock)(void *clock_ctx);
    /** Passed to `clock`. Default NULL. */
    void *clock_ctx;
} sbr_recog_config_t;

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

#endif /* SBR_RECOG_H */
