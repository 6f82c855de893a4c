/* SPDX-License-Identifier: MIT */
/**
 * @file servo.h
 * @brief Visual servoing with a learned inverse image Jacobian (the thesis's paper F and
 *        chapter 4): local linear models over the joint space, learned online from the
 *        arm's own motions, and the servo step that uses them.
 *
 * Terms (thesis ch. 4.3): joint space y (the arm's m commands), task space x (n image
 * features of the gripper, e.g. its position u, v in pixels and its orientation in
 * radians). The image Jacobian maps joint changes to feature changes, dx = J_img dy; the
 * inverse image Jacobian J (m x n) maps a wanted feature change to a joint change,
 * dy = J dx. J need not be the inverse of J_img (a 5-joint arm seen as 3 features has no
 * inverse); learned from random motions with isotropic dy, J tends to the minimum-norm
 * inverse J_img^T (J_img J_img^T)^-1.
 *
 * **Learning** (sbr_servo_learn(), one pair (y, dy, dx): at command y, the change dy gave
 * the feature change dx). The model is a bounded set of receptive fields, in the spirit
 * of LWPR: field k has a centre c_k in joint space, activation
 * w_k(y) = exp(-1/2 sum_j ((y_j - c_kj) / width_j)^2), and a local linear model
 * dy = B_k dx (m x n) fitted by weighted recursive least squares (exponential forgetting
 * `forgetting`, the inverse covariance of its inputs P_k, n x n, started at
 * `prior` * I). Every field with w_k >= ::SBR_SERVO_MIN_ACTIVATION is updated with weight
 * w_k; then, when no field had w_k >= `new_field_activation`, a new field is placed at y
 * (its model started from the prediction there after those updates, or 0) and learns the
 * sample with weight 1, up to `max_fields`. Angles among
 * the features (`angle_mask`) have their differences wrapped to (-pi, pi].
 *
 * **Prediction** (sbr_servo_jacobian()): J(y) = sum_k w_k B_k / sum_k w_k over the fields
 * with w_k >= ::SBR_SERVO_MIN_ACTIVATION; where no field reaches y, the nearest field's
 * B_k (by the widths' distance), so a run that leaves the learned region keeps going and
 * its learned steps start fields there.
 *
 * **Servo step** (sbr_servo_step(), eq. 4.4): with the deviation d = x - x_w (current
 * minus wanted, angles wrapped), the new command is y_new = y - gain * J(y) d, i.e. the
 * step is the learned dy for the wanted change x_w - x. The step is then scaled down
 * as a whole so that no joint moves more than its `max_step` (the trust bound).
 * Joint limits: a joint the step would take beyond [`joint_min`, `joint_max`] is held at
 * that limit and the other joints' step re-solved for the rest of the wanted change, as
 * the minimum-norm step under the image Jacobian that J is a right inverse of
 * (A = (J^T J)^-1 J^T; rows scaled to unit length, damping 1e-4), itself scaled to the
 * trust bound; repeated while another joint reaches a limit, at most m times (a step
 * that no limit stops is exactly -gain J d, scaled). y_new is then clamped to the
 * limits. Stopping rule, checked before a step:
 * converged when |d_i| <= `tolerance`_i for every feature (no step); otherwise, when the
 * run has taken `max_iterations` steps, the iteration bound (no step). Learning the
 * executed steps during the run (sbr_servo_learn() with the step taken and the feature
 * change seen) keeps the model improving where the arm works.
 *
 * Memory: the fields live in a caller workspace (sbr_servo_workspace_size(),
 * ::SBR_SERVO_WORKSPACE_SIZE); the instance is a plain struct. No heap, no globals,
 * float32 only. Cost: learning O(F (m n + n^2)) and a step O(F m n) for F fields.
 */
#ifndef SBR_SERVO_H
#define SBR_SERVO_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most joints. */
#define SBR_SERVO_MAX_JOINTS 8u
/** Most image features. */
#define SBR_SERVO_MAX_FEATURES 4u
/** Most receptive fields. */
#define SBR_SERVO_MAX_FIELDS 1024u
/** Fields below this activation are neither updated nor used. */
#define SBR_SERVO_MIN_ACTIVATION 1.0e-3f

/** Floats of one field: centre (m), model B (m x n), inverse covariance P (n x n), and
    its weight sum. */
#define SBR_SERVO_FIELD_FLOATS(joints, features) \
    ((size_t)(joints) + ((size_t)(joints) * (size_t)(features)) + \
     ((size_t)(features) * (size_t)(features)) + 1u)
