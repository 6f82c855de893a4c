/* SPDX-License-Identifier: MIT */
/**
 * @file track.h
 * @brief Channel-based multi-target tracking with a learned second-order motion model
 *        (paper E).
 *
 * **Representation.** Each target carries, per image axis, a density over
 * (position, velocity) stored as cos² channel coefficients (thesis chapter 3.3): a
 * window of `window` position channels that moves with the target, times the model's
 * `vel_count` velocity channels. Position and velocity share the spacing s =
 * `vel_spacing` (pixels, velocities in pixels per model period), so a velocity channel
 * moves a density by a whole number of position channels per period. The two axes are
 * filtered independently (a separable density; the association uses both).
 *
 * **Motion model (order 2).** The state (x_{t-1}, v_{t-1} = x_{t-1} - x_{t-2}) makes
 * p(x_t | x_{t-1}, x_{t-2}) a transition on velocity channels,
 * T[axis][region][j][k] = p(v_t in channel k | v_{t-1} in channel j, position in region),
 * where the region is a coarse cos² channel of the image position along that axis (the
 * motion of objects seen from a moving car depends on where they are in the image). It is
 * learned from frame-wise detections **without associations** (host tool
 * `sbr_train_track`): every detection triple in three consecutive frames whose displacements fit
 * the velocity range adds a soft (channel-coded) count; the correct triples pile up
 * coherently, wrong ones spread into a flat floor. The same counts over detection pairs
 * give the velocity prior a new target starts with, per region. sbr_track_model_cv()
 * makes a model from a constant-velocity assumption instead (for data without
 * sequences to learn from).
 *
 * **One step** (sbr_track_step(), `dt_us` microseconds since the previous step, dt):
 * 1. Predict every target: for each coefficient (p, j), the velocity moves to channel k
 *    with T[.][region][j][k] (region weights at the window centre), the position by
 *    (k - centre) * dt / period channels (a fractional shift is split between the two
 *    neighbouring channels). Steps longer than 1.5 periods are done in sub-steps of at
 *    most one period. The window is re-centred on the predicted mean first.
 * 2. Encode each detection as a channel likelihood per axis,
 *    l(x_p) = (1 - w) + w * B((x_p - z) / W), with B the cos² kernel of support W =
 *    5.53 * `meas_sigma` (the kernel's standard deviation is then `meas_sigma`) and w the
 *    detection's certainty in (0, 1]: a certain detection is the kernel, an uncertain
 *    one flattens towards "no information".
 * 3. Associate (documented order, deterministic): every (target, detection) pair whose
 *    normalised distance to the prediction, sum over axes of (z - mean)² / (var +
 *    meas_sigma²), is at most `gate`² is a candidate with cost -log of its predictive
 *    likelihood (the prediction's position channels times the detection's kernel). The
 *    candidates of confirmed targets are taken first, then those of tentative targets;
 *    within each group, cheapest first, each target and each detection at most once.
 *    A target keeps its id for life, so ids are stable as long as association is right.
 * 4. Update: multiply the position channels by the detection's likelihood and
 *    normalise. Targets without a detection coast on the prediction.
 * 5. Deaths: a tentative target dies at its first miss, a confirmed one after more than
 *    `max_misses` consecutive misses, any target whose estimate leaves the image.
 *    Births: every unassigned detection starts a tentative target (position: the
 *    detection's kernel; velocity: the model's prior for that region) with a new id;
 *    a target is confirmed after `confirm_hits` hits.
 * 6. Decode: the strongest valid window (3 channels) of the position marginal gives the
 *    estimate (sbr_channel_decode()), likewise for the velocity; the estimate's
 *    certainty is that window's share of the density.
 *
 * Memory: all densities live in a caller workspace (sbr_track_workspace_size(),
 * ::SBR_TRACK_WORKSPACE_SIZE); the instance is a plain struct. No heap, no globals.
 */
#ifndef SBR_TRACK_H
#define SBR_TRACK_H

