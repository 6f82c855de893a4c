/* SPDX-License-Identifier: MIT */
/*
 * Maximally stable extremal regions: one flood fill per polarity builds the component
 * tree (Nistér–Stewénius), nodes of area >= min_area are kept with the area of their
 * region delta levels below; a second, linear pass over those nodes computes the
 * variations and selects the stable ones. See include/sbr/mser.h for the definitions.
 */
#include "sbr/mser.h"

#include "../common/sbr_util.h"

#include <string.h>

#define MSER_NONE 0xFFFFFFFFu
#define MSER_LEVELS 256u
#define MSER_SENTINEL 256u
#define MSER_REACHED 0xFFFFu
#define LEV_REACHED 0x100u /* the pixel was reached by this pass's flood */
#define LEV_BOXED 0x200u   /* the pixel is in the region whose box is being measured */
#define LEV_LEVEL 0xFFu

/* The flood keeps one 16-bit word per pixel: the map's level (inverted for the bright
   pass), with LEV_REACHED set once the pixel is reached (the image border is MSER_REACHED
   from the start, which bounds the fill); one load tells whether a neighbour is new and
   its level. The level stays, so after the flood a selected node's pixels can be found
   again (a fill from its seed over levels <= its own): its bounding box is measured then,
   for the few selected nodes, not kept up per pixel. What else a pixel waiting in the heap needs travels with its heap entry:
   (pixel index << 3) | the next neighbour to look at (1 right, 2 down, 3 left, 4 up,
   5 none left); its level is the level of the stack it waits on. Pixel indices are below
   SBR_IMAGE_MAX_DIM^2 = 2^28, so an entry fits 32 bits. */
