/* SPDX-License-Identifier: MIT */
/*
 * Recogniser: prototype matches -> star-model votes -> hypotheses -> evidence per class
 * and cascade verification. See include/sbr/recog.h.
 */
#include "recog_internal.h"

#include <math.h>
#include <string.h>

/* Vote order (sbr_recog_priv_sort_votes()). Returns 1 if a comes strictly before b. */
static int vote_before(const void *pa, const void *pb, int mode)
{
    const recog_vote_t *a = (const recog_vote_t *)pa;
    const recog_vote_t *b = (const recog_vote_t *)pb;
    int before = 0;
    if (mode == 0) {
        if (a->weight > b->weight) {
            before = 1;
        }
    } else if (a->hyp != b->hyp) {
        if (a->hyp < b->hyp) {
            before = 1;
        }
    } else if (a->part != b->part) {
        if (a->part < b->part) {
            before = 1;
        }
    } else if (a->weight > b->weight) {
        before = 1;
    } else {
        before = 0;
    }
    return before;
}

sbr_status_t sbr_recog_priv_cast_votes(recog_ctx_t *c, uint32_t pi)
{
    const sbr_part_t *p = &c->parts[pi];
    const sbr_model_t *m = c->model;
    const uint32_t g = sbr_model_group(p->map, p->polarity);
    uint32_t first;
    uint32_t n;
    uint32_t best = 0u;
    uint32_t k;
    sbr_status_t st;
    if (g >= SBR_MODEL_GROUPS) {
        return SBR_OK;
    }
    first = m->group_first[g];
    n = (uint32_t)m->group_first[g + 1u] - first;
    if (n == 0u) {
        return SBR_OK;
    }
    /* the model's prototypes were checked once this frame (sbr_fd_table_init()) */
    st = sbr_fd_match_prepared(c->fft_p, &c->mcfg, &c->table, first, n, &p->fd, c->work,
                               c->work_len, c->results, &best);
    if (st != SBR_OK) {
        return st;
    }
    c->st.matches += n;
    for (k = 0u; k < n; k++) {
        const float e = c->results[k].error;
        if (e <= c->vote_error) {
            const sbr_model_proto_t *q = &m->protos[first + k];
            const float s = p->fd.scale;
            const float w = q->w * s;
            const float h = q->h * s;
            const float size = sbr_util_maxf(w, h);
            if ((size >= c->cfg->min_size) && (size <= c->cfg->max_size)) {
                if (c->nvotes >= c->cfg->max_votes) {
                    c->st.capacity_hit |= SBR_RECOG_HIT_VOTES;
                } else {
                    recog_vote_t *v = &c->votes[c->nvotes];
                    v->cx = p->fd.cx + (q->dx * s);
                    v->cy = p->fd.cy + (q->dy * s);
                    v->w = w;
                    v->h = h;
                    v->weight = q->weight * (1.0f - (e / c->vote_error));
                    v->part = pi;
                    v->hyp = 0u;
                    v->proto = (uint16_t)(first + k);
                    v->pad = 0u;
                    c->nvotes++;
                }
            }
        }
    }
    return SBR_OK;
}

/* Swap two votes. */
static inline void vote_swap(recog_vote_t *a, recog_vote_t *b)
{
    const recog_vote_t t = *a;
    *a = *b;
    *b = t;
}

/* sbr_util_heap_sort() of the votes, written out for their type: the same steps (so the
   same order, ties included) with the comparison inlined and whole-struct swaps. */
void sbr_recog_priv_sort_votes(recog_ctx_t *c, int mode)
{
    recog_vote_t *const v = c->votes;
    const uint32_t n = c->nvotes;
    uint32_t start = n / 2u;
    uint32_t end = (n < 2u) ? 1u : n; /* fewer than two: nothing to do */
    while (end > 1u) {
        uint32_t root;
        if (start > 0u) {
            start--;
            root = start;
        } else {
            end--;
            vote_swap(&v[0], &v[end]);
            root = 0u;
        }
        while (((2u * root) + 1u) < end) {
            uint32_t child = (2u * root) + 1u;
            if (((child + 1u) < end) && (vote_before(&v[child], &v[child + 1u], mode) != 0)) {
                child++;
            }
            if (vote_before(&v[root], &v[child], mode) != 0) {
                vote_swap(&v[root], &v[child]);
                root = child;
            } else {
                root = end; /* in place: stop */
            }
        }
    }
}

