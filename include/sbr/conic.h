/* SPDX-License-Identifier: MIT */
/**
 * @file conic.h
 * @brief Conics (thesis ch. 2.2-2.3, papers A and B): direct least-squares ellipse fit,
 *        conic classification, ellipse parameters, fit residual and coverage, torchlight
 *        pose, and ellipse detection from the region/contour stage.
 *
 * A conic is a x^2 + 2b xy + c y^2 + 2d x + 2e y + f = 0, i.e. the symmetric matrix
 * C = [[a, b, d], [b, c, e], [d, e, f]] (up to scale), in image coordinates (x = column,
 * y = row) unless a function says otherwise.
 *
 * Everything is float32; no function allocates, none keeps state.
 */
#ifndef SBR_CONIC_H
#define SBR_CONIC_H

#include "sbr/contour.h"
#include "sbr/image.h"
#include "sbr/mser.h"
#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A conic a x^2 + 2b xy + c y^2 + 2d x + 2e y + f = 0. */
typedef struct sbr_conic_s {
    float a; /**< x^2 */
    float b; /**< xy (half its coefficient) */
    float c; /**< y^2 */
    float d; /**< x (half its coefficient) */
    float e; /**< y (half its coefficient) */
    float f; /**< constant */
} sbr_conic_t;


/** An ellipse by its geometry. */
typedef struct sbr_ellipse_s {
    float cx;        /**< centre, column */
    float cy;        /**< centre, row */
    float semi_major; /**< > 0 */
    float semi_minor; /**< > 0, <= semi_major */
    float angle;     /**< direction of the major axis, radians in (-pi/2, pi/2], from +x
                          towards +y */
} sbr_ellipse_t;

/** The cases of the thesis's table 2.1 (plus the imaginary parallel lines it merges). */
typedef enum sbr_conic_class_e {
    SBR_CONIC_REAL_ELLIPSE = 1,      /**< det(C22) > 0, det(C) != 0, (a + c) det(C) < 0 */
    SBR_CONIC_IMAGINARY_ELLIPSE = 2, /**< det(C22) > 0, det(C) != 0, (a + c) det(C) > 0 */
    SBR_CONIC_POINT_ELLIPSE = 3,     /**< det(C22) > 0, det(C) = 0 (a single real point) */
    SBR_CONIC_PARABOLA = 4,          /**< det(C22) = 0, det(C) != 0 */
    SBR_CONIC_PARALLEL_LINES = 5,    /**< det(C22) = 0, det(C) = 0, rank 2, real lines */
    SBR_CONIC_IMAGINARY_PARALLEL_LINES = 6, /**< as above, no real point */
    SBR_CONIC_DOUBLE_LINE = 7,       /**< det(C22) = 0, rank 1: one line counted twice */
    SBR_CONIC_HYPERBOLA = 8,         /**< det(C22) < 0, det(C) != 0 */
    SBR_CONIC_INTERSECTING_LINES = 9 /**< det(C22) < 0, det(C) = 0 */
} sbr_conic_class_t;

/** Largest |coordinate| (pixels) of the points and ellipses the conic functions take:
    conics of larger coordinates overflow float32 or lose their constant term. */
#define SBR_CONIC_MAX_COORD 1e6f
/** Smallest semi-axis (pixels) of an ellipse given to sbr_ellipse_to_conic(). */
#define SBR_CONIC_MIN_AXIS 1e-3f

/** Default relative tolerance of sbr_conic_classify(). */
#define SBR_CONIC_ZERO_TOL 1e-5f

