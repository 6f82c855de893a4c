/* SPDX-License-Identifier: MIT */
/**
 * @file status.h
 * @brief Status codes shared by every sbr module.
 *
 * Every public sbr function returns an ::sbr_status_t. ::SBR_OK is zero and every
 * error is negative, so `if (st != SBR_OK)` and `if (st < 0)` are equivalent.
 * No sbr function asserts on user input: bad input always comes back as one of
 * these codes, and outputs are left in the documented state for that code.
 */
#ifndef SBR_STATUS_H
#define SBR_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

/** Result of every public sbr call. */
typedef enum sbr_status_e {
    SBR_OK = 0,                /**< Success. */
    SBR_ERR_NULL = -1,         /**< A required pointer argument is NULL. */
    SBR_ERR_SIZE = -2,         /**< A size, length or count is zero or not supported
                                    (for example an FFT length that is not a power of
                                    two in 16..1024). */
    SBR_ERR_RANGE = -3,        /**< A value is outside its documented range, or is
                                    NaN or infinite. */
    SBR_ERR_ALIGN = -4,        /**< A stride, alignment or layout is invalid (for
                                    example a stride smaller than a row). */
    SBR_ERR_CAPACITY = -5,     /**< A caller-provided result array was too small. The
                                    array holds the first (or best, where the function
                                    says so) `capacity` results and the count says how
                                    many were written; the rest were dropped. */
    SBR_ERR_WORKSPACE = -6,    /**< The workspace is NULL, too small or misaligned. */
    SBR_ERR_STATE = -7,        /**< An instance was not initialised, or its contents
                                    fail the integrity check (corrupted or overwritten). */
    SBR_ERR_OVERLAP = -8,      /**< Input and output buffers overlap in a way the
                                    function does not support. */
    SBR_ERR_DEGENERATE = -9,   /**< The input is well-formed but geometrically or
                                    numerically degenerate (no solution exists). */
    SBR_ERR_CORRUPT = -10      /**< Received data failed an integrity check (CRC,
                                    counter, length). */
} sbr_status_t;

/**
 * @brief Short, constant, human-readable name of a status code.
 * @param[in] status any value; unknown values give "SBR_ERR_UNKNOWN".
 * @return a pointer to a static constant string (never NULL).
 */
const char *sbr_status_str(sbr_status_t status);

#ifdef __cplusplus
}
#endif

#endif /* SBR_STATUS_H */