/* Does a (centre, size) agree with a hypothesis's current mean? */
static int agrees(const recog_hyp_t *h, float cx, float cy, float w, float hh,
                  const sbr_recog_config_t *cfg)
{
    const float f = 1.0f + cfg->size_tol;
    int ok = 0;
    if ((fabsf(cx - h->mx) <= (cfg->centre_tol * h->mw)) &&
        (fabsf(cy - h->my) <= (cfg->centre_tol * h->mh)) && (w <= (h->mw * f)) &&
        ((w * f) >= h->mw) && (hh <= (h->mh * f)) && ((hh * f) >= h->mh)) {
        ok = 1;
    }
    return ok;
}

/* The hypotheses by the column (RECOG_GRID_CELL pixels wide) of their mean centre x, so
   that a vote is compared only with the hypotheses that can agree with it: one that
   agrees has its mean within centre_tol x its width <= centre_tol x (1 + size_tol) x the
   vote's width of the vote's centre. Columns are doubly linked lists over the hypotheses
   in the grid's block (recog_internal.h); x outside the view falls in the first or last
   column. */
#define RECOG_NONE 0xFFFFFFFFu

static uint32_t grid_col(const recog_ctx_t *c, float x)
{
    const float f = x / RECOG_GRID_CELL;
    const uint32_t last = c->grid_cols - 1u;
    uint32_t col = 0u;
    if (f >= (float)last) {
        col = last;
    } else if (f > 0.0f) {
        col = (uint32_t)f;
    } else {
        /* left of the view (or not a number): the first column */
    }
    return col;
}

static void grid_link(recog_ctx_t *c, uint32_t h, uint32_t col)
{
    const uint32_t first = c->grid_head[col];
    c->grid_prev[h] = RECOG_NONE;
    c->grid_next[h] = first;
    if (first != RECOG_NONE) {
        c->grid_prev[first] = h;
    }
    c->grid_head[col] = h;
}

static void grid_unlink(recog_ctx_t *c, uint32_t h, uint32_t col)
{
    const uint32_t pv = c->grid_prev[h];
    const uint32_t nx = c->grid_next[h];
    if (pv != RECOG_NONE) {
        c->grid_next[pv] = nx;
    } else {
        c->grid_head[col] = nx;
    }
    if (nx != RECOG_NONE) {
        c->grid_prev[nx] = pv;
    }
}

/* The first hypothesis (smallest index) that agrees with vote v, or nhyps: the hypotheses
   in the columns the agreement bound allows, each tested as a scan over all would test it
   (the bound has a margin far above float rounding). */
static uint32_t first_agreeing(const recog_ctx_t *c, const recog_vote_t *v)
{
    const float r = (c->cfg->centre_tol * v->w * (1.0f + c->cfg->size_tol) * 1.01f) + 2.0f;
    const uint32_t hi = grid_col(c, v->cx + r);
    uint32_t col = grid_col(c, v->cx - r);
    uint32_t found = c->nhyps;
    while (col <= hi) {
        uint32_t h = c->grid_head[col];
        while (h != RECOG_NONE) {
            if ((h < found) && (agrees(&c->hyps[h], v->cx, v->cy, v->w, v->h, c->cfg) != 0)) {
                found = h;
            }
            h = c->grid_next[h];
        }
        col++;
    }
    return found;
}

void sbr_recog_priv_group_votes(recog_ctx_t *c)
{
    uint32_t i;
    for (i = 0u; i < c->grid_cols; i++) {
        c->grid_head[i] = RECOG_NONE;
    }
    for (i = 0u; i < c->nvotes; i++) {
        recog_vote_t *v = &c->votes[i];
        const uint32_t found = first_agreeing(c, v);
        uint32_t col = RECOG_NONE; /* the hypothesis's column before this vote */
        if (found == c->nhyps) {
            if (c->nhyps >= c->cfg->max_hypotheses) {
                c->st.capacity_hit |= SBR_RECOG_HIT_HYPOTHESES;
                v->hyp = 0xFFFFFFFFu; /* dropped */
                continue;
            }
            (void)memset(&c->hyps[found], 0, sizeof c->hyps[found]);
            c->nhyps++;
        } else {
            col = grid_col(c, c->hyps[found].mx);
        }
        c->hyps[found].sx += v->weight * v->cx;
        c->hyps[found].sy += v->weight * v->cy;
        c->hyps[found].sw += v->weight * v->w;
        c->hyps[found].sh += v->weight * v->h;
        c->hyps[found].sum += v->weight;
        c->hyps[found].mx = c->hyps[found].sx / c->hyps[found].sum;
        c->hyps[found].my = c->hyps[found].sy / c->hyps[found].sum;
        c->hyps[found].mw = c->hyps[found].sw / c->hyps[found].sum;
        c->hyps[found].mh = c->hyps[found].sh / c->hyps[found].sum;
        v->hyp = found;
        {
            const uint32_t now = grid_col(c, c->hyps[found].mx);
            if (now != col) {
                if (col != RECOG_NONE) {
                    grid_unlink(c, found, col);
                }
                grid_link(c, found, now);
            }
        }
    }
}