#define HEAP_DIR_BITS 3u
#define HEAP_DIR_MASK 7u

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
    uint32_t *heap_base; /* [256] first heap slot of each level */
    uint32_t *heap_top;  /* [256] entries on each level's stack */
    mser_comp_t *comp;   /* [SBR_MSER_STACK] */
    uint32_t *ring_size; /* [SBR_MSER_STACK * ring_cap] main-chain areas */
    uint16_t *ring_val;  /* [SBR_MSER_STACK * ring_cap] their levels */
    mser_node_t *node;   /* [node_cap] */
    uint32_t *heap;      /* [pixels] entries (HEAP_DIR_BITS) */
    uint16_t *lev;       /* [pixels] the map (inverted for the bright pass) with
                            LEV_REACHED once reached; the border MSER_REACHED */
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
} mser_ctx_t;

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
    if ((cfg->polarity == 0u) || (cfg->polarity > (uint32_t)SBR_MSER_BOTH)) {
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
        return (size_t)SBR_MSER_HEAP_HEADER_BYTES + ((size_t)SBR_MSER_STACK * per_comp) + nodes +
               (pixels * (size_t)SBR_MSER_PIXEL_BYTES) + (size_t)SBR_MSER_TAIL_BYTES;
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

static void heap_push(mser_ctx_t *c, uint32_t level, uint32_t p)
{
    c->heap[c->heap_base[level] + c->heap_top[level]] = p;
    c->heap_top[level]++;
}

static uint32_t heap_pop(mser_ctx_t *c, uint32_t level)
{
    c->heap_top[level]--;
    return c->heap[c->heap_base[level] + c->heap_top[level]];
}

/* Prepare one pass: the (inverted) copy of the map with its border reached, and the heap layout. The
   heap's layout needs the number of interior pixels per level: counted for the first
   pass; the second pass (same map, inverted) reads them off the first pass's layout,
   level v of the inverted map being level 255 - v of the map. */
static void pass_setup(mser_ctx_t *c, const sbr_image_t *map, uint8_t xor_mask, int second)
{
    const uint32_t w = c->width;
    const uint32_t h = c->height;
    const uint32_t interior = (w - 2u) * (h - 2u);
    uint32_t y;
    uint32_t v;
    uint32_t acc = 0u;

    if (second != 0) {
        /* heap_top[v] = count of level 255 - v of the first pass, from its layout */
        for (v = 0u; v < MSER_LEVELS; v++) {
            const uint32_t u = (MSER_LEVELS - 1u) - v;
            const uint32_t end = (u == (MSER_LEVELS - 1u)) ? interior : c->heap_base[u + 1u];
            c->heap_top[v] = end - c->heap_base[u];
        }
    } else {
        for (v = 0u; v < MSER_LEVELS; v++) {
            c->heap_top[v] = 0u;
        }
    }
    for (y = 0u; y < h; y++) {
        const uint8_t *src = &map->data[(size_t)y * map->stride];
        uint16_t *g = &c->lev[(size_t)y * w];
        uint32_t x;
        for (x = 0u; x < w; x++) {
            g[x] = (uint16_t)((uint32_t)src[x] ^ (uint32_t)xor_mask);
        }
        if ((second == 0) && (y > 0u) && (y < (h - 1u))) {
            for (x = 1u; x < (w - 1u); x++) {
                c->heap_top[g[x]]++; /* count per level for now */
            }
        }
    }
    /* the border is reached from the start, so the flood never enters it */
    {
        uint32_t i;
        for (i = 0u; i < w; i++) {
            c->lev[i] = (uint16_t)MSER_REACHED;
            c->lev[((h - 1u) * w) + i] = (uint16_t)MSER_REACHED;
        }
        for (y = 1u; y < (h - 1u); y++) {
            c->lev[y * w] = (uint16_t)MSER_REACHED;
            c->lev[(y * w) + (w - 1u)] = (uint16_t)MSER_REACHED;
        }
    }
    for (v = 0u; v < MSER_LEVELS; v++) {
        c->heap_base[v] = acc;
        acc += c->heap_top[v];
        c->heap_top[v] = 0u;
    }
    c->node_count = 0u;
}

/* Build the tree of one pass. */
static void pass_flood(mser_ctx_t *c)
{
    const uint32_t w = c->width;
    uint16_t *const lev = c->lev;
    uint32_t off[5];
    uint32_t p = w + 1u;
    uint32_t k = 1u;
    uint32_t cur = (uint32_t)c->lev[p];
    uint32_t top = 1u;
    int done = 0;

    off[0] = 0u;
    off[1] = 1u;
    off[2] = w;
    off[3] = 0xFFFFFFFFu;       /* unsigned wrap-around: adds -1 */
    off[4] = (0xFFFFFFFFu - w) + 1u; /* adds -w */

    comp_init(c, 0u, MSER_SENTINEL);
    comp_init(c, 1u, cur);
    c->lev[p] = (uint16_t)(cur | LEV_REACHED);
    while (done == 0) {
        uint32_t e; /* the next heap entry */
        while (k <= 4u) {
            const uint32_t q = p + off[k];
            const uint32_t g = (uint32_t)lev[q];
            if (g < LEV_REACHED) {
                lev[q] = (uint16_t)(g | LEV_REACHED);
                if (g < cur) {
                    /* a lower neighbour: come back to p later (at its next neighbour),
                       descend into q */
                    heap_push(c, cur, (p << HEAP_DIR_BITS) | (k + 1u));
                    p = q;
                    top++;
                    comp_init(c, top, g);
                    cur = g;
                    k = 1u;
                } else {
                    heap_push(c, g, (q << HEAP_DIR_BITS) | 1u);
                    k++;
                }
            } else {
                k++;
            }
        }
        comp_add_pixel(&c->comp[top], p);
        e = 0u;
        if (c->heap_top[cur] > 0u) {
            e = heap_pop(c, cur);
        } else {
            uint32_t lv = cur + 1u;
            while ((lv < MSER_LEVELS) && (c->heap_top[lv] == 0u)) {
                lv++;
            }
            if (lv >= MSER_LEVELS) {
                done = 1;
            } else {
                e = heap_pop(c, lv);
                if (lv < (uint32_t)c->comp[top - 1u].level) {
                    comp_grow(c, top, lv);
                } else {
                    /* the component below is at exactly this level (its pixel waits in
                       the heap): merge the top into it */
                    comp_merge(c, top - 1u, top);
                    top--;
                }
                cur = lv;
            }
        }
        p = e >> HEAP_DIR_BITS;
        k = e & HEAP_DIR_MASK;
    }
    while ((top > 0u) && ((uint32_t)c->comp[top].level != MSER_SENTINEL)) {
        comp_grow(c, top, MSER_SENTINEL);
        top--;
    }
}

/* Variations, selection and duplicate removal over the nodes of one pass; emits regions. */
/* Each node's variation (growth over delta levels relative to its size) and, in its
   parent, the smallest variation of its children. */
static void select_variation(mser_ctx_t *c)
{
    uint32_t n;
    for (n = 0u; n < c->node_count; n++) {
        mser_node_t *nd = &c->node[n];
        const uint32_t top_val = (uint32_t)nd->val + c->delta;
        uint32_t a = n;
        uint32_t grown;
        while ((c->node[a].parent != MSER_NONE) &&
               ((uint32_t)c->node[c->node[a].parent].val <= top_val)) {
            a = c->node[a].parent;
        }
        grown = c->node[a].size - nd->size_lo;
        nd->var = (float)grown / (float)nd->size;
        if ((nd->parent != MSER_NONE) && (nd->var < c->node[nd->parent].child_var)) {
            c->node[nd->parent].child_var = nd->var;
        }
    }
}

/* Stable nodes: small enough, variation within bounds and a local minimum against the
   children and the parent (children come before their parents, so child_var is
   complete here). */
static void select_stable(mser_ctx_t *c, const sbr_mser_config_t *cfg)
{
    uint32_t n;
    for (n = 0u; n < c->node_count; n++) {
        mser_node_t *nd = &c->node[n];
        int ok = 1;
        if ((nd->size > cfg->max_area) || (nd->var > cfg->max_variation) ||
            (nd->var > nd->child_var)) {
            ok = 0;
        }
        if ((ok != 0) && (nd->var > 0.0f) && (nd->parent != MSER_NONE) &&
            (nd->var >= c->node[nd->parent].var)) {
            ok = 0;
        }
        if (ok != 0) {
            nd->flags = NODE_SELECTED;
        }
    }
}

/* Diversity: of a selected node and its nearest selected ancestor that differ in size by
   less than min_diversity of the ancestor's, the less stable one is dropped. */
static void select_diverse(mser_ctx_t *c, float min_diversity)
{
    uint32_t n;
    for (n = 0u; n < c->node_count; n++) {
        mser_node_t *nd = &c->node[n];
        uint32_t a = MSER_NONE;
        if (nd->flags == NODE_SELECTED) {
            a = nd->parent;
            while ((a != MSER_NONE) && (c->node[a].flags != NODE_SELECTED)) {
                a = c->node[a].parent;
            }
        }
        if (a != MSER_NONE) {
            mser_node_t *an = &c->node[a];
            const uint32_t gap = an->size - nd->size;
            if ((float)gap >= (min_diversity * (float)an->size)) {
                /* diverse enough */
            } else if (an->var < nd->var) {
                nd->flags = 0u;
            } else {
                an->flags = 0u;
            }
        }
    }
}

/* The bounding box of a node's pixels, after its pass's flood: the 4-connected pixels of
   level <= its level around its seed (the component the flood grew), found again by a
   fill that lists them in the heap (free after the flood) and marks them LEV_BOXED until
   it is done. The border (MSER_REACHED) has every bit set, so the fill never enters it. */
static uint32_t box_visit(uint16_t *lev, uint32_t *list, uint32_t n, uint32_t q, uint32_t val)
{
    const uint32_t g = (uint32_t)lev[q];
    uint32_t m = n;
    if ((g < LEV_BOXED) && ((g & LEV_LEVEL) <= val)) {
        lev[q] = (uint16_t)(g | LEV_BOXED);
        list[n] = q;
        m = n + 1u;
    }
    return m;
}

static void node_bbox(mser_ctx_t *c, const mser_node_t *nd, sbr_rect_t *box)
{
    uint16_t *const lev = c->lev;
    uint32_t *const list = c->heap;
    const uint32_t w = c->width;
    const uint32_t val = (uint32_t)nd->val;
    uint32_t x0 = 0xFFFFFFFFu;
    uint32_t x1 = 0u;
    uint32_t p0 = 0xFFFFFFFFu; /* the first and last pixel in row order give the rows */
    uint32_t p1 = 0u;
    uint32_t n = 1u;
    uint32_t i;
    uint32_t y0;
    uint32_t y1;

    list[0] = nd->seed;
    lev[nd->seed] = (uint16_t)((uint32_t)lev[nd->seed] | LEV_BOXED);
    for (i = 0u; i < n; i++) {
        const uint32_t p = list[i];
        const uint32_t y = (uint32_t)(((uint64_t)p * c->div_magic) >> c->div_shift);
        const uint32_t x = p - (y * w);
        x0 = (x < x0) ? x : x0;
        x1 = (x > x1) ? x : x1;
        p0 = (p < p0) ? p : p0;
        p1 = (p > p1) ? p : p1;
        n = box_visit(lev, list, n, p + 1u, val);
        n = box_visit(lev, list, n, p + w, val);
        n = box_visit(lev, list, n, p - 1u, val);
        n = box_visit(lev, list, n, p - w, val);
    }
    for (i = 0u; i < n; i++) {
        lev[list[i]] = (uint16_t)((uint32_t)lev[list[i]] & ~LEV_BOXED);
    }
    y0 = (uint32_t)(((uint64_t)p0 * c->div_magic) >> c->div_shift);
    y1 = (uint32_t)(((uint64_t)p1 * c->div_magic) >> c->div_shift);
    box->x = x0;
    box->y = y0;
    box->width = (x1 - x0) + 1u;
    box->height = (y1 - y0) + 1u;
}

/* A selected node as a region of the given polarity. */
static void select_region(mser_ctx_t *c, const mser_node_t *nd, uint8_t polarity,
                          sbr_mser_region_t *r)
{
    const uint32_t sy = (uint32_t)(((uint64_t)nd->seed * c->div_magic) >> c->div_shift);
    node_bbox(c, nd, &r->bbox);
    r->area = nd->size;
    r->variation = nd->var;
    r->seed_x = (uint16_t)(nd->seed - (sy * c->width));
    r->seed_y = (uint16_t)sy;
    if (polarity == (uint8_t)SBR_MSER_DARK) {
        r->level = nd->val;
    } else {
        r->level = (uint8_t)(255u - (uint32_t)nd->val);
    }
    r->polarity = polarity;
}

static void pass_select(mser_ctx_t *c, const sbr_mser_config_t *cfg, uint8_t polarity,
                        sbr_mser_region_t *regions, uint32_t capacity, uint32_t *count,
                        int *full)
{
    uint32_t n;
    select_variation(c);
    select_stable(c, cfg);
    if (cfg->min_diversity > 0.0f) {
        select_diverse(c, cfg->min_diversity);
    }
    for (n = 0u; n < c->node_count; n++) {
        if (c->node[n].flags != NODE_SELECTED) {
            /* not a region */
        } else if (*count < capacity) {
            select_region(c, &c->node[n], polarity, &regions[*count]);
            (*count)++;
        } else {
            *full = 1;
        }
    }
}

/* The context of one detection over the workspace (layout of sbr_mser_workspace_size()),
   with the exact division by the width (2^shift > width^2 * height). */
static void mser_ctx_init(mser_ctx_t *c, const sbr_image_t *map, const sbr_mser_config_t *cfg,
                          void *workspace)
{
    const size_t pixels = (size_t)map->width * (size_t)map->height;
    const size_t nodes = mser_nodes_for(map->width, map->height, cfg);
    const uint64_t span = (uint64_t)map->width * (uint64_t)map->width * (uint64_t)map->height;
    uint8_t *base = (uint8_t *)workspace;
    uint32_t bits = 1u;
    c->heap_base = (uint32_t *)(void *)base;
    c->heap_top = &c->heap_base[MSER_LEVELS];
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
    base = &base[pixels * 4u];
    c->lev = (uint16_t *)(void *)base;
    c->width = map->width;
    c->height = map->height;
    c->node_cap = (uint32_t)nodes;
    c->node_count = 0u;
    c->delta = cfg->delta;
    c->min_area = cfg->min_area;
    c->overflow = 0;
    while ((bits < 63u) && ((((uint64_t)1u) << bits) <= span)) {
        bits++;
    }
    c->div_shift = bits;
    c->div_magic = ((((uint64_t)1u) << bits) / (uint64_t)map->width) + 1u;
}

sbr_status_t sbr_mser_detect(const sbr_image_t *map, const sbr_mser_config_t *cfg,
                             void *workspace, size_t workspace_size,
                             sbr_mser_region_t *regions, uint32_t capacity, uint32_t *count)
{
    sbr_status_t st;
    mser_ctx_t c;
    size_t need;
    int full = 0;
    int overflow = 0;
    int counted = 0; /* the dark pass counted the levels */

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
    st = sbr_mser_config_check(cfg);
    if (st != SBR_OK) {
        return st;
    }
    if ((map->width < 3u) || (map->height < 3u) || (capacity == 0u)) {
        return SBR_ERR_SIZE;
    }
    need = sbr_mser_workspace_size(cfg, map->width, map->height);
    if ((workspace == NULL) || (workspace_size < need) || (sbr_util_aligned(workspace, 4u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    mser_ctx_init(&c, map, cfg, workspace);
    if ((cfg->polarity & (uint32_t)SBR_MSER_DARK) != 0u) {
        pass_setup(&c, map, 0u, 0);
        pass_flood(&c);
        pass_select(&c, cfg, (uint8_t)SBR_MSER_DARK, regions, capacity, count, &full);
        overflow |= c.overflow;
        counted = 1;
    }
    if ((cfg->polarity & (uint32_t)SBR_MSER_BRIGHT) != 0u) {
        c.overflow = 0;
        pass_setup(&c, map, 0xFFu, counted);
        pass_flood(&c);
        pass_select(&c, cfg, (uint8_t)SBR_MSER_BRIGHT, regions, capacity, count, &full);
        overflow |= c.overflow;
    }
    if ((full != 0) || (overflow != 0)) {
        return SBR_ERR_CAPACITY;
    }
    return SBR_OK;
}