/**
 * @brief Classify a conic.
 *
 * The zero rule (what "= 0" means in ::sbr_conic_class_t), each determinant relative to
 * the entries it is made of, so that it does not depend on the conic's scale:
 * - det(C22) = ac - b^2 counts as zero when |ac - b^2| <= tol q^2, q = max(|a|, |b|, |c|);
 * - where det(C22) != 0 the conic has a centre (xc, yc), and det(C) = det(C22) f0 with f0
 *   = d xc + e yc + f its value there; det(C) counts as zero when
 *   |f0| <= tol (|d xc| + |e yc| + |f|), the terms f0 is summed from (so a small ellipse
 *   far from the origin, whose f0 is small against those terms, is a point ellipse unless
 *   tol is smaller);
 * - where det(C22) = 0, det(C) counts as zero when |det(C)| <= tol |r0| |r1| |r2| (the
 *   product of the row norms of C scaled to a largest entry of 1), and the rank is 1 when
 *   every 2 x 2 minor of that C is at most tol.
 * Determinants, minors and f0 are computed exactly enough (float-float products) that
 * their sign is right whenever they are above 2^-40 of their terms. Where det(C22) = 0,
 * det(C) and the minors count as zero at every tol when within 2^-40 of the sum of the
 * absolute products they are made of (below their rounding), and each
 * row of C is first scaled by a power of two of its own, so that entries of any range
 * (1e-30 beside 1e30) neither overflow nor underflow in the products (an entry below
 * 2^-126 of its row's largest counts as zero). So tol = 0 classifies exactly constructed
 * conics exactly, at any scale. Where the conic has a quadratic part, it is first scaled by
 * a power of two (exactly) to a largest quadratic entry in [0.5, 1); entries then below
 * 2^-33 count as zero (e.g. an ellipse whose axes differ by a factor above 2^16.5 has a
 * zero det(C22)).
 *
 * @param[in] conic the conic
 * @param[in] tol relative zero tolerance, >= 0 and < 1 (::SBR_CONIC_ZERO_TOL suits float32
 *            data; 0 for exact arithmetic on constructed matrices).
 * @param[out] cls the class.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a non-finite entry or tol, or a
 *         conic with det(C22) != 0 whose linear or constant terms exceed 2^50 and 2^100
 *         times the largest entry of its quadratic part (rounded up to a power of two);
 *         ::SBR_ERR_DEGENERATE for the zero matrix (no conic).
 */
sbr_status_t sbr_conic_classify(const sbr_conic_t *conic, float tol, sbr_conic_class_t *cls);

/**
 * @brief Centre, semi-axes and orientation of a real ellipse.
 * @param[in]  conic   the conic.
 * @param[out] ellipse its geometry, written on ::SBR_OK only; always one that
 *                     sbr_ellipse_to_conic() takes (the two round-trip).
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (a non-finite entry, or an ellipse
 *         outside what sbr_ellipse_to_conic() takes: centre or semi-major beyond
 *         ::SBR_CONIC_MAX_COORD, semi-minor below ::SBR_CONIC_MIN_AXIS, or one whose
 *         float32 conic is more than 1 % another ellipse);
 *         ::SBR_ERR_DEGENERATE when the conic is not a real ellipse (sbr_conic_classify()
 *         at ::SBR_CONIC_ZERO_TOL: a thin ellipse far from the origin may be a point
 *         ellipse there).
 */
sbr_status_t sbr_conic_to_ellipse(const sbr_conic_t *conic, sbr_ellipse_t *ellipse);

/**
 * @brief The conic of an ellipse, scaled so that f = -1 at the centre's origin shift
 *        (a, c of order 1 / axis^2).
 * @param[in]  ellipse the ellipse.
 * @param[out] conic   its conic, written on ::SBR_OK only: finite, and in exact arithmetic
 *                     a real ellipse whose centre and semi-axes are this ellipse's within
 *                     1 % of each semi-axis (of the semi-major for the centre)
 *                     (sbr_conic_classify()'s relative tolerance may still call a small
 *                     ellipse far from the origin a point ellipse).
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (non-finite values; |cx|, |cy| or
 *         semi_major above ::SBR_CONIC_MAX_COORD; semi_minor below ::SBR_CONIC_MIN_AXIS
 *         or above semi_major; or an ellipse so small or thin for its distance from the
 *         origin that its float32 conic, whose constant term carries the rounding error of
 *         cx^2 / axis^2, is no ellipse or another one by more than those 1 %).
 */
