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

#ifdef __cplusplus
}
#endif

#endif /* SBR_TYPES_H */
