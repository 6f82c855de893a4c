/* SPDX-License-Identifier: MIT */
/* A region of sbr_mser_detect() rebuilt from the map as a mask of its bounding box
   (sbr_mser_region_mask()): a fill from its seed over the pixels of its level or beyond.
   See include/sbr/mser.h. */
#include "sbr/mser.h"

#include "../common/sbr_util.h"

#include <string.h>

/* A region's level test as one comparison: v is in the region when (v ^ flip) <= the
   returned level (dark: v <= level; bright, flip 0xFF: 255 - v <= 255 - level). */
static uint8_t region_flip(const sbr_mser_region_t *r, uint8_t *flip)
{
    *flip = (r->polarity == (uint8_t)SBR_MSER_DARK) ? 0u : 0xFFu;
    return (uint8_t)(r->level ^ *flip);
}

/* The fill's view of a region: its box's first map pixel and mask byte, the strides, and
   its level test (region_flip()). */
typedef struct mask_fill_s {
    const uint8_t *map;  /* the map pixel at the box's top left */
    uint8_t *mask;
    size_t map_stride;
    size_t mask_stride;
    uint32_t *stack;
    uint32_t sp;
    uint32_t filled;
    uint8_t flip;        /* 0 dark, 0xFF bright */
    uint8_t level;       /* in the flipped values */
} mask_fill_t;

/* Is box pixel (x, y) in the region and not yet in the mask? */
static inline int run_in(const mask_fill_t *f, uint32_t x, uint32_t y)
{
    return ((f->mask[((size_t)y * f->mask_stride) + x] == 0u) &&
            ((uint8_t)(f->map[((size_t)y * f->map_stride) + x] ^ f->flip) <= f->level))
               ? 1
               : 0;
}

/* One neighbour (nx, ny) of the region mask's pixel fill: marked and stacked if it is in
   the region and not marked yet. */
static inline void mask_grow(mask_fill_t *f, uint32_t nx, uint32_t ny)
{
    if (run_in(f, nx, ny) != 0) {
        f->mask[((size_t)ny * f->mask_stride) + nx] = 255u;
        f->stack[f->sp] = (ny << 16) | nx;
        f->sp++;
        f->filled++;
    }
}

/* A region that lies inside the map, one pixel off its border, with its seed inside its
   box and an area the box can hold. */
static int region_in_map(const sbr_image_t *map, const sbr_mser_region_t *region)
{
    const sbr_rect_t *b = &region->bbox;
    int ok = 1;
    if ((region->polarity != (uint8_t)SBR_MSER_DARK) &&
        (region->polarity != (uint8_t)SBR_MSER_BRIGHT)) {
        ok = 0;
    } else if ((b->width == 0u) || (b->height == 0u) || (b->x < 1u) || (b->y < 1u) ||
               (b->x >= (map->width - 1u)) || (b->y >= (map->height - 1u)) ||
               (b->width > ((map->width - 1u) - b->x)) ||
               (b->height > ((map->height - 1u) - b->y)) ||
               ((uint32_t)region->seed_x < b->x) || ((uint32_t)region->seed_y < b->y) ||
               ((uint32_t)region->seed_x >= (b->x + b->width)) ||
               ((uint32_t)region->seed_y >= (b->y + b->height)) || (region->area == 0u) ||
               (region->area > (b->width * b->height))) {
        ok = 0;
    } else {
        /* inside */
    }
    return ok;
}

/* The fill's view of a region's box (one entry on the stack, nothing filled yet). */
static void mask_fill_init(mask_fill_t *f, const sbr_image_t *map, const sbr_mser_region_t *region,
                           uint8_t *mask, uint32_t mask_stride, uint32_t *stack)
{
    const sbr_rect_t *b = &region->bbox;
    f->map = &map->data[((size_t)b->y * map->stride) + b->x];
    f->mask = mask;
    f->map_stride = map->stride;
    f->mask_stride = mask_stride;
    f->stack = stack;
    f->sp = 1u;
    f->filled = 0u;
    f->level = region_flip(region, &f->flip);
}

/* Flood fill of the region's pixels from its seed (already set in the mask and pushed);
   returns the number of pixels filled. */
static uint32_t mask_fill(const sbr_image_t *map, const sbr_mser_region_t *region, uint8_t *mask,
                          uint32_t mask_stride, uint32_t *stack)
{
    const sbr_rect_t *b = &region->bbox;
    mask_fill_t f;
    mask_fill_init(&f, map, region, mask, mask_stride, stack);
    f.filled = 1u;
    while (f.sp > 0u) {
        /* stack entries pack (y, x) in 16 bits each (region boxes are below 65536 px) */
        uint32_t lx;
        uint32_t ly;
        f.sp--;
        ly = stack[f.sp] >> 16;
        lx = stack[f.sp] & 0xFFFFu;
        if ((lx + 1u) < b->width) {
            mask_grow(&f, lx + 1u, ly);
        }
        if ((ly + 1u) < b->height) {
            mask_grow(&f, lx, ly + 1u);
        }
        if (lx > 0u) {
            mask_grow(&f, lx - 1u, ly);
        }
        if (ly > 0u) {
            mask_grow(&f, lx, ly - 1u);
        }
    }
    return f.filled;
}