#include "sbr/channel.h"
#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most targets one tracker holds. */
#define SBR_TRACK_MAX_TARGETS 64u
/** Most detections per step. */
#define SBR_TRACK_MAX_DETECTIONS 256u
/** Most position channels in a target's window (per axis). */
#define SBR_TRACK_MAX_WINDOW 63u
/** Most velocity channels. */
#define SBR_TRACK_MAX_VEL 127u
/** Most region channels per axis. */
#define SBR_TRACK_MAX_REGIONS 32u
/** Largest image extent (pixels) of a model. */
#define SBR_TRACK_MAX_EXTENT 1.0e6f
/** The model order this implementation supports: p(x_t | x_{t-1}, x_{t-2}). */
#define SBR_TRACK_ORDER 2u

/** Floats of a model's transition table: both axes, every region, V x V. */
#define SBR_TRACK_MODEL_TRANSITION_LEN(rx, ry, vel) \
    (((size_t)(rx) + (size_t)(ry)) * (size_t)(vel) * (size_t)(vel))
/** Floats of a model's birth (velocity prior) table: both axes, every region, V. */
#define SBR_TRACK_MODEL_BIRTH_LEN(rx, ry, vel) (((size_t)(rx) + (size_t)(ry)) * (size_t)(vel))

/**
 * A motion model (learned, or from sbr_track_model_cv()). The tables are the caller's
 * (const; a generated model keeps them in flash).
 *
 * Region channels along an axis of extent E with R regions: spacing E / (R - 2), first
 * centre -spacing / 2, overlap 3, so every position in [0, E) is encoded.
 * Velocity channel k is centred on (k - (V - 1) / 2) * vel_spacing.
 */
typedef struct sbr_track_model_s {
    uint32_t order;          /**< ::SBR_TRACK_ORDER (others are refused). */
    float period;            /**< seconds between the frames the model describes, > 0. */
    float extent[2];         /**< image width and height in pixels (the grid), 8 ..
                                  ::SBR_TRACK_MAX_EXTENT. */
    uint32_t regions[2];     /**< region channels per axis, 3 .. ::SBR_TRACK_MAX_REGIONS. */
    uint32_t vel_count;      /**< V, odd, 5 .. ::SBR_TRACK_MAX_VEL. */
    float vel_spacing;       /**< s, pixels (per period), > 0 and at most the larger extent:
                                  also the position spacing. */
    /** T: axis x first (regions[0] blocks of V x V, row j = previous velocity), then
        axis y. Every row non-negative, finite, summing to 1 (within 1e-3). */
    const float *transition;
    /** Velocity prior of a new target, same layout with V per region, rows sum to 1. */
    const float *birth;
} sbr_track_model_t;

/** Tracker configuration. Start from sbr_track_config_default(). */
typedef struct sbr_track_config_s {
    const sbr_track_model_t *model; /**< the motion model (default: NULL, must be set). */
    uint32_t max_targets; /**< 1 .. ::SBR_TRACK_MAX_TARGETS; sizes the workspace. Default 32. */
    uint32_t window;      /**< position channels per axis, odd, 7 .. ::SBR_TRACK_MAX_WINDOW.
                               Wider: survives longer gaps and harder manoeuvres, costs
                               time and memory linearly. Default 21. */
    float meas_sigma;     /**< detection noise, pixels (> 0): the width of a detection's
                               kernel. The kernel, 5.53 * meas_sigma / vel_spacing
                               channels, must fit in the window (at most `window`
                               channels). Default 3. */
    float gate;           /**< association gate in standard deviations, > 0. Default 4. */
    uint32_t confirm_hits;/**< hits that confirm a target, 1 .. 16. Default 2. */
    uint32_t max_misses;  /**< consecutive misses a confirmed target survives, 0 .. 255.
                               Default 5. */
} sbr_track_config_t;

/** Floats one target needs (both axes). */
#define SBR_TRACK_TARGET_FLOATS(window, vel) (2u * (size_t)(window) * (size_t)(vel))
/** Association candidates kept per target (the cheapest within the gate). */
#define SBR_TRACK_CANDIDATES 8u
/** Workspace bytes: every target's densities, one scratch density and the association
    candidates (8 bytes each). */
