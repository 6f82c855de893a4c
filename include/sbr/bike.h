/* SPDX-License-Identifier: MIT */
/**
 * @file bike.h
 * @brief Bicycle tracking from wheel ellipses (paper B): the projection of a bicycle's
 *        wheels, pairing of wheel ellipses in an image, and a bootstrap particle filter
 *        on a kinematic bicycle model with roll.
 *
 * Coordinates. The camera frame has X to the right, Y down and Z forward (the optical
 * axis, horizontal); the camera is `height` metres above a flat ground plane Y = height.
 * Image: u = focal X / Z + cx, v = focal Y / Z + cy (pixels, u = column).
 *
 * The bicycle (::sbr_bike_state_t) is described by its rear wheel's ground contact point
 * (x, z) on that plane, its heading on the ground (0 = travelling towards +X, i.e. to
 * the right across the image; pi/2 = travelling away from the camera; increasing =
 * turning left seen from above), its speed along the heading (>= 0: a bicycle does not
 * ride backwards, which is what resolves the front/rear ambiguity of a single image),
 * the steering angle of the front wheel relative to the frame (+ = left) and the roll of
 * the bicycle about its contact line (+ = leaning left). Each wheel is a circle of radius
 * `wheel_radius` (the tyre's mid-line) in the bicycle's leaning plane; the front wheel's
 * plane is turned by the steering angle. The contact points are `wheelbase` apart along
 * the heading.
 *
 * Motion (sbr_bike_predict_state()): the kinematic single-track model
 *   x' = v cos(psi), z' = v sin(psi), psi' = v tan(delta) / L,
 * integrated in sub-steps of at most 20 ms, and a roll that relaxes with time constant
 * `roll_tau` towards the balance lean of the turn, tan(phi_eq) = v psi' / g.
 *
 * Everything is float32; nothing allocates; the particle filter keeps its particles in a
 * caller-provided workspace and its random generator (xorshift32, seeded by the
 * configuration) in its instance, so a run is repeatable bit for bit on one platform.
 */
#ifndef SBR_BIKE_H
#define SBR_BIKE_H

#include "sbr/conic.h"
#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A pinhole camera with a horizontal optical axis above a flat ground. */
typedef struct sbr_camera_s {
    float focal;  /**< pixels, 1 .. 1e6 */
    float cx;     /**< principal point, column, |cx| < 1e6 */
    float cy;     /**< principal point, row, |cy| < 1e6 */
    float height; /**< metres above the ground, 1e-3 .. 1e3 */
} sbr_camera_t;

/** Bicycle geometry and roll dynamics. */
typedef struct sbr_bike_model_s {
    float wheel_radius; /**< metres, tyre mid-line, 1e-3 .. 10. Default 0.34 (28-inch
                             wheel). */
    float wheelbase;    /**< metres between the contact points, > 2 x wheel_radius and
                             < 100. Default 1.05. */
    float roll_tau;     /**< seconds, 1e-3 .. 1e3: how fast the roll follows the balance
                             lean. Default 0.3. */
} sbr_bike_model_t;

/** Bicycle state (see the file comment for the conventions). */
typedef struct sbr_bike_state_s {
    float x;       /**< rear contact point, metres, camera X, |x| < 1e4 */
    float z;       /**< rear contact point, metres, camera Z, |z| < 1e4 */
    float heading; /**< radians, (-pi, pi] (pi as the float nearest to it) */
    float speed;   /**< metres per second, 0 .. 100 */
    float steer;   /**< radians, |steer| < pi/2 */
    float roll;    /**< radians, |roll| < pi/2 */
} sbr_bike_state_t;

/**
 * @brief Default model as documented above. No-op for NULL.
 * @param[out] model the model
 */
void sbr_bike_model_default(sbr_bike_model_t *model);

/**
 * @brief Advance a state by dt_us microseconds with the deterministic model (no noise).
 * @param[in]  model the model.
 * @param[in]  state the state now.
 * @param[in]  dt_us microseconds, at most 10 s (sub-steps of at most 20 ms).
 * @param[out] out   the state dt_us later (may be `state`); written on ::SBR_OK only.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (bad model, dt, or a state value that
 *         is not finite or out of its range; also when the state dt_us later would leave
 *         the state's range, e.g. |x| reaching 1e4 m: ::SBR_OK always comes with a state
 *         that this function takes back as input).
 */
