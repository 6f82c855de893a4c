/* SPDX-License-Identifier: MIT */
/**
 * @file picto.h
 * @brief The recogniser's class stage: what a candidate sign box contains, from the
 *        shape of its pictogram.
 *
 * The part model (recog.h) finds where signs are and their outline, but small
 * pictograms (a "3" against an "8" at 20 px) rarely give stable contours of their own. This
 * stage looks at the whole candidate box instead:
 *
 * 1. The box is resampled to ::SBR_PICTO_SIZE x ::SBR_PICTO_SIZE pixels (area-averaged
 *    bilinear samples, so a 90 px sign and a 16 px sign give comparable patches).
 * 2. Features (::SBR_PICTO_FEATURES values), all invariant to brightness and contrast:
 *    - edge orientation histograms: ::SBR_PICTO_CELLS x ::SBR_PICTO_CELLS cells (6 x 6
 *      of 6 px), 8 signed directions (the gradient of the contrast-normalised grey patch
 *      projected on 4 axes, positive and negative parts apart), L2-normalised over the
 *      patch: the shape of the pictogram's boundaries;
 *    - the contrast-normalised grey patch at ::SBR_PICTO_THUMB x ::SBR_PICTO_THUMB
 *      (12 x 12): the pictogram's mask;
 *    - red and blue chromaticity per cell of a 4 x 4 grid (4 x 4 x 2): the sign's colour
 *      layout;
 *    - finer edge orientation histograms of the middle half of the patch
 *      (::SBR_PICTO_CENTRE_CELLS per side, 6 x 6 cells of 3 px, 8 directions,
 *      L2-normalised on their own): the pictogram's detail (the digits of a speed limit
 *      are only a few pixels wide).
 * 3. A classifier learned by `sbr_train_picto` (a layer of rectified units, or none, then a
 *    softmax) gives the probability of each of the model's sign classes
 *    (sbr_picto_model_t::classes, e.g. GTSDB's 43) and of "no sign" (the last output).
 * 4. Optionally (sbr_picto_model_t::w3) a box regression from the same hidden units:
 *    where the sign's own box is relative to the candidate box (centre shift as fractions
 *    of the box's width and height, log of the width and height ratios). The recogniser
 *    moves a candidate box by it and classifies again (sbr_picto_refine()), so a box
 *    that the part model placed loosely is classified where the sign is.
 *
 * Bounded work: one box costs SBR_PICTO_SIZE^2 x (up to 16) samples plus the classifier's
 * multiply-adds ((features + 1) x hidden + (hidden + 1) x outputs). No heap, no statics.
 */
#ifndef SBR_PICTO_H
#define SBR_PICTO_H

#include "sbr/image.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Patch side in pixels. */
#define SBR_PICTO_SIZE 36u
/** Orientation-histogram cells per side. */
#define SBR_PICTO_CELLS 6u
/** Grey thumbnail side. */
#define SBR_PICTO_THUMB 12u
/** Cells per side of the middle half's finer orientation histograms. */
#define SBR_PICTO_CENTRE_CELLS 6u
/** Feature vector length: cells^2 x 8 orientations + thumb^2 grey + 4 x 4 x 2 colours +
    centre cells^2 x 8 orientations. */
#define SBR_PICTO_FEATURES \
    ((SBR_PICTO_CELLS * SBR_PICTO_CELLS * 8u) + (SBR_PICTO_THUMB * SBR_PICTO_THUMB) + 32u + \
     (SBR_PICTO_CENTRE_CELLS * SBR_PICTO_CENTRE_CELLS * 8u))
/** Largest number of sign classes of a classifier (sbr_picto_model_t::classes); a bound of
    the core, not of a dataset (GTSDB has 43). */
#define SBR_PICTO_MAX_CLASSES 64u
/** Largest number of classifier outputs: the sign classes and the background. */
#define SBR_PICTO_MAX_OUTPUTS (SBR_PICTO_MAX_CLASSES + 1u)
/** Largest hidden layer. */
#define SBR_PICTO_HIDDEN_MAX 256u
/** Classifier format version (the class count is the model's; 4: the looks' thresholds,
    sbr_picto_looks_t, are the model's). */
#define SBR_PICTO_VERSION 4u
/** Box-regression outputs: centre shift in x and y (fractions of the box's width and
    height), natural log of the width and height ratios. */
