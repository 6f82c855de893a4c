/* SPDX-License-Identifier: MIT */
/**
 * @file ecu.h
 * @brief The ECU's per-frame job in one object: a frame's signs in; the confirmed signs,
 *        the restrictions in force and the frame's detections out on CAN.
 *
 * Set up once (sbr_ecu_init()), then once per frame with its time:
 * - sbr_ecu_frame(): the recogniser on the frame (sbr_recog_detect()), then the rest;
 * - sbr_ecu_output(): the rest, for detections made elsewhere (a recogniser run by the
 *   caller, a detection file):
 *   1. detections below `min_score` are left out; the others go to the sign tracking
 *      (signs.h), which confirms each sign once per pass and names it by its evidence;
 *   2. the signs confirmed (or renamed) in the frame update the restrictions (rules.h);
 *   3. the cycle's CAN records are made (can.h): the four newest confirmed signs with
 *      their age (SBR_ConfirmedSign, the speed of a speed-limit class from the rules'
 *      meanings), the status (SBR_EcuStatus: frame counter, processing time, regions,
 *      detections, error and capacity flags), every detection with the id of its sign
 *      (SBR_Detection, id modulo 63), the restrictions in force (SBR_Restrictions: the
 *      limit, the bans, priority road, the limit's age in seconds);
 *   4. the scheduler packs and protects them (sbr_can_schedule()) and they leave through
 *      the port (sbr_can_send()).
 * A frame that fails (the recogniser refuses the image, or the caller says so with
 * sbr_ecu_frame_info_t::error) still sends its cycle: the status frame carries error = 1,
 * the tracks coast and the restrictions expire as without detections. Capacity reached
 * anywhere sets capacity_hit in the status frame.
 *
 * With `stills` set, the frames are independent pictures (no tracking): every detection is
 * a confirmed sign in its own frame, with ids 0..254 in turn.
 *
 * Memory: the sign tracking's workspace and the cycle's records live in a caller
 * workspace (sbr_ecu_workspace_size(), ::SBR_ECU_WORKSPACE_SIZE); the recogniser keeps its
 * own. Bounded work: at most ::SBR_ECU_MAX_DETECTIONS detections a frame.
 */
#ifndef SBR_ECU_H
#define SBR_ECU_H

#include "sbr/can.h"
#include "sbr/recog.h"
#include "sbr/rules.h"
#include "sbr/signs.h"
#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most detections one frame hands on (more are left out, with capacity_hit). */
#define SBR_ECU_MAX_DETECTIONS 64u
/** Most CAN frames one cycle sends (sbr_can_sched_config_t::frame_budget). */
#define SBR_ECU_MAX_FRAMES 64u
/** Confirmed signs listed on CAN (SBR_ConfirmedSign's slots). */
#define SBR_ECU_LISTED 4u
/** Frames a listed sign stays listed (its age field's range). */
#define SBR_ECU_LIST_FRAMES 255u

/** Options. Start from sbr_ecu_config_default(). */
typedef struct sbr_ecu_config_s {
    sbr_signs_config_t signs;       /**< the sign tracking */
    sbr_rules_config_t rules;       /**< the restrictions (its class count must be the
                                         signs' class count) */
    sbr_can_sched_config_t sched;   /**< the CAN cycle (frame_budget at most
                                         ::SBR_ECU_MAX_FRAMES) */
    float min_score;                /**< detections below are left out, 0..1. Default 0. */
    uint32_t stills;                /**< 1: independent pictures, no tracking. Default 0. */
} sbr_ecu_config_t;

/** What the caller knows about the frame (sbr_ecu_output()). */
typedef struct sbr_ecu_frame_info_s {
    float processing_ms;   /**< time the frame took, ms (clamped to the status signal's
                                0..6553.4) */
    uint32_t regions;      /**< regions of the frame (the recogniser's parts_stats.regions) */
    uint32_t error;        /**< 1: the frame failed */
    uint32_t capacity_hit; /**< 1: a bound of the recogniser ran full and lost results
                                (::SBR_RECOG_HIT_LOSSES) */
} sbr_ecu_frame_info_t;

/** What one frame did. */
typedef struct sbr_ecu_result_s {
    sbr_rules_state_t restrictions; /**< in force after the frame */
    uint32_t detections;  /**< detections at or above min_score */
    uint32_t confirmed;   /**< signs confirmed (or renamed) in the frame */
    uint32_t signs;       /**< confirmed signs alive */
    uint32_t frames_sent; /**< CAN frames the port took */
    uint32_t dropped;     /**< results without a frame (budget, limits) */
    uint32_t capacity_hit;/**< 1: something ran full (as in the status frame) */
    sbr_status_t recog;   /**< sbr_ecu_frame(): the recogniser's status */
} sbr_ecu_result_t;

/** A listed confirmed sign (private; part of the instance). */
typedef struct sbr_ecu_listed_s {
    uint32_t class_id;
    uint32_t track_id;
    uint32_t frame;
    float score;
} sbr_ecu_listed_t;