sbr_status_t sbr_bike_predict_state(const sbr_bike_model_t *model, const sbr_bike_state_t *state,
                                    uint32_t dt_us, sbr_bike_state_t *out);

/**
 * @brief The image ellipses of the two wheels (exact perspective images of the circles).
 * @param[in] camera the camera
 * @param[in] model the model
 * @param[in] state the state
 * @param[out] rear, front the ellipses; either may be NULL.
 * @return ::SBR_OK; ::SBR_ERR_NULL (camera, model or state); ::SBR_ERR_RANGE (bad
 *         camera, model or state); ::SBR_ERR_DEGENERATE when a wheel is not entirely in
 *         front of the camera (Z > 0.1 m), so that its image is no ellipse.
 */
sbr_status_t sbr_bike_project(const sbr_camera_t *camera, const sbr_bike_model_t *model,
                              const sbr_bike_state_t *state, sbr_ellipse_t *rear,
                              sbr_ellipse_t *front);

/** Largest number of ellipses sbr_bike_pair_wheels() and sbr_bike_pf_step() take. */
#define SBR_BIKE_MAX_ELLIPSES 32u

/** Two wheel candidates that may belong to one bicycle (unordered: which one is the front
    wheel is for the filter to decide). */
typedef struct sbr_wheel_pair_s {
    sbr_ellipse_t wheel[2]; /**< each the mean of the concentric ellipses of one tyre */
    uint32_t first;         /**< index of one of wheel[0]'s ellipses in the input */
    uint32_t second;        /**< index of one of wheel[1]'s ellipses in the input */
    float score;            /**< >= 0, lower is more bicycle-like */
} sbr_wheel_pair_t;

/**
 * @brief Pair wheel ellipses of one image.
 *
 * First, concentric ellipses (centres closer than 2 px + 0.2 x the larger semi-major,
 * semi-major axes within a factor 1.5) are grouped: a tyre's inner and outer edges give
 * two ellipses, the group's mean geometry is the tyre's mid-line. Then every two groups
 * form a pair when they could be the wheels of one bicycle seen from the side or
 * obliquely: semi-major axes within a factor 1.6, axis ratios (minor/major) within 0.35,
 * centre distance between 0.5 and 1.3 x (wheelbase / wheel_radius + 0.5) times the mean
 * semi-major axis, and a vertical offset of the centres at most 0.6 x the mean semi-major
 * axis plus 0.3 x their horizontal distance. The score sums the relative size mismatch,
 * the axis-ratio mismatch, the vertical offset and the deviation of the distance from
 * the side view's (all normalised as above); pairs are written best first.
 *
 * @param[in] ellipses the ellipses of one image (may be NULL when n = 0).
 * @param[in] n  0 .. ::SBR_BIKE_MAX_ELLIPSES.
 * @param[in] model the model
 * @param[out] pairs candidate pairs, best first.
 * @param[in] capacity entries of the result array
 * @param[out] count entries written
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (n too large); ::SBR_ERR_RANGE (bad
 *         model, an ellipse not finite, with axes <= 0 or semi_minor > semi_major, or with
 *         |cx|, |cy|, semi_major or |angle| >= 1e6); ::SBR_ERR_CAPACITY when more
 *         pairs qualified than `capacity` (the best `capacity` are written).
 */
sbr_status_t sbr_bike_pair_wheels(const sbr_ellipse_t *ellipses, uint32_t n,
                                  const sbr_bike_model_t *model, sbr_wheel_pair_t *pairs,
                                  uint32_t capacity, uint32_t *count);

/** Smallest and largest particle count. */
#define SBR_BIKE_PF_MIN_PARTICLES 16u
#define SBR_BIKE_PF_MAX_PARTICLES 65536u

/** One particle: a state and its log weight. */
typedef struct sbr_bike_particle_s {
    sbr_bike_state_t s;
    float logw;
} sbr_bike_particle_t;

/** Workspace bytes for `particles` particles: two generations (for resampling) and each
    particle's predicted wheels (12 floats, projected once per step). */
