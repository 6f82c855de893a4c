/* SPDX-License-Identifier: MIT */
/**
 * @file signs.h
 * @brief Sign tracking: a drive's recognised signs become tracks with a stable id and a
 *        class decided from the evidence of all their frames; each sign is confirmed once
 *        per pass.
 *
 * Positions are the detections' box centres, tracked by the channel tracker (track.h,
 * paper E) with a constant-velocity model that the instance makes at set-up
 * (sbr_track_model_cv(): ::SBR_SIGNS_VEL velocity channels ::SBR_SIGNS_VEL_SPACING px
 * apart, a velocity change of ::SBR_SIGNS_ACCEL px per period, a new sign's velocity
 * prior ::SBR_SIGNS_BIRTH px per period; windows of ::SBR_SIGNS_WINDOW channels). A
 * detection's certainty for the tracker is its score, at least `min_certainty`.
 *
 * **Class evidence.** Each track sums, per class, the scores of the detections it was
 * given (a class's evidence); its class is the class with the most evidence (the lowest
 * class id on a tie). One frame's misclassification adds a little evidence to another
 * class, and the track keeps its name.
 *
 * **Confirmation.** A track is confirmed, once, in the first frame in which it has had
 * `confirm_hits` detections and its class holds at least `confirm_share` of its evidence
 * (all classes summed). That frame reports the sign with ::SBR_SIGN_NEW. Should the
 * evidence later turn to another class, the frame in which it does reports the sign
 * again, under the same id, with ::SBR_SIGN_RENAMED. A confirmed track lives on through
 * up to `max_misses` frames without a detection; then, or when it leaves the image, it
 * ends.
 *
 * **Time.** sbr_signs_update() takes each frame's time in microseconds. The first frame is
 * taken to follow a nominal period. A gap longer than ::SBR_SIGNS_MAX_GAP periods ends
 * every track (the tracker cannot predict that far); ids continue from where they were.
 * Ids start at 1 and are never reused while the instance lives.
 *
 * Memory: the model's tables, the tracker's densities, the evidence and per-frame scratch
 * live in a caller workspace (sbr_signs_workspace_size(), ::SBR_SIGNS_WORKSPACE_SIZE);
 * the instance is a plain struct. Bounded work: per frame O(detections x tracks) for the
 * association and O(tracks x classes) for the evidence. No heap, no statics.
 */
#ifndef SBR_SIGNS_H
#define SBR_SIGNS_H

#include "sbr/recog.h"
#include "sbr/track.h"
#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most tracks one instance holds. */
#define SBR_SIGNS_MAX_TRACKS 32u
/** Most classes (the recogniser's ::SBR_RECOG_MAX_CLASSES). */
#define SBR_SIGNS_MAX_CLASSES 64u
/** Velocity channels of the motion model. */
#define SBR_SIGNS_VEL 41u
/** Pixels per period between velocity channels (and between position channels). */
#define SBR_SIGNS_VEL_SPACING 4.0f
/** Velocity change per period of the motion model, pixels (Gaussian sigma). */
#define SBR_SIGNS_ACCEL 4.0f
/** A new sign's velocity prior, pixels per period (Gaussian sigma). */
#define SBR_SIGNS_BIRTH 20.0f
/** Position channels of a track's window, per axis. */
#define SBR_SIGNS_WINDOW 21u
/** The longest gap between two frames that keeps the tracks, in nominal periods. */
#define SBR_SIGNS_MAX_GAP 8u

/** Options. Start from sbr_signs_config_default(). */
typedef struct sbr_signs_config_s {
    float width;           /**< image width, pixels, 8 .. ::SBR_TRACK_MAX_EXTENT. Default 1360. */
    float height;          /**< image height, pixels, 8 .. ::SBR_TRACK_MAX_EXTENT. Default 800. */
    uint32_t period_us;    /**< nominal time between frames, 1000 .. 1000000 us. Default 100000. */
    uint32_t class_count;  /**< classes of the detections, 1 .. ::SBR_SIGNS_MAX_CLASSES.
                                Default 43 (GTSDB). */
    uint32_t max_tracks;   /**< 1 .. ::SBR_SIGNS_MAX_TRACKS; sizes the workspace. Default 16. */
    uint32_t confirm_hits; /**< detections that confirm a track, 1 .. 16. Default 2. */
    /** The share of a track's evidence its class needs for confirmation, 0 .. 1 (0: the
        hits alone confirm). Default 0.6 (docs/results/ecu.md). */
    float confirm_share;
    uint32_t max_misses;   /**< frames without a detection a confirmed track survives,
                                0 .. 255. Default 5. */
    float meas_sigma;      /**< detection noise, pixels, 1 .. 20. Default 4. */
    float min_certainty;   /**< floor of a detection's certainty for the tracker, (0, 1].
                                Default 0.05. */
} sbr_signs_config_t;

/** Sign flags (sbr_sign_t::flags). */
#define SBR_SIGN_NEW 1u      /**< confirmed in this frame: report it */
#define SBR_SIGN_RENAMED 2u  /**< confirmed before; its class changed in this frame */
#define SBR_SIGN_SEEN 4u     /**< a detection was given to it in this frame */

