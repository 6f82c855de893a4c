/* SPDX-License-Identifier: MIT */
/**
 * @file fd.h
 * @brief Fourier descriptors of closed contours and their correlation matching
 *        (thesis papers C and D).
 *
 * A contour c(l) = x(l) + i y(l) is resampled at N points equally spaced in arc length
 * (starting at its first point), transformed with the N-point FFT, and reduced to
 * C(n) = X[n] / N for n = -M..M. C(0) (the centroid) is dropped for translation
 * invariance and kept aside; the rest is normalised to unit energy for scale invariance,
 * and the energy's square root is kept as the contour's scale.
 *
 * Matching a query Q against a prototype C correlates them for every start point at once:
 * r(l) = sum_n conj(Q(n)) C(n) e^{i 2 pi n l / P}, l = 0..P-1, one inverse FFT of size P
 * (zero-padded). With both unit-energy, r(l) lies in the unit disc and
 *   rotation invariant:  e = 2 - 2 max_l |r(l)|
 *   rotation covariant:  e = 2 - 2 max_l Re r(l)   (optionally only over rotations whose
 *                                                   magnitude is at most a bound)
 * e = 0 for the same shape under translation, scale, rotation (invariant mode) and start
 * point; e <= 4 always. If the query is the prototype rotated by theta (counter-clockwise
 * in x-right/y-up axes, i.e. multiplied by e^{i theta}) and started s of its length later,
 * the peak has arg r = -theta at l = s * P: sbr reports rotation = theta and
 * shift = s (a fraction of the length, in [0, 1)). The grid peak is refined between
 * samples by a parabola and one exact evaluation of r, so rotation and shift are not
 * limited to the grid of P.
 *
 * Mirror images: a mirrored contour traced in the same direction has the descriptor
 * -conj(C(n)) (sbr_fd_mirror()); matching against both gives mirror invariance.
 */
#ifndef SBR_FD_H
#define SBR_FD_H

#include "sbr/contour.h"
#include "sbr/fft.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number M of kept coefficients on each side: 16, enough for a match of the
    FFT size 32 the recogniser uses (2M + 1 <= P keeps M <= 15; the recogniser's parts use
    12) and it sizes every descriptor a frame holds (a part's record, the model's tables in
    flash). */
#define SBR_FD_MAX_M 16u
/** Largest absolute coordinate accepted (keeps float arc lengths accurate). */
#define SBR_FD_MAX_COORD 1.0e6f


/** A Fourier descriptor. `c[k]` holds C(k - m), k = 0..2m; `c[m]` (the DC term) is 0. */
typedef struct sbr_fd_s {
    uint32_t m;                            /**< M: coefficients kept on each side */
    float scale;                           /**< sqrt of the energy before normalisation
                                                (a length: doubles when the shape does) */
    float cx;                              /**< centroid x (of the resampled contour) */
    float cy;                              /**< centroid y */
    sbr_complex_t c[(2u * SBR_FD_MAX_M) + 1u]; /**< normalised coefficients */
} sbr_fd_t;

/**
 * @brief Descriptor of a traced contour (integer points, as sbr_contour_find_external()).
 * @param[in]  fft      an FFT instance of length N (the resampling size), N > 2M.
 * @param[in]  points   closed contour, `count` points (the last connects to the first).
 * @param[in]  count    number of points.
 * @param[in]  m        M, 1 .. ::SBR_FD_MAX_M, and 2M < N.
 * @param[in]  work     scratch of at least N complex values.
 * @param[in]  work_len length of `work`.
 * @param[out] out      the descriptor.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (bad FFT instance); ::SBR_ERR_SIZE for
 *         0 points, `work_len` < N, or M out of range; ::SBR_ERR_DEGENERATE for 1 or 2
 *         points, zero length or zero area (collinear points); ::SBR_ERR_RANGE for a
 *         non-finite coordinate or one beyond ::SBR_FD_MAX_COORD. `out` is written only
 *         on success.
 */