#define SBR_BIKE_PF_WORKSPACE_SIZE(particles) \
    ((size_t)(particles) * ((2u * sizeof(sbr_bike_particle_t)) + (12u * sizeof(float))))

/** Particle filter configuration. Start from sbr_bike_pf_config_default(). */
typedef struct sbr_bike_pf_config_s {
    sbr_camera_t camera;     /**< default: focal 1000, principal point (639.5, 359.5),
                                  height 1.2 m (a 1280 x 720 camera) */
    sbr_bike_model_t model;  /**< default sbr_bike_model_default() */
    uint32_t particles;      /**< fixed count, ::SBR_BIKE_PF_MIN_PARTICLES ..
                                  ::SBR_BIKE_PF_MAX_PARTICLES. More: better estimates, time
                                  and workspace grow linearly. Default 1000. */
    uint32_t seed;           /**< random generator seed, any value (0 is mapped to a fixed
                                  non-zero seed). Default 1. */
    /** Process noise, each as the standard deviation of a random walk after one second
        (it scales with sqrt(dt)). Defaults: speed 1.5 m/s, steering 0.3 rad,
        heading 0.05 rad, position 0.1 m, roll 0.05 rad. Larger: follows manoeuvres
        faster, noisier estimates. */
    float speed_noise;
    float steer_noise;
    float heading_noise;
    float position_noise;
    float roll_noise;
    /** Measurement noise of an ellipse's centre and semi-axes: meas_px + meas_rel x the
        semi-major axis (pixels). Defaults 0.5 px and 0.015 (a tyre's fitted edges are
        good to a few tenths of a pixel; smaller values make the cloud collapse faster than
        the motion resolves the heading). */
    float meas_px;
    float meas_rel;
    /** Gate: the largest normalised squared distance (sum over the six ellipse features
        of a wheel) between a measured wheel and the prediction of the most likely particle
        for the measurement to be used. Default 200. */
    float gate;
    /** Speed range of the initial particles, m/s, > 0. Default 12. */
    float max_speed;
    /** Resample when the effective sample size falls below this fraction of the particle
        count, in (0, 1]. Default 0.5. */
    float resample_fraction;
    /** Frames without a usable measurement after which the track is dropped (the next
        pair starts a new one), >= 1. Default 12. */
    uint32_t max_missed;
} sbr_bike_pf_config_t;

/** A particle filter instance. Fields are private; use the functions. */
typedef struct sbr_bike_pf_s {
    sbr_bike_pf_config_t cfg;
    sbr_bike_particle_t *cur;
    sbr_bike_particle_t *next;
    float *pred;
    uint32_t rng;
    uint32_t started;
    uint32_t missed;
    uint32_t age;
    uint32_t magic;
} sbr_bike_pf_t;

/** Result flags of sbr_bike_pf_step(). */
#define SBR_BIKE_TRACKING 1u  /**< a track exists and `mean` is its estimate */
#define SBR_BIKE_STARTED 2u   /**< the track was started in this step */
#define SBR_BIKE_UPDATED 4u   /**< a measurement was used in this step */
#define SBR_BIKE_RESAMPLED 8u /**< the particles were resampled in this step */
#define SBR_BIKE_LOST 16u     /**< the track was dropped in this step */

/** What one step produced. */
typedef struct sbr_bike_result_s {
    uint32_t flags;           /**< SBR_BIKE_* */
    sbr_bike_state_t mean;    /**< weighted mean of the particles of the dominant heading
                                   mode (headings within 90 degrees of the most likely
                                   particle's; a circular mean for the heading) */
    sbr_bike_state_t stddev;  /**< their weighted standard deviations */
    sbr_ellipse_t rear;       /**< the measured rear wheel used (valid if wheels & 1) */
    sbr_ellipse_t front;      /**< the measured front wheel used (valid if wheels & 2) */
    uint32_t wheels;          /**< bit 0: rear measured, bit 1: front measured */
    float ess;                /**< effective sample size after the update, in particles */
} sbr_bike_result_t;

