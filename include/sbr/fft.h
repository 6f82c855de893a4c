/* SPDX-License-Identifier: MIT */
/**
 * @file fft.h
 * @brief Fixed-size complex float32 FFT for the lengths 16, 32, ..., 1024.
 *
 * Mixed radix-4/radix-2 decimation in time with const, precomputed tables: nothing is
 * computed with trigonometric functions at run time and nothing is allocated.
 *
 * @par Usage
 * @code
 *   sbr_fft_t fft;
 *   if (sbr_fft_init_256(&fft) != SBR_OK) { ... }
 *   sbr_fft_forward(&fft, in, out);   // out-of-place
 *   sbr_fft_inverse(&fft, out, out);  // in place: out now equals in (to float rounding)
 * @endcode
 *
 * @par Scaling
 * Forward: X[k] = sum_{n} x[n] e^{-i 2 pi k n / N} (unscaled).
 * Inverse: x[n] = (1/N) sum_{k} X[k] e^{+i 2 pi k n / N} (scaled by 1/N), so that
 * inverse(forward(x)) = x.
 *
 * @par Linker and flash
 * Each length has its own init function in its own translation unit, and every table is
 * a separate const object. Built with `-ffunction-sections -fdata-sections` and linked
 * with `--gc-sections` (the sbr CMake package does both for its own code), an ECU image
 * that calls only sbr_fft_init_64() carries only the tables for N <= 64. The generic
 * sbr_fft_init() references every table.
 *
 * Table flash per length (twiddles + bit reversal):
 * 16: 128 B, 32: 304 B, 64: 608 B, 128: 1.2 KiB, 256: 2.5 KiB, 512: 5.0 KiB,
 * 1024: 10.0 KiB (stages of equal span share one table across lengths).
 *
 * @par Buffers
 * `in` and `out` hold N ::sbr_complex_t each. They may be the same pointer (in place);
 * any other overlap is rejected with ::SBR_ERR_OVERLAP. Nothing beyond N elements is read
 * or written.
 *
 * @par Real input
 * There is no separate real-input transform: sbr's Fourier descriptors transform
 * complex contours (x + iy), and the correlation spectra are complex as well.
 */
#ifndef SBR_FFT_H
#define SBR_FFT_H

#include "sbr/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Smallest supported transform length. */
#define SBR_FFT_MIN_SIZE 16u
/** Largest supported transform length. */
#define SBR_FFT_MAX_SIZE 1024u
/** Most radix-4 stages with twiddle factors (for N = 1024: spans 4, 16, 64, 256). */
#define SBR_FFT_MAX_STAGES 4u
/** Workspace bytes an FFT needs: none (kept for the common module API shape). */
#define SBR_FFT_WORKSPACE_SIZE(n) (0u)

/**
 * @brief An FFT instance: the length and pointers to const tables.
 *
 * Fill it only with an init function. It owns nothing; copying it is fine. Treat the
 * members as read-only: the transforms validate them (an instance that was never
 * initialised or was overwritten gives ::SBR_ERR_STATE).
 */
typedef struct sbr_fft_s {
    uint32_t n;                                    /**< Transform length N. */
    uint32_t log2n;                                /**< log2(N). */
    uint32_t stages;                               /**< Radix-4 stages with twiddles. */
    const uint16_t *bitrev;                        /**< N bit-reversed indices. */
    const sbr_complex_t *twiddle[SBR_FFT_MAX_STAGES]; /**< Per stage: 3*L factors. */
    uint32_t check;                                /**< Integrity word set by init. */
} sbr_fft_t;

/**
 * @brief Initialise an instance for any supported length.
 *
 * Convenient on the host; on an ECU prefer the per-length functions below, because this
 * one makes the linker keep the tables of every length.
 *
 * @param[out] fft instance to fill.
 * @param[in]  n   transform length: 16, 32, 64, 128, 256, 512 or 1024.
 * @return ::SBR_OK; ::SBR_ERR_NULL if `fft` is NULL; ::SBR_ERR_SIZE for any other `n`
 *         (the instance is then cleared, so using it gives ::SBR_ERR_STATE).
 */
sbr_status_t sbr_fft_init(sbr_fft_t *fft, uint32_t n);

/**
 * @name Per-length initialisation
 * Each fills `fft` for one length and references only the tables that length needs.
 * @param[out] fft instance to fill.
 * @return ::SBR_OK, or ::SBR_ERR_NULL if `fft` is NULL.
 * @{
 */
sbr_status_t sbr_fft_init_16(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_32(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_64(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_128(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_256(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_512(sbr_fft_t *fft);
sbr_status_t sbr_fft_init_1024(sbr_fft_t *fft);
/** @} */

/**
 * @brief Forward transform (unscaled), out of place or in place.
 * @param[in]  fft an initialised instance.
 * @param[in]  in  N input values.
 * @param[out] out N output values; may equal `in` (in place).
 * @return ::SBR_OK; ::SBR_ERR_NULL for a NULL pointer; ::SBR_ERR_STATE if `fft` was not
 *         initialised or is corrupted; ::SBR_ERR_OVERLAP if the buffers overlap without
 *         being identical. On error `out` is not written.
 * @note The input is not checked for NaN or infinity (that would cost a pass over the
 *       data); non-finite input gives non-finite output and nothing worse.
 */
sbr_status_t sbr_fft_forward(const sbr_fft_t *fft, const sbr_complex_t *in,
                             sbr_complex_t *out);

/**
 * @brief Inverse transform scaled by 1/N, out of place or in place.
 * @param[in]  fft an initialised instance.
 * @param[in]  in  N input values.
 * @param[out] out N output values; may equal `in` (in place).
 * @return as sbr_fft_forward().
 */
sbr_status_t sbr_fft_inverse(const sbr_fft_t *fft, const sbr_complex_t *in,
                             sbr_complex_t *out);

/**
 * @brief Check that an instance was initialised and is intact (the same check every
 *        transform makes; for modules that hold an instance and want to validate it once).
 * @param[in] fft an initialised FFT instance
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_STATE for an instance that was never
 *         initialised, was initialised with an unsupported length, or was overwritten.
 */
sbr_status_t sbr_fft_check(const sbr_fft_t *fft);

/**
 * @brief Whether `n` is a supported transform length.
 * @param[in] n a transform length
 * @return 1 for 16, 32, ..., 1024; 0 otherwise.
 */
int sbr_fft_size_supported(uint32_t n);

#ifdef __cplusplus
}
#endif

#endif /* SBR_FFT_H */