/* Share of class `cls` in a prototype (0 if it does not hold the class). */
static float class_share(const sbr_model_proto_t *q, uint32_t cls)
{
    uint32_t k;
    float p = 0.0f;
    for (k = 0u; k < SBR_MODEL_PROTO_CLASSES; k++) {
        if ((uint32_t)q->class_id[k] == cls) {
            p = q->class_p[k];
        }
    }
    return p;
}

/* Did prototype `q` vote in votes[a..b)? */
static int voted(const recog_vote_t *votes, uint32_t a, uint32_t b, uint32_t q)
{
    uint32_t i;
    int found = 0;
    for (i = a; (i < b) && (found == 0); i++) {
        if ((uint32_t)votes[i].proto == q) {
            found = 1;
        }
    }
    return found;
}

/* Index order: by group, then centre x, then part. */
static int index_before(const void *pa, const void *pb, int mode)
{
    const recog_index_t *a = (const recog_index_t *)pa;
    const recog_index_t *b = (const recog_index_t *)pb;
    int before = 0;
    (void)mode;
    if (a->group != b->group) {
        if (a->group < b->group) {
            before = 1;
        }
    } else if (a->cx != b->cx) {
        if (a->cx < b->cx) {
            before = 1;
        }
    } else if (a->part < b->part) {
        before = 1;
    } else {
        before = 0;
    }
    return before;
}

void sbr_recog_priv_index_parts(recog_ctx_t *c)
{
    uint32_t i;
    uint32_t g = 0u;
    for (i = 0u; i < c->nparts; i++) {
        const sbr_part_t *p = &c->parts[i];
        c->index[i].cx = p->fd.cx;
        c->index[i].part = i;
        c->index[i].group = sbr_model_group(p->map, p->polarity); /* SBR_MODEL_GROUPS (never
                                                               searched) if invalid */
    }
    sbr_util_heap_sort((uint8_t *)(void *)c->index, c->nparts, sizeof(recog_index_t), index_before, 0);
    for (i = 0u; i <= c->nparts; i++) {
        const uint32_t gi = (i < c->nparts) ? c->index[i].group : SBR_MODEL_GROUPS;
        while (g <= gi) {
            c->group_first[g] = i;
            g++;
        }
    }
}

/* Bisection in index entries [lo, hi) of one group: the first entry with cx >= x
   (above = 0) or with cx > x (above = 1); hi if there is none. */
static uint32_t index_bound(const recog_ctx_t *c, uint32_t lo, uint32_t hi, float x, int above)
{
    uint32_t a = lo;
    uint32_t b = hi;
    while (a < b) {
        const uint32_t mid = a + ((b - a) / 2u);
        const float v = c->index[mid].cx;
        int left = 0; /* the answer lies right of mid */
        if ((v < x) || ((above != 0) && (v <= x))) {
            left = 1;
        }
        if (left != 0) {
            a = mid + 1u;
        } else {
            b = mid;
        }
    }
    return a;
}

/* Look for cascade prototype q of class cls near where hypothesis h predicts it.
   Returns the weight it adds (0 if not found). */
static float verify_part(recog_ctx_t *c, const recog_hyp_t *h, uint32_t q, uint32_t cls)
{
    const sbr_model_proto_t *pr = &c->model->protos[q];
    const float s = 0.5f * ((h->mw / pr->w) + (h->mh / pr->h)); /* predicted part scale */
    const float px = h->mx - (pr->dx * s);
    const float py = h->my - (pr->dy * s);
    const float f = 1.0f + c->cfg->size_tol;
    const float tol = c->cfg->centre_tol * sbr_util_maxf(h->mw, h->mh);
    /* the index range holds every part whose x passes the test below (one pixel of
       margin for rounding); the test itself decides */
    const float xlo = (px - tol) - 1.0f;
    const float xhi = (px + tol) + 1.0f;
    const uint32_t g = sbr_model_group(pr->map, pr->polarity); /* < SBR_MODEL_GROUPS: checked */
    const uint32_t a = index_bound(c, c->group_first[g], c->group_first[g + 1u], xlo, 0);
    const uint32_t b = index_bound(c, a, c->group_first[g + 1u], xhi, 1);
    float best = 0.0f;
    uint32_t i;
    for (i = a; i < b; i++) {
        /* entries of group g only: the part's map and polarity are the prototype's */
        const sbr_part_t *p = &c->parts[c->index[i].part];
        if ((fabsf(p->fd.cx - px) <= tol) && (fabsf(p->fd.cy - py) <= tol) &&
            (p->fd.scale <= (s * f)) && ((p->fd.scale * f) >= s)) {
            sbr_fd_match_t r;
            c->st.matches++;
            if ((sbr_fd_match(c->fft_p, &c->vcfg, &p->fd, &c->model->fds[q], c->work,
                              c->work_len, &r) == SBR_OK) &&
                (r.error <= c->cfg->verify_error)) {
                const float w = pr->weight * (1.0f - (r.error / c->cfg->verify_error)) *
                                class_share(pr, cls);
                best = sbr_util_maxf(best, w);
            }
        }
    }
    return best;
}

