/* SPDX-License-Identifier: MIT */
/* MSER's pixel words (mser_internal.h): one pass's levels from the map or the last pass's,
   walls and the border, and the map written back after the last pass. */
#include "mser_internal.h"

/* The (inverted) copy of the map; with a level limit (values above `limit` of the
   possibly inverted map) those pixels are walls, reached from the start like the border,
   so no flood enters them. Walls keep their level under LEV_WALL. In place (map->data
   the second half of c->lev, stride the width), every row is read before its words are
   written: word i covers bytes 2i and 2i + 1 of the block, below the unread map bytes
   from wh + i + 1 on. */
static void pass_copy(mser_ctx_t *c, const sbr_image_t *map, uint8_t xor_mask, uint32_t limit)
{
    const uint32_t w = c->width;
    const uint32_t h = c->height;
    uint32_t y;
    for (y = 0u; y < h; y++) {
        const uint8_t *src = &map->data[(size_t)y * map->stride];
        uint16_t *g = &c->lev[(size_t)y * w];
        uint32_t x;
        if (limit < (MSER_LEVELS - 1u)) {
            for (x = 0u; x < w; x++) {
                const uint32_t v = (uint32_t)src[x] ^ (uint32_t)xor_mask;
                g[x] = (uint16_t)((v > limit) ? (LEV_WALL | v) : v);
            }
        } else {
            for (x = 0u; x < w; x++) {
                g[x] = (uint16_t)((uint32_t)src[x] ^ (uint32_t)xor_mask);
            }
        }
    }
}

/* The next pass's levels from the last pass's (its levels under the flags, `flip` the
   change of inversion), walls as pass_copy(). */
static void pass_relevel(mser_ctx_t *c, uint8_t flip, uint32_t limit)
{
    const size_t n = (size_t)c->width * (size_t)c->height;
    size_t i;
    for (i = 0u; i < n; i++) {
        const uint32_t v = ((uint32_t)c->lev[i] & LEV_LEVEL) ^ (uint32_t)flip;
        c->lev[i] = (uint16_t)(((limit < (MSER_LEVELS - 1u)) && (v > limit)) ? (LEV_WALL | v) : v);
    }
}

/* Prepare one pass: the (inverted) levels with the border walled off, and the heap empty
   (every level without a chunk, every chunk unused). map NULL: from the last pass's
   levels in c->lev, inverted when `flip`. */
void sbr_mser_priv_pass_setup(mser_ctx_t *c, const sbr_image_t *map, uint8_t xor_mask, uint8_t flip,
                              uint32_t limit)
{
    const uint32_t w = c->width;
    const uint32_t h = c->height;
    uint32_t v;

    if (map != NULL) {
        pass_copy(c, map, xor_mask, limit);
    } else {
        pass_relevel(c, flip, limit);
    }
    /* the border is reached from the start (a wall that keeps its level), so the flood
       never enters it */
    {
        uint32_t i;
        uint32_t y;
        for (i = 0u; i < w; i++) {
            c->lev[i] = (uint16_t)((uint32_t)c->lev[i] | LEV_WALL);
            c->lev[((h - 1u) * w) + i] = (uint16_t)((uint32_t)c->lev[((h - 1u) * w) + i] | LEV_WALL);
        }
        for (y = 1u; y < (h - 1u); y++) {
            c->lev[y * w] = (uint16_t)((uint32_t)c->lev[y * w] | LEV_WALL);
            c->lev[(y * w) + (w - 1u)] = (uint16_t)((uint32_t)c->lev[(y * w) + (w - 1u)] | LEV_WALL);
        }
    }
    for (v = 0u; v < MSER_LEVELS; v++) {
        c->heap_top[v] = MSER_NONE;
    }
    c->heap_free = MSER_NONE;
    c->heap_next = 0u;
    c->heap_full = 0;
    c->node_count = 0u;
}

/* After the last pass: the map back at the start of c->lev, byte i from word i (bytes
   2i and 2i + 1, not yet overwritten: four words are read before their four bytes, which
   lie in words below i, are written); `last` the inversion the levels have. */
void sbr_mser_priv_map_back(mser_ctx_t *c, uint8_t last)
{
    uint8_t *const out = (uint8_t *)(void *)c->lev;
    const uint16_t *const lev = c->lev;
    const size_t n = (size_t)c->width * (size_t)c->height;
    const uint32_t x = (uint32_t)last;
    size_t i;
    for (i = 0u; (i + 4u) <= n; i += 4u) {
        const uint32_t v0 = ((uint32_t)lev[i] & LEV_LEVEL) ^ x;
        const uint32_t v1 = ((uint32_t)lev[i + 1u] & LEV_LEVEL) ^ x;
        const uint32_t v2 = ((uint32_t)lev[i + 2u] & LEV_LEVEL) ^ x;
        const uint32_t v3 = ((uint32_t)lev[i + 3u] & LEV_LEVEL) ^ x;
        out[i] = (uint8_t)v0;
        out[i + 1u] = (uint8_t)v1;
        out[i + 2u] = (uint8_t)v2;
        out[i + 3u] = (uint8_t)v3;
    }
    for (; i < n; i++) {
        out[i] = (uint8_t)(((uint32_t)lev[i] & LEV_LEVEL) ^ x);
    }
}