#define SBR_TRACK_WORKSPACE_SIZE(targets, window, vel)                                      \
    (((((size_t)(targets) * SBR_TRACK_TARGET_FLOATS(window, vel)) + ((size_t)(window) * (vel))) * \
      sizeof(float)) +                                                                      \
     ((size_t)(targets) * SBR_TRACK_CANDIDATES * 8u))

/** Per-target bookkeeping (private; part of the instance). */
typedef struct sbr_track_slot_s {
    float origin[2];   /* centre of position channel 0, per axis */
    float est[4];      /* decoded x, y, vx, vy */
    float certainty;
    uint32_t id;
    uint32_t hits;
    uint32_t misses;
    uint32_t age;
    int32_t det;
    uint32_t flags;
} sbr_track_slot_t;

/** A tracker instance. Fields are private; use the functions. */
typedef struct sbr_track_s {
    sbr_track_config_t cfg;
    float *dens;       /* max_targets densities */
    float *scratch;    /* one density */
    float *cand_cost;  /* per target SBR_TRACK_CANDIDATES costs */
    uint32_t *cand_det;/* and their detections */
    uint32_t ncand[SBR_TRACK_MAX_TARGETS];
    sbr_track_slot_t slot[SBR_TRACK_MAX_TARGETS];
    uint32_t next_id;
    uint32_t frame;
    uint32_t magic;
} sbr_track_t;

/** One detection. */
typedef struct sbr_track_detection_s {
    float x;         /**< pixels, in [0, extent[0]) */
    float y;         /**< pixels, in [0, extent[1]) */
    float certainty; /**< (0, 1] */
} sbr_track_detection_t;

/** Target flags. */
#define SBR_TRACK_CONFIRMED 1u /**< confirmed (reached confirm_hits) */
#define SBR_TRACK_UPDATED 2u   /**< a detection was used in this step */
#define SBR_TRACK_BORN 4u      /**< born in this step */

/** One target estimate. */
typedef struct sbr_track_target_s {
    uint32_t id;        /**< stable for the target's life, never reused (starts at 1) */
    float x;            /**< decoded position, pixels */
    float y;
    float vx;           /**< decoded velocity, pixels per model period */
    float vy;
    float certainty;    /**< share of the density in the decoded position windows, 0..1 */
    uint32_t hits;      /**< detections used so far */
    uint32_t misses;    /**< consecutive steps without a detection */
    uint32_t age;       /**< steps since birth */
    int32_t detection;  /**< index of the detection used in this step, -1 if none */
    uint32_t flags;     /**< SBR_TRACK_* */
} sbr_track_target_t;

/**
 * @brief Defaults as documented in ::sbr_track_config_t. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_track_config_default(sbr_track_config_t *cfg);

/**
 * @brief Check a model: order, sizes, extents, and that every table row is finite,
 *        non-negative and sums to 1 (within 1e-3).
 * @param[in] model the model
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (a count out of range);
 *         ::SBR_ERR_RANGE (order, period, extent, spacing); ::SBR_ERR_CORRUPT (a table
 *         row that is not a distribution).
 */
sbr_status_t sbr_track_model_check(const sbr_track_model_t *model);

/**
 * @brief The region channels of a model's axis as a channel layout (spacing
 *        extent / (regions - 2), first centre -spacing / 2, overlap 3). The tracker weighs
 *        a position's regions with sbr_channel_encode() on this layout; learning must use
 *        the same, so a learned table's regions mean what the tracker reads.
 * @param[in] model the model
 * @param[in] axis 0 for x, 1 for y.
 * @param[out] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (axis, region count or extent).
 */
sbr_status_t sbr_track_region_config(const sbr_track_model_t *model, uint32_t axis,
                                     sbr_channel_config_t *cfg);