#define SBR_PICTO_BOX_OUTPUTS 4u
/** Largest centre shift one refinement applies, as a fraction of the box size. */
#define SBR_PICTO_MAX_SHIFT 0.5f
/** Largest |log scale| one refinement applies (about a factor 2 either way). */
#define SBR_PICTO_MAX_LOG_SCALE 0.7f
/** Smallest width and height (pixels) of a box given to sbr_picto_features() and
    sbr_picto_refine(). */
#define SBR_PICTO_MIN_BOX 2.0f
/** Sample grid side of the gate's features (sbr_picto_gate_features()). */
#define SBR_PICTO_GATE_GRID 12u
/** Gate features: the contrast-normalised grey grid (12 x 12), red and blue chromaticity
    per cell of a 4 x 4 grid (32) and signed edge orientations (8) per cell of a 3 x 3
    grid, L2-normalised (72). */
#define SBR_PICTO_GATE_FEATURES \
    ((SBR_PICTO_GATE_GRID * SBR_PICTO_GATE_GRID) + 32u + 72u)
/** Largest hidden layer of the gate. */
#define SBR_PICTO_GATE_HIDDEN_MAX 32u
/** Gate weights for `hidden` rectified units (0: a linear gate). */
#define SBR_PICTO_GATE_WEIGHTS(hidden) \
    (((hidden) == 0u) ? (SBR_PICTO_GATE_FEATURES + 1u) \
                      : (((hidden) * (SBR_PICTO_GATE_FEATURES + 1u)) + (hidden) + 1u))
/** Workspace bytes of sbr_picto_gate_features() (the grey grid and the sample taps; four
    grids of floats). */
#define SBR_PICTO_GATE_WORKSPACE_SIZE \
    ((size_t)4u * SBR_PICTO_GATE_GRID * SBR_PICTO_GATE_GRID * sizeof(float))
/** Sample grid side of sbr_picto_rim_contrast() (its work per box is this squared). */
#define SBR_PICTO_RIM_GRID 32u
/** The outline of a sign class whose rim is checked for colour (sbr_picto_rim_contrast()). */
typedef enum sbr_picto_rim_e {
    SBR_PICTO_RIM_NONE = 0,          /**< no colour check for this class */
    SBR_PICTO_RIM_DISC = 1,          /**< a disc inscribed in the box */
    SBR_PICTO_RIM_TRIANGLE = 2,      /**< apex up, base along the box's bottom side */
    SBR_PICTO_RIM_TRIANGLE_DOWN = 3  /**< apex down, base along the box's top side (yield) */
} sbr_picto_rim_t;

/** Largest |coordinate| (pixels) of a box given to sbr_picto_refine(): four times the
    largest image side, so every box of an image (and one that reaches outside it) is in,
    and the refined box stays finite. */
#define SBR_PICTO_MAX_COORD (4.0f * (float)SBR_IMAGE_MAX_DIM)
/** Workspace bytes of sbr_picto_features() and sbr_picto_classify(). */
#define SBR_PICTO_WORKSPACE_SIZE \
    ((size_t)SBR_PICTO_SIZE * SBR_PICTO_SIZE * 4u * sizeof(float) + \
     (size_t)SBR_PICTO_SIZE * 24u * sizeof(float) + \
     (size_t)SBR_PICTO_HIDDEN_MAX * sizeof(float))

/** How the recogniser looks at a candidate with this classifier: thresholds on its
    probabilities, so they belong to the trained model (sbr_train_picto writes them; the
    table sbr_picto_look_field_at() gives each one's range, default and meaning). */
typedef struct sbr_picto_looks_s {
    float refine_first_score;      /**< sign probability to start refining (colour) */
    float grey_refine_first_score; /**< the same on a GRAY8 frame */
    float refine_score;            /**< sign probability to go on refining */
    float view_score;              /**< sign probability for the extra views */
    float triangle_score;          /**< danger probability for the triangle view */
} sbr_picto_looks_t;

/**
 * A learned classifier. Inputs are standardised features ((f - mean) / scale is folded
 * into the first layer by the trainer, so raw features go in).
 * With K = classes, the outputs are the K sign classes (ids 0..K-1) and the background
 * (output K).
 * hidden = 0: logits = w2 * [f; 1] with w2 of K + 1 rows x (features + 1).
 * hidden > 0: a = max(0, w1 * [f; 1]) with w1 of hidden rows x (features + 1), then
 *             logits = w2 * [a; 1] with w2 of K + 1 rows x (hidden + 1).
 * Box regression (optional): d = w3 * [a; 1] (or w3 * [f; 1] when hidden = 0) with w3 of
 * SBR_PICTO_BOX_OUTPUTS rows: dx, dy, log(w' / w), log(h' / h).
 * Rows are contiguous, the bias last.
 */
