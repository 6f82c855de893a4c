/* SPDX-License-Identifier: MIT */
/**
 * @file can.h
 * @brief sbr's CAN messages: packing per `dbc/sbr.dbc`, end-to-end protection, and the
 *        per-cycle scheduler that turns one frame's results into CAN frames.
 *
 * `dbc/sbr.dbc` is the single source of truth; this module implements exactly its
 * layout: standard 11-bit identifiers, classical CAN (DLC 8), Intel (little-endian) byte
 * order, every signal written with explicit shifts and masks (no bit-fields).
 *
 * | id    | message             | cycle  | content                                           |
 * | 0x300 | SBR_ConfirmedSign   | 100 ms | confirmed signs from the tracker (speed limit)    |
 * | 0x301 | SBR_EcuStatus       | 100 ms | frame counter, time, counts, overload/error flags |
 * | 0x302 | SBR_Restrictions    | 100 ms | the speed limit in force, overtaking bans, priority |
 * | 0x310 | SBR_Detection       | 100 ms | one frame per sign detection of the image         |
 * | 0x320 | SBR_TrackedObject   | 100 ms | one frame per tracked object                      |
 *
 * End-to-end protection (AUTOSAR E2E Profile 1 style): byte 0 is a CRC-8/SAE-J1850
 * (polynomial 0x1D, initial value 0xFF, final XOR 0xFF; check value 0x4B for "123456789")
 * over the message's 16-bit Data ID (low byte, then high byte) followed by payload bytes
 * 1..7; the low nibble of byte 1 is an alive counter 0..14 that increases by one per sent
 * frame of that message and wraps to 0 (15 is never sent). Data ID = 0x5B00 | (id & 0xFF).
 *
 * Physical values outside a signal's range (or NaN) are rejected by the pack functions
 * with ::SBR_ERR_RANGE, never clamped silently; counts in the status message saturate at
 * their maximum by definition (documented per signal). Unpacking never fails on a
 * well-formed frame: it returns the values the bits encode (a consumer checks E2E first).
 */
#ifndef SBR_CAN_H
#define SBR_CAN_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Message identifiers (11-bit). */
#define SBR_CAN_ID_CONFIRMED_SIGN 0x300u
#define SBR_CAN_ID_ECU_STATUS 0x301u
#define SBR_CAN_ID_RESTRICTIONS 0x302u
#define SBR_CAN_ID_DETECTION 0x310u
#define SBR_CAN_ID_TRACKED_OBJECT 0x320u

/** E2E Data ID of a message identifier. */
#define SBR_CAN_DATA_ID(id) (0x5B00u | ((uint32_t)(id) & 0xFFu))

/** Largest alive-counter value (15 is never sent). */
#define SBR_CAN_COUNTER_MAX 14u

/** Sentinels. */
#define SBR_CAN_CLASS_NONE_DET 63u   /**< SBR_Detection: no detection this cycle */
#define SBR_CAN_TRACK_NONE_DET 63u   /**< SBR_Detection: not (yet) tracked */
#define SBR_CAN_CLASS_NONE 255u      /**< SBR_ConfirmedSign: no sign */
#define SBR_CAN_TRACK_NONE 255u      /**< SBR_ConfirmedSign / SBR_TrackedObject: none */
#define SBR_CAN_SPEED_NONE 255u      /**< SBR_ConfirmedSign: not a speed limit / n.a. */

/** A classical CAN frame. */
typedef struct sbr_can_frame_s {
    uint32_t id;     /**< 11-bit identifier */
    uint8_t dlc;     /**< data length, 0..8 */
    uint8_t data[8]; /**< payload */
} sbr_can_frame_t;

/** SBR_Detection (0x310): one detected sign. */
typedef struct sbr_can_detection_s {
    uint32_t class_id;  /**< GTSDB class 0..42, or ::SBR_CAN_CLASS_NONE_DET */
    float confidence;   /**< %, 0..100, resolution 2 */
    float center_x;     /**< px, box centre, 0..2046, resolution 2 */
    float center_y;     /**< px, 0..2046, resolution 2 */
    float width;        /**< px, box width, 0..508, resolution 4 */
    float height;       /**< px, 0..508, resolution 4 */
    uint32_t track_id;  /**< 0..62, or ::SBR_CAN_TRACK_NONE_DET */
} sbr_can_detection_t;