/** A confirmed sign after a frame. */
typedef struct sbr_sign_s {
    uint32_t id;          /**< stable for the pass, never reused (from 1) */
    uint16_t class_id;    /**< the class with the most evidence */
    uint16_t flags;       /**< ::SBR_SIGN_NEW, ::SBR_SIGN_RENAMED, ::SBR_SIGN_SEEN */
    float x;              /**< the tracker's position, pixels */
    float y;
    float width;          /**< the last detection's box, pixels */
    float height;
    float score;          /**< the best score of its detections, 0..1 */
    float share;          /**< its class's share of its evidence, 0..1 */
    uint32_t hits;        /**< detections given to it */
    uint32_t frames;      /**< frames since its confirmation (0 in that frame) */
} sbr_sign_t;

/** Per-track bookkeeping (private; part of the instance). */
typedef struct sbr_signs_slot_s {
    uint32_t id;          /* the tracker's id; 0: free */
    uint32_t confirmed;   /* 1 once confirmed */
    uint32_t hits;
    uint32_t frames;      /* frames since confirmation */
    uint32_t class_id;    /* the class last reported */
    uint32_t seen;        /* scratch: alive in this frame */
    float best;
    float box[2];
} sbr_signs_slot_t;

/** An instance. Fields are private; use the functions. */
typedef struct sbr_signs_s {
    sbr_signs_config_t cfg;
    sbr_track_model_t model;
    sbr_track_t trk;
    float *evidence;                   /* max_tracks x class_count */
    sbr_track_detection_t *dets;       /* ::SBR_TRACK_MAX_DETECTIONS */
    uint32_t *src;                     /* their detections' indices */
    sbr_track_target_t *targets;       /* max_tracks */
    sbr_signs_slot_t slot[SBR_SIGNS_MAX_TRACKS];
    uint64_t now_us;
    uint32_t started;
    uint32_t id_base;                  /* added to the tracker's ids (after a gap) */
    uint32_t id_top;                   /* the largest id handed out */
    uint32_t magic;
} sbr_signs_t;

/** Workspace bytes: the model's tables, the tracker's workspace, the evidence, and
    scratch for one frame's detections and targets. */
#define SBR_SIGNS_WORKSPACE_SIZE(tracks, classes)                                          \
    (((SBR_TRACK_MODEL_TRANSITION_LEN(3u, 3u, SBR_SIGNS_VEL) +                                 \
       SBR_TRACK_MODEL_BIRTH_LEN(3u, 3u, SBR_SIGNS_VEL) + ((size_t)(tracks) * (size_t)(classes))) * \
      sizeof(float)) +                                                                        \
     SBR_TRACK_WORKSPACE_SIZE((tracks), SBR_SIGNS_WINDOW, SBR_SIGNS_VEL) +                    \
     ((size_t)SBR_TRACK_MAX_DETECTIONS * (sizeof(sbr_track_detection_t) + sizeof(uint32_t))) + \
     ((size_t)(tracks) * sizeof(sbr_track_target_t)))

/**
 * @brief Defaults as documented in ::sbr_signs_config_t. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_signs_config_default(sbr_signs_config_t *cfg);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (class_count, max_tracks);
 *         ::SBR_ERR_RANGE (a value outside its documented range, NaN).
 */
sbr_status_t sbr_signs_config_check(const sbr_signs_config_t *cfg);

/**
 * @brief Workspace bytes for a configuration; 0 if it is invalid.
 * @param[in] cfg the configuration
 */
size_t sbr_signs_workspace_size(const sbr_signs_config_t *cfg);

/**
 * @brief Set up an instance without tracks.
 * @param[out] signs the instance (unusable on any status but ::SBR_OK)
 * @param[in] cfg the configuration (copied)
 * @param[in,out] workspace sbr_signs_workspace_size() bytes, 4-byte aligned, owned by the
 *        instance while it is used
 * @param[in] workspace_size bytes at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; configuration errors; ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_signs_init(sbr_signs_t *signs, const sbr_signs_config_t *cfg, void *workspace,
                            size_t workspace_size);

/**
 * @brief Drop every track (e.g. after a camera restart); ids continue, never reused.
 * @param[in,out] signs an instance from sbr_signs_init()
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE.
 */
sbr_status_t sbr_signs_reset(sbr_signs_t *signs);

/**
 * @brief One frame: track its detections, add their evidence, confirm, report.
 *
 * Detections whose box centre lies outside the image are not tracked (their
 * `det_sign` is 0); beyond ::SBR_TRACK_MAX_DETECTIONS, the first are tracked.
 *
 * @param[in,out] signs an instance
 * @param[in] now_us the frame's time, microseconds, after the previous frame's
 * @param[in] dets the frame's detections (NULL allowed when n is 0): scores in [0, 1],
 *        classes below class_count
 * @param[in] n their number
 * @param[out] det_sign n entries (may be NULL): the id of the confirmed sign each detection
 *        was given to, 0 for none
 * @param[out] out the confirmed signs alive after the frame, by id
 * @param[in] capacity entries at `out`
 * @param[out] count signs written
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted);
 *         ::SBR_ERR_RANGE (a time not after the previous frame's, a malformed detection:
 *         nothing changes); ::SBR_ERR_CAPACITY (the frame is done, but more than
 *         ::SBR_TRACK_MAX_DETECTIONS detections, all max_tracks taken when a new sign
 *         appeared, or more signs than `capacity`: the first are written).
 */
sbr_status_t sbr_signs_update(sbr_signs_t *signs, uint64_t now_us, const sbr_detection_t *dets,
                              uint32_t n, uint32_t *det_sign, sbr_sign_t *out, uint32_t capacity,
                              uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif /* SBR_SIGNS_H */