sbr_status_t sbr_fd_from_points(const sbr_fft_t *fft, const sbr_point_t *points,
                                uint32_t count, uint32_t m, sbr_complex_t *work,
                                uint32_t work_len, sbr_fd_t *out);

/**
 * @brief As sbr_fd_from_points() for float points.
 * @param[in] fft an initialised FFT instance
 * @param[in] points the points
 * @param[in] count number of entries
 * @param[in] m descriptor order M (coefficients -M..M), 1..::SBR_FD_MAX_M, 2M < N.
 * @param[out] work scratch of `work_len` complex values
 * @param[in] work_len length of `work`
 * @param[out] out the result
 */
sbr_status_t sbr_fd_from_pointsf(const sbr_fft_t *fft, const sbr_pointf_t *points,
                                 uint32_t count, uint32_t m, sbr_complex_t *work,
                                 uint32_t work_len, sbr_fd_t *out);

/**
 * @brief Check a descriptor as the matcher and the other descriptor functions do: M in
 *        1..::SBR_FD_MAX_M, finite positive scale, finite centroid, finite coefficients
 *        whose energy (the sum of |C(n)|^2) is finite in float32 too (so no |C(n)| above
 *        about 1.8e19).
 * @param[in] fd the descriptor
 * @param[out] energy (may be NULL) sum of |C(n)|^2 over the 2M + 1 coefficients (1 for a
 *                    descriptor sbr computed), written on success.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE.
 */
sbr_status_t sbr_fd_check(const sbr_fd_t *fd, float *energy);

/**
 * @brief Descriptor of the mirror image (x -> -x), traced in the same direction.
 * @param[in] in the input
 * @param[out] out the result
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for an invalid descriptor.
 *         `in` and `out` may be the same.
 */
sbr_status_t sbr_fd_mirror(const sbr_fd_t *in, sbr_fd_t *out);

/**
 * @brief Descriptor of the contour smoothed by a Gaussian along its length.
 *
 * Convolving the closed contour with a Gaussian of standard deviation `sigma` (a
 * fraction of the contour length) multiplies C(n) by exp(-2 pi^2 n^2 sigma^2); the result
 * is normalised to unit energy again (`scale` keeps the unsmoothed value). Smoothing
 * suppresses small boundary noise and articulation detail, which helps retrieval of
 * deformable shapes and costs discrimination of fine detail.
 *
 * @param[in]  in    descriptor.
 * @param[in]  sigma 0 (copy) .. 0.5.
 * @param[out] out   smoothed descriptor; may equal `in`; written on ::SBR_OK only.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a bad descriptor or sigma, or a
 *         damaged descriptor whose smoothed, renormalised coefficients are not finite.
 */
sbr_status_t sbr_fd_smooth(const sbr_fd_t *in, float sigma, sbr_fd_t *out);

/** Matching modes. */
typedef enum sbr_fd_mode_e {
    SBR_FD_ROTATION_INVARIANT = 0, /**< maximise |r|: any rotation matches */
    SBR_FD_ROTATION_COVARIANT = 1  /**< maximise Re r: rotation costs (6 and 9 differ) */
} sbr_fd_mode_t;

/** Matching options. */
typedef struct sbr_fd_match_config_s {
    /** Invariant or covariant (default: covariant, what traffic signs need). */
    sbr_fd_mode_t mode;
    /** Covariant mode only: accept only peaks whose rotation magnitude is at most this
        (radians, >= 0; pi or more = no bound, pi the default). A bound keeps, say, a left arrow
        from matching a right arrow turned upside down. If no peak qualifies the error
        is 4 (the worst). */
    float max_rotation;
    /** 1 (default): refine the peak between grid samples (exact rotation and shift, a
        slightly lower error); 0: grid peak only (faster, for bulk screening). */
    int refine;
    /** Screening (>= 0; default 0, none; 0 and values of 2 or more screen nothing, so a
        zero-initialised configuration behaves as before this field existed): a prototype
        whose error is certainly above `max_error` is not correlated and gets the no-match
        result (error 4, rotation and shift 0, scale_ratio as always). The test is a
        bound, |r| <= sum |Q(n)| |C(n)| over the coefficients (so e >= 2 - 2 sum), with a
        margin of 1e-4 for rounding: every match whose error is at most `max_error` comes
        out exactly as without screening, while most unrelated pairs skip the transform.
        For callers that only use matches up to some error (such as the recogniser's
        votes). Costs one square root per coefficient of each prototype. Invalid
        prototypes get their status as without screening (a non-finite coefficient makes
        the bound non-finite, which is never screened out). */
    float max_error;
} sbr_fd_match_config_t;