/** An instance. Fields are private; use the functions. */
typedef struct sbr_ecu_s {
    sbr_ecu_config_t cfg;
    sbr_signs_t signs;
    sbr_rules_t rules;
    sbr_can_e2e_tx_t tx;
    sbr_ecu_listed_t listed[SBR_ECU_LISTED];
    uint32_t listed_count;
    uint64_t now_us;       /* the last frame's time */
    uint32_t started;      /* 1 after the first frame */
    uint32_t frame;        /* frames done */
    uint32_t next_still;   /* the next still's id */
    sbr_detection_t *dets;         /* SBR_ECU_MAX_DETECTIONS: the frame's kept detections */
    uint32_t *det_sign;            /* their signs' ids */
    sbr_can_detection_t *records;  /* their CAN records */
    sbr_sign_t *alive;             /* the signs after the frame (max_tracks) */
    sbr_can_frame_t *frames;       /* the cycle's frames (frame_budget) */
    uint32_t magic;
} sbr_ecu_t;

/** Workspace bytes for `tracks` and `classes` of the sign tracking and a frame budget. */
#define SBR_ECU_WORKSPACE_SIZE(tracks, classes, budget)                                        \
    (SBR_SIGNS_WORKSPACE_SIZE((tracks), (classes)) +                                          \
     ((size_t)SBR_ECU_MAX_DETECTIONS *                                                        \
      (sizeof(sbr_detection_t) + sizeof(uint32_t) + sizeof(sbr_can_detection_t))) +           \
     ((size_t)(tracks) * sizeof(sbr_sign_t)) + ((size_t)(budget) * sizeof(sbr_can_frame_t)))

/**
 * @brief Defaults: the sign tracking's, the rules' (GTSDB), the scheduler's; min_score 0,
 *        frames tracked. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_ecu_config_default(sbr_ecu_config_t *cfg);

/**
 * @brief Check a configuration (its parts by their own checks).
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (min_score, stills, frame_budget,
 *         the rules' class count not the signs'); the parts' statuses.
 */
sbr_status_t sbr_ecu_config_check(const sbr_ecu_config_t *cfg);

/**
 * @brief Workspace bytes for a configuration; 0 if it is invalid.
 * @param[in] cfg the configuration
 */
size_t sbr_ecu_workspace_size(const sbr_ecu_config_t *cfg);

/**
 * @brief Set up: no tracks, no restriction, CAN counters at 0.
 * @param[out] ecu the instance
 * @param[in] cfg the configuration (copied; the rules' meanings borrowed)
 * @param[in,out] workspace sbr_ecu_workspace_size() bytes, 8-byte aligned, owned by the
 *        instance while it is used
 * @param[in] workspace_size bytes at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; configuration errors; ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_ecu_init(sbr_ecu_t *ecu, const sbr_ecu_config_t *cfg, void *workspace, size_t workspace_size);

/**
 * @brief One frame's detections in, its CAN cycle out through the port.
 * @param[in,out] ecu an instance
 * @param[in] now_us the frame's time, microseconds, after the previous frame's
 * @param[in] dets the frame's detections (NULL allowed when n is 0); beyond
 *        ::SBR_ECU_MAX_DETECTIONS at or above min_score, the first are kept
 * @param[in] n their number
 * @param[in] info the frame's processing time, regions and flags
 * @param[in] port the port the frames leave through
 * @param[in,out] port_ctx the port's context
 * @param[out] result what the frame did (may be NULL)
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted);
 *         ::SBR_ERR_RANGE (a time not after the previous frame's, a malformed detection:
 *         nothing is sent and nothing changes); ::SBR_ERR_CAPACITY (the cycle was sent,
 *         but something ran full: capacity_hit); the port's status when it refused a
 *         frame (the frames before it were sent).
 */
sbr_status_t sbr_ecu_output(sbr_ecu_t *ecu, uint64_t now_us, const sbr_detection_t *dets, uint32_t n,
                            const sbr_ecu_frame_info_t *info, const sbr_can_port_t *port, void *port_ctx,
                            sbr_ecu_result_t *result);

/**
 * @brief One frame: the recogniser, then sbr_ecu_output(). The frame's processing time is
 *        the recogniser's stage ticks summed, at `ticks_per_ms` (0: reported as 0).
 * @param[in,out] ecu an instance
 * @param[in,out] rec an initialised recogniser
 * @param[in] img the frame
 * @param[in] now_us its time, microseconds, after the previous frame's
 * @param[in] ticks_per_ms clock ticks per millisecond of the recogniser's stage ticks
 * @param[in] port the port the frames leave through
 * @param[in,out] port_ctx the port's context
 * @param[out] result what the frame did (may be NULL); `recog` the recogniser's status
 * @return as sbr_ecu_output(); a frame the recogniser refused is still sent (error = 1)
 *         and the recogniser's status is returned.
 */
sbr_status_t sbr_ecu_frame(sbr_ecu_t *ecu, sbr_recog_t *rec, const sbr_image_t *img, uint64_t now_us,
                           uint32_t ticks_per_ms, const sbr_can_port_t *port, void *port_ctx,
                           sbr_ecu_result_t *result);

#ifdef __cplusplus
}
#endif

#endif /* SBR_ECU_H */