/** SBR_ConfirmedSign (0x300): a sign confirmed by the tracker. */
typedef struct sbr_can_confirmed_sign_s {
    uint32_t slot;        /**< 0..3, newest first */
    uint32_t count;       /**< confirmed signs listed this cycle, 0..4 */
    uint32_t class_id;    /**< 0..42, or ::SBR_CAN_CLASS_NONE */
    uint32_t track_id;    /**< 0..254, or ::SBR_CAN_TRACK_NONE */
    uint32_t speed_kmh;   /**< speed value of a speed-limit sign, 0..250, or
                               ::SBR_CAN_SPEED_NONE */
    float confidence;     /**< %, 0..100, resolution 1 */
    uint32_t age_frames;  /**< frames since confirmation, 0..255 (saturate before packing) */
} sbr_can_confirmed_sign_t;

/** SBR_TrackedObject (0x320): a tracked object in the image plane. */
typedef struct sbr_can_object_s {
    uint32_t index;     /**< 0..15, order of this cycle */
    uint32_t track_id;  /**< 0..254, or ::SBR_CAN_TRACK_NONE (no object) */
    float x;            /**< px, 0..2047, resolution 1 */
    float y;            /**< px, 0..1023, resolution 1 */
    float vx;           /**< px/s, -256..252, resolution 4 */
    float vy;           /**< px/s, -256..252, resolution 4 */
    float certainty;    /**< %, 0..100, resolution 4 */
} sbr_can_object_t;

/** SBR_EcuStatus (0x301). */
typedef struct sbr_can_ecu_status_s {
    uint32_t frame_counter;    /**< processed images, modulo 65536 */
    float processing_ms;       /**< ms, 0..6553.4, resolution 0.1 */
    uint32_t region_count;     /**< regions of the image, saturates at 4095 */
    uint32_t detection_count;  /**< detections of the image, saturates at 15 */
    uint32_t overload;         /**< 1: frames of this cycle were dropped (budget) */
    uint32_t error;            /**< 1: a module reported an error this cycle */
    uint32_t capacity_hit;     /**< 1: a result array or node pool ran full */
} sbr_can_ecu_status_t;

/** SBR_Restrictions (0x302): the restrictions in force (rules.h), as the driver is shown. */
typedef struct sbr_can_restrictions_s {
    uint32_t speed_limit_kmh;      /**< km/h, 0..255; 0: no limit known */
    uint32_t no_overtaking;        /**< 0/1 */
    uint32_t no_overtaking_trucks; /**< 0/1 */
    uint32_t priority_road;        /**< 0/1 */
    uint32_t speed_age_s;          /**< s since the limit was last seen, 0..65535 (saturate
                                        before packing) */
} sbr_can_restrictions_t;

/** @name Pack (E2E bytes left zero) and unpack. Pack: ::SBR_OK, ::SBR_ERR_NULL,
 *  ::SBR_ERR_RANGE (a value outside its signal's range or NaN; the frame is untouched).
 *  Unpack: ::SBR_OK, ::SBR_ERR_NULL, ::SBR_ERR_RANGE (another message id, or a signal
 *  whose raw value is outside its range, e.g. class 50 or confidence 126 %: a corrupted
 *  or foreign frame; `out` is untouched), ::SBR_ERR_SIZE (DLC not 8).
 * @param[in]  in    pack: the message's values.
 * @param[out] frame pack: the frame written; unpack ([in]): the frame read.
 * @param[out] out   unpack: the decoded values.
 * @{ */
sbr_status_t sbr_can_pack_detection(const sbr_can_detection_t *in, sbr_can_frame_t *frame);
sbr_status_t sbr_can_unpack_detection(const sbr_can_frame_t *frame, sbr_can_detection_t *out);
sbr_status_t sbr_can_pack_confirmed_sign(const sbr_can_confirmed_sign_t *in,
                                         sbr_can_frame_t *frame);
sbr_status_t sbr_can_unpack_confirmed_sign(const sbr_can_frame_t *frame,
                                           sbr_can_confirmed_sign_t *out);
