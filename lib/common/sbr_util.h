/* SPDX-License-Identifier: MIT */
/* Private helpers shared by the core's modules (not installed). */
#ifndef SBR_UTIL_H
#define SBR_UTIL_H

#include "sbr/types.h"

#include <math.h>

/* 1 on cores without a vector unit (Arm M-profile): there the whole-lane loops that
   compilers turn into SIMD code on hosts (blocks through local arrays, four lanes side by
   side) cost more than the one-at-a-time loops, so those keep the simple form. */
#if defined(__ARM_ARCH_PROFILE) && (__ARM_ARCH_PROFILE == 'M')
#define SBR_UTIL_SCALAR_CORE 1
#else
#define SBR_UTIL_SCALAR_CORE 0
#endif

/* pi and 2 pi as float (every file of the core uses these). */
#define SBR_PI_F 3.14159265f
#define SBR_TWO_PI_F 6.28318531f

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

/* The address p folded to 32 bits, for integrity words; never converted back to a pointer
   (MISRA.md, 11.6). */
static inline uint32_t sbr_util_addr32(const void *p)
{
    const uintptr_t a = (uintptr_t)p;
    const uintptr_t folded = a ^ ((a >> 16u) >> 16u);
    return (uint32_t)folded;
}

/* FNV-1a over n bytes: the integrity word of an instance (its bytes before the word),
   so that a call can refuse an instance never initialised or changed since. */
static inline uint32_t sbr_util_fnv1a(const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    uint32_t h = 2166136261u;
    size_t i;
    for (i = 0u; i < n; i++) {
        h = (h ^ (uint32_t)b[i]) * 16777619u;
    }
    return h;
}

/* a . b over n elements in four interleaved partial sums: element k goes to sum k mod 4
   (the tail after the last whole group of four to sum 0), and the result is
   (s0 + s1) + (s2 + s3). Independent additions the FPU can pipeline (one vector register
   on SIMD hosts); the order is fixed, so every target adds the same way. Code that must
   agree with it bit for bit (the class stage's four-row products) keeps this order. */
static inline float sbr_util_dot(const float *a, const float *b, size_t n)
{
    float s0 = 0.0f;
    float s1 = 0.0f;
    float s2 = 0.0f;
    float s3 = 0.0f;
    const size_t n4 = n - (n % 4u); /* the four-lane part; the tail loop is then
                                        visibly bounded by n - n4 < 4 */
    size_t k;
    for (k = 0u; k < n4; k += 4u) {
        s0 += a[k] * b[k];
        s1 += a[k + 1u] * b[k + 1u];
        s2 += a[k + 2u] * b[k + 2u];
        s3 += a[k + 3u] * b[k + 3u];
    }
    for (k = n4; k < n; k++) {
        s0 += a[k] * b[k];
    }
    return (s0 + s1) + (s2 + s3);
}

/* The angle of the point (x, y) in (-pi, pi] for finite arguments, to within 6e-7 rad
   (a degree-13 odd near-minimax polynomial of atan on [0, 1], 3.3e-7 rad, plus float
   rounding), several times faster than libm's atan2f. y = -0 counts as positive (the
   result for x < 0 is +pi); (0, 0) gives 0. */
static inline float sbr_util_atan2f(float y, float x)
{
    const float ax = fabsf(x);
    const float ay = fabsf(y);
    float mn = ax;
    float mx = ay;
    float a = 0.0f;
    float t;
    float r;

    if (ax > ay) {
        mn = ay;
        mx = ax;
    }
    if (mx > 0.0f) {
        a = mn / mx;
    }
    t = a * a;
    r = (0.00681178128f * t) - 0.0336041852f;
    r = (r * t) + 0.0796236328f;
    r = (r * t) - 0.1323334f;
    r = (r * t) + 0.198078151f;
    r = (r * t) - 0.33317368f;
    r = (r * t) + 0.999996112f;
    r *= a;
    if (ay > ax) {
        r = 1.57079633f - r;
    }
    if (x < 0.0f) {
        r = SBR_PI_F - r;
    }
    if (y < 0.0f) {
        r = -r;
    }
    return r;
}

/* The larger of two finite values (what fmaxf gives them, without a library call). */
static inline float sbr_util_maxf(float a, float b)
{
    float r = a;
    if (b > a) {
        r = b;
    }
    return r;
}

/* The smaller of two finite values (what fminf gives them, without a library call). */
static inline float sbr_util_minf(float a, float b)
{
    float r = a;
    if (b < a) {
        r = b;
    }
    return r;
}

/* v limited to lo .. hi (lo <= hi); NaN gives lo, so a cast of the result is defined. */
static inline float sbr_util_clampf(float v, float lo, float hi)
{
    float r = v;
    if (!(v >= lo)) {
        r = lo;
    }
    if (r > hi) {
        r = hi;
    }
    return r;
}

/* Intersection over union of two boxes x0, y0, x1, y1 (exclusive); 0 when they do not
   overlap or the union is empty. */
static inline float sbr_util_box_iou(const float a[4], const float b[4])
{
    const float iw = sbr_util_minf(a[2], b[2]) - sbr_util_maxf(a[0], b[0]);
    const float ih = sbr_util_minf(a[3], b[3]) - sbr_util_maxf(a[1], b[1]);
    float iou = 0.0f;
    if ((iw > 0.0f) && (ih > 0.0f)) {
        const float inter = iw * ih;
        const float uni = ((a[2] - a[0]) * (a[3] - a[1])) + ((b[2] - b[0]) * (b[3] - b[1])) - inter;
        if (uni > 0.0f) {
            iou = inter / uni;
        }
    }
    return iou;
}

/* Microseconds as seconds: a correctly rounded quotient of two exact floats, so 100000 us
   is exactly 0.1f (durations enter the core in microseconds, models keep seconds). */
static inline float sbr_util_seconds(uint32_t us)
{
    return (float)us / 1.0e6f;
}

/* Iterative heap sort of n elements of `size` bytes (no recursion, O(n log n), in place,
   not stable): `before(a, b, mode)` is 1 when a comes strictly before b. */
void sbr_util_heap_sort(uint8_t *base, uint32_t n, size_t size,
                        int (*before)(const void *a, const void *b, int mode), int mode);

#endif /* SBR_UTIL_H */
