/* SPDX-License-Identifier: MIT */
/**
 * @file channel.h
 * @brief Channel representation: cos² channel encoding, soft histograms and mode
 *        decoding (thesis chapter 3.3, paper E).
 *
 * A scalar x is encoded into channel values c_k = B(x - x_k) with centres
 * x_k = first_centre + k * spacing (k = 0 .. count-1, 0-based here, 1-based in the
 * thesis) and the kernel
 *
 *     B(d) = cos²(pi * d / (overlap * spacing))   for |d| < overlap * spacing / 2,
 *     B(d) = 0                                    otherwise.
 *
 * `overlap` (M, the thesis's pi/a in units of the spacing) is how many channels one value
 * activates; the values of one encoding always sum to M/2 (1.5 for the thesis's M = 3).
 * Adding encodings (optionally weighted by a certainty) gives a soft histogram.
 *
 * Decoding window l (channels l .. l+M-1) gives
 *
 *     x_l = x_l0 + spacing * (M / (2 pi)) * arg( sum_{k=0}^{M-1} c_{l+k} e^{i 2 pi k / M} )
 *     r_l = sum_{k=0}^{M-1} c_{l+k}                      (certainty: the plain sum)
 *
 * with x_l0 the centre of channel l and arg in (-pi, pi]. The estimate is valid only
 * inside the window's middle: [x_l0 + ((M-1)/2 - 1/2) * spacing,
 * x_l0 + ((M-1)/2 + 1/2) * spacing) (for M = 3: the middle channel ± half a spacing; the
 * interval is widened by 1e-3 channels at both ends so that float rounding cannot drop a
 * value that lies on the boundary between two windows; decode() merges estimates closer
 * than 4e-3 channels into one mode, keeping the stronger). A single encoded
 * value is decoded exactly (to float rounding) by exactly one valid window, and values
 * further apart than about M spacings decode independently.
 *
 * 2-D points use a separable grid: the outer product of an x and a y encoding, stored row
 * by row (`grid[iy * count_x + ix]`).
 *
 * Nothing here allocates or needs a workspace; all arrays are the caller's.
 */
#ifndef SBR_CHANNEL_H
#define SBR_CHANNEL_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Smallest supported overlap M (two channels per value cannot be decoded). */
#define SBR_CHANNEL_MIN_OVERLAP 3u
/** Largest supported overlap M. */
#define SBR_CHANNEL_MAX_OVERLAP 8u
/** Largest channel count per axis (bounds the work of every call). */
#define SBR_CHANNEL_MAX_COUNT 4096u
/** Largest channel value (and encoding weight): sums of a window's channels stay finite
    in float32. */
#define SBR_CHANNEL_MAX_VALUE 1e30f

/** Layout of one channel axis. */
typedef struct sbr_channel_config_s {
    float first_centre; /**< Centre of channel 0 (the thesis's x_1). Finite. */
    float spacing;      /**< Distance between neighbouring centres; finite, > 0. */
    uint32_t count;     /**< Number of channels, overlap .. ::SBR_CHANNEL_MAX_COUNT. */
    uint32_t overlap;   /**< M: channels one value activates (kernel support M*spacing),
                             ::SBR_CHANNEL_MIN_OVERLAP .. ::SBR_CHANNEL_MAX_OVERLAP.
                             3 is the thesis's choice: the least smoothing; larger M
                             smooths more (more robust modes, less resolution). */
} sbr_channel_config_t;

/** Layout of a 2-D channel grid: one axis for x, one for y. */
typedef struct sbr_channel2d_config_s {
    sbr_channel_config_t x; /**< Columns. */
    sbr_channel_config_t y; /**< Rows. */
} sbr_channel2d_config_t;

/** One decoded mode of a 1-D soft histogram. */
typedef struct sbr_channel_mode_s {
    float value;     /**< Decoded position (same units as the centres). */
    float certainty; /**< Sum of the window's channels (one value of weight w gives w*M/2). */
} sbr_channel_mode_t;