typedef struct sbr_picto_model_s {
    uint32_t version;  /**< ::SBR_PICTO_VERSION */
    uint32_t features; /**< ::SBR_PICTO_FEATURES */
    uint32_t hidden;   /**< hidden units, 0 .. ::SBR_PICTO_HIDDEN_MAX */
    uint32_t classes;  /**< sign classes K, 1 .. ::SBR_PICTO_MAX_CLASSES (outputs: K + 1) */
    float threshold;   /**< operating point for the reported probability, (0, 1) */
    sbr_picto_looks_t looks; /**< the recogniser's looks with it (each in [0, 1]) */
    const float *w1;   /**< hidden x (features + 1), NULL when hidden = 0 */
    const float *w2;   /**< (classes + 1) x (hidden or features, + 1) */
    const float *w3;   /**< SBR_PICTO_BOX_OUTPUTS x (hidden or features, + 1), or NULL (no
                            box regression: sbr_picto_refine() keeps the box) */
    /** Colour check (optional; both NULL: none): per sign class (`classes`
        entries) the outline of its red rim (::sbr_picto_rim_t) and the floor of its rim
        contrast (sbr_picto_rim_contrast(), in [-2, 2]), learned from the class's training
        signs. The recogniser drops a candidate of a class with an outline whose contrast
        lies below the floor: a sign without the red rim its class always has (e.g. grey
        triangles of a pylon as "yield"). */
    const uint8_t *rim_shape;
    const float *rim_floor;
    /** Gate (optional; NULL: none): the class stage's cheap first look, a score of the
        gate features g (sbr_picto_gate_features()): with gate_hidden = 0 the linear
        gate . [g; 1] (::SBR_PICTO_GATE_FEATURES + 1 weights, the bias last); with
        gate_hidden = H > 0, a = max(0, W1 [g; 1]) with W1 the first H (features + 1)
        weights (rows contiguous, bias last), then score = w2 . [a; 1] with the last H + 1
        (::SBR_PICTO_GATE_WEIGHTS(H) in all). The recogniser classifies a candidate with
        the full classifier only when its score reaches gate_threshold; the trainer sets
        the threshold so that nearly all training candidates that cover a sign, or that
        the classifier finds sign-like, pass (sbr_train_picto --gate). */
    const float *gate;
    uint32_t gate_hidden; /**< 0 .. ::SBR_PICTO_GATE_HIDDEN_MAX */
    float gate_threshold; /**< finite; ignored without a gate */
} sbr_picto_model_t;

/**
 * @brief Check a classifier's header (version, sizes, threshold in (0, 1), the looks'
 *        thresholds in their table's ranges), that every
 *        weight is finite, its colour check tables (both or neither; outlines in
 *        range, floors finite in [-2, 2]) and its gate (finite weights and threshold).
 * @param[in] model the model
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_CORRUPT (version, sizes, a NULL table, a
 *         non-finite weight, one colour table without the other or a value out of range).
 */
sbr_status_t sbr_picto_check(const sbr_picto_model_t *model);

/**
 * @brief Fields in the table of sbr_picto_looks_t (offsets into sbr_picto_model_t).
 * @return the count.
 */
uint32_t sbr_picto_look_field_count(void);

/**
 * @brief One field of the looks' table: its name, range, default (the values the
 *        trainer writes) and meaning.
 * @param[in]  index 0 .. sbr_picto_look_field_count() - 1
 * @param[out] out   the field (name and help point into const tables)
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE beyond the table.
 */
sbr_status_t sbr_picto_look_field_at(uint32_t index, sbr_field_t *out);

/**
 * @brief The looks' defaults, as the trainer writes them (and as a model file of format 3,
 *        which had none, is read). No-op for NULL.
 * @param[out] looks the looks
 */
void sbr_picto_looks_default(sbr_picto_looks_t *looks);