/** Workspace bytes for `fields` fields. */
#define SBR_SERVO_WORKSPACE_SIZE(fields, joints, features) \
    ((size_t)(fields) * SBR_SERVO_FIELD_FLOATS(joints, features) * sizeof(float))

/** Learner and servo configuration. Start from sbr_servo_config_default(). */
typedef struct sbr_servo_config_s {
    uint32_t joints;       /**< m, 1 .. ::SBR_SERVO_MAX_JOINTS */
    uint32_t features;     /**< n, 1 .. ::SBR_SERVO_MAX_FEATURES */
    uint32_t max_fields;   /**< receptive fields, 1 .. ::SBR_SERVO_MAX_FIELDS; sizes the
                                workspace. Default 128. */
    uint32_t angle_mask;   /**< bit i set: feature i is an angle in radians (differences
                                wrapped to (-pi, pi]). Default 0. */
    float width[SBR_SERVO_MAX_JOINTS]; /**< field width per joint, joint units, > 0 and
                                finite. Default 0.5. */
    float new_field_activation; /**< a sample no field reaches this activation for starts a
                                field, (::SBR_SERVO_MIN_ACTIVATION, 1). Default 0.3. */
    float forgetting;      /**< RLS forgetting factor, [0.9, 1]. Default 0.999. */
    float prior;           /**< a new field's P = prior * I (inverse input covariance:
                                large = little trust in the start), > 0, finite. Default
                                1e3. */
    float gain;            /**< servo step fraction, (0, 1]. Default 0.9. */
    float max_step[SBR_SERVO_MAX_JOINTS]; /**< trust bound per joint, joint units, > 0.
                                Default 0.2. */
    float joint_min[SBR_SERVO_MAX_JOINTS]; /**< command limits, finite, min < max. Default
                                -3.2 .. 3.2. */
    float joint_max[SBR_SERVO_MAX_JOINTS]; /**< see joint_min */
    float tolerance[SBR_SERVO_MAX_FEATURES]; /**< converged when every |d_i| <= this, >= 0.
                                Default 1 (e.g. pixels). */
    uint32_t max_iterations; /**< steps of one run, 1 .. 100000. Default 30. */
} sbr_servo_config_t;

/** A learner instance. Fields are private; use the functions. */
typedef struct sbr_servo_s {
    sbr_servo_config_t cfg;
    float *fields;     /* max_fields records of SBR_SERVO_FIELD_FLOATS floats */
    uint32_t count;    /* fields in use */
    uint32_t samples;  /* pairs learned */
    uint32_t magic;
} sbr_servo_t;

/** A servo run's state: the steps taken so far. Start with sbr_servo_run_start(). */
typedef struct sbr_servo_run_s {
    uint32_t iterations; /**< steps taken */
    uint32_t magic;      /**< private */
} sbr_servo_run_t;

/** What sbr_servo_step() decided. */
typedef enum sbr_servo_result_e {
    SBR_SERVO_STEP = 0,      /**< a step: y_new differs from y (unless clamped) */
    SBR_SERVO_CONVERGED = 1, /**< every feature within tolerance: y_new = y */
    SBR_SERVO_LIMIT = 2      /**< max_iterations steps taken without converging: y_new = y */
} sbr_servo_result_t;

/**
 * @brief Defaults as documented in ::sbr_servo_config_t for `joints` joints and
 *        `features` features (stored as given; sbr_servo_config_check() judges them).
 *        No-op for NULL.
 * @param[out] cfg the configuration
 * @param[in] joints m
 * @param[in] features n
 */
void sbr_servo_config_default(sbr_servo_config_t *cfg, uint32_t joints, uint32_t features);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (joints, features or max_fields out of
 *         range); ::SBR_ERR_RANGE (a value outside its documented range, NaN or infinite,
 *         an angle bit beyond the features).
 */
sbr_status_t sbr_servo_config_check(const sbr_servo_config_t *cfg);

/**
 * @brief Workspace bytes for a configuration; 0 if it is invalid.
 * @param[in] cfg the configuration
 */
size_t sbr_servo_workspace_size(const sbr_servo_config_t *cfg);

/**
 * @brief Set up a learner with no fields.
 * @param[out] servo the instance
 * @param[in] cfg the configuration (copied)
 * @param[in,out] workspace sbr_servo_workspace_size() bytes, 4-byte aligned, owned by
 *        the instance while it is used
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; configuration errors; ::SBR_ERR_WORKSPACE (too small
 *         or misaligned).
 */
sbr_status_t sbr_servo_init(sbr_servo_t *servo, const sbr_servo_config_t *cfg, void *workspace,
                            size_t workspace_size);

