/* SPDX-License-Identifier: MIT */
/* Private to lib/mser: the flood's working types (tree nodes, growing components, the
   context of one detection) shared by the flood (mser.c) and the selection
   (mser_select.c). Not installed. */
#ifndef SBR_MSER_INTERNAL_H
#define SBR_MSER_INTERNAL_H

#include "sbr/mser.h"

#include "../common/sbr_util.h"

#include <string.h>

#define MSER_NONE 0xFFFFFFFFu
#define MSER_LEVELS 256u
#define MSER_SENTINEL 256u
#define LEV_WALL 0xFF00u /* a wall or the border: every flag set over its level */
#define LEV_REACHED 0x100u /* the pixel was reached by this pass's flood */
#define LEV_BOXED 0x200u   /* the pixel is in the region whose box is being measured */
#define LEV_LEVEL 0xFFu
#define MSER_LIMIT_NONE 0xFFFFu /* no pass limit: every node's variation is known */

/* The flood keeps one 16-bit word per pixel: the map's level (inverted for the bright
   pass), with LEV_REACHED set once the pixel is reached (the image border and a pass's
   walls are LEV_WALL over their level from the start, which bounds the fill); one load tells whether a neighbour is new and
   its level. The level stays, so after the flood a selected node's pixels can be found
   again (a fill from its seed over levels <= its own): its bounding box is measured then,
   for the few selected nodes, not kept up per pixel. What else a pixel waiting in the heap needs travels with its heap entry:
   (pixel index << 3) | the next neighbour to look at (1 right, 2 down, 3 left, 4 up,
   5 none left); its level is the level of the stack it waits on. Pixel indices are below
   SBR_IMAGE_MAX_DIM^2 = 2^28, so an entry fits 32 bits. */
#define HEAP_DIR_BITS 3u
#define HEAP_DIR_MASK 7u
/* Entries of a heap chunk; its last word links to the chunk below it on its level (or to
   the next free chunk). */
#define HEAP_ENTRIES (SBR_MSER_HEAP_CHUNK - 1u)
#define HEAP_LINK_MASK (SBR_MSER_HEAP_CHUNK - 1u) /* a slot's place in its chunk */
/* the mask needs a power of two; MSER_NONE reads as a full chunk */
typedef char mser_heap_chunk_check[(((SBR_MSER_HEAP_CHUNK & HEAP_LINK_MASK) == 0u) &&
                                    ((MSER_NONE & HEAP_LINK_MASK) == HEAP_ENTRIES)) ? 1 : -1];

#define NODE_SELECTED 1u

/* A completed tree node of area >= min_area. */
typedef struct mser_node_s {
    uint32_t parent;  /* node index or MSER_NONE */
    uint32_t next;    /* next node in its owner's list of nodes still waiting for a parent */
    uint32_t size;    /* area at level val */
    uint32_t size_lo; /* area of the main-chain node delta levels below */
    uint32_t seed;    /* a pixel (index y * width + x) */
    float var;        /* variation */
    float child_var;  /* smallest variation among its children */
    uint8_t val;      /* level (in the pass's possibly inverted values) */
    uint8_t flags;
    uint8_t pad[2];
} mser_node_t;

/* A component on the flood's stack (levels strictly decrease towards the top). */
typedef struct mser_comp_s {
    uint32_t size;
    uint32_t seed;
    uint32_t pend_head; /* its completed nodes whose parent is not complete yet */
    uint32_t pend_tail;
    uint32_t ring_len;  /* entries of its main-chain history (oldest first) */
    uint16_t level;     /* 0..255, MSER_SENTINEL for the bottom entry */
    uint16_t pad;
} mser_comp_t;

/* The public size macro spells these sizes out; keep them true. */
typedef char mser_node_size_check[(sizeof(mser_node_t) == SBR_MSER_NODE_BYTES) ? 1 : -1];
typedef char mser_comp_size_check[(sizeof(mser_comp_t) == SBR_MSER_COMP_BYTES) ? 1 : -1];

typedef struct mser_ctx_s {
    uint32_t *heap_top;  /* [256] each level's next free slot in the heap, or MSER_NONE */
    mser_comp_t *comp;   /* [SBR_MSER_STACK] */
    uint32_t *ring_size; /* [SBR_MSER_STACK * ring_cap] main-chain areas */
    uint16_t *ring_val;  /* [SBR_MSER_STACK * ring_cap] their levels */
    mser_node_t *node;   /* [node_cap] */
    uint32_t *heap;      /* [heap_chunks * SBR_MSER_HEAP_CHUNK] the heap's chunks: entries
                            (HEAP_DIR_BITS), the link last; after the flood a list */
    uint32_t heap_chunks;
    uint32_t heap_free;  /* first free chunk of the free list, or MSER_NONE */
    uint32_t heap_next;  /* chunks below it have been used */
    uint16_t *lev;       /* [pixels] the map (inverted for the bright pass) with
                            LEV_REACHED once reached; the border and walls
                            LEV_WALL over their level */
    uint32_t width;
    uint32_t height;
    uint32_t ring_cap;   /* delta + 1 */
    uint32_t node_cap;
    uint32_t node_count;
    uint32_t delta;
    uint32_t min_area;
    uint32_t div_shift;  /* y = (p * div_magic) >> div_shift, exact for p < width * height */
    uint64_t div_magic;
    int overflow;
    int heap_full;       /* the heap's bound was reached in the flood in progress */
    uint32_t busy[MSER_LEVELS / 32u]; /* bit v of word v / 32 set: heap_top[v] != MSER_NONE
                                         (the next level with waiting pixels in a few steps) */
} mser_ctx_t;

/* Every level's stack empty (heap_top[] all MSER_NONE, busy[] clear). */
static inline void mser_heap_clear(mser_ctx_t *c)
{
    uint32_t v;
    for (v = 0u; v < MSER_LEVELS; v++) {
        c->heap_top[v] = MSER_NONE;
    }
    for (v = 0u; v < (MSER_LEVELS / 32u); v++) {
        c->busy[v] = 0u;
    }
}

/* Prepare one pass (mser_levels.c): the (inverted: xor_mask 0xFF) levels of `map`, or
   with map NULL the last pass's levels in c->lev inverted when `flip`; values above
   `limit` walls, the border walled off; the heap empty, no nodes. */
void sbr_mser_priv_pass_setup(mser_ctx_t *c, const sbr_image_t *map, uint8_t xor_mask, uint8_t flip,
                              uint32_t limit);

/* After the last pass of an in-place detection: the map back at the start of c->lev, a
   byte a pixel (`last`: the inversion the levels have). */
void sbr_mser_priv_map_back(mser_ctx_t *c, uint8_t last);

/* Variations, stable nodes, duplicates and the regions of one pass's tree (its pixels'
   levels still in c->lev); limit: the pass's level limit (0xFFFF none). */
void sbr_mser_priv_pass_select(mser_ctx_t *c, const sbr_mser_config_t *cfg, uint8_t polarity,
                               uint32_t limit, sbr_mser_region_t *regions, uint32_t capacity,
                               uint32_t *count, int *full);

#endif