/** Result of one match. */
typedef struct sbr_fd_match_s {
    float error;       /**< e = 2 - 2 max, in [0, 4] */
    float rotation;    /**< rotation of the query relative to the prototype, (-pi, pi] */
    float shift;       /**< start-point shift as a fraction of the length, [0, 1) */
    float scale_ratio; /**< query scale / prototype scale */
} sbr_fd_match_t;

/** @brief Defaults: covariant, no rotation bound, refined, no screening (max_error 0).
    No-op for NULL.
    @param[out] cfg the configuration to fill. */
void sbr_fd_match_config_default(sbr_fd_match_config_t *cfg);

/** @brief Check a match configuration (every match function checks it too).
    @param[in] cfg the configuration.
    @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE (unknown mode, max_rotation negative
            or not finite, max_error negative or NaN). */
sbr_status_t sbr_fd_match_config_check(const sbr_fd_match_config_t *cfg);

/**
 * @brief Correlate a query with one prototype.
 * @param[in]  fft      FFT instance of size P, P >= 2M + 1 (M of the descriptors).
 * @param[in]  cfg      options.
 * @param[in]  query    query descriptor.
 * @param[in]  proto    prototype descriptor with the same M.
 * @param[in]  work     scratch of at least P complex values.
 * @param[in]  work_len its length.
 * @param[out] result   the match.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE (bad FFT instance); ::SBR_ERR_SIZE for
 *         different M, P < 2M+1 or short `work`; ::SBR_ERR_RANGE for a bad config, an
 *         invalid descriptor (the conditions of sbr_fd_check()), a scale ratio that
 *         float32 cannot hold (zero or infinite), or a correlation that overflows float32
 *         (descriptors of far more than the unit energy sbr gives them); `result` is
 *         written on ::SBR_OK only.
 */
sbr_status_t sbr_fd_match(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                          const sbr_fd_t *query, const sbr_fd_t *proto, sbr_complex_t *work,
                          uint32_t work_len, sbr_fd_match_t *result);

/** Scratch length (complex values) with which sbr_fd_match_table() correlates four
    prototypes at a time (lane-interleaved transforms that compilers map to SIMD on hosts);
    shorter scratch (>= P) matches one after another. Both give the same matches up to
    float rounding (a different butterfly order). */
#define SBR_FD_TABLE_WORK_LEN(p) (5u * (uint32_t)(p))

/**
 * @brief Correlate a query with a table of prototypes.
 * @param[in] fft an initialised FFT instance
 * @param[in] cfg the configuration
 * @param[in] query the descriptor to look up.
 * @param[in] protos the prototype table (`count` descriptors of the query's M).
 * @param[in] count number of entries
 * @param[in]  work     scratch of at least P complex values; with
 *                      SBR_FD_TABLE_WORK_LEN(P) the faster four-lane path is used.
 * @param[in] work_len length of `work`
 * @param[out] results  one result per prototype (`count` entries).
 * @param[out] best     index of the prototype with the smallest error.
 * @return as sbr_fd_match(); ::SBR_ERR_SIZE for count 0. An invalid prototype (the
 *         conditions of sbr_fd_check(), or another M) stops the call with the status of
 *         the first invalid one in table order; results before it may have been written.
 *         Both paths refuse the same prototypes; a correlation that overflows float32 is
 *         found by each where it overflows (so at that edge the paths may differ in which
 *         call they refuse).
 */