/* The evidence a hypothesis has gathered: class sums, their best, and what all its parts
   give together. */
typedef struct recog_evidence_s {
    float cls[SBR_RECOG_MAX_CLASSES];
    float total;
    float miss; /* probability that no supporting part is a sign's part */
    float best_s;
    uint32_t best_c;
    uint32_t nprotos;
} recog_evidence_t;

/* Evidence from the votes votes[i..j) of one hypothesis: a region counts once, with its
   strongest vote (the first of its part); then the best class. */
static void vote_evidence(const recog_ctx_t *c, uint32_t i, uint32_t j, recog_evidence_t *ev)
{
    const sbr_model_t *m = c->model;
    uint32_t k;
    (void)memset(ev, 0, sizeof *ev);
    ev->miss = 1.0f;
    for (k = i; k < j; k++) {
        if ((k == i) || (c->votes[k].part != c->votes[k - 1u].part)) {
            const sbr_model_proto_t *q = &m->protos[c->votes[k].proto];
            uint32_t t;
            for (t = 0u; t < SBR_MODEL_PROTO_CLASSES; t++) {
                if ((uint32_t)q->class_id[t] < m->class_count) {
                    ev->cls[q->class_id[t]] += c->votes[k].weight * q->class_p[t];
                }
            }
            ev->total += c->votes[k].weight;
            ev->miss *= 1.0f - c->votes[k].weight;
            ev->nprotos++;
        }
    }
    for (k = 0u; k < m->class_count; k++) {
        if (ev->cls[k] > ev->best_s) {
            ev->best_s = ev->cls[k];
            ev->best_c = k;
        }
    }
}

/* Cascade verification of the best class's other parts (those that did not vote in
   votes[i..j)), at most cascade_depth of them: each one found adds its weight. */
static void cascade_verify(recog_ctx_t *c, uint32_t h, uint32_t i, uint32_t j,
                           recog_evidence_t *ev)
{
    const sbr_model_t *m = c->model;
    const uint32_t a = m->class_first[ev->best_c];
    const uint32_t b = m->class_first[ev->best_c + 1u];
    uint32_t checked = 0u;
    uint32_t k;
    for (k = a; (k < b) && (checked < c->cfg->cascade_depth); k++) {
        const uint32_t q = m->cascade[k];
        if (voted(c->votes, i, j, q) == 0) {
            const float add = verify_part(c, &c->hyps[h], q, ev->best_c);
            checked++;
            if (add > 0.0f) {
                ev->best_s += add;
                ev->total += add;
                ev->miss *= 1.0f - add;
                ev->nprotos++;
                c->st.verified++;
            }
        }
    }
}

/* A hypothesis's class, score and share from its evidence, and whether it stays. */
static void hyp_verdict(recog_ctx_t *c, recog_hyp_t *hy, const recog_evidence_t *ev)
{
    hy->class_id = (uint16_t)ev->best_c;
    hy->parts = (uint16_t)((ev->nprotos > 65535u) ? 65535u : ev->nprotos);
    hy->score = 1.0f - ev->miss;
    if (ev->total > 0.0f) {
        hy->share = ev->best_s / ev->total;
    } else {
        hy->share = 0.0f;
    }
    if ((ev->nprotos >= c->cfg->min_parts) && (hy->score >= c->score_floor)) {
        hy->keep = 1u;
    } else {
        hy->keep = 0u;
        c->st.rejected++;
    }
}

void sbr_recog_priv_score_hyps(recog_ctx_t *c)
{
    uint32_t i = 0u;
    while (i < c->nvotes) {
        const uint32_t h = c->votes[i].hyp;
        uint32_t j = i;
        while ((j < c->nvotes) && (c->votes[j].hyp == h)) {
            j++;
        }
        if (h < c->nhyps) { /* dropped votes sort last */
            recog_evidence_t ev;
            vote_evidence(c, i, j, &ev);
            if (ev.best_s > 0.0f) {
                cascade_verify(c, h, i, j, &ev);
            }
            hyp_verdict(c, &c->hyps[h], &ev);
        }
        i = j;
    }
}