sbr_status_t sbr_ellipse_to_conic(const sbr_ellipse_t *ellipse, sbr_conic_t *conic);

/**
 * @brief Direct least-squares ellipse fit (Fitzgibbon's constraint 4ac - b'^2 = 1 with
 *        b' = 2b, solved the numerically stable way of Halir and Flusser) in float32.
 *
 * The points are first moved to their centroid and scaled to unit mean distance, which
 * keeps the 3 x 3 reduced problem well conditioned in single precision; the conic is
 * transformed back and returned normalised (largest absolute entry 1).
 *
 * @param[in] points  n points (any order; a traced contour or an arc).
 * @param[in] n       >= 5 (::SBR_ERR_SIZE otherwise).
 * @param[out] conic   the fitted conic.
 * @param[out] ellipse its geometry; may be NULL.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (n < 5); ::SBR_ERR_RANGE (non-finite or
 *         |coordinate| > 1e6); ::SBR_ERR_DEGENERATE when the points do not determine an
 *         ellipse (collinear, fewer than 5 distinct points, or the best conic is not a
 *         real ellipse, e.g. points of a hyperbola), or when the returned float32 conic
 *         would not be that ellipse (within 1 %, as sbr_ellipse_to_conic()).
 */
sbr_status_t sbr_ellipse_fit(const sbr_pointf_t *points, uint32_t n, sbr_conic_t *conic,
                             sbr_ellipse_t *ellipse);

/**
 * @brief Geometric fit residual: the Sampson distance |Q(p)| / |grad Q(p)| of each point
 *        (a first-order approximation of its distance to the conic, in pixels).
 * @param[in] conic the conic
 * @param[in]  points  n points, |coordinate| <= ::SBR_CONIC_MAX_COORD.
 * @param[in] n number of entries
 * @param[out] rms     root mean square distance (finite on ::SBR_OK).
 * @param[out] max_abs largest distance; may be NULL.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (n = 0); ::SBR_ERR_RANGE (non-finite
 *         input, a point beyond ::SBR_CONIC_MAX_COORD, or distances that overflow float32).
 */
sbr_status_t sbr_conic_residual(const sbr_conic_t *conic, const sbr_pointf_t *points,
                                uint32_t n, float *rms, float *max_abs);

/**
 * @brief Coverage: the fraction of 64 equal sectors of the ellipse (by parametric angle)
 *        that hold a point within `tol` pixels (Sampson distance) of the curve. 1 for a
 *        closed contour, about 0.5 for half an arc.
 * @param[in] conic the conic
 * @param[in] points the points
 * @param[in] n number of entries
 * @param[in] tol the tolerance
 * @param[out] coverage the covered fraction, 0..1.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE (n = 0); ::SBR_ERR_RANGE (non-finite,
 *         a point beyond ::SBR_CONIC_MAX_COORD, tol <= 0, or an ellipse that
 *         sbr_conic_to_ellipse() refuses as out of range); ::SBR_ERR_DEGENERATE (not a real
 *         ellipse).
 */
sbr_status_t sbr_ellipse_coverage(const sbr_conic_t *conic, const sbr_pointf_t *points,
                                  uint32_t n, float tol, float *coverage);

/** Relative pose of a plane lit by a torchlight (paper A): Z = n1 X + n2 Y + Z0 in camera
    coordinates, beam radius R along the optical axis. */
typedef struct sbr_torch_pose_s {
    float n1;        /**< plane slope along X */
    float n2;        /**< plane slope along Y */
    float z0_over_r; /**< distance along the optical axis in beam radii */
    float residual;  /**< rms misfit of the nine conic entries (unweighted), relative to
                          |C| (Frobenius, in focal-normalised coordinates) */
} sbr_torch_pose_t;