/** One decoded mode of a 2-D soft histogram. */
typedef struct sbr_channel_mode2d_s {
    float x;         /**< Decoded x. */
    float y;         /**< Decoded y. */
    float certainty; /**< Sum of the M*M window (one point of weight w gives w*M*M/4). */
} sbr_channel_mode2d_t;

/**
 * @brief The thesis's worked example: centres 1..10, spacing 1, M = 3 (a = pi/3).
 *        No-op for NULL.
 * @param[out] cfg the configuration to fill.
 */
void sbr_channel_config_default(sbr_channel_config_t *cfg);

/**
 * @brief Check a configuration.
 * @param[in] cfg the configuration
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_RANGE for a non-finite centre, a spacing that
 *         is not finite and > 0, an overlap outside 3..8, or centres that are not finite
 *         one kernel (overlap x spacing) beyond either end (decoded values lie there);
 *         ::SBR_ERR_SIZE for a count below the overlap or above ::SBR_CHANNEL_MAX_COUNT.
 */
sbr_status_t sbr_channel_config_check(const sbr_channel_config_t *cfg);

/**
 * @brief The interval of values that can be encoded and decoded validly:
 *        [first_centre + (M/2 - 1) * spacing, last_centre - (M/2 - 1) * spacing).
 * @param[in]  cfg configuration.
 * @param[out] lo  smallest representable value.
 * @param[out] hi  upper end (exclusive).
 * @return ::SBR_OK, or as sbr_channel_config_check(); ::SBR_ERR_NULL for NULL outputs.
 */
sbr_status_t sbr_channel_range(const sbr_channel_config_t *cfg, float *lo, float *hi);

/**
 * @brief Encode one value into a fresh channel vector (all other channels set to 0).
 * @param[in]  cfg    configuration.
 * @param[in]  x      value; must lie in the range of sbr_channel_range().
 * @param[in]  weight certainty multiplying the encoding; finite, > 0 and at most
 *                    ::SBR_CHANNEL_MAX_VALUE (1 for plain).
 * @param[out] out    channel vector.
 * @param[in]  len    length of `out`; must be >= cfg->count (only count are written).
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE if `len` < count; ::SBR_ERR_RANGE
 *         for x outside the range, or a bad weight (then `out` is left untouched).
 */
sbr_status_t sbr_channel_encode(const sbr_channel_config_t *cfg, float x, float weight,
                                float *out, uint32_t len);

/**
 * @brief Add one weighted encoding into a soft histogram.
 * @param[in] cfg the configuration
 * @param[in] x the value along x
 * @param[in] weight the weight, finite and >= 0
 * @param[in,out] hist the histogram (`len` channel values) the encoding is added to.
 * @param[in] len length of `hist`, >= cfg->count
 * @return as sbr_channel_encode(); ::SBR_ERR_RANGE also when a channel it adds to is not
 *         a valid value (finite, >= 0) or would exceed ::SBR_CHANNEL_MAX_VALUE; on error
 *         nothing is added.
 */
sbr_status_t sbr_channel_accumulate(const sbr_channel_config_t *cfg, float x, float weight,
                                    float *hist, uint32_t len);

/**
 * @brief Decode one window, valid or not (what the thesis's example tabulates).
 * @param[in]  cfg       configuration.
 * @param[in]  hist      channel vector of `len` >= count values, each finite, >= 0 and
 *                       at most ::SBR_CHANNEL_MAX_VALUE.
 * @param[in]  len       length of `hist`.
 * @param[in]  window    first channel of the window, 0 .. count - M.
 * @param[out] value     the window's estimate (an all-zero window gives its first
 *                       channel's centre: arg(0) is taken as 0, as in the thesis).
 * @param[out] certainty the window's plain sum.
 * @param[out] valid     1 if `value` lies in the window's valid interval, else 0.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE for `len` < count; ::SBR_ERR_RANGE for
 *         a window out of range or a negative or non-finite channel value in the window.
 */
