/* SPDX-License-Identifier: MIT */
/* Private to lib/track: what the tracker's set-up (track_model.c), densities
   (track_density.c) and step (tracker.c) share. Not installed. */
#ifndef SBR_TRACK_INTERNAL_H
#define SBR_TRACK_INTERNAL_H

#include "sbr/track.h"

#define TRK_MAGIC 0x5452434Bu
/* cos² kernel of support W has standard deviation 0.1808 W: W = sigma / 0.1808. */
#define TRK_KERNEL_PER_SIGMA 5.53f
#define TRK_ALIVE 0x100u
#define TRK_TINY 1e-30f
#define TRK_ROW_TOL 1e-3f

/* The geometry of a step's density grids. */
typedef struct trk_geo_s {
    uint32_t w;   /* window */
    uint32_t v;   /* velocity channels */
    float s;      /* spacing */
    float c0;     /* velocity centre channel */
    float half;   /* window centre channel */
    float kw;     /* detection kernel support */
} trk_geo_t;

/* cos^2 kernel B(d) with support w (|d| < w / 2). */
float sbr_track_priv_kernel(float d, float w);
/* The active region channels (at most 3) of position `pos` on axis `axis`, weights
   normalised to sum 1; returns how many. */
uint32_t sbr_track_priv_region_weights(const sbr_track_model_t *m, uint32_t axis, float pos,
                                       uint32_t *idx, float *w);
/* The model's transition table of an axis (birth: the birth table). */
const float *sbr_track_priv_table(const sbr_track_model_t *m, uint32_t axis, int birth);
/* A model's sizes and scalars (sbr_track_model_check() without the tables). */
sbr_status_t sbr_track_priv_model_header(const sbr_track_model_t *model);
/* A configuration's scalar fields. */
sbr_status_t sbr_track_priv_config_scalars(const sbr_track_config_t *cfg);
/* Target t's density of an axis in the workspace. */
float *sbr_track_priv_dens(const sbr_track_t *trk, const trk_geo_t *g, uint32_t t, uint32_t axis);
/* The position marginal of a density; returns its mass. */
float sbr_track_priv_marginal(const float *d, const trk_geo_t *g, float *m);
/* Mean and variance of a marginal. */
void sbr_track_priv_moments(const float *m, const trk_geo_t *g, float origin, float *mean,
                            float *var);
/* One axis of a target predicted through the motion model. */
void sbr_track_priv_predict_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis,
                                 float *d, float *origin, float ratio);
/* One axis of a target updated with a measurement z of weight w. */
void sbr_track_priv_update_axis(const trk_geo_t *g, float *d, float origin, float z, float w,
                                float *vel_marg);
/* One axis of a new target at z. */
void sbr_track_priv_birth_axis(const sbr_track_t *trk, const trk_geo_t *g, uint32_t axis, float *d,
                               float *origin, float z);
/* Position, velocity and certainty of one axis decoded from its density. */
void sbr_track_priv_decode_axis(const trk_geo_t *g, const float *d, float origin, float *pos,
                                float *vel, float *cert);

#endif /* SBR_TRACK_INTERNAL_H */