sbr_status_t sbr_can_pack_object(const sbr_can_object_t *in, sbr_can_frame_t *frame);
sbr_status_t sbr_can_unpack_object(const sbr_can_frame_t *frame, sbr_can_object_t *out);
sbr_status_t sbr_can_pack_ecu_status(const sbr_can_ecu_status_t *in, sbr_can_frame_t *frame);
sbr_status_t sbr_can_unpack_ecu_status(const sbr_can_frame_t *frame, sbr_can_ecu_status_t *out);
sbr_status_t sbr_can_pack_restrictions(const sbr_can_restrictions_t *in, sbr_can_frame_t *frame);
sbr_status_t sbr_can_unpack_restrictions(const sbr_can_frame_t *frame, sbr_can_restrictions_t *out);
/** @} */

/**
 * @brief CRC-8/SAE-J1850 (0x1D, init 0xFF, xorout 0xFF) of `len` bytes; 0 for NULL.
 * @param[in] data the values
 * @param[in] len number of bytes at `data`
 */
uint8_t sbr_crc8_j1850(const uint8_t *data, uint32_t len);

/** Sender side of E2E: the next alive counter of each message. */
typedef struct sbr_can_e2e_tx_s {
    uint8_t counter[5]; /**< per message: confirmed sign, status, detection, object,
                             restrictions */
} sbr_can_e2e_tx_t;

/** Receiver side of E2E for one message. */
typedef struct sbr_can_e2e_rx_s {
    uint32_t id;          /**< message identifier this state checks */
    uint8_t last_counter; /**< last accepted counter */
    uint8_t synced;       /**< 0 until the first valid frame */
} sbr_can_e2e_rx_t;

/** Outcome of an E2E check. */
typedef enum sbr_can_e2e_result_e {
    SBR_E2E_OK = 0,           /**< valid, counter advanced by one */
    SBR_E2E_FIRST = 1,        /**< valid, first frame since init (counter taken as is) */
    SBR_E2E_WRONG_ID = 2,     /**< not the message this state checks */
    SBR_E2E_WRONG_LENGTH = 3, /**< DLC is not 8 */
    SBR_E2E_WRONG_CRC = 4,    /**< CRC mismatch (corrupted payload, wrong Data ID) */
    SBR_E2E_BAD_COUNTER = 5,  /**< counter 15 (never sent) */
    SBR_E2E_REPEATED = 6,     /**< same counter as the last frame */
    SBR_E2E_SKIPPED = 7       /**< counter jumped: frames were lost (state resyncs) */
} sbr_can_e2e_result_t;

/**
 * @brief Start a sender: all counters 0.
 * @param[in,out] tx the sender's E2E state
 * @return ::SBR_OK, ::SBR_ERR_NULL.
 */
sbr_status_t sbr_can_e2e_tx_init(sbr_can_e2e_tx_t *tx);

/**
 * @brief Write the alive counter and CRC of a packed frame and advance its counter.
 * @param[in,out] tx the sender's E2E state
 * @param[in,out] frame the CAN frame
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (not an sbr message id);
 *         ::SBR_ERR_SIZE (DLC not 8); ::SBR_ERR_STATE (a counter above 14: corrupted state).
 */
sbr_status_t sbr_can_e2e_protect(sbr_can_e2e_tx_t *tx, sbr_can_frame_t *frame);

/** @brief Start a receiver for message `id`. @return ::SBR_OK, ::SBR_ERR_NULL,
 *  ::SBR_ERR_RANGE (not an sbr message id).
 * @param[in,out] rx the receiver's E2E state
 * @param[in] id the CAN identifier
 */
sbr_status_t sbr_can_e2e_rx_init(sbr_can_e2e_rx_t *rx, uint32_t id);

/**
 * @brief Check a received frame.
 * @param[in,out] rx the receiver's E2E state
 * @param[in] frame the CAN frame
 * @param[out] result what the check found (also on error).
 * @return ::SBR_OK for ::SBR_E2E_OK and ::SBR_E2E_FIRST; ::SBR_ERR_CORRUPT for every other
 *         result; ::SBR_ERR_NULL. A repeated frame leaves the state as it was; a skipped
 *         counter is reported and the state follows the new counter.
 */
sbr_status_t sbr_can_e2e_check(sbr_can_e2e_rx_t *rx, const sbr_can_frame_t *frame,
                               sbr_can_e2e_result_t *result);