/**
 * @brief Features of the box [x0, x1) x [y0, y1) of an image (pixel units, pixel (i, j)
 *        covers [i, i + 1) x [j, j + 1)). The box may reach outside the image by up to its
 *        own size (samples there repeat the border).
 * @param[in]  img        RGB888, BGR888 or GRAY8 view (a grey view gives the features of
 *                        an image with R = G = B: neutral chromaticities).
 * @param[in]  box        x0, y0, x1, y1; finite, at least ::SBR_PICTO_MIN_BOX wide and high.
 * @param[out] feat       ::SBR_PICTO_FEATURES values.
 * @param[in]  len        length of feat, >= ::SBR_PICTO_FEATURES.
 * @param[in,out] workspace  ::SBR_PICTO_WORKSPACE_SIZE bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (len); ::SBR_ERR_RANGE (box not
 *         finite, too small, or too far outside); errors of
 *         sbr_image_check(); ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_picto_features(const sbr_image_t *img, const float box[4], float *feat,
                                uint32_t len, void *workspace, size_t workspace_size);

/** What of a box sbr_picto_features_outline() looks at. */
typedef enum sbr_picto_outline_e {
    /** The whole box (sbr_picto_features()). */
    SBR_PICTO_OUTLINE_BOX = 0,
    /** An upward triangle inscribed in the box (apex at the middle of the top side, base
        along the bottom side), grown by one patch pixel: the outline of a danger sign.
        Patch pixels outside it are replaced by a plain grey of half the inside's mean
        grey, so clutter in the box's top corners (branches, a bright sky behind a
        backlit sign) does not enter the features. */
    SBR_PICTO_OUTLINE_TRIANGLE = 1
} sbr_picto_outline_t;

/**
 * @brief sbr_picto_features() of what lies inside an outline in the box.
 * @param[in] img the frame
 * @param[in] box x0, y0, x1, y1 in pixels (at least ::SBR_PICTO_MIN_BOX wide and high).
 * @param[in]  outline  ::sbr_picto_outline_t.
 * @param[out] feat ::SBR_PICTO_FEATURES values.
 * @param[in] len length of `feat`, >= ::SBR_PICTO_FEATURES
 * @param[in,out] workspace ::SBR_PICTO_WORKSPACE_SIZE bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @return as sbr_picto_features(); ::SBR_ERR_RANGE also for an outline out of range.
 */
sbr_status_t sbr_picto_features_outline(const sbr_image_t *img, const float box[4],
                                        uint32_t outline, float *feat, uint32_t len,
                                        void *workspace, size_t workspace_size);

/**
 * @brief How much redder a sign's rim is than its inside: the mean redness
 *        (R - max(G, B)) / (R + G + B + 3) of the rim (inside the outline, outside the
 *        outline shrunk to 0.6 of its size about its centroid; 0.75 for a disc) minus the
 *        mean redness of the middle (inside the outline shrunk to 0.45; 0.6 for a disc).
 *        A red-rimmed sign with a white or pale inside gives about 0.1 to 0.2, grey
 *        clutter about 0. Bounded work: the box is sampled on a grid of
 *        ::SBR_PICTO_RIM_GRID x ::SBR_PICTO_RIM_GRID points (nearest pixel; points outside
 *        the image repeat its border).
 * @param[in]  img       RGB888 or BGR888 view.
 * @param[in]  box       x0, y0, x1, y1 (pixel units as sbr_picto_features()); finite, at
 *                       least ::SBR_PICTO_MIN_BOX wide and high, each |coordinate| <=
 *                       ::SBR_PICTO_MAX_COORD.
 * @param[in]  shape     ::SBR_PICTO_RIM_DISC, ::SBR_PICTO_RIM_TRIANGLE or
 *                       ::SBR_PICTO_RIM_TRIANGLE_DOWN.
 * @param[out] contrast  in [-2, 2]; written on ::SBR_OK only.
 * @return ::SBR_OK; ::SBR_ERR_NULL; errors of sbr_image_check(); ::SBR_ERR_RANGE (a grey
 *         image, a shape out of range, a box not finite, too small or too far out).
 */
sbr_status_t sbr_picto_rim_contrast(const sbr_image_t *img, const float box[4], uint32_t shape,
                                    float *contrast);