/* A seed for every stretch of region pixels among columns [l, r] of box row y; 0 when the
   stack (cap entries) is full. */
static int run_seeds(mask_fill_t *f, uint32_t l, uint32_t r, uint32_t y, uint32_t cap)
{
    uint32_t x = l;
    int ok = 1;
    while (x <= r) {
        if (run_in(f, x, y) == 0) {
            x++;
        } else {
            if (f->sp >= cap) {
                ok = 0;
            } else {
                f->stack[f->sp] = (y << 16) | x;
                f->sp++;
            }
            x++;
            while ((x <= r) && (run_in(f, x, y) != 0)) {
                x++;
            }
        }
    }
    return ok;
}

/* mask_fill() a row stretch at a time: each stretch of the region is filled in the mask
   and its neighbour rows searched once (the same pixels as the pixel-by-pixel fill).
   Returns the pixels filled, or 0 when the stack (cap entries) ran out. */
static uint32_t mask_fill_runs(const sbr_image_t *map, const sbr_mser_region_t *region,
                               uint8_t *mask, uint32_t mask_stride, uint32_t *stack, uint32_t cap)
{
    const sbr_rect_t *b = &region->bbox;
    mask_fill_t f;
    int ok = 1;
    mask_fill_init(&f, map, region, mask, mask_stride, stack);
    stack[0] = (((uint32_t)region->seed_y - b->y) << 16) | ((uint32_t)region->seed_x - b->x);
    while ((f.sp > 0u) && (ok != 0)) {
        uint32_t y;
        uint32_t l;
        uint32_t r;
        f.sp--;
        y = stack[f.sp] >> 16;
        l = stack[f.sp] & 0xFFFFu;
        r = l;
        if (run_in(&f, l, y) != 0) {
            while ((l > 0u) && (run_in(&f, l - 1u, y) != 0)) {
                l--;
            }
            while (((r + 1u) < b->width) && (run_in(&f, r + 1u, y) != 0)) {
                r++;
            }
            (void)memset(&mask[((size_t)y * mask_stride) + l], 255, ((size_t)r - (size_t)l) + 1u);
            f.filled += (r - l) + 1u;
            if (y > 0u) {
                ok = run_seeds(&f, l, r, y - 1u, cap);
            }
            if ((ok != 0) && ((y + 1u) < b->height)) {
                ok = run_seeds(&f, l, r, y + 1u, cap);
            }
        }
    }
    return (ok != 0) ? f.filled : 0u;
}

sbr_status_t sbr_mser_region_mask(const sbr_image_t *map, const sbr_mser_region_t *region,
                                  void *workspace, size_t workspace_size, uint8_t *mask,
                                  uint32_t mask_stride, size_t mask_size)
{
    sbr_status_t st;
    const sbr_rect_t *b;
    uint32_t *stack;
    uint32_t y;
    uint32_t filled;

    if ((map == NULL) || (region == NULL) || (mask == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_image_check(map);
    if (st != SBR_OK) {
        return st;
    }
    if ((map->format != SBR_PIXEL_GRAY8) || (map->width < 3u) || (map->height < 3u) ||
        (region_in_map(map, region) == 0)) {
        return SBR_ERR_RANGE;
    }
    b = &region->bbox;
    if ((mask_stride < b->width) ||
        (mask_size < (((size_t)(b->height - 1u) * mask_stride) + (size_t)b->width))) {
        return SBR_ERR_ALIGN;
    }
    if ((workspace == NULL) ||
        (workspace_size < SBR_MSER_MASK_WORKSPACE_SIZE(b->width, b->height)) ||
        (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    stack = (uint32_t *)workspace;
    for (y = 0u; y < b->height; y++) {
        (void)memset(&mask[(size_t)y * mask_stride], 0, (size_t)b->width);
    }
    {
        uint8_t flip;
        const uint8_t level = region_flip(region, &flip);
        if ((uint8_t)(map->data[((size_t)region->seed_y * map->stride) + region->seed_x] ^ flip) >
            level) {
            return SBR_ERR_CORRUPT;
        }
    }
    filled = mask_fill_runs(map, region, mask, mask_stride, stack,
                            (uint32_t)((size_t)b->width * (size_t)b->height));
    if (filled == 0u) {
        /* the stretches' seeds did not fit: the pixel-by-pixel fill, from a clear mask */
        const uint32_t sx = (uint32_t)region->seed_x - b->x;
        const uint32_t sy = (uint32_t)region->seed_y - b->y;
        for (y = 0u; y < b->height; y++) {
            (void)memset(&mask[(size_t)y * mask_stride], 0, (size_t)b->width);
        }
        mask[((size_t)sy * mask_stride) + sx] = 255u;
        stack[0] = (sy << 16) | sx;
        filled = mask_fill(map, region, mask, mask_stride, stack);
    }
    if (filled != region->area) {
        return SBR_ERR_CORRUPT;
    }
    return SBR_OK;
}