/** Largest residual sbr_torch_pose() accepts by default (relative to |C|). */
#define SBR_TORCH_MAX_RESIDUAL 0.05f

/**
 * @brief Torchlight pose from the beam's ellipse.
 *
 * The model conic (THESIS_NOTES.md) is, up to a scale lambda,
 * Cp = [[k - n1^2, -n1 n2, f n1], [-n1 n2, k - n2^2, f n2], [f n1, f n2, -f^2]] with
 * k = (Z0/R)^2, in coordinates centred at the principal point (x right, y down as the
 * image). The closed form (scale from C33) starts a Gauss-Newton least-squares fit of
 * (lambda, n1, n2, k) to all six distinct entries of the conic in focal-normalised
 * coordinates (x / f), scaled to unit norm. The entries 13, 23, 33 (the ellipse's centre
 * and size) weigh 1, the entries 11, 12, 22 (its elongation, poorly conditioned for
 * distant planes: Z0/R = 10 at f = 500 px elongates a 50 px beam by 0.2 %) weigh 0.1;
 * the unweighted misfit is the consistency test.
 *
 * @param[in] conic  the ellipse in principal-point-centred pixel coordinates.
 * @param[in] focal  focal length in pixels, > 0 and finite.
 * @param[in] max_residual accepted misfit (relative), > 0; ::SBR_TORCH_MAX_RESIDUAL.
 * @param[out] pose the plane's normal (n1, n2), distance over radius and the misfit.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (non-finite input, focal <= 0,
 *         max_residual <= 0); ::SBR_ERR_DEGENERATE when the conic is not a real ellipse
 *         or does not fit the model (k <= 0, C33 of the wrong sign, or the residual above
 *         max_residual; `pose` then holds the estimate and its residual).
 */
sbr_status_t sbr_torch_pose(const sbr_conic_t *conic, float focal, float max_residual,
                            sbr_torch_pose_t *pose);

/** Ellipse detection options. Start from sbr_ellipse_detect_config_default(). */
typedef struct sbr_ellipse_detect_config_s {
    /** Regions (MSER on the GRAY8 image). Default: delta 5, areas 40 .. 200000,
        max_variation 0.5, min_diversity 0.2, both polarities. */
    sbr_mser_config_t mser;
    /** Largest rms Sampson distance in pixels of the contour to its fitted ellipse,
        > 0. Larger: accepts rougher shapes. Default 1.0. */
    float max_residual;
    /** Smallest fraction of the ellipse covered by contour points within
        2 x max_residual, in (0, 1]. Default 0.9 (closed outlines). */
    float min_coverage;
    /** Smallest semi-minor axis in pixels, > 0. Default 4. */
    float min_semi_minor;
    /** Smallest ratio semi_minor / semi_major, in (0, 1]. Default 0.1. */
    float min_axis_ratio;
    /** Contour points are boundary pixel centres; they are moved this many pixels
        outward along the contour normal before fitting, so the fit follows the region's
        edge. In [0, 1]. Default 0.5. */
    float edge_offset;
    /** Bounds: regions examined and contour points per region. Defaults 1024, 4096. */
    uint32_t max_regions;
    uint32_t max_contour_points;
} sbr_ellipse_detect_config_t;

/** One detected ellipse. */
typedef struct sbr_ellipse_det_s {
    sbr_ellipse_t ellipse;
    sbr_conic_t conic;  /**< scaled to a + c = 1 */
    float residual;    /**< rms Sampson distance, pixels */
    float coverage;    /**< 0..1 */
    uint32_t area;     /**< region pixels (of the first region found) */
    uint32_t merged;   /**< regions merged into this detection (>= 1) */
    uint8_t polarity;  /**< ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT */
} sbr_ellipse_det_t;


