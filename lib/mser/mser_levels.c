/* SPDX-License-Identifier: MIT */
/* MSER's pixel words (mser_internal.h): one pass's levels from the map or the last pass's,
   walls and the border, and the map written back after the last pass. */
#include "mser_internal.h"

/* Pixels a block of the level loops below: fixed-size blocks through local arrays, which
   compilers turn into vector code on SIMD hosts (16 pixels: one 16-byte load, two 16-byte
   stores), the pixels left over one by one with the same arithmetic; on a core without
   SIMD (SBR_UTIL_SCALAR_CORE) every pixel one by one. */
#define LEV_BLOCK 16u

/* One pixel's level word: v (a level, possibly inverted) over the wall flags when v is
   above `limit` (a level; 255: no wall). */
static uint16_t level_word(uint8_t v, uint8_t limit)
{
    const uint8_t hi = (v > limit) ? (uint8_t)(LEV_WALL >> 8u) : 0u;
    return (uint16_t)(((uint32_t)hi << 8u) | (uint32_t)v);
}

/* The (inverted) copy of the map; with a level limit (values above `limit` of the
   possibly inverted map) those pixels are walls, reached from the start like the border,
   so no flood enters them. Walls keep their level under LEV_WALL. In place (map->data
   the second half of c->lev, stride the width), every row is read before its words are
   written: a block's 16 bytes are read before its 16 words are written, which lie below
   the unread map bytes (word i covers bytes 2i and 2i + 1, below byte wh + i + 1). */
static void pass_copy(mser_ctx_t *c, const sbr_image_t *map, uint8_t xor_mask, uint32_t limit)
{
    const uint32_t w = c->width;
    const uint32_t h = c->height;
    const uint8_t lim = (uint8_t)((limit < (MSER_LEVELS - 1u)) ? limit : (MSER_LEVELS - 1u));
    uint32_t y;
    for (y = 0u; y < h; y++) {
        const uint8_t *src = &map->data[(size_t)y * map->stride];
        uint16_t *g = &c->lev[(size_t)y * w];
        uint32_t x = 0u;
#if SBR_UTIL_SCALAR_CORE == 0
        while ((x + LEV_BLOCK) <= w) {
            uint8_t t[LEV_BLOCK];
            uint16_t o[LEV_BLOCK];
            uint32_t i;
            (void)memcpy(t, &src[x], sizeof t);
            for (i = 0u; i < LEV_BLOCK; i++) {
                o[i] = level_word((uint8_t)(t[i] ^ xor_mask), lim);
            }
            (void)memcpy(&g[x], o, sizeof o);
            x += LEV_BLOCK;
        }
#endif
        if (lim < (uint8_t)(MSER_LEVELS - 1u)) {
            while (x < w) {
                g[x] = level_word((uint8_t)(src[x] ^ xor_mask), lim);
                x++;
            }
        } else {
            while (x < w) {
                g[x] = (uint16_t)(uint8_t)(src[x] ^ xor_mask); /* no walls */
                x++;
            }
        }
    }
}

/* The next pass's levels from the last pass's (its levels under the flags, `flip` the
   change of inversion), walls as pass_copy(). */
static void pass_relevel(mser_ctx_t *c, uint8_t flip, uint32_t limit)
{
    const size_t n = (size_t)c->width * (size_t)c->height;
    const uint8_t lim = (uint8_t)((limit < (MSER_LEVELS - 1u)) ? limit : (MSER_LEVELS - 1u));
    size_t i = 0u;
#if SBR_UTIL_SCALAR_CORE == 0
    while ((i + LEV_BLOCK) <= n) {
        uint16_t t[LEV_BLOCK];
        uint32_t j;
        (void)memcpy(t, &c->lev[i], sizeof t);
        for (j = 0u; j < LEV_BLOCK; j++) {
            t[j] = level_word((uint8_t)(((uint32_t)t[j] & LEV_LEVEL) ^ (uint32_t)flip), lim);
        }
        (void)memcpy(&c->lev[i], t, sizeof t);
        i += LEV_BLOCK;
    }
#endif
    while (i < n) {
        c->lev[i] = level_word((uint8_t)(((uint32_t)c->lev[i] & LEV_LEVEL) ^ (uint32_t)flip), lim);
        i++;
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
    mser_heap_clear(c);
    c->heap_free = MSER_NONE;
    c->heap_next = 0u;
    c->heap_full = 0;
    c->node_count = 0u;
}

/* After the last pass: the map back at the start of c->lev, byte i from word i (bytes
   2i and 2i + 1: a block's 16 words are read before its 16 bytes, which lie below them
   or in them, are written); `last` the inversion the levels have. */
void sbr_mser_priv_map_back(mser_ctx_t *c, uint8_t last)
{
    uint8_t *const out = (uint8_t *)(void *)c->lev;
    const size_t n = (size_t)c->width * (size_t)c->height;
    size_t i = 0u;
#if SBR_UTIL_SCALAR_CORE == 0
    while ((i + LEV_BLOCK) <= n) {
        uint16_t t[LEV_BLOCK];
        uint8_t o[LEV_BLOCK];
        uint32_t j;
        (void)memcpy(t, &c->lev[i], sizeof t);
        for (j = 0u; j < LEV_BLOCK; j++) {
            o[j] = (uint8_t)((uint32_t)t[j] ^ (uint32_t)last);
        }
        (void)memcpy(&out[i], o, sizeof o);
        i += LEV_BLOCK;
    }
#endif
    while (i < n) {
        out[i] = (uint8_t)(((uint32_t)c->lev[i] & LEV_LEVEL) ^ (uint32_t)last);
        i++;
    }
}