/** One image's results, as the scheduler takes them. */
typedef struct sbr_can_cycle_s {
    const sbr_can_confirmed_sign_t *signs; /**< newest first; slot/count are set by the
                                                scheduler */
    uint32_t sign_count;
    const sbr_can_detection_t *detections;
    uint32_t detection_count;
    const sbr_can_object_t *objects;       /**< index is set by the scheduler */
    uint32_t object_count;
    sbr_can_ecu_status_t status;           /**< overload is set by the scheduler */
    /** The restrictions in force; NULL: no SBR_Restrictions frame this cycle. */
    const sbr_can_restrictions_t *restrictions;
} sbr_can_cycle_t;

/** Scheduler limits. */
typedef struct sbr_can_sched_config_s {
    uint32_t frame_budget;    /**< frames per cycle, >= 4 (one of each message). Default 16. */
    uint32_t max_signs;       /**< 1..4. Default 4. */
    uint32_t max_detections;  /**< >= 1. Default 8. */
    uint32_t max_objects;     /**< 1..16. Default 8. */
} sbr_can_sched_config_t;

/** @brief Defaults as documented above. No-op for NULL.
    @param[out] cfg the configuration to fill. */
void sbr_can_sched_config_default(sbr_can_sched_config_t *cfg);

/** @brief Check a scheduler configuration (sbr_can_schedule() checks it too).
    @param[in] cfg the configuration.
    @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (frame_budget < 4, max_signs not
            1..4, max_detections 0, max_objects not 1..16). */
sbr_status_t sbr_can_sched_config_check(const sbr_can_sched_config_t *cfg);

/**
 * @brief Turn one cycle's results into protected frames, in priority order.
 *
 * Order (and priority when the budget is short): confirmed signs (a "no sign" frame when
 * there is none), the ECU status, the restrictions (when the cycle has them), detections by decreasing confidence (a "no detection"
 * frame when there is none), tracked objects by decreasing certainty (a "no object" frame
 * when there is none). Frames beyond the budget or beyond the max_* limits are dropped,
 * lowest priority first; the status frame then carries overload = 1 and `dropped` says
 * how many. Every frame is packed, then E2E-protected with `tx`.
 *
 * @param[in,out] tx the sender's E2E state
 * @param[in] cfg the configuration
 * @param[in] cycle this cycle's results (signs, status, detections, objects).
 * @param[out] frames   at least cfg->frame_budget entries (`capacity`).
 * @param[in] capacity entries of the result array
 * @param[out] count    frames written.
 * @param[out] dropped  results that did not get a frame (budget, limits, invalid values).
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a bad config or when a result had
 *         an out-of-range value (that result is left out, the other frames are complete);
 *         ::SBR_ERR_CAPACITY if `capacity` < frame_budget (nothing written).
 */
sbr_status_t sbr_can_schedule(sbr_can_e2e_tx_t *tx, const sbr_can_sched_config_t *cfg,
                              const sbr_can_cycle_t *cycle, sbr_can_frame_t *frames,
                              uint32_t capacity, uint32_t *count, uint32_t *dropped);

/**
 * A port: how frames leave the ECU (SocketCAN, a candump log, a test mock, an MCU
 * driver). A const table of functions plus the port's own context, handed to the core.
 */
typedef struct sbr_can_port_s {
    const char *name; /**< for logs */
    /** Queue one frame. ::SBR_OK; ::SBR_ERR_CAPACITY when the driver's queue is full and
        the port's policy dropped the frame; other errors for a broken port. */
    sbr_status_t (*send)(void *ctx, const sbr_can_frame_t *frame);
} sbr_can_port_t;

/**
 * @brief Send frames in order through a port; stops at the first frame the port refuses.
 * @param[in] port the port
 * @param[in,out] ctx the port's own context, handed to its functions
 * @param[in] frames the frames
 * @param[in] count number of entries
 * @param[out] sent frames the port accepted.
 * @return ::SBR_OK; ::SBR_ERR_NULL; the port's status for the first refused frame.
 */
sbr_status_t sbr_can_send(const sbr_can_port_t *port, void *ctx, const sbr_can_frame_t *frames,
                          uint32_t count, uint32_t *sent);

#ifdef __cplusplus
}
#endif

#endif /* SBR_CAN_H */