sbr_status_t sbr_channel_decode_window(const sbr_channel_config_t *cfg, const float *hist,
                                       uint32_t len, uint32_t window, float *value,
                                       float *certainty, int *valid);

/**
 * @brief Decode every valid mode whose certainty exceeds `min_certainty`, strongest first.
 * @param[in]  cfg           configuration.
 * @param[in]  hist          channel vector (`len` >= count values, finite, >= 0, at most
 *                           ::SBR_CHANNEL_MAX_VALUE).
 * @param[in]  len           length of `hist`.
 * @param[in]  min_certainty modes with certainty <= this are ignored; finite, >= 0.
 * @param[out] modes         result array, sorted by decreasing certainty (ties: by value).
 * @param[in]  capacity      length of `modes` (0 allowed only with modes == NULL: then
 *                           ::SBR_ERR_CAPACITY says that at least one mode qualified).
 * @param[out] count         number of modes written.
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE; ::SBR_ERR_RANGE for a bad channel value
 *         or threshold; ::SBR_ERR_CAPACITY if more modes qualified than fit: `modes` then
 *         holds the `capacity` strongest and `count` = capacity.
 */
sbr_status_t sbr_channel_decode(const sbr_channel_config_t *cfg, const float *hist,
                                uint32_t len, float min_certainty, sbr_channel_mode_t *modes,
                                uint32_t capacity, uint32_t *count);

/**
 * @brief Both axes set to sbr_channel_config_default(). No-op for NULL.
 * @param[out] cfg the configuration to fill.
 */
void sbr_channel2d_config_default(sbr_channel2d_config_t *cfg);

/**
 * @brief Check a 2-D configuration (both axes as sbr_channel_config_check(); the grid
 *        count_x * count_y must not exceed ::SBR_CHANNEL_MAX_COUNT squared).
 * @param[in] cfg the configuration
 */
sbr_status_t sbr_channel2d_config_check(const sbr_channel2d_config_t *cfg);

/**
 * @brief Number of floats a 2-D grid needs (count_x * count_y), 0 for a bad config.
 * @param[in] cfg the configuration
 */
uint32_t sbr_channel2d_grid_len(const sbr_channel2d_config_t *cfg);

/**
 * @brief Add one weighted 2-D point into a grid (outer product of the x and y encodings).
 * @param[in] cfg the configuration
 * @param[in] x the value along x
 * @param[in] y the value along y
 * @param[in] weight the weight, finite and >= 0
 * @param[in,out] grid the grid (x.count * y.count values, row-major by y).
 * @param[in] len length of `grid`, >= x.count * y.count
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_SIZE if `len` < the grid length;
 *         ::SBR_ERR_RANGE if x or y is outside its axis range, the weight is not finite,
 *         > 0 and at most ::SBR_CHANNEL_MAX_VALUE, or a cell it adds to is not a valid
 *         value or would exceed ::SBR_CHANNEL_MAX_VALUE (nothing is added).
 */
sbr_status_t sbr_channel2d_accumulate(const sbr_channel2d_config_t *cfg, float x, float y,
                                      float weight, float *grid, uint32_t len);

/**
 * @brief Decode every valid 2-D mode above `min_certainty`, strongest first. A window
 *        (M x M channels) is valid when both its x and y estimates are valid.
 * @param[in] cfg the configuration
 * @param[in] grid the grid (x.count * y.count values, row-major by y).
 * @param[in] len length of `grid`, >= x.count * y.count
 * @param[in] min_certainty smallest window sum that counts as a mode, >= 0.
 * @param[out] modes the decoded modes, strongest first.
 * @param[in] capacity entries of the result array
 * @param[out] count entries written
 * @return as sbr_channel_decode().
 */
sbr_status_t sbr_channel2d_decode(const sbr_channel2d_config_t *cfg, const float *grid,
                                  uint32_t len, float min_certainty,
                                  sbr_channel_mode2d_t *modes, uint32_t capacity,
                                  uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif /* SBR_CHANNEL_H */
