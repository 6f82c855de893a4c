/* SPDX-License-Identifier: MIT */
/*
 * Maximally stable extremal regions: one flood fill per polarity builds the component
 * tree (Nistér–Stewénius), nodes of area >= min_area are kept with the area of their
 * region delta levels below; a second, linear pass over those nodes computes the
 * variations and selects the stable ones (mser_select.c). See include/sbr/mser.h for the
 * definitions.
 */
#include "mser_internal.h"

void sbr_mser_config_default(sbr_mser_config_t *cfg)
{
    if (cfg != NULL) {
        cfg->delta = 5u;
        cfg->min_area = 60u;
        cfg->max_area = 14400u;
        cfg->max_variation = 0.25f;
        cfg->min_diversity = 0.2f;
        cfg->polarity = (uint32_t)SBR_MSER_BOTH;
        cfg->max_nodes = 0u;
        cfg->dark_max = 255u;
        cfg->bright_min = 0u;
        cfg->max_heap = 0u;
    }
}

sbr_status_t sbr_mser_config_check(const sbr_mser_config_t *cfg)
{
    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    if ((cfg->delta == 0u) || (cfg->delta > SBR_MSER_MAX_DELTA) || (cfg->min_area == 0u) ||
        (cfg->max_area < cfg->min_area)) {
        return SBR_ERR_RANGE;
    }
    /* Written so that NaN fails every test. */
    if (!((cfg->max_variation > 0.0f) && (cfg->max_variation <= 1.0e30f))) {
        return SBR_ERR_RANGE;
    }
    if (!((cfg->min_diversity >= 0.0f) && (cfg->min_diversity < 1.0f))) {
        return SBR_ERR_RANGE;
    }
    if ((cfg->polarity == 0u) || (cfg->polarity > (uint32_t)SBR_MSER_BOTH) ||
        (cfg->dark_max > 255u) || (cfg->bright_min > 255u)) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

static size_t mser_nodes_for(uint32_t width, uint32_t height, const sbr_mser_config_t *cfg)
{
    size_t n = SBR_MSER_WORST_NODES(width, height);
    if ((cfg->max_nodes != 0u) && ((size_t)cfg->max_nodes < n)) {
        n = (size_t)cfg->max_nodes;
    }
    return n;
}

/* Chunks of the boundary heap (SBR_MSER_HEAP_CHUNKS of SBR_MSER_HEAP). */
static size_t mser_heap_chunks_for(uint32_t width, uint32_t height, const sbr_mser_config_t *cfg)
{
    size_t n = SBR_MSER_WORST_NODES(width, height);
    if ((cfg->max_heap != 0u) && ((size_t)cfg->max_heap < n)) {
        n = (size_t)cfg->max_heap;
    }
    return SBR_MSER_HEAP_CHUNKS(n);
}

size_t sbr_mser_workspace_size(const sbr_mser_config_t *cfg, uint32_t width, uint32_t height)
{
    if ((sbr_mser_config_check(cfg) != SBR_OK) || (width < 3u) || (height < 3u) ||
        (width > SBR_IMAGE_MAX_DIM) || (height > SBR_IMAGE_MAX_DIM)) {
        return 0u;
    }
    {
        const size_t pixels = (size_t)width * (size_t)height;
        const size_t nodes = mser_nodes_for(width, height, cfg) * (size_t)SBR_MSER_NODE_BYTES;
        const size_t ring = ((size_t)cfg->delta + 1u) * (size_t)SBR_MSER_HISTORY_BYTES;
        const size_t per_comp = (size_t)SBR_MSER_COMP_BYTES + ring;
        const size_t heap = mser_heap_chunks_for(width, height, cfg) * (size_t)SBR_MSER_HEAP_CHUNK * 4u;
        return (size_t)SBR_MSER_HEAP_HEADER_BYTES + ((size_t)SBR_MSER_STACK * per_comp) + nodes +
               heap + (pixels * (size_t)SBR_MSER_PIXEL_BYTES) + (size_t)SBR_MSER_TAIL_BYTES;
    }
}

/* ---- the flood fill ----------------------------------------------------------------- */

static void comp_init(mser_ctx_t *c, uint32_t k, uint32_t level)
{
    mser_comp_t *cp = &c->comp[k];
    cp->size = 0u;
    cp->seed = 0u;
    cp->pend_head = MSER_NONE;
    cp->pend_tail = MSER_NONE;
    cp->level = (uint16_t)level;
    cp->pad = 0u;
    cp->ring_len = 0u;
}

static void comp_add_pixel(mser_comp_t *cp, uint32_t p)
{
    if (cp->size == 0u) {
        cp->seed = p;
    }
    cp->size++;
}

/* Append (val, size) to component k's main-chain history, keeping the newest ring_cap. */
static void ring_push(mser_ctx_t *c, uint32_t k, uint32_t val, uint32_t size)
{
    uint32_t *rs = &c->ring_size[k * c->ring_cap];
    uint16_t *rv = &c->ring_val[k * c->ring_cap];
    uint32_t len = c->comp[k].ring_len;

    if (len == c->ring_cap) {
        uint32_t i;
        for (i = 1u; i < len; i++) {
            rs[i - 1u] = rs[i];
            rv[i - 1u] = rv[i];
        }
        len--;
    }
    rs[len] = size;
    rv[len] = (uint16_t)val;
    c->comp[k].ring_len = len + 1u;
}

static void ring_copy(mser_ctx_t *c, uint32_t dst, uint32_t src)
{
    const uint32_t len = c->comp[src].ring_len;
    (void)memcpy(&c->ring_size[dst * c->ring_cap], &c->ring_size[src * c->ring_cap],
                 (size_t)len * sizeof(uint32_t));
    (void)memcpy(&c->ring_val[dst * c->ring_cap], &c->ring_val[src * c->ring_cap],
                 (size_t)len * sizeof(uint16_t));
    c->comp[dst].ring_len = len;
}

/* Component k leaves its level for new_level (> level): its node at the old level is
   complete. */
static void comp_grow(mser_ctx_t *c, uint32_t k, uint32_t new_level)
{
    mser_comp_t *cp = &c->comp[k];
    const uint32_t level = (uint32_t)cp->level;

    ring_push(c, k, level, cp->size);
    if (cp->size >= c->min_area) {
        /* first main-chain node at or above level - delta */
        const uint32_t *rs = &c->ring_size[k * c->ring_cap];
        const uint16_t *rv = &c->ring_val[k * c->ring_cap];
        uint32_t lo_size;
        uint32_t i = cp->ring_len - 1u;
        while ((i > 0u) && (((uint32_t)rv[i - 1u] + c->delta) >= level)) {
            i--;
        }
        lo_size = rs[i];
        if (c->node_count < c->node_cap) {
            mser_node_t *nd;
            uint32_t q;
            const uint32_t n = c->node_count;
            c->node_count++;
            nd = &c->node[n];
            nd->parent = MSER_NONE;
            nd->next = MSER_NONE;
            nd->size = cp->size;
            nd->size_lo = lo_size;
            nd->seed = cp->seed;
            nd->var = 0.0f;
            nd->child_var = 3.0e38f;
            nd->val = (uint8_t)level;
            nd->flags = 0u;
            nd->pad[0] = 0u;
            nd->pad[1] = 0u;
            q = cp->pend_head;
            while (q != MSER_NONE) {
                c->node[q].parent = n;
                q = c->node[q].next;
            }
            cp->pend_head = n;
            cp->pend_tail = n;
        } else {
            /* Out of nodes: this node is lost, its children become roots. */
            c->overflow = 1;
            cp->pend_head = MSER_NONE;
            cp->pend_tail = MSER_NONE;
        }
    }
    cp->level = (uint16_t)new_level;
}

/* The top component b (lower level) joins a (level == the new level). */
static void comp_merge(mser_ctx_t *c, uint32_t a, uint32_t b)
{
    mser_comp_t *ca = &c->comp[a];
    const mser_comp_t *cb = &c->comp[b];
    int keep_a;

    comp_grow(c, b, (uint32_t)ca->level);
    /* The main chain continues through the larger of the two histories (b on a tie). */
    keep_a = 0;
    if (ca->ring_len > 0u) {
        const uint32_t sa = c->ring_size[(a * c->ring_cap) + (ca->ring_len - 1u)];
        const uint32_t sb = c->ring_size[(b * c->ring_cap) + (cb->ring_len - 1u)];
        if (sa > sb) {
            keep_a = 1;
        }
    }
    if (keep_a == 0) {
        ring_copy(c, a, b);
    }
    if (cb->pend_head != MSER_NONE) {
        if (ca->pend_head == MSER_NONE) {
            ca->pend_head = cb->pend_head;
        } else {
            c->node[ca->pend_tail].next = cb->pend_head;
        }
        ca->pend_tail = cb->pend_tail;
    }
    if (ca->size == 0u) {
        ca->seed = cb->seed;
    }
    ca->size += cb->size;
}

/* The boundary heap: one stack per level, each a list of chunks of HEAP_ENTRIES entries
   taken from a shared pool, so that the pixels waiting at once, not the pixels of each
   level, size it. heap_top[level] is the pool index of the level's next free slot in its
   top chunk: at a chunk's link word (index & HEAP_LINK_MASK == HEAP_ENTRIES) when that
   chunk is full, MSER_NONE (the same low bits) when the level has no chunk; either way
   the next push takes a new chunk. A chunk emptied goes to the free list. */
static uint32_t heap_chunk(mser_ctx_t *c, uint32_t i, uint32_t level)
{
    /* a new top chunk (a freed one, else the next unused one) linked to the full one at
       i, or to none; its first slot, or MSER_NONE at the bound */
    uint32_t fresh = c->heap_free;
    uint32_t slot = MSER_NONE;
    if (fresh != MSER_NONE) {
        c->heap_free = c->heap[(fresh * SBR_MSER_HEAP_CHUNK) + HEAP_ENTRIES];
    } else if (c->heap_next < c->heap_chunks) {
        fresh = c->heap_next;
        c->heap_next++;
    } else if (c->heap_full == 0) {
        /* the bound: the flood stops at its next pop, which finds every level empty (no
           test per pixel); a lost entry could otherwise leave the component stack out of
           level order. heap_next stays at the bound until flood_stopped(). */
        mser_heap_clear(c);
        c->overflow = 1;
        c->heap_full = 1;
    } else {
        /* stopped already */
    }
    if (fresh != MSER_NONE) {
        slot = fresh * SBR_MSER_HEAP_CHUNK;
        if (i == MSER_NONE) {
            c->heap[slot + HEAP_ENTRIES] = MSER_NONE;
            c->busy[level / 32u] |= 1u << (level % 32u); /* the level's first chunk */
        } else {
            c->heap[slot + HEAP_ENTRIES] = i / SBR_MSER_HEAP_CHUNK;
        }
    }
    return slot;
}

static inline void heap_push(mser_ctx_t *c, uint32_t *heap, uint32_t level, uint32_t e)
{
    uint32_t i = c->heap_top[level];
    if ((i & HEAP_LINK_MASK) == HEAP_ENTRIES) {
        i = heap_chunk(c, i, level);
    }
    if (i != MSER_NONE) {
        heap[i] = e;
        c->heap_top[level] = i + 1u;
    }
}

/* The emptied chunk of slot i to the free list; the one below it (full) becomes the
   level's top, or the level has none. */
static void heap_release(mser_ctx_t *c, uint32_t level, uint32_t i)
{
    const uint32_t below = c->heap[i + HEAP_ENTRIES];
    c->heap_top[level] =
        (below == MSER_NONE) ? MSER_NONE : ((below * SBR_MSER_HEAP_CHUNK) + HEAP_ENTRIES);
    c->heap[i + HEAP_ENTRIES] = c->heap_free;
    c->heap_free = i / SBR_MSER_HEAP_CHUNK;
}

/* The top entry of a level that has one (heap_top[level] != MSER_NONE). */
static inline uint32_t heap_pop(mser_ctx_t *c, uint32_t level)
{
    const uint32_t i = c->heap_top[level] - 1u;
    const uint32_t e = c->heap[i];
    if ((i & HEAP_LINK_MASK) == 0u) {
        heap_release(c, level, i);
    } else {
        c->heap_top[level] = i;
    }
    return e;
}

/* The index of the lowest set bit of x != 0 (a de Bruijn sequence: x & -x times the
   constant has a distinct top five bits for each of the 32 powers of two). */
static uint32_t lowest_bit(uint32_t x)
{
    static const uint8_t k_pos[32] = {0u,  1u,  28u, 2u,  29u, 14u, 24u, 3u,  30u, 22u, 20u,
                                      15u, 25u, 17u, 4u,  8u,  31u, 27u, 13u, 23u, 21u, 19u,
                                      16u, 7u,  26u, 12u, 18u, 6u,  11u, 5u,  10u, 9u};
    return (uint32_t)k_pos[((x & (0u - x)) * 0x077CB531u) >> 27];
}

/* The lowest level >= from with waiting pixels, or MSER_LEVELS if none: the first v >=
   from with heap_top[v] != MSER_NONE. busy[] has the bit of every such level (set with a
   level's first chunk) and may keep the bits of levels emptied since: those are cleared
   here when met. */
static uint32_t next_busy(mser_ctx_t *c, uint32_t from)
{
    uint32_t r = MSER_LEVELS;
    uint32_t v = from;
    while (v < MSER_LEVELS) {
        uint32_t wi = v / 32u;
        uint32_t word = c->busy[wi] & (0xFFFFFFFFu << (v % 32u));
        while ((word == 0u) && ((wi + 1u) < (MSER_LEVELS / 32u))) {
            wi++;
            word = c->busy[wi];
        }
        if (word == 0u) {
            v = MSER_LEVELS; /* none */
        } else {
            v = (wi * 32u) + lowest_bit(word);
            if (c->heap_top[v] != MSER_NONE) {
                r = v;
                v = MSER_LEVELS; /* found */
            } else {
                c->busy[wi] &= ~(1u << (v % 32u)); /* emptied since its bit was set */
                v++;
            }
        }
    }
    return r;
}

/* After a flood: if the heap's bound stopped it (what it had not taken stays unflooded;
   a lost entry would have left the component stack out of level order), the components
   still open join the ones below them (their levels rise down the stack towards the
   sentinel) and the heap is emptied for the next flood. Returns the new top. */
static uint32_t flood_stopped(mser_ctx_t *c, uint32_t top)
{
    uint32_t t = top;
    if (c->heap_full != 0) {
        while (t > 1u) {
            comp_merge(c, t - 1u, t);
            t--;
        }
        mser_heap_clear(c);
        c->heap_free = MSER_NONE;
        c->heap_next = 0u;
        c->heap_full = 0;
    }
    return t;
}

/* A neighbour q of the pixel being visited: when not yet reached it is marked, and when
   lower than the current level `cur` its level is returned (the flood descends into it);
   otherwise it waits in the heap at its level. MSER_NONE: no descent. */
static inline uint32_t flood_look(mser_ctx_t *c, uint16_t *lev, uint32_t *heap, uint32_t cur,
                                  uint32_t q)
{
    const uint32_t g = (uint32_t)lev[q];
    uint32_t lower = MSER_NONE;
    if (g < LEV_REACHED) {
        lev[q] = (uint16_t)(g | LEV_REACHED);
        if (g < cur) {
            lower = g;
        } else {
            heap_push(c, heap, g, (q << HEAP_DIR_BITS) | 1u);
        }
    }
    return lower;
}

/* Build the tree of the pixels connected to p (not yet reached): the whole interior when
   no pass limit walls parts of it off. A pixel's neighbours are looked at in the order
   right, below, left, above, from its entry's k (1..4; 5: none left); the flood comes
   back to a pixel it left for a lower neighbour at the next one. */
static void flood_from(mser_ctx_t *c, uint32_t start)
{
    const uint32_t w = c->width;
    uint16_t *const lev = c->lev;
    uint32_t *const heap = c->heap; /* a local: heap_chunk() cannot change it */
    uint32_t p = start;
    uint32_t k = 1u;
    uint32_t cur = (uint32_t)c->lev[p];
    uint32_t top = 1u;
    mser_comp_t *tc = &c->comp[1]; /* the top component, &c->comp[top] */
    int done = 0;

    comp_init(c, 0u, MSER_SENTINEL);
    comp_init(c, 1u, cur);
    c->lev[p] = (uint16_t)(cur | LEV_REACHED);
    while (done == 0) {
        uint32_t q = 0u;
        uint32_t g = MSER_NONE; /* a lower neighbour's level */
        if (k <= 1u) {
            q = p + 1u;
            g = flood_look(c, lev, heap, cur, q);
            k = 2u;
        }
        if ((g == MSER_NONE) && (k <= 2u)) {
            q = p + w;
            g = flood_look(c, lev, heap, cur, q);
            k = 3u;
        }
        if ((g == MSER_NONE) && (k <= 3u)) {
            q = p - 1u;
            g = flood_look(c, lev, heap, cur, q);
            k = 4u;
        }
        if ((g == MSER_NONE) && (k <= 4u)) {
            q = p - w;
            g = flood_look(c, lev, heap, cur, q);
            k = 5u;
        }
        if (g != MSER_NONE) {
            /* come back to p later (at its next neighbour), descend into q */
            heap_push(c, heap, cur, (p << HEAP_DIR_BITS) | k);
            p = q;
            top++;
            tc = &c->comp[top];
            comp_init(c, top, g);
            cur = g;
            k = 1u;
        } else {
            uint32_t e = 0u; /* the next heap entry */
            comp_add_pixel(tc, p);
            if (c->heap_top[cur] != MSER_NONE) {
                e = heap_pop(c, cur);
            } else {
                const uint32_t lv = next_busy(c, cur + 1u);
                if (lv >= MSER_LEVELS) {
                    done = 1;
                } else {
                    e = heap_pop(c, lv);
                    if (lv < (uint32_t)c->comp[top - 1u].level) {
                        comp_grow(c, top, lv);
                    } else {
                        /* the component below is at exactly this level (its pixel waits
                           in the heap): merge the top into it */
                        comp_merge(c, top - 1u, top);
                        top--;
                        tc = &c->comp[top];
                    }
                    cur = lv;
                }
            }
            p = e >> HEAP_DIR_BITS;
            k = e & HEAP_DIR_MASK;
        }
    }
    top = flood_stopped(c, top);
    while ((top > 0u) && ((uint32_t)c->comp[top].level != MSER_SENTINEL)) {
        comp_grow(c, top, MSER_SENTINEL);
        top--;
    }
}

/* Build the tree (a forest with walls) of one pass: one flood from the first interior
   pixel, and with walls (limit below 255) one from every interior pixel no earlier flood
   reached. */
static void pass_flood(mser_ctx_t *c, uint32_t limit)
{
    const uint32_t w = c->width;
    if (limit >= (MSER_LEVELS - 1u)) {
        flood_from(c, w + 1u);
    } else {
        /* the interior row by row, four words at a time while all four are reached (a
           wall, the border or flooded: LEV_REACHED set in each; p + 3 stays within the
           last row) */
        const uint16_t *const lev = c->lev;
        const uint32_t end = (c->height - 1u) * w;
        uint32_t p = w + 1u;
        while (p < end) {
            const uint32_t four = (uint32_t)lev[p] & (uint32_t)lev[p + 1u] &
                                  (uint32_t)lev[p + 2u] & (uint32_t)lev[p + 3u];
            if ((four & LEV_REACHED) != 0u) {
                p += 4u;
            } else {
                if ((uint32_t)c->lev[p] < LEV_REACHED) {
                    flood_from(c, p);
                }
                p++;
            }
        }
    }
}

/* The context of one detection over the workspace (layout of sbr_mser_workspace_size()),
   with the exact division by the width (2^shift > width^2 * height). */
static void mser_ctx_init(mser_ctx_t *c, uint32_t width, uint32_t height,
                          const sbr_mser_config_t *cfg, void *workspace)
{
    const size_t nodes = mser_nodes_for(width, height, cfg);
    const size_t chunks = mser_heap_chunks_for(width, height, cfg);
    const uint64_t span = (uint64_t)width * (uint64_t)width * (uint64_t)height;
    uint8_t *base = (uint8_t *)workspace;
    uint32_t bits = 1u;
    c->heap_top = (uint32_t *)(void *)base;
    base = &base[SBR_MSER_HEAP_HEADER_BYTES];
    c->comp = (mser_comp_t *)(void *)base;
    base = &base[(size_t)SBR_MSER_STACK * SBR_MSER_COMP_BYTES];
    c->ring_cap = cfg->delta + 1u;
    c->ring_size = (uint32_t *)(void *)base;
    base = &base[(size_t)SBR_MSER_STACK * c->ring_cap * 4u];
    c->ring_val = (uint16_t *)(void *)base;
    base = &base[(size_t)SBR_MSER_STACK * c->ring_cap * 4u];
    c->node = (mser_node_t *)(void *)base;
    base = &base[nodes * SBR_MSER_NODE_BYTES];
    c->heap = (uint32_t *)(void *)base;
    c->heap_chunks = (uint32_t)chunks;
    base = &base[chunks * SBR_MSER_HEAP_CHUNK * 4u];
    c->lev = (uint16_t *)(void *)base;
    c->width = width;
    c->height = height;
    c->node_cap = (uint32_t)nodes;
    c->node_count = 0u;
    c->delta = cfg->delta;
    c->min_area = cfg->min_area;
    c->overflow = 0;
    c->heap_full = 0;
    while ((bits < 63u) && ((((uint64_t)1u) << bits) <= span)) {
        bits++;
    }
    c->div_shift = bits;
    c->div_magic = ((((uint64_t)1u) << bits) / (uint64_t)width) + 1u;
}

/* Both passes of a configuration over a prepared context. map NULL: the map is in place
   (the second half of c->lev) and every pass after the first takes its levels from the
   last pass's; afterwards the map is back at the start of c->lev (stride the width). */
static sbr_status_t mser_run(mser_ctx_t *c, const sbr_image_t *map, const sbr_mser_config_t *cfg,
                             sbr_mser_region_t *regions, uint32_t capacity, uint32_t *count)
{
    sbr_image_t in_place;
    const sbr_image_t *src = map;
    uint8_t last = 0u; /* the inversion the levels in c->lev have */
    int full = 0;
    int overflow = 0;
    if (map == NULL) {
        in_place.width = c->width;
        in_place.height = c->height;
        in_place.stride = c->width;
        in_place.format = SBR_PIXEL_GRAY8;
        in_place.data = &((const uint8_t *)(const void *)c->lev)[(size_t)c->width * c->height];
        src = &in_place;
    }
    if ((cfg->polarity & (uint32_t)SBR_MSER_DARK) != 0u) {
        sbr_mser_priv_pass_setup(c, src, 0u, 0u, cfg->dark_max);
        pass_flood(c, cfg->dark_max);
        sbr_mser_priv_pass_select(c, cfg, (uint8_t)SBR_MSER_DARK, cfg->dark_max, regions,
                                  capacity, count, &full);
        overflow |= c->overflow;
        if (map == NULL) {
            src = NULL; /* the map's bytes are the levels' now */
        }
    }
    if ((cfg->polarity & (uint32_t)SBR_MSER_BRIGHT) != 0u) {
        const uint32_t limit = 255u - cfg->bright_min; /* in the inverted map's values */
        c->overflow = 0;
        sbr_mser_priv_pass_setup(c, src, 0xFFu, 0xFFu, limit);
        pass_flood(c, limit);
        sbr_mser_priv_pass_select(c, cfg, (uint8_t)SBR_MSER_BRIGHT, limit, regions, capacity,
                                  count, &full);
        overflow |= c->overflow;
        last = 0xFFu;
    }
    if (map == NULL) {
        sbr_mser_priv_map_back(c, last);
    }
    return ((full != 0) || (overflow != 0)) ? SBR_ERR_CAPACITY : SBR_OK;
}

/* The checks sbr_mser_detect() documents after the map's: configuration, size, capacity,
   workspace. */
static sbr_status_t mser_args_check(const sbr_mser_config_t *cfg, uint32_t width, uint32_t height,
                                    uint32_t capacity, const void *workspace, size_t workspace_size)
{
    sbr_status_t st = sbr_mser_config_check(cfg);
    if (st == SBR_OK) {
        if ((width < 3u) || (height < 3u) || (capacity == 0u)) {
            st = SBR_ERR_SIZE;
        } else if ((workspace == NULL) ||
                   (workspace_size < sbr_mser_workspace_size(cfg, width, height)) ||
                   (sbr_util_aligned(workspace, 4u) == 0)) {
            st = SBR_ERR_WORKSPACE;
        } else {
            /* fine */
        }
    }
    return st;
}

sbr_status_t sbr_mser_detect(const sbr_image_t *map, const sbr_mser_config_t *cfg,
                             void *workspace, size_t workspace_size,
                             sbr_mser_region_t *regions, uint32_t capacity, uint32_t *count)
{
    sbr_status_t st;
    mser_ctx_t c;

    if ((map == NULL) || (cfg == NULL) || (regions == NULL) || (count == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = sbr_image_check(map);
    if (st != SBR_OK) {
        return st;
    }
    if (map->format != SBR_PIXEL_GRAY8) {
        return SBR_ERR_RANGE;
    }
    st = mser_args_check(cfg, map->width, map->height, capacity, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    mser_ctx_init(&c, map->width, map->height, cfg, workspace);
    return mser_run(&c, map, cfg, regions, capacity, count);
}

uint8_t *sbr_mser_map_slot(const sbr_mser_config_t *cfg, uint32_t width, uint32_t height,
                           void *workspace, size_t workspace_size)
{
    mser_ctx_t c;
    uint8_t *slot = NULL;
    if ((cfg != NULL) && (mser_args_check(cfg, width, height, 1u, workspace, workspace_size) == SBR_OK)) {
        mser_ctx_init(&c, width, height, cfg, workspace);
        slot = &((uint8_t *)(void *)c.lev)[(size_t)width * height];
    }
    return slot;
}

sbr_status_t sbr_mser_detect_in_place(uint32_t width, uint32_t height, const sbr_mser_config_t *cfg,
                                      void *workspace, size_t workspace_size,
                                      sbr_mser_region_t *regions, uint32_t capacity,
                                      uint32_t *count, sbr_image_t *map)
{
    mser_ctx_t c;
    sbr_status_t st;
    if ((cfg == NULL) || (regions == NULL) || (count == NULL) || (map == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = mser_args_check(cfg, width, height, capacity, workspace, workspace_size);
    if (st == SBR_OK) {
        mser_ctx_init(&c, width, height, cfg, workspace);
        st = mser_run(&c, NULL, cfg, regions, capacity, count);
        map->width = width;
        map->height = height;
        map->stride = width;
        map->format = SBR_PIXEL_GRAY8;
        map->data = (const uint8_t *)(const void *)c.lev;
    }
    return st;
}