sbr_status_t sbr_fd_match_table(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                const sbr_fd_t *query, const sbr_fd_t *protos, uint32_t count,
                                sbr_complex_t *work, uint32_t work_len, sbr_fd_match_t *results,
                                uint32_t *best);

/** @name A prepared table (sbr_fd_table_init(), sbr_fd_match_prepared()) @{ */
/** Range of a prepared table's prototype scales and of its queries' scales, so that a
    query's scale over a prototype's stays a float32 value. */
#define SBR_FD_TABLE_MIN_SCALE 1e-10f
#define SBR_FD_TABLE_MAX_SCALE 1e10f
/** Floats of a prepared table's magnitudes for `count` prototypes of M `m`. */
#define SBR_FD_TABLE_MAGS_LEN(count, m) ((size_t)(count) * ((2u * (size_t)(m)) + 1u))
/** @} */

/** A prototype table checked once, for matching many queries against it (the
    recogniser's library: thousands of queries a frame). Fields are private; use
    sbr_fd_table_init(). The prototypes and the magnitudes are borrowed and must stay
    unchanged while the table is used. */
typedef struct sbr_fd_table_s {
    const sbr_fd_t *protos;
    const float *mags; /* per prototype its 2M + 1 coefficient magnitudes */
    uint32_t count;
    uint32_t m;
    uint32_t magic;
    uint32_t check; /* integrity word over everything before it */
} sbr_fd_table_t;

/**
 * @brief Prepare a prototype table: check every entry once and compute the coefficient
 *        magnitudes the matcher's screening reads, so that sbr_fd_match_prepared() checks
 *        only its query.
 * @param[out] table    the prepared table (left unusable on any status but ::SBR_OK).
 * @param[in]  protos   `count` descriptors, each valid (sbr_fd_check()), all of one M, with
 *                      scales in ::SBR_FD_TABLE_MIN_SCALE .. ::SBR_FD_TABLE_MAX_SCALE
 *                      (borrowed).
 * @param[in]  count    entries, >= 1.
 * @param[out] mags     ::SBR_FD_TABLE_MAGS_LEN(count, M) floats, written (borrowed).
 * @param[in]  mags_len floats available at `mags`.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE for count 0 or `mags` too short;
 *         ::SBR_ERR_RANGE for an invalid entry, a scale out of range or entries of
 *         different M.
 */
sbr_status_t sbr_fd_table_init(sbr_fd_table_t *table, const sbr_fd_t *protos, uint32_t count,
                               float *mags, size_t mags_len);

/**
 * @brief sbr_fd_match_table() of a query against entries first .. first + count - 1 of a
 *        prepared table: the same results, bit for bit, without checking the entries again.
 * @param[in] fft      an initialised FFT instance
 * @param[in] cfg      the configuration
 * @param[in] table    a table from sbr_fd_table_init()
 * @param[in] first    the first entry
 * @param[in] count    entries, >= 1, first + count at most the table's
 * @param[in] query    the descriptor to look up, of the table's M, with a scale in
 *                     ::SBR_FD_TABLE_MIN_SCALE .. ::SBR_FD_TABLE_MAX_SCALE
 * @param[in] work     scratch, as sbr_fd_match_table()
 * @param[in] work_len length of `work`
 * @param[out] results one result per entry (`count`)
 * @param[out] best    index (from `first`) of the entry with the smallest error
 * @return as sbr_fd_match_table(); ::SBR_ERR_STATE for a table not initialised or changed
 *         since; ::SBR_ERR_SIZE for count 0 or a range beyond the table; ::SBR_ERR_RANGE
 *         for a query scale out of range.
 */
sbr_status_t sbr_fd_match_prepared(const sbr_fft_t *fft, const sbr_fd_match_config_t *cfg,
                                   const sbr_fd_table_t *table, uint32_t first, uint32_t count,
                                   const sbr_fd_t *query, sbr_complex_t *work, uint32_t work_len,
                                   sbr_fd_match_t *results, uint32_t *best);

#ifdef __cplusplus
}
#endif

#endif /* SBR_FD_H */
