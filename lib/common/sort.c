/* SPDX-License-Identifier: MIT */
/* Private helpers shared by the core's modules: sorting. */
#include "sbr_util.h"

#include <string.h>

/* Swap two elements of `size` bytes: four bytes at a time (fixed-size memcpy, which
   compilers turn into word loads and stores), then any bytes left. */
static void swap_bytes(uint8_t *a, uint8_t *b, size_t size)
{
    size_t i = 0u;
    while ((i + 4u) <= size) {
        uint8_t t[4];
        (void)memcpy(t, &a[i], 4u);
        (void)memcpy(&a[i], &b[i], 4u);
        (void)memcpy(&b[i], t, 4u);
        i += 4u;
    }
    while (i < size) {
        const uint8_t t = a[i];
        a[i] = b[i];
        b[i] = t;
        i++;
    }
}

/* Iterative heap sort of n elements of `size` bytes (no recursion, O(n log n), in place):
   a max-heap of "comes last" leaves the elements in `before` order. */
void sbr_util_heap_sort(uint8_t *base, uint32_t n, size_t size,
                        int (*before)(const void *a, const void *b, int mode), int mode)
{
    uint32_t end;
    uint32_t start;
    if (n < 2u) {
        return;
    }
    start = n / 2u;
    end = n;
    while (end > 1u) {
        uint32_t root;
        if (start > 0u) {
            start--;
            root = start;
        } else {
            end--;
            swap_bytes(base, &base[(size_t)end * size], size);
            root = 0u;
        }
        while (((2u * root) + 1u) < end) {
            uint32_t child = (2u * root) + 1u;
            if (((child + 1u) < end) &&
                (before(&base[(size_t)child * size], &base[((size_t)child + 1u) * size], mode) != 0)) {
                child++;
            }
            if (before(&base[(size_t)root * size], &base[(size_t)child * size], mode) != 0) {
                swap_bytes(&base[(size_t)root * size], &base[(size_t)child * size], size);
                root = child;
            } else {
                root = end; /* in place: stop */
            }
        }
    }
}
