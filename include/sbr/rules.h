/* SPDX-License-Identifier: MIT */
/**
 * @file rules.h
 * @brief The restrictions in force, from confirmed signs: what an intelligent speed
 *        assistant shows the driver (the speed limit, the overtaking bans, priority road).
 *
 * Each confirmed sign (a track's class, once per pass: the sign tracking's output) means
 * something for the restrictions, by its class (sbr_rules_meaning_t; the built-in table
 * is GTSDB's, sbr_rules_gtsdb()):
 * - a speed-limit sign sets the limit; an end sign of one limit (GTSDB 6, end of 80) clears
 *   it when it is that limit; the end of all restrictions (GTSDB 32) clears the limit and
 *   both overtaking bans;
 * - no overtaking (9) and no overtaking for trucks (10) set a ban, their end signs (41,
 *   42) clear it;
 * - priority road (12) sets priority; give way (13) and stop (14) clear it;
 * - any other class means nothing here.
 * A restriction expires `hold_ms` after it was last set or confirmed again (a limit seen
 * again is refreshed). Signs of one call are applied in the order given, after the
 * expiries of that call's time.
 *
 * An instance is a plain struct set up by sbr_rules_init() (no workspace: the state is a
 * few words); sbr_rules_update() takes each frame's confirmed classes with the frame's
 * time. No heap, no statics; bounded work (the meanings are looked up by class).
 */
#ifndef SBR_RULES_H
#define SBR_RULES_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest class count of a meanings table (the recogniser's ::SBR_RECOG_MAX_CLASSES). */
#define SBR_RULES_MAX_CLASSES 64u
/** Largest sbr_rules_config_t::hold_ms: a day. */
#define SBR_RULES_MAX_HOLD_MS 86400000u
/** Default sbr_rules_config_t::hold_ms: ten minutes. */
#define SBR_RULES_DEFAULT_HOLD_MS 600000u

/** What a class means for the restrictions (sbr_rules_meaning_t::kind). */
typedef enum sbr_rules_kind_e {
    SBR_RULES_NONE = 0,                     /**< nothing */
    SBR_RULES_SPEED = 1,                    /**< a speed limit of `value` km/h (1..255) */
    SBR_RULES_END_SPEED = 2,                /**< the end of the `value` km/h limit */
    SBR_RULES_END_ALL = 3,                  /**< the end of the limit and of both bans */
    SBR_RULES_NO_OVERTAKING = 4,            /**< no overtaking */
    SBR_RULES_END_NO_OVERTAKING = 5,        /**< its end */
    SBR_RULES_NO_OVERTAKING_TRUCKS = 6,     /**< no overtaking for trucks */
    SBR_RULES_END_NO_OVERTAKING_TRUCKS = 7, /**< its end */
    SBR_RULES_PRIORITY = 8,                 /**< priority road */
    SBR_RULES_END_PRIORITY = 9,             /**< give way or stop: no longer a priority road */
    SBR_RULES_KINDS = 10
} sbr_rules_kind_t;

/** A class's meaning. */
typedef struct sbr_rules_meaning_s {
    uint8_t kind;  /**< ::sbr_rules_kind_t */
    uint8_t value; /**< km/h for ::SBR_RULES_SPEED and ::SBR_RULES_END_SPEED, else 0 */
} sbr_rules_meaning_t;

/** Options. */
typedef struct sbr_rules_config_s {
    /** A restriction expires this long after it was last set or confirmed, 1 ..
        ::SBR_RULES_MAX_HOLD_MS. Default ::SBR_RULES_DEFAULT_HOLD_MS. */
    uint32_t hold_ms;
    /** Classes of the table, 1 .. ::SBR_RULES_MAX_CLASSES (GTSDB: 43). */
    uint32_t class_count;
    /** class_count meanings, by class id (borrowed; default sbr_rules_gtsdb()'s). */
    const sbr_rules_meaning_t *meanings;
} sbr_rules_config_t;

/** What the driver is shown. */
typedef struct sbr_rules_state_s {
    uint32_t speed_limit_kmh;      /**< the limit in force; 0: none known */
    uint32_t no_overtaking;        /**< 1: in force */
    uint32_t no_overtaking_trucks; /**< 1: in force */
    uint32_t priority_road;        /**< 1: in force */
    /** Milliseconds since the limit was last set or confirmed (0 without one). */
    uint32_t speed_age_ms;
} sbr_rules_state_t;

/** The restrictions' instance. Fields are private; use the functions. */
typedef struct sbr_rules_s {
    sbr_rules_config_t cfg;
    sbr_rules_state_t state;
    uint64_t now_us;         /* the last update's time */
    uint64_t since_us[4];    /* when each restriction was last set: limit, bans, priority */
    uint32_t started;        /* 1 after the first update */
    uint32_t magic;
    uint32_t check;          /* integrity word over everything before it */
} sbr_rules_t;

/**
 * @brief GTSDB's meanings (43 classes; the built-in models' class ids).
 * @param[out] out the table (a pointer to const data)
 * @param[out] count its class count
 * @return ::SBR_OK; ::SBR_ERR_NULL.
 */
sbr_status_t sbr_rules_gtsdb(const sbr_rules_meaning_t **out, uint32_t *count);

/**
 * @brief Defaults: hold ::SBR_RULES_DEFAULT_HOLD_MS, GTSDB's meanings. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_rules_config_default(sbr_rules_config_t *cfg);

/**
 * @brief Check a configuration: hold and class count in range, every meaning's kind
 *        known, speeds 1..255 km/h (an end of speed 0..255: 0 ends any limit), other
 *        kinds' values 0.
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL (cfg or its meanings); ::SBR_ERR_RANGE.
 */
sbr_status_t sbr_rules_config_check(const sbr_rules_config_t *cfg);

/**
 * @brief Set up an instance: no restriction in force, no time seen yet.
 * @param[out] rules the instance (left unusable on any status but ::SBR_OK)
 * @param[in]  cfg   the configuration (copied; its meanings borrowed)
 * @return ::SBR_OK; the statuses of sbr_rules_config_check(); ::SBR_ERR_NULL for rules.
 */
sbr_status_t sbr_rules_init(sbr_rules_t *rules, const sbr_rules_config_t *cfg);

/**
 * @brief One frame: expire what was not confirmed within hold_ms of `now_us`, then apply
 *        the frame's confirmed signs in order, and report the state.
 * @param[in,out] rules   an instance from sbr_rules_init()
 * @param[in]     now_us  the frame's time, microseconds, not before the previous call's
 * @param[in]     classes the classes of the signs confirmed in this frame (may be NULL
 *                        when `count` is 0)
 * @param[in]     count   how many
 * @param[out]    out     the state after the frame
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised, or changed since);
 *         ::SBR_ERR_RANGE for a time before the previous call's or a class outside the
 *         table. On an error nothing changes and `out` is not written.
 */
sbr_status_t sbr_rules_update(sbr_rules_t *rules, uint64_t now_us, const uint16_t *classes,
                              uint32_t count, sbr_rules_state_t *out);

/**
 * @brief Back to what sbr_rules_init() left (no restriction, no time seen), with the same
 *        configuration: e.g. after the ignition cycle.
 * @param[in,out] rules an instance from sbr_rules_init()
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE.
 */
sbr_status_t sbr_rules_reset(sbr_rules_t *rules);

#ifdef __cplusplus
}
#endif

#endif /* SBR_RULES_H */
