/* SPDX-License-Identifier: MIT */
/* Private to lib/picto: what the class stage's files share (features, classifier, rim
   check, gate, looks). Not installed. */
#ifndef SBR_PICTO_INTERNAL_H
#define SBR_PICTO_INTERNAL_H

#include "sbr/picto.h"

/* sbr_picto_refine() from the last layer's inputs `in` instead of the features: the
   rectified hidden units that sbr_picto_classify() leaves at the start of its workspace
   (or the features themselves when the model has no hidden layer), of the model's size.
   Returns ::SBR_ERR_CORRUPT for a bad model header, ::SBR_ERR_RANGE for a box outside
   sbr_picto_refine()'s domain or a regression that overflows. */
sbr_status_t sbr_picto_priv_refine_from(const sbr_picto_model_t *model, const float *in,
                                        const float box[4], float refined[4]);


/* The features' geometry (the model's and the feature vector's layout). */
#define PS SBR_PICTO_SIZE
#define CELLS SBR_PICTO_CELLS
#define CELL (PS / CELLS)
#define ORIENT 8u
#define THUMB SBR_PICTO_THUMB
#define THUMB_CELL (PS / THUMB)
#define CCELLS 4u
#define CCELL (PS / CCELLS)
#define F_HOG 0u
#define F_THUMB (CELLS * CELLS * ORIENT)
#define F_COLOUR (F_THUMB + (THUMB * THUMB))
#define F_CENTRE (F_COLOUR + (2u * CCELLS * CCELLS))
/* The middle half of the patch, [PS / 4, 3 PS / 4), in cells of CENTRE_CELL pixels. */
#define CENTRE_CELLS SBR_PICTO_CENTRE_CELLS
#define CENTRE_LO (PS / 4u)
#define CENTRE_CELL ((PS / 2u) / CENTRE_CELLS)

/* Pixel counts of a thumbnail cell and a colour cell. */
#define THUMB_AREA ((float)SBR_PICTO_SIZE * (float)SBR_PICTO_SIZE / \
                    ((float)SBR_PICTO_THUMB * (float)SBR_PICTO_THUMB))
#define CCELL_AREA ((float)SBR_PICTO_SIZE * (float)SBR_PICTO_SIZE / ((float)CCELLS * (float)CCELLS))

/* One over the square root of two: the diagonal axes. */
#define DIAG 0.70710678f

/* One bilinear tap along an axis: the two neighbouring sample coordinates and the weight
   of the second. */
typedef struct picto_tap_s {
    uint32_t lo;
    uint32_t hi;
    float f;
} picto_tap_t;

/* The taps of both axes live in the workspace's fourth patch-sized block. */
typedef char picto_tap_fits[((sizeof(picto_tap_t) * 2u * PS * 4u) <= (PS * PS * sizeof(float)))
                                ? 1 : -1];

/* Where a pixel's red, green and blue bytes are, and its size in bytes: RGB888, BGR888,
   or GRAY8 (one byte read as all three: a grey frame is an image with R = G = B). */
typedef struct picto_px_s {
    uint32_t ch[3];
    uint32_t bpp;
} picto_px_t;

int sbr_picto_priv_finite4(const float b[4]);

/* The float value of every byte, 0.0f .. 255.0f: the resamplers read a channel byte's
   value with one load instead of an integer-to-float conversion. */
extern const float sbr_picto_priv_u8f[256];

void sbr_picto_priv_colour_channels(const sbr_image_t *img, picto_px_t *px);

/* 1 for the formats the class stage's features read (RGB888, BGR888, GRAY8). */
int sbr_picto_priv_format_ok(const sbr_image_t *img);

/* The taps of `count` output pixels with n sub-samples each along one axis: sub-sample i
   of pixel u sits at start + step (u + (i + 0.5) / n) - 0.5 in pixel-centre coordinates,
   clamped to [0, size - 1]. */
void sbr_picto_priv_taps(float start, float step, uint32_t n, uint32_t size, uint32_t count,
                         picto_tap_t *t);

/* Normalise a vector segment to unit L2 norm (left alone when it is all zero). */
void sbr_picto_priv_unit_norm(float *f, uint32_t n);

/* out[r] = w[r] . [in; 1] for `rows` rows of `n_in` inputs and a bias (row stride
   n_in + 1). */
void sbr_picto_priv_affine(const float *w, const float *in, size_t n_in, uint32_t rows, float *out);

/* A box sbr_picto_refine() and sbr_picto_rim_contrast() take: finite, each |coordinate|
   <= SBR_PICTO_MAX_COORD, at least SBR_PICTO_MIN_BOX wide and high. */
int sbr_picto_priv_box_in_domain(const float box[4]);

/* What sbr_picto_rim_contrast() and sbr_picto_gate_features() check of their image and
   box: ::SBR_ERR_NULL, sbr_image_check()'s errors, ::SBR_ERR_RANGE for a box outside
   sbr_picto_priv_box_in_domain() or a grey image unless `grey` is 1. */
sbr_status_t sbr_picto_priv_colour_box_check(const sbr_image_t *img, const float box[4], int grey);

/* 1 when every look threshold of the model is within the looks' table's range
   (picto_looks.c). */
int sbr_picto_priv_looks_ok(const sbr_picto_model_t *model);

#endif /* SBR_PICTO_INTERNAL_H */