/**
 * @brief Make a constant-velocity model: the velocity changes per period by a Gaussian
 *        of `accel_sigma` pixels (discretised on the velocity channels, the same for all
 *        regions); a new target's velocity prior is a Gaussian of `birth_sigma` around 0.
 * @param[out] model filled (its tables point to `transition` and `birth`).
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 * @param[in] period seconds between the frames the model describes, > 0.
 * @param[in] vel_count velocity channels (odd, 5 .. ::SBR_TRACK_MAX_VEL).
 * @param[in] vel_spacing pixels per period between velocity channels, > 0.
 * @param[in] accel_sigma velocity change per period, pixels (Gaussian sigma), > 0.
 * @param[in] birth_sigma a new target's velocity prior, pixels per period, > 0.
 * @param[out] transition caller array of SBR_TRACK_MODEL_TRANSITION_LEN(3, 3, vel_count)
 *        floats (3 regions per axis); `birth` of SBR_TRACK_MODEL_BIRTH_LEN(3, 3, vel_count).
 * @param[in] transition_len length of `transition` in floats.
 * @param[out] birth caller array for the birth prior (`birth_len` floats).
 * @param[in] birth_len length of `birth` in floats.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (vel_count, or an array too short);
 *         ::SBR_ERR_RANGE (a value not finite and > 0).
 */
sbr_status_t sbr_track_model_cv(sbr_track_model_t *model, float width, float height,
                                float period, uint32_t vel_count, float vel_spacing,
                                float accel_sigma, float birth_sigma, float *transition,
                                size_t transition_len, float *birth, size_t birth_len);

/**
 * @brief Check a configuration (its model by sbr_track_model_check()).
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (max_targets, window);
 *         ::SBR_ERR_RANGE (meas_sigma not finite, <= 0 or with a kernel wider than the
 *         window; gate; confirm_hits; max_misses); model errors.
 */
sbr_status_t sbr_track_config_check(const sbr_track_config_t *cfg);

/**
 * @brief Workspace bytes for a configuration; 0 if it is invalid.
 * @param[in] cfg the configuration
 */
size_t sbr_track_workspace_size(const sbr_track_config_t *cfg);

/**
 * @brief Set up a tracker with no targets.
 * @param[in,out] trk the tracker to set up (its previous content is ignored).
 * @param[in] cfg the configuration
 * @param[in,out] workspace sbr_track_workspace_size() bytes, 4-byte aligned, owned by the tracker
 *        (and the model's tables must stay valid) while it is used.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; configuration errors; ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_track_init(sbr_track_t *trk, const sbr_track_config_t *cfg, void *workspace,
                            size_t workspace_size);

/**
 * @brief Drop every target and start the identities again at 1, as after
 *        sbr_track_init() with the same configuration and workspace (e.g. after a scene
 *        cut or a camera restart).
 * @param[in,out] trk an initialised tracker.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted).
 */
sbr_status_t sbr_track_reset(sbr_track_t *trk);

/**
 * @brief One frame: predict by dt, associate, update, deaths and births, decode.
 * @param[in,out] trk   the tracker.
 * @param[in]     dt_us microseconds since the previous step, 0 < dt <= 8 model periods
 *        (the first step's dt only has to be valid).
 * @param[in]     dets this frame's detections (NULL allowed when n = 0).
 * @param[in]     n number of detections, 0 .. ::SBR_TRACK_MAX_DETECTIONS.
 * @param[out]    targets result array: every live target after the step, confirmed ones first
 *        (each group by id).
 * @param[in]     capacity length of `targets`.
 * @param[out]    count targets written.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted);
 *         ::SBR_ERR_RANGE (dt; a detection that is not finite, outside the image or with a
 *         certainty outside (0, 1]) - then nothing changes; ::SBR_ERR_SIZE (n too large) -
 *         nothing changes; ::SBR_ERR_CAPACITY when detections could not start targets
 *         because all `max_targets` slots were taken, or when `targets` was too short
 *         (the step is done in both cases; the first `capacity` targets are written).
 */
sbr_status_t sbr_track_step(sbr_track_t *trk, uint32_t dt_us, const sbr_track_detection_t *dets,
                            uint32_t n, sbr_track_target_t *targets, uint32_t capacity,
                            uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif /* SBR_TRACK_H */