/**
 * @brief The gate's features of a box (sbr_picto_model_t::gate): the box is sampled on a
 *        ::SBR_PICTO_GATE_GRID x ::SBR_PICTO_GATE_GRID grid, each cell the mean of 2 x 2
 *        bilinear samples (points outside the image repeat its border), about a tenth of
 *        the work of sbr_picto_features(). Features as ::SBR_PICTO_GATE_FEATURES says, all
 *        invariant to brightness and contrast except the chromaticities.
 * @param[in]  img       RGB888, BGR888 or GRAY8 view (grey: as an image with R = G = B).
 * @param[in]  box       x0, y0, x1, y1 as for sbr_picto_features(); finite, at least
 *                       ::SBR_PICTO_MIN_BOX wide and high, each |coordinate| <=
 *                       ::SBR_PICTO_MAX_COORD.
 * @param[out] feat      ::SBR_PICTO_GATE_FEATURES values (len at least that), written on
 *                       ::SBR_OK only.
 * @param[in] len length of `feat`, >= ::SBR_PICTO_GATE_FEATURES
 * @param[in,out] workspace ::SBR_PICTO_GATE_WORKSPACE_SIZE bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; errors of sbr_image_check(); ::SBR_ERR_RANGE (a box
 *         not finite, too small or too far out); ::SBR_ERR_SIZE (len);
 *         ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_picto_gate_features(const sbr_image_t *img, const float box[4], float *feat,
                                     uint32_t len, void *workspace, size_t workspace_size);

/**
 * @brief The gate's score of gate features (sbr_picto_model_t::gate).
 * @param[in]  model  checked with sbr_picto_check() first; with a gate.
 * @param[in]  feat   ::SBR_PICTO_GATE_FEATURES finite values (len at least that).
 * @param[in] len length of `feat`, >= ::SBR_PICTO_GATE_FEATURES
 * @param[out] score  written on ::SBR_OK only; the candidate passes when
 *                    score >= model->gate_threshold.
 * @return ::SBR_OK; ::SBR_ERR_NULL (also a model without a gate); ::SBR_ERR_SIZE (len);
 *         ::SBR_ERR_CORRUPT (gate_hidden above ::SBR_PICTO_GATE_HIDDEN_MAX);
 *         ::SBR_ERR_RANGE (a non-finite feature, or a score that overflows float32).
 */
sbr_status_t sbr_picto_gate(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                            float *score);

/**
 * @brief Class probabilities of a feature vector.
 * @param[in]  model  checked with sbr_picto_check() first (not repeated here per call:
 *                    sbr_recog_init() checks the recogniser's once).
 * @param[in]  feat   ::SBR_PICTO_FEATURES finite values.
 * @param[in] len length of `feat`, >= ::SBR_PICTO_FEATURES
 * @param[out] prob   model->classes + 1 probabilities summing to 1: the sign classes,
 *                    then the background.
 * @param[in] nprob length of `prob`, >= model->classes + 1 (::SBR_PICTO_MAX_OUTPUTS
 *                  always suffices).
 * @param[in,out] workspace ::SBR_PICTO_WORKSPACE_SIZE bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (len or nprob too small);
 *         ::SBR_ERR_CORRUPT (model header); ::SBR_ERR_RANGE (a non-finite feature, or
 *         features so large that the logits overflow float32; sbr_picto_features()
 *         never gives such); ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_picto_classify(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                                float *prob, uint32_t nprob, void *workspace,
                                size_t workspace_size);

/**
 * @brief The sign's box predicted from a candidate box's features (the model's box
 *        regression). Per call the centre moves by at most ::SBR_PICTO_MAX_SHIFT of the
 *        box size and each side scales by at most exp(::SBR_PICTO_MAX_LOG_SCALE); the
 *        caller can repeat it on the new box's features. Without a regression
 *        (w3 = NULL) the box is returned unchanged.
 * @param[in]  model  checked with sbr_picto_check() first.
 * @param[in]  feat   ::SBR_PICTO_FEATURES finite values, of `box`.
 * @param[in] len length of `feat`, >= ::SBR_PICTO_FEATURES
 * @param[in]  box    x0, y0, x1, y1 the features came from; finite, at least
 *                    ::SBR_PICTO_MIN_BOX wide and high, each |coordinate| <=
 *                    ::SBR_PICTO_MAX_COORD.
 * @param[out] refined x0, y0, x1, y1 (may be the same array as box); finite and not
 *                    empty, written on ::SBR_OK only.
 * @param[in,out] workspace ::SBR_PICTO_WORKSPACE_SIZE bytes, 4-byte aligned.
 * @param[in] workspace_size bytes available at `workspace`
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (len); ::SBR_ERR_CORRUPT (model
 *         header); ::SBR_ERR_RANGE (a non-finite feature, or features whose regression
 *         overflows float32; a box not finite, smaller than
 *         ::SBR_PICTO_MIN_BOX or beyond ::SBR_PICTO_MAX_COORD); ::SBR_ERR_WORKSPACE.
 */
sbr_status_t sbr_picto_refine(const sbr_picto_model_t *model, const float *feat, uint32_t len,
                              const float box[4], float refined[4], void *workspace,
                              size_t workspace_size);