/**
 * @brief Learn one motion: at command `y`, the command change `dy` gave the feature
 *        change `dx`.
 * @param[in,out] servo an initialised instance
 * @param[in] y the command before the motion (m values)
 * @param[in] dy the command change (m values)
 * @param[in] dx the feature change seen (n values; angles need not be wrapped)
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted);
 *         ::SBR_ERR_RANGE (a value not finite, or |value| > 1e6) - nothing changes;
 *         ::SBR_ERR_CAPACITY when a new field was due but all `max_fields` are in use
 *         (the sample was learned by the fields that reach it, if any).
 */
sbr_status_t sbr_servo_learn(sbr_servo_t *servo, const float *y, const float *dy,
                             const float *dx);

/**
 * @brief The inverse image Jacobian at `y`.
 * @param[in] servo an initialised instance
 * @param[in] y the command (m values)
 * @param[out] jacobian m x n values, row-major (row j: joint j), written on ::SBR_OK
 * @param[out] activation (may be NULL) the summed activation of the fields used (below
 *        ::SBR_SERVO_MIN_ACTIVATION: the nearest field's, nothing learned near `y`)
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE; ::SBR_ERR_RANGE (y not finite);
 *         ::SBR_ERR_DEGENERATE when nothing has been learned (no field).
 */
sbr_status_t sbr_servo_jacobian(const sbr_servo_t *servo, const float *y, float *jacobian,
                                float *activation);

/**
 * @brief Start a servo run (0 steps).
 * @param[out] run the run state
 * @return ::SBR_OK; ::SBR_ERR_NULL.
 */
sbr_status_t sbr_servo_run_start(sbr_servo_run_t *run);

/**
 * @brief One servo step (eq. 4.4 with the trust bound and the stopping rule above).
 * @param[in] servo an initialised instance
 * @param[in,out] run the run's state (its step count grows by one when a step is taken)
 * @param[in] y the current command (m values)
 * @param[in] x the current features (n values)
 * @param[in] x_wanted the target features (n values)
 * @param[out] y_new the next command (m values; `y` itself on CONVERGED and LIMIT); may be
 *        the same array as `y`
 * @param[out] result what was decided
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (instance or run not initialised or
 *         corrupted); ::SBR_ERR_RANGE (a value not finite or |value| > 1e6, y outside
 *         the joint limits); ::SBR_ERR_DEGENERATE (nothing learned yet: no field).
 *         Outputs are written on ::SBR_OK only.
 */
sbr_status_t sbr_servo_step(const sbr_servo_t *servo, sbr_servo_run_t *run, const float *y,
                            const float *x, const float *x_wanted, float *y_new,
                            sbr_servo_result_t *result);

/**
 * @brief One servo step as sbr_servo_step(), with a given inverse image Jacobian instead
 *        of the learned one (a calibrated kinematic model's, another estimator's): the
 *        same stopping rule, trust bound and joint-limit handling, from `cfg`.
 * @param[in] cfg the configuration (joints, features, gain, max_step, limits, tolerance,
 *        max_iterations and angle_mask are used)
 * @param[in,out] run the run's state (its step count grows by one when a step is taken)
 * @param[in] jacobian the inverse image Jacobian at `y`, m x n values, row-major (row j:
 *        joint j)
 * @param[in] y the current command (m values)
 * @param[in] x the current features (n values)
 * @param[in] x_wanted the target features (n values)
 * @param[out] y_new the next command (m values); may be the same array as `y`
 * @param[out] result what was decided
 * @return ::SBR_OK; ::SBR_ERR_NULL; configuration errors (sbr_servo_config_check());
 *         ::SBR_ERR_STATE (run not started); ::SBR_ERR_RANGE (a value not finite or
 *         |value| > 1e6, y outside the joint limits). Outputs are written on ::SBR_OK only.
 */
sbr_status_t sbr_servo_step_with(const sbr_servo_config_t *cfg, sbr_servo_run_t *run,
                                 const float *jacobian, const float *y, const float *x,
                                 const float *x_wanted, float *y_new,
                                 sbr_servo_result_t *result);

/**
 * @brief Fields in use and pairs learned.
 * @param[in] servo an initialised instance
 * @param[out] fields fields in use (may be NULL)
 * @param[out] samples pairs learned (may be NULL)
 * @return ::SBR_OK; ::SBR_ERR_NULL (servo); ::SBR_ERR_STATE.
 */
sbr_status_t sbr_servo_stats(const sbr_servo_t *servo, uint32_t *fields, uint32_t *samples);

#ifdef __cplusplus
}
#endif

#endif /* SBR_SERVO_H */