/**
 * @brief Defaults as documented above. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_bike_pf_config_default(sbr_bike_pf_config_t *cfg);

/** @brief Check a configuration: ::SBR_OK, ::SBR_ERR_NULL, ::SBR_ERR_RANGE,
           ::SBR_ERR_SIZE (particle count out of range).
 * @param[in] cfg the configuration
 */
sbr_status_t sbr_bike_pf_config_check(const sbr_bike_pf_config_t *cfg);

/**
 * @brief Workspace bytes for a configuration; 0 if it is invalid.
 * @param[in] cfg the configuration
 */
size_t sbr_bike_pf_workspace_size(const sbr_bike_pf_config_t *cfg);

/**
 * @brief Set up a filter with no track.
 * @param[in,out] pf the filter to set up (its previous content is ignored).
 * @param[in] cfg the configuration
 * @param[in,out] workspace ::SBR_BIKE_PF_WORKSPACE_SIZE(cfg->particles) bytes, 4-byte aligned,
 *        owned by the filter until it is no longer used.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; errors of sbr_bike_pf_config_check();
 *         ::SBR_ERR_WORKSPACE (too small or misaligned).
 */
sbr_status_t sbr_bike_pf_init(sbr_bike_pf_t *pf, const sbr_bike_pf_config_t *cfg, void *workspace,
                              size_t workspace_size);

/**
 * @brief Drop the track and restart the random generator from the configured seed: the
 *        filter then behaves exactly as after sbr_bike_pf_init() with the same
 *        configuration and workspace.
 * @param[in,out] pf an initialised filter.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (not initialised or corrupted).
 */
sbr_status_t sbr_bike_pf_reset(sbr_bike_pf_t *pf);

/**
 * @brief One frame: predict by dt, associate, update, resample.
 *
 * Without a track, the best wheel pair of the ellipses (sbr_bike_pair_wheels()) starts
 * one: each wheel's distance follows from its semi-major axis (focal x radius / axis)
 * and its centre's ray; particles sample those distances with the measurement noise,
 * both front/rear assignments (half each), speeds uniform in [0, max_speed], small
 * steering and roll; then they are weighted by the pair.
 *
 * With a track, every particle is moved by the bicycle model with process noise.
 * Association: the wheel pairs of the ellipses and both front/rear assignments are
 * compared with the wheels predicted by the most likely particle; the closest within the
 * gate is used, otherwise the closest single ellipse within the gate (one wheel hidden),
 * otherwise none (the filter coasts). The weight of a particle is the Gaussian
 * likelihood of the used wheels' features (centre, semi-axes, and the elongation vector
 * (a - b)(cos 2 theta, sin 2 theta)), its own best front/rear assignment, each wheel's
 * squared distance capped at 200 so that no single outlier wipes out the cloud. A
 * particle whose wheels leave the front of the camera weighs nothing. After
 * `max_missed` frames without a measurement the track is dropped.
 *
 * Cost: both wheels of every particle are projected once per step, into the workspace;
 * association, weighting and resampling then pass over the particles. About 3.6 kB of
 * stack (Cortex-M4 build, -fstack-usage), most of it the candidate list for
 * ::SBR_BIKE_MAX_ELLIPSES ellipses.
 *
 * @param[in,out] pf the filter.
 * @param[in] dt_us microseconds since the previous step, at most 1 s (ignored when a track
 *        starts).
 * @param[in] ellipses the ellipses of this frame (may be NULL when n = 0).
 * @param[in] n        their number, at most ::SBR_BIKE_MAX_ELLIPSES.
 * @param[out] result  the frame's estimate and flags.
 * @return ::SBR_OK (also when no track exists: flags tell); ::SBR_ERR_NULL;
 *         ::SBR_ERR_STATE (pf not initialised or corrupted); ::SBR_ERR_RANGE (dt, or an
 *         ellipse refused as by sbr_bike_pair_wheels()); ::SBR_ERR_SIZE (n >
 *         ::SBR_BIKE_MAX_ELLIPSES).
 */
sbr_status_t sbr_bike_pf_step(sbr_bike_pf_t *pf, uint32_t dt_us, const sbr_ellipse_t *ellipses, uint32_t n,
                              sbr_bike_result_t *result);

#ifdef __cplusplus
}
#endif

#endif /* SBR_BIKE_H */