/** @name Looks at boxes: features and classifier together, with private buffers
    The class stage as a caller runs it on candidate boxes (the recogniser does): a look
    computes a box's features and its class probabilities in a workspace that keeps the
    box and its features, so that the box regression (sbr_picto_look_refine()) reuses
    them. The workspace's layout is the classifier's own; a caller only sizes it.
    The results equal sbr_picto_features() or sbr_picto_features_outline() followed by
    sbr_picto_classify(), sbr_picto_refine() and sbr_picto_gate() bit for bit.
    @{ */

/** Bytes at the head of a look's workspace: the last look's box and whether it holds. */
#define SBR_PICTO_LOOK_HEAD_BYTES 32u
/** Workspace bytes of sbr_picto_look(), sbr_picto_look_refine() and sbr_picto_look_gate():
    the head, one feature vector and the classifier's scratch (::SBR_PICTO_WORKSPACE_SIZE). */
#define SBR_PICTO_LOOK_WORKSPACE_SIZE \
    ((size_t)SBR_PICTO_LOOK_HEAD_BYTES + (SBR_PICTO_FEATURES * sizeof(float)) + \
     SBR_PICTO_WORKSPACE_SIZE)

/**
 * @brief Look at a box: its features (the whole box, or the inside of an outline) and its
 *        class probabilities; the box and its features stay in the workspace for
 *        sbr_picto_look_refine().
 * @param[in]  model     checked with sbr_picto_check() first (only its header is checked
 *                       here).
 * @param[in]  img       as sbr_picto_features().
 * @param[in]  box       x0, y0, x1, y1, as sbr_picto_features().
 * @param[in]  outline   ::sbr_picto_outline_t.
 * @param[out] prob      model->classes + 1 probabilities (the sign classes, then the
 *                       background), written on ::SBR_OK only.
 * @param[in]  nprob     length of `prob`, >= model->classes + 1.
 * @param[in,out] workspace ::SBR_PICTO_LOOK_WORKSPACE_SIZE bytes, 8-byte aligned.
 * @param[in]  workspace_size bytes available at `workspace`.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (nprob); ::SBR_ERR_CORRUPT (model
 *         header); ::SBR_ERR_RANGE (box, outline, or features whose logits overflow);
 *         errors of sbr_image_check(); ::SBR_ERR_WORKSPACE. After any status other than
 *         ::SBR_OK the workspace holds no look.
 */
sbr_status_t sbr_picto_look(const sbr_picto_model_t *model, const sbr_image_t *img,
                            const float box[4], uint32_t outline, float *prob, uint32_t nprob,
                            void *workspace, size_t workspace_size);

/**
 * @brief sbr_picto_refine() of the last successful sbr_picto_look() in the workspace (its
 *        box and features).
 * @param[in]  model     the model of that look.
 * @param[out] refined   x0, y0, x1, y1, written on ::SBR_OK only.
 * @param[in,out] workspace the look's workspace.
 * @param[in]  workspace_size bytes available at `workspace`.
 * @return as sbr_picto_refine(); ::SBR_ERR_STATE when the workspace holds no look, or one
 *         of a model with another hidden layer size. The regression reuses the hidden
 *         units the look's classifier computed instead of computing them again.
 */
sbr_status_t sbr_picto_look_refine(const sbr_picto_model_t *model, float refined[4],
                                   void *workspace, size_t workspace_size);

/**
 * @brief The gate's score of a box (sbr_picto_gate_features() then sbr_picto_gate()). Uses
 *        the look's workspace, which holds no look afterwards.
 * @param[in]  model     checked with sbr_picto_check() first; with a gate.
 * @param[in]  img       as sbr_picto_gate_features().
 * @param[in]  box       x0, y0, x1, y1, as sbr_picto_gate_features().
 * @param[out] score     written on ::SBR_OK only.
 * @param[in,out] workspace ::SBR_PICTO_LOOK_WORKSPACE_SIZE bytes, 8-byte aligned.
 * @param[in]  workspace_size bytes available at `workspace`.
 * @return as sbr_picto_gate_features() and sbr_picto_gate().
 */
sbr_status_t sbr_picto_look_gate(const sbr_picto_model_t *model, const sbr_image_t *img,
                                 const float box[4], float *score, void *workspace,
                                 size_t workspace_size);
/** @} */

#ifdef __cplusplus
}
#endif

#endif /* SBR_PICTO_H */
