/* SPDX-License-Identifier: MIT */
/* Private to lib/bike: what the particle filter (bike_filter.c) shares with the geometry
   (bicycle.c). Not installed. */
#ifndef SBR_BIKE_INTERNAL_H
#define SBR_BIKE_INTERNAL_H

#include "sbr/bike.h"

#define BIKE_G 9.81f
#define BIKE_SUBSTEP 0.02f
#define BIKE_MAX_DT_STATE_US 10000000u
#define BIKE_MAX_DT_STEP_US 1000000u
#define BIKE_MIN_Z 0.1f
#define BIKE_MAX_STEER 0.7f
#define BIKE_MAX_ROLL 0.7f
#define BIKE_MAX_SPEED 30.0f
#define BIKE_LL_CAP 200.0f
#define BIKE_DEAD_LOGW (-1.0e6f)
#define BIKE_MAGIC 0x42494b45u
#define BIKE_PAIR_CAP 8u
#define BIKE_NFEAT 6u
#define BIKE_WARMUP 4u

/* A group of wheel ellipses that are one wheel (sums; group_ellipse() gives the mean). */
typedef struct {
    float cx;
    float cy;
    float a;
    float b;
    float ex; /* elongation vector (a - b)(cos 2t, sin 2t) */
    float ey;
    uint32_t n;
    uint32_t first; /* index of its first ellipse */
} wheel_group_t;

/* The checks of the public entry points: a model, a camera, n ellipses within range. */
int sbr_bike_priv_model_ok(const sbr_bike_model_t *m);
int sbr_bike_priv_camera_ok(const sbr_camera_t *c);
int sbr_bike_priv_ellipses_ok(const sbr_ellipse_t *e, uint32_t n);

/* a in (-pi, pi], whatever the number of turns. */
float sbr_bike_priv_wrap_angle(float a);

/* The state advanced by dt seconds in sub-steps of BIKE_SUBSTEP. */
void sbr_bike_priv_advance(const sbr_bike_model_t *m, sbr_bike_state_t *s, float dt);

/* Both wheels of a checked state; 0 when either is not an ellipse in front of the camera. */
int sbr_bike_priv_project_both(const sbr_camera_t *cam, const sbr_bike_model_t *m, const sbr_bike_state_t *s,
                               sbr_ellipse_t *rear, sbr_ellipse_t *front);

/* The mean ellipse of a group; the groups of n ellipses (returns how many); the pairs of
   groups, best first, at most cap (returns how many qualified in all). */
sbr_ellipse_t sbr_bike_priv_group_ellipse(const wheel_group_t *g);
uint32_t sbr_bike_priv_group_ellipses(const sbr_ellipse_t *el, uint32_t n, wheel_group_t *g);
uint32_t sbr_bike_priv_pair_groups(const wheel_group_t *g, uint32_t ng, const sbr_bike_model_t *m,
                                   sbr_wheel_pair_t *pairs, uint32_t cap);

#endif /* SBR_BIKE_INTERNAL_H */
