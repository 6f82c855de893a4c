/* SPDX-License-Identifier: MIT */
/**
 * @file types.h
 * @brief Basic types shared by the sbr modules.
 */
#ifndef SBR_TYPES_H
#define SBR_TYPES_H

#include <stdint.h>
#include <stddef.h>
#include "sbr/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Complex single-precision number, real part first.
 *
 * A plain struct rather than C99 `_Complex`, so that the layout is the same for every
 * compiler an ECU project may use (two consecutive floats, 8 bytes, 4-byte aligned), and
 * an array of it can be shared with interleaved re/im buffers of other libraries.
 */
typedef struct sbr_complex_s {
    float re; /**< Real part. */
    float im; /**< Imaginary part. */
} sbr_complex_t;

/** A pixel position (contours, region seeds). */
typedef struct sbr_point_s {
    int16_t x; /**< column */
    int16_t y; /**< row */
} sbr_point_t;

/** A point with float coordinates, pixels (descriptors, conics). */
typedef struct sbr_pointf_s {
    float x; /**< column */
    float y; /**< row */
} sbr_pointf_t;

/** @name Workspace sizing helpers
 * Used by the modules' workspace macros (constant expressions): a module's workspace is a
 * sequence of blocks, each starting on an 8-byte boundary. @{ */
/** Bytes `v` rounded up to a multiple of 8. */
#define SBR_WS_ALIGN8(v) ((((size_t)(v)) + 7u) & ~(size_t)7u)
/** The larger of two byte counts (blocks that are used one after the other share bytes). */
#define SBR_WS_MAX(a, b) (((a) > (b)) ? (a) : (b))
/** @} */

#ifdef __cplusplus
}
#endif

#endif /* SBR_TYPES_H */
