/* SPDX-License-Identifier: MIT */
/* Helpers shared by sbr's Unity tests (not part of the library). */
#ifndef SBR_TEST_SUPPORT_H
#define SBR_TEST_SUPPORT_H

#include <stdint.h>
#include <string.h>

/* Deterministic generator (same sequence on every target): 32-bit LCG, top bits. */
typedef struct { uint32_t s; } tsup_rng_t;

static inline float tsup_uniform(tsup_rng_t *r, float lo, float hi)
{
    r->s = r->s * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(r->s >> 8) * (1.0f / 16777216.0f);
}

/* n pseudo-random bytes (the same LCG's top 8 bits) from `seed`. */
static inline void tsup_fill_bytes(uint8_t *p, size_t n, uint32_t seed)
{
    uint32_t state = seed;
    size_t i;
    for (i = 0u; i < n; i++) {
        state = (state * 1664525u) + 1013904223u;
        p[i] = (uint8_t)(state >> 24);
    }
}

/* Approximately standard normal: the sum of 12 uniforms minus 6. */
static inline float tsup_gauss(tsup_rng_t *r)
{
    float s = 0.0f;
    uint32_t i;
    for (i = 0u; i < 12u; i++) {
        s += tsup_uniform(r, 0.0f, 1.0f);
    }
    return s - 6.0f;
}

/* Guard tail after an output buffer: filled with a pattern, later checked untouched. */
#define TSUP_GUARD_BYTES 64u
#define TSUP_GUARD_BYTE 0xA5u

static inline void tsup_guard_fill(void *after, size_t bytes)
{
    memset(after, (int)TSUP_GUARD_BYTE, bytes);
}

static inline int tsup_guard_intact(const void *after, size_t bytes)
{
    const unsigned char *p = (const unsigned char *)after;
    size_t i;
    for (i = 0; i < bytes; i++) {
        if (p[i] != TSUP_GUARD_BYTE) {
            return 0;
        }
    }
    return 1;
}

#endif
