/* SPDX-License-Identifier: MIT */
/* MSER's second stage: over one pass's tree nodes, the variations, the stable nodes, the
   duplicates removed, and each selected node as a region (its box measured by a fill).
   See include/sbr/mser.h for the definitions. */
#include "mser_internal.h"

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
static void select_stable(mser_ctx_t *c, const sbr_mser_config_t *cfg, uint32_t limit)
{
    uint32_t n;
    for (n = 0u; n < c->node_count; n++) {
        mser_node_t *nd = &c->node[n];
        int ok = 1;
        if ((nd->size > cfg->max_area) || (nd->var > cfg->max_variation) ||
            (nd->var > nd->child_var) || (((uint32_t)nd->val + c->delta) > limit)) {
            ok = 0; /* (a node within delta of a pass limit: its variation is not known) */
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
   fill that lists them in the heap's chunks (free after the flood) and marks them
   LEV_BOXED until it is done. The border and walls (LEV_WALL) have LEV_BOXED set, so the
   fill never enters them. A node larger than the list (a heap bound below the node's area) gets
   the box of the pixels the list holds, and the call reports the bound reached. */
/* Is a pixel of value g (lev[]) in the region of level val and not yet boxed: no flag but
   LEV_REACHED set, its level <= val? (One comparison: with LEV_REACHED set in both, any
   other flag makes g the larger.) */
static inline int box_in(uint32_t g, uint32_t val)
{
    return ((g | LEV_REACHED) <= (val | LEV_REACHED)) ? 1 : 0;
}

static uint32_t box_visit(uint16_t *lev, uint32_t *list, uint32_t n, uint32_t cap, uint32_t q,
                          uint32_t val)
{
    const uint32_t g = (uint32_t)lev[q];
    uint32_t m = n;
    if ((box_in(g, val) != 0) && (n < cap)) {
        lev[q] = (uint16_t)(g | LEV_BOXED);
        list[n] = q;
        m = n + 1u;
    }
    return m;
}


/* The run fill's state: the pending seeds at the list's start (list[0, sp)), the runs
   found at its end (list[rn, cap): first pixel, last pixel), the box so far. */
typedef struct box_runs_s {
    uint32_t *list;
    uint32_t cap;
    uint32_t sp;
    uint32_t rn;
    uint32_t x0;
    uint32_t x1;
    uint32_t p0;
    uint32_t p1;
} box_runs_t;

/* Push a seed for every stretch of region pixels among [a, b] (a row above or below a
   run); 0 when the list is full. */
static int box_seeds(const uint16_t *lev, uint32_t a, uint32_t b, uint32_t val, box_runs_t *f)
{
    uint32_t q = a;
    int ok = 1;
    while (q <= b) {
        if (box_in((uint32_t)lev[q], val) == 0) {
            q++;
        } else {
            /* a stretch starts at q: one seed for it */
            if (f->sp >= f->rn) {
                ok = 0;
            } else {
                f->list[f->sp] = q;
                f->sp++;
            }
            q++;
            while ((q <= b) && (box_in((uint32_t)lev[q], val) != 0)) {
                q++;
            }
        }
    }
    return ok;
}

/* Clear LEV_BOXED on the runs found. */
static void box_unmark(uint16_t *lev, const box_runs_t *f)
{
    uint32_t i;
    for (i = f->rn; i < f->cap; i += 2u) {
        uint32_t q;
        for (q = f->list[i]; q <= f->list[i + 1u]; q++) {
            lev[q] = (uint16_t)((uint32_t)lev[q] & ~LEV_BOXED);
        }
    }
}

/* node_bbox() by runs: the same pixels (the 4-connected pixels of level <= the node's
   around its seed) found a row stretch at a time, each stretch marked, measured and its
   neighbour rows searched once, instead of pixel by pixel. 0 when the list is too small
   for its seeds and runs (nothing left marked; node_bbox() then fills pixel by pixel). */
static int node_bbox_runs(mser_ctx_t *c, const mser_node_t *nd, sbr_rect_t *box)
{
    uint16_t *const lev = c->lev;
    const uint32_t w = c->width;
    const uint32_t val = (uint32_t)nd->val;
    box_runs_t f;
    int ok = 1;
    f.list = c->heap;
    f.cap = c->heap_chunks * SBR_MSER_HEAP_CHUNK;
    f.sp = 0u;
    f.rn = f.cap;
    f.x0 = 0xFFFFFFFFu;
    f.x1 = 0u;
    f.p0 = 0xFFFFFFFFu;
    f.p1 = 0u;
    if (f.cap < 3u) {
        ok = 0; /* no room for the seed and a stretch */
    } else {
        f.list[0] = nd->seed;
        f.sp = 1u;
    }
    while ((f.sp > 0u) && (ok != 0)) {
        uint32_t l;
        uint32_t r;
        f.sp--;
        l = f.list[f.sp];
        r = l;
        if ((box_in((uint32_t)lev[l], val) != 0) && ((f.rn - f.sp) >= 2u)) {
            uint32_t q;
            uint32_t y;
            uint32_t x;
            /* the border and walls are never in a region: the stretch ends inside the map */
            while (box_in((uint32_t)lev[l - 1u], val) != 0) {
                l--;
            }
            while (box_in((uint32_t)lev[r + 1u], val) != 0) {
                r++;
            }
            for (q = l; q <= r; q++) {
                lev[q] = (uint16_t)((uint32_t)lev[q] | LEV_BOXED);
            }
            f.rn -= 2u;
            f.list[f.rn] = l;
            f.list[f.rn + 1u] = r;
            y = (uint32_t)(((uint64_t)l * c->div_magic) >> c->div_shift);
            x = l - (y * w);
            f.x0 = (x < f.x0) ? x : f.x0;
            f.x1 = ((x + (r - l)) > f.x1) ? (x + (r - l)) : f.x1;
            f.p0 = (l < f.p0) ? l : f.p0;
            f.p1 = (r > f.p1) ? r : f.p1;
            ok = box_seeds(lev, l - w, r - w, val, &f);
            if (ok != 0) {
                ok = box_seeds(lev, l + w, r + w, val, &f);
            }
        } else if (box_in((uint32_t)lev[l], val) != 0) {
            ok = 0; /* no room for the run */
        } else {
            /* boxed by an earlier run since it was pushed */
        }
    }
    box_unmark(lev, &f);
    if (ok != 0) {
        const uint32_t y0 = (uint32_t)(((uint64_t)f.p0 * c->div_magic) >> c->div_shift);
        const uint32_t y1 = (uint32_t)(((uint64_t)f.p1 * c->div_magic) >> c->div_shift);
        box->x = f.x0;
        box->y = y0;
        box->width = (f.x1 - f.x0) + 1u;
        box->height = (y1 - y0) + 1u;
    }
    return ok;
}

static void node_bbox(mser_ctx_t *c, const mser_node_t *nd, sbr_rect_t *box)
{
    uint16_t *const lev = c->lev;
    uint32_t *const list = c->heap;
    const uint32_t cap = c->heap_chunks * SBR_MSER_HEAP_CHUNK;
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
        n = box_visit(lev, list, n, cap, p + 1u, val);
        n = box_visit(lev, list, n, cap, p + w, val);
        n = box_visit(lev, list, n, cap, p - 1u, val);
        n = box_visit(lev, list, n, cap, p - w, val);
    }
    for (i = 0u; i < n; i++) {
        lev[list[i]] = (uint16_t)((uint32_t)lev[list[i]] & ~LEV_BOXED);
    }
    if (n >= cap) {
        c->overflow = 1;
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
    if (node_bbox_runs(c, nd, &r->bbox) == 0) {
        node_bbox(c, nd, &r->bbox);
    }
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

void sbr_mser_priv_pass_select(mser_ctx_t *c, const sbr_mser_config_t *cfg, uint8_t polarity,
                               uint32_t limit, sbr_mser_region_t *regions, uint32_t capacity,
                               uint32_t *count, int *full)
{
    uint32_t n;
    select_variation(c);
    select_stable(c, cfg, (limit < (MSER_LEVELS - 1u)) ? limit : MSER_LIMIT_NONE);
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
