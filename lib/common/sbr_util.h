/* Private helpers shared by the core's modules (not installed). */
#ifndef SBR_UTIL_H
#define SBR_UTIL_H

#include "sbr/types.h"

/* Do the byte ranges [a, a + na) and [b, b + nb) share a byte? Compared as integers:
   relational comparison of pointers into different objects is undefined in C
   (MISRA.md, 11.4). */
static inline int sbr_util_overlap(const void *a, size_t na, const void *b, size_t nb)
{
    const uintptr_t ia = (uintptr_t)a;
    const uintptr_t ib = (uintptr_t)b;
    int ov = 0;
    if ((ia < (ib + (uintptr_t)nb)) && (ib < (ia + (uintptr_t)na))) {
        ov = 1;
    }
    return ov;
}

/* Is p a multiple of `align` (a power of two)? (MISRA.md, 11.4 and 11.6) */
static inline int sbr_util_aligned(const void *p, uint32_t align)
{
    const uintptr_t a = (uintptr_t)p;
    int ok = 0;
    if ((a & ((uintptr_t)align - 1u)) == 0u) {
        ok = 1;
    }
    return ok;
}

#endif /* SBR_UTIL_H */