/**
 * @brief Workspace bytes of sbr_ellipse_detect() for a width x height image, as a constant
 *        expression: `delta`, `nodes` and `heap` as for ::SBR_MSER_WORKSPACE_SIZE (the
 *        configuration's mser.max_nodes and mser.max_heap; 0 or a bound above the
 *        image's worst case reserve that worst case),
 *        `max_regions` and `max_points` as in the configuration. Equal to
 *        sbr_ellipse_detect_workspace_size() for that configuration.
 */
#define SBR_ELLIPSE_DETECT_WORKSPACE_SIZE(width, height, delta, nodes, heap, max_regions,       \
                                          max_points)                                           \
    (SBR_WS_ALIGN8((size_t)(max_regions) * sizeof(sbr_mser_region_t)) +                          \
     SBR_WS_MAX(SBR_WS_ALIGN8(SBR_MSER_WORKSPACE_SIZE(width, height, delta, nodes, heap)),    \
                    SBR_WS_ALIGN8(SBR_MSER_MASK_WORKSPACE_SIZE(width, height)) +                  \
                        SBR_WS_ALIGN8((size_t)(width) * (size_t)(height)) +                       \
                        SBR_WS_ALIGN8(SBR_CONTOUR_WORKSPACE_SIZE(width, height)) +                \
                        SBR_WS_ALIGN8((size_t)(max_points) * sizeof(sbr_point_t)) +               \
                        SBR_WS_ALIGN8(4u * sizeof(sbr_contour_t)) +                               \
                        SBR_WS_ALIGN8((size_t)(max_points) * sizeof(sbr_pointf_t))))

/**
 * @brief Defaults as documented above. No-op for NULL.
 * @param[out] cfg the configuration
 */
void sbr_ellipse_detect_config_default(sbr_ellipse_detect_config_t *cfg);

/**
 * @brief Check a configuration. ::SBR_OK, ::SBR_ERR_NULL, ::SBR_ERR_RANGE.
 * @param[in] cfg the configuration
 */
sbr_status_t sbr_ellipse_detect_config_check(const sbr_ellipse_detect_config_t *cfg);

/**
 * @brief Workspace bytes for sbr_ellipse_detect() on a width x height image; 0 for an
 *        invalid configuration or size.
 * @param[in] cfg the configuration
 * @param[in] width frame (or view) width, pixels
 * @param[in] height frame (or view) height, pixels
 */
size_t sbr_ellipse_detect_workspace_size(const sbr_ellipse_detect_config_t *cfg, uint32_t width,
                                         uint32_t height);

/**
 * @brief Ellipses of an image: MSER regions of both polarities, the outer contour of each,
 *        a direct fit, and the residual and coverage tests. Nested level sets of the same
 *        edge (centres within 1 px, axes within 1.5 px or 3 %) are merged into one
 *        detection: the mean of their conics (each scaled to a + c = 1) and its geometry
 *        (an anti-aliased edge gives a few such regions; their mean follows the edge's mid
 *        level).
 *
 * @param[in] image GRAY8 view, at least 3 x 3.
 * @param[in] cfg the configuration
 * @param[in,out] workspace the query's bytes, 8-byte aligned (scratch)
 * @param[in] workspace_size bytes available at `workspace`
 * @param[out] out     detections, in the order their regions were found.
 * @param[in] capacity     length of `out`.
 * @param[out] count   detections written.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (bad configuration or format);
 *         errors of sbr_image_check(); ::SBR_ERR_WORKSPACE (too small or not 8-byte
 *         aligned); ::SBR_ERR_CAPACITY when `out` or an internal bound ran full (the
 *         detections written are valid).
 */
sbr_status_t sbr_ellipse_detect(const sbr_image_t *image, const sbr_ellipse_detect_config_t *cfg,
                                void *workspace, size_t workspace_size, sbr_ellipse_det_t *out,
                                uint32_t capacity, uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif /* SBR_CONIC_H */
