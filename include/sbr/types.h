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

/** Kinds of a configuration field's values (sbr_field_t::kind). */
typedef enum sbr_field_kind_e {
    SBR_FIELD_U32 = 0, /**< uint32_t */
    SBR_FIELD_F32 = 1  /**< float */
} sbr_field_kind_t;

/** sbr_field_t::flags: the field's range also depends on other fields (its help names
    them); the check blames one field of each rule. */
#define SBR_FIELD_LINKED 1u
/** "No field": a name not found, a configuration that passes. */
#define SBR_FIELD_NONE 0xFFFFFFFFu
/** Most values of one field (one per map kind). */
#define SBR_FIELD_MAX_VALUES 4u
/** Room for a field's name and its meaning in the core's tables (with the terminator). */
#define SBR_FIELD_NAME_LEN 28u
#define SBR_FIELD_HELP_LEN 100u

/** One field of a configuration struct, as the core's tables describe it (the
    recogniser's configuration, recog.h; the class stage's looks, picto.h): the one place
    its name, range, default and meaning are written. The checks, the host tools' options,
    the Python keywords and docs/usage/configuration.md are made from the tables. A
    caller's copy, filled by the table's function (name and help point into const
    tables). */
typedef struct sbr_field_s {
    const char *name;  /**< snake_case; the host tools' option is --name with '-' */
    const char *help;  /**< one line: what it does, when to change it */
    uint32_t offset;   /**< byte offset of its first value in its struct */
    uint8_t kind;      /**< ::sbr_field_kind_t */
    uint8_t count;     /**< values: 1, or up to ::SBR_FIELD_MAX_VALUES (U32 only) */
    uint8_t flags;     /**< ::SBR_FIELD_LINKED or 0 */
    uint32_t lo_u;     /**< U32: smallest value */
    uint32_t hi_u;     /**< U32: largest value */
    uint32_t def_u[SBR_FIELD_MAX_VALUES]; /**< U32: the default of each value */
    float lo_f;        /**< F32: smallest value */
    float hi_f;        /**< F32: largest value */
    float def_f;       /**< F32: the default */
} sbr_field_t;

#ifdef __cplusplus
}
#endif

#endif /* SBR_TYPES_H */
