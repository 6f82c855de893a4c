/*
 * Traffic-sign recogniser: parts -> prototype matches -> star-model votes -> hypotheses
 * -> cascade verification -> NMS. See include/sbr/recognizer.h.
 */
#include "sbr/recognizer.h"

#include "../common/sbr_util.h"

#include <math.h>
#include <string.h>

#define RECOG_ALIGN(x) ((((size_t)(x)) + 7u) & ~((size_t)7u))
#define RECOG_PI 3.14159265f

/* A vote: a predicted sign (centre, size) from one part-prototype match. */
typedef struct recog_vote_s {
    float cx;
    float cy;
    float w;
    float h;
    float weight;
    uint32_t part;
    uint32_t hyp;
    uint16_t proto;
    uint16_t pad;
} recog_vote_t;

/* A hypothesis: weighted sums of its votes' geometry and their means (kept current as
   votes join), then its verdict. */
typedef struct recog_hyp_s {
    float sx;
    float sy;
    float sw;
    float sh;
    float sum;
    float mx;
    float my;
    float mw;
    float mh;
    float score;
    float share;
    uint16_t class_id;
    uint16_t parts;
    uint32_t keep;
} recog_hyp_t;

/* An entry of the part index: the parts of each group (map, polarity) in order of their
   centre's x, so that the cascade looks only at parts near a predicted position. */
typedef struct recog_index_s {
    float cx;
    uint32_t part;
    uint32_t group;
} recog_index_t;

typedef struct recog_layout_s {
    size_t parts_ws;
    size_t parts;
    size_t index;
    size_t results;
    size_t work;
    size_t votes;
    size_t hyps;
    size_t picto;
    size_t total;
} recog_layout_t;

/* The class stage's share of the workspace: its scratch, a feature vector, the
   probabilities and their mean over views. */
#define RECOG_PICTO_BYTES \
    (SBR_PICTO_WORKSPACE_SIZE + ((SBR_PICTO_FEATURES + (2u * SBR_PICTO_OUTPUTS)) * sizeof(float)))

void sbr_recog_config_default(sbr_recog_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_parts_config_default(&cfg->parts);
        /* finer than the MSER defaults: small, blurred signs need a smaller delta and a
           looser stability bound to come out as regions at all */
        cfg->parts.mser.delta = 3u;
        cfg->parts.mser.max_variation = 0.5f;
        /* intensity and blue: red rims already stand out in intensity, blue signs need
           their own map (the red map's parts added false hypotheses and time:
           docs/results/recognition.md) */
        cfg->parts.maps = (1u << (uint32_t)SBR_MAP_INTENSITY) | (1u << (uint32_t)SBR_MAP_BLUE);
        /* blue at half resolution: a quarter of its MSER time; blue signs small enough to
           be lost there are still found by their intensity parts (same accuracy, measured
           in docs/results/recognition.md) */
        cfg->parts.map_subsample[SBR_MAP_BLUE] = 2u;
        cfg->parts.map_min_area[SBR_MAP_BLUE] = 40u;
        cfg->match_p = 32u;
        cfg->max_parts = 4096u;
        cfg->max_votes = 16384u;
        cfg->max_hypotheses = 4096u;
        cfg->max_model_protos = 1024u;
        cfg->vote_error = 0.0f;
        cfg->verify_error = 0.25f;
        cfg->max_rotation = 0.35f;
        cfg->min_size = 12.0f;
        cfg->max_size = 200.0f;
        cfg->centre_tol = 0.2f;
        cfg->size_tol = 0.3f;
        cfg->cascade_depth = 8u;
        cfg->min_parts = 1u;
        cfg->candidate_score = 0.0f;
        cfg->max_candidates = 256u;
        cfg->refine_steps = 2u;
        cfg->refine_first_score = 0.0f;
        cfg->refine_score = 0.001f;
        cfg->views = 5u;
        cfg->view_score = 0.1f;
        cfg->triangle_view = 1u;
        cfg->triangle_score = 0.001f;
        cfg->min_score = 0.3f;
        cfg->nms_iou = 0.3f;
        cfg->candidate_iou = 1.0f;
        cfg->gate = 1u;
        cfg->clock = NULL;
        cfg->clock_ctx = NULL;
    }
}

/* Is v in [lo, hi] (false for NaN)? */
static int in_range(float v, float lo, float hi)
{
    int ok = 0;
    if ((v >= lo) && (v <= hi)) {
        ok = 1;
    }
    return ok;
}

sbr_status_t sbr_recog_config_check(const sbr_recog_config_t *cfg)
{
    sbr_status_t st;
    if (cfg == NULL) {
        return SBR_ERR_NULL;
    }
    st = sbr_parts_config_check(&cfg->parts);
    if (st != SBR_OK) {
        return st;
    }
    if ((sbr_fft_size_supported(cfg->match_p) == 0) ||
        (cfg->match_p < ((2u * cfg->parts.fd_m) + 1u)) || (cfg->max_parts == 0u) ||
        (cfg->max_parts > 1000000u) || (cfg->max_votes == 0u) || (cfg->max_votes > 4000000u) ||
        (cfg->max_hypotheses == 0u) || (cfg->max_hypotheses > 1000000u) ||
        (cfg->max_model_protos == 0u) || (cfg->max_model_protos > 65535u) ||
        (cfg->cascade_depth > 65535u) || (cfg->min_parts > 65535u) ||
        (cfg->max_candidates > 1000000u) || (cfg->refine_steps > SBR_RECOG_MAX_REFINE) ||
        (cfg->views == 0u) || (cfg->views > SBR_RECOG_MAX_VIEWS) || (cfg->triangle_view > 1u) ||
        (cfg->gate > 1u)) {
        return SBR_ERR_RANGE;
    }
    if ((in_range(cfg->vote_error, 0.0f, 4.0f) == 0) ||
        (in_range(cfg->verify_error, 1.0e-6f, 4.0f) == 0) ||
        (in_range(cfg->max_rotation, 1.0e-6f, RECOG_PI) == 0) ||
        (in_range(cfg->min_size, 1.0f, 16384.0f) == 0) ||
        (in_range(cfg->max_size, cfg->min_size, 16384.0f) == 0) ||
        (in_range(cfg->centre_tol, 1.0e-6f, 10.0f) == 0) ||
        (in_range(cfg->size_tol, 0.0f, 10.0f) == 0) ||
        (in_range(cfg->min_score, 0.0f, 0.999999f) == 0) ||
        (in_range(cfg->candidate_score, 0.0f, 0.999999f) == 0) ||
        (in_range(cfg->refine_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->refine_first_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->view_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->triangle_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->nms_iou, 1.0e-6f, 1.0f) == 0) ||
        (in_range(cfg->candidate_iou, 1.0e-6f, 1.0f) == 0)) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
}

/* The prototype group of a (map, polarity): map * 2 + polarity - 1, or SBR_MODEL_GROUPS
   for a polarity that is neither dark nor bright. */
static uint32_t group_of(uint8_t map, uint8_t polarity)
{
    uint32_t g = SBR_MODEL_GROUPS;
    if (((polarity == (uint8_t)SBR_MSER_DARK) || (polarity == (uint8_t)SBR_MSER_BRIGHT)) &&
        ((uint32_t)map < (SBR_MODEL_GROUPS / 2u))) {
        g = ((uint32_t)map * 2u) + ((uint32_t)polarity - 1u);
    }
    return g;
}

static int proto_ok(const sbr_model_proto_t *p, uint32_t g)
{
    uint32_t k;
    float sum = 0.0f;
    int ok = 1;
    if ((in_range(p->dx, -100.0f, 100.0f) == 0) || (in_range(p->dy, -100.0f, 100.0f) == 0) ||
        (in_range(p->w, 1.0e-3f, 100.0f) == 0) || (in_range(p->h, 1.0e-3f, 100.0f) == 0) ||
        (in_range(p->weight, 1.0e-6f, 1.0f) == 0) ||
        (group_of(p->map, p->polarity) != g)) { /* also a map or polarity out of range */
        ok = 0;
    }
    for (k = 0u; (k < SBR_MODEL_PROTO_CLASSES) && (ok != 0); k++) {
        if (p->class_id[k] == (uint8_t)SBR_MODEL_NO_CLASS) {
            if (p->class_p[k] != 0.0f) {
                ok = 0;
            }
        } else if ((p->class_id[k] >= SBR_RECOG_CLASSES) ||
                   (in_range(p->class_p[k], 0.0f, 1.0f) == 0)) {
            ok = 0;
        } else {
            sum += p->class_p[k];
        }
    }
    if (sum > 1.001f) {
        ok = 0;
    }
    return ok;
}

sbr_status_t sbr_model_check(const sbr_model_t *model)
{
    uint32_t g;
    uint32_t c;
    uint32_t i;
    if (model == NULL) {
        return SBR_ERR_NULL;
    }
    if ((model->fds == NULL) || (model->protos == NULL) || (model->cascade == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((model->version != SBR_MODEL_VERSION) || (model->proto_count == 0u) ||
        (model->proto_count > 65535u) || (model->fd_m == 0u) || (model->fd_m > SBR_FD_MAX_M) ||
        (sbr_fft_size_supported(model->fd_n) == 0) || ((2u * model->fd_m) >= model->fd_n) ||
        (in_range(model->vote_error, 1.0e-6f, 4.0f) == 0) ||
        (in_range(model->score_threshold, 0.0f, 1.0f) == 0) || (model->group_first[0] != 0u) ||
        (model->group_first[SBR_MODEL_GROUPS] != model->proto_count) ||
        (model->class_first[0] != 0u)) {
        return SBR_ERR_CORRUPT;
    }
    for (g = 0u; g < SBR_MODEL_GROUPS; g++) {
        if (model->group_first[g + 1u] < model->group_first[g]) {
            return SBR_ERR_CORRUPT;
        }
        for (i = model->group_first[g]; i < model->group_first[g + 1u]; i++) {
            float e = 0.0f;
            /* sbr's descriptors have unit energy: anything else is a damaged table */
            if ((proto_ok(&model->protos[i], g) == 0) || (model->fds[i].m != model->fd_m) ||
                (sbr_fd_check(&model->fds[i], &e) != SBR_OK) || (in_range(e, 0.99f, 1.01f) == 0)) {
                return SBR_ERR_CORRUPT;
            }
        }
    }
    for (c = 0u; c < SBR_RECOG_CLASSES; c++) {
        if (model->class_first[c + 1u] < model->class_first[c]) {
            return SBR_ERR_CORRUPT;
        }
    }
    for (i = 0u; i < model->class_first[SBR_RECOG_CLASSES]; i++) {
        if (model->cascade[i] >= model->proto_count) {
            return SBR_ERR_CORRUPT;
        }
    }
    if ((model->picto.version != 0u) && (sbr_picto_check(&model->picto) != SBR_OK)) {
        return SBR_ERR_CORRUPT;
    }
    return SBR_OK;
}

static int recog_layout(uint32_t width, uint32_t height, const sbr_recog_config_t *cfg,
                        recog_layout_t *l)
{
    l->parts_ws = RECOG_ALIGN(sbr_parts_workspace_size(width, height, &cfg->parts));
    if (l->parts_ws == 0u) {
        return 0;
    }
    l->parts = RECOG_ALIGN((size_t)cfg->max_parts * sizeof(sbr_part_t));
    l->index = RECOG_ALIGN((size_t)cfg->max_parts * sizeof(recog_index_t));
    l->results = RECOG_ALIGN((size_t)cfg->max_model_protos * sizeof(sbr_fd_match_t));
    l->work = RECOG_ALIGN((size_t)cfg->match_p * 5u * sizeof(sbr_complex_t)); /* the table
                                                                    matcher's four-lane scratch */
    l->votes = RECOG_ALIGN((size_t)cfg->max_votes * sizeof(recog_vote_t));
    l->hyps = RECOG_ALIGN((size_t)cfg->max_hypotheses * sizeof(recog_hyp_t));
    l->picto = RECOG_ALIGN(RECOG_PICTO_BYTES);
    l->total = l->parts_ws + l->parts + l->index + l->results + l->work + l->votes + l->hyps +
               l->picto;
    return 1;
}

size_t sbr_recog_workspace_size(uint32_t width, uint32_t height, const sbr_recog_config_t *cfg)
{
    recog_layout_t l;
    if ((sbr_recog_config_check(cfg) != SBR_OK) || (width > SBR_IMAGE_MAX_DIM) ||
        (height > SBR_IMAGE_MAX_DIM) || (recog_layout(width, height, cfg, &l) == 0)) {
        return 0u;
    }
    return l.total;
}

/* Vote order: by weight, descending (mode 0), or by hypothesis, part, then weight
   descending (mode 1). Returns 1 if a comes strictly before b. */
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

/* Hypothesis order: by score, descending. */
static int hyp_before(const void *pa, const void *pb, int mode)
{
    const recog_hyp_t *a = (const recog_hyp_t *)pa;
    const recog_hyp_t *b = (const recog_hyp_t *)pb;
    int before = 0;
    (void)mode;
    if (a->score > b->score) {
        before = 1;
    }
    return before;
}

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
static void heap_sort(uint8_t *base, uint32_t n, size_t size,
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

/* Everything one call works with. */
typedef struct recog_ctx_s {
    const sbr_recog_config_t *cfg;
    const sbr_model_t *model;
    sbr_fft_t fft_p;
    sbr_fd_match_config_t mcfg;  /* votes: screened at the vote error */
    sbr_fd_match_config_t vcfg;  /* cascade: screened at the verification error */
    sbr_part_t *parts;
    uint32_t nparts;
    recog_index_t *index;                          /* [nparts] */
    uint32_t group_first[SBR_MODEL_GROUPS + 1u];   /* each group's first index entry */
    sbr_fd_match_t *results;
    sbr_complex_t *work;
    uint32_t work_len;
    recog_vote_t *votes;
    uint32_t nvotes;
    recog_hyp_t *hyps;
    uint32_t nhyps;
    float vote_error;
    float score_floor; /* part-evidence floor: min_score, or candidate_score before the
                          class stage */
    sbr_recog_stats_t st;
} recog_ctx_t;

/* Close a timed stage: ticks since *t0 go to stage `s`; *t0 moves on. */
static void stage_end(recog_ctx_t *c, uint32_t s, uint32_t *t0)
{
    if (c->cfg->clock != NULL) {
        const uint32_t t = c->cfg->clock(c->cfg->clock_ctx);
        c->st.stage_ticks[s] = t - *t0;
        *t0 = t;
    }
}

static float maxf(float a, float b)
{
    float r = a;
    if (b > a) {
        r = b;
    }
    return r;
}

/* The smaller of two finite values (what fminf gives them, without a library call). */
static float minf(float a, float b)
{
    float r = a;
    if (b < a) {
        r = b;
    }
    return r;
}

/* Match one part against its group and cast its votes. */
static sbr_status_t cast_votes(recog_ctx_t *c, uint32_t pi)
{
    const sbr_part_t *p = &c->parts[pi];
    const sbr_model_t *m = c->model;
    const uint32_t g = group_of(p->map, p->polarity);
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
    st = sbr_fd_match_table(&c->fft_p, &c->mcfg, &p->fd, &m->fds[first], n, c->work,
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
            const float size = maxf(w, h);
            if ((size >= c->cfg->min_size) && (size <= c->cfg->max_size)) {
                if (c->nvotes >= c->cfg->max_votes) {
                    c->st.capacity_hit |= 2u;
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

/* Group the votes (sorted by weight) into hypotheses. */
static void group_votes(recog_ctx_t *c)
{
    uint32_t i;
    for (i = 0u; i < c->nvotes; i++) {
        recog_vote_t *v = &c->votes[i];
        uint32_t h;
        uint32_t found = c->nhyps;
        for (h = 0u; h < c->nhyps; h++) {
            if (agrees(&c->hyps[h], v->cx, v->cy, v->w, v->h, c->cfg) != 0) {
                found = h;
                break;
            }
        }
        if (found == c->nhyps) {
            if (c->nhyps >= c->cfg->max_hypotheses) {
                c->st.capacity_hit |= 4u;
                v->hyp = 0xFFFFFFFFu; /* dropped */
                continue;
            }
            (void)memset(&c->hyps[found], 0, sizeof c->hyps[found]);
            c->nhyps++;
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

/* Build the part index and each group's first entry. */
static void index_parts(recog_ctx_t *c)
{
    uint32_t i;
    uint32_t g = 0u;
    for (i = 0u; i < c->nparts; i++) {
        const sbr_part_t *p = &c->parts[i];
        c->index[i].cx = p->fd.cx;
        c->index[i].part = i;
        c->index[i].group = group_of(p->map, p->polarity); /* SBR_MODEL_GROUPS (never
                                                               searched) if invalid */
    }
    heap_sort((uint8_t *)(void *)c->index, c->nparts, sizeof(recog_index_t), index_before, 0);
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
    const float tol = c->cfg->centre_tol * maxf(h->mw, h->mh);
    /* the index range holds every part whose x passes the test below (one pixel of
       margin for rounding); the test itself decides */
    const float xlo = (px - tol) - 1.0f;
    const float xhi = (px + tol) + 1.0f;
    const uint32_t g = group_of(pr->map, pr->polarity); /* < SBR_MODEL_GROUPS: checked */
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
            if ((sbr_fd_match(&c->fft_p, &c->vcfg, &p->fd, &c->model->fds[q], c->work,
                              c->work_len, &r) == SBR_OK) &&
                (r.error <= c->cfg->verify_error)) {
                const float w = pr->weight * (1.0f - (r.error / c->cfg->verify_error)) *
                                class_share(pr, cls);
                best = maxf(best, w);
            }
        }
    }
    return best;
}

/* Score every hypothesis (votes sorted by hypothesis and part). */
static void score_hyps(recog_ctx_t *c)
{
    const sbr_model_t *m = c->model;
    uint32_t i = 0u;
    while (i < c->nvotes) {
        const uint32_t h = c->votes[i].hyp;
        uint32_t j = i;
        float cls[SBR_RECOG_CLASSES];
        float total = 0.0f;
        float miss = 1.0f; /* probability that no supporting part is a sign's part */
        float best_s = 0.0f;
        uint32_t best_c = 0u;
        uint32_t nprotos = 0u;
        uint32_t k;
        while ((j < c->nvotes) && (c->votes[j].hyp == h)) {
            j++;
        }
        if (h >= c->nhyps) {
            i = j; /* dropped votes sort last */
            continue;
        }
        (void)memset(cls, 0, sizeof cls);
        for (k = i; k < j; k++) {
            /* a region counts once, with its strongest vote (the first of its part) */
            if ((k == i) || (c->votes[k].part != c->votes[k - 1u].part)) {
                const sbr_model_proto_t *q = &m->protos[c->votes[k].proto];
                uint32_t t;
                for (t = 0u; t < SBR_MODEL_PROTO_CLASSES; t++) {
                    if (q->class_id[t] < SBR_RECOG_CLASSES) {
                        cls[q->class_id[t]] += c->votes[k].weight * q->class_p[t];
                    }
                }
                total += c->votes[k].weight;
                miss *= 1.0f - c->votes[k].weight;
                nprotos++;
            }
        }
        for (k = 0u; k < SBR_RECOG_CLASSES; k++) {
            if (cls[k] > best_s) {
                best_s = cls[k];
                best_c = k;
            }
        }
        /* cascade verification of the best class's other parts */
        if (best_s > 0.0f) {
            const uint32_t a = m->class_first[best_c];
            const uint32_t b = m->class_first[best_c + 1u];
            uint32_t checked = 0u;
            for (k = a; (k < b) && (checked < c->cfg->cascade_depth); k++) {
                const uint32_t q = m->cascade[k];
                if (voted(c->votes, i, j, q) == 0) {
                    const float add = verify_part(c, &c->hyps[h], q, best_c);
                    checked++;
                    if (add > 0.0f) {
                        best_s += add;
                        total += add;
                        miss *= 1.0f - add;
                        nprotos++;
                        c->st.verified++;
                    }
                }
            }
        }
        c->hyps[h].class_id = (uint16_t)best_c;
        c->hyps[h].parts = (uint16_t)((nprotos > 65535u) ? 65535u : nprotos);
        c->hyps[h].score = 1.0f - miss;
        if (total > 0.0f) {
            c->hyps[h].share = best_s / total;
        } else {
            c->hyps[h].share = 0.0f;
        }
        if ((nprotos >= c->cfg->min_parts) && (c->hyps[h].score >= c->score_floor)) {
            c->hyps[h].keep = 1u;
        } else {
            c->hyps[h].keep = 0u;
            c->st.rejected++;
        }
        i = j;
    }
}

/* Box of a hypothesis in view pixels, clamped to the view: x0, y0, x1, y1 (exclusive). */
static void hyp_box(const recog_hyp_t *h, uint32_t vw, uint32_t vh, float b[4])
{
    const float hw = 0.5f * h->mw;
    const float hh = 0.5f * h->mh;
    b[0] = maxf(0.0f, h->mx - hw);
    b[1] = maxf(0.0f, h->my - hh);
    b[2] = minf((float)vw, h->mx + hw);
    b[3] = minf((float)vh, h->my + hh);
}

static float box_iou(const float a[4], const float b[4])
{
    const float iw = minf(a[2], b[2]) - maxf(a[0], b[0]);
    const float ih = minf(a[3], b[3]) - maxf(a[1], b[1]);
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

/* Move the kept hypotheses to the front, sorted best first; returns their count. */
static uint32_t compact_sorted(recog_ctx_t *c)
{
    uint32_t kept = 0u;
    uint32_t i;
    for (i = 0u; i < c->nhyps; i++) {
        if (c->hyps[i].keep != 0u) {
            c->hyps[kept] = c->hyps[i];
            kept++;
        }
    }
    heap_sort((uint8_t *)(void *)c->hyps, kept, sizeof(recog_hyp_t), hyp_before, 0);
    c->nhyps = kept;
    return kept;
}

/* Greedy non-maximum suppression over the first n (sorted) hypotheses: one overlapping
   a better kept one by more than iou, or with an empty box, is dropped (iou 1: only the
   empty boxes, as no IoU exceeds 1). */
static void suppress(recog_ctx_t *c, uint32_t n, uint32_t vw, uint32_t vh, float iou)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        float bi[4];
        uint32_t j;
        uint32_t earlier = 0u; /* the better hypotheses to compare with */
        int suppressed = 0;
        hyp_box(&c->hyps[i], vw, vh, bi);
        if (iou < 1.0f) {
            earlier = i;
        }
        for (j = 0u; (j < earlier) && (suppressed == 0); j++) {
            if (c->hyps[j].keep != 0u) {
                float bj[4];
                hyp_box(&c->hyps[j], vw, vh, bj);
                if (box_iou(bi, bj) > iou) {
                    suppressed = 1;
                }
            }
        }
        if ((suppressed != 0) || (bi[2] <= bi[0]) || (bi[3] <= bi[1])) {
            c->hyps[i].keep = 0u;
        }
    }
}

/* Class and score of one classified box: class = the most probable sign class, score = its
   probability, share = its share of the sign classes' probability. Returns the sign
   classes' total probability. */
static float take_class(recog_hyp_t *h, const float *prob)
{
    float signs = 0.0f;
    uint32_t best = 0u;
    uint32_t k;
    for (k = 0u; k < SBR_PICTO_BACKGROUND; k++) {
        signs += prob[k];
        if (prob[k] > prob[best]) {
            best = k;
        }
    }
    h->class_id = (uint16_t)best;
    h->score = prob[best];
    h->share = (signs > 0.0f) ? (prob[best] / signs) : 0.0f;
    return signs;
}

/* The class stage's buffers in the workspace. */
typedef struct recog_picto_buf_s {
    float *feat;
    float *prob;
    float *mean; /* averaged probabilities of several views */
    void *ws;
} recog_picto_buf_t;

/* The box of a hypothesis's centre and size, x0, y0, x1, y1 (unclipped). */
static void centre_box(const recog_hyp_t *h, float box[4])
{
    box[0] = h->mx - (0.5f * h->mw);
    box[1] = h->my - (0.5f * h->mh);
    box[2] = h->mx + (0.5f * h->mw);
    box[3] = h->my + (0.5f * h->mh);
}

/* Features and class probabilities of one box; 0 when it cannot be sampled. */
static int picto_box(const sbr_image_t *view, const sbr_picto_model_t *pm, const float box[4],
                     recog_picto_buf_t *b)
{
    int ok = 0;
    if ((sbr_picto_features(view, box, b->feat, SBR_PICTO_FEATURES, b->ws,
                            SBR_PICTO_WORKSPACE_SIZE) == SBR_OK) &&
        (sbr_picto_classify(pm, b->feat, SBR_PICTO_FEATURES, b->prob, SBR_PICTO_OUTPUTS, b->ws,
                            SBR_PICTO_WORKSPACE_SIZE) == SBR_OK)) {
        ok = 1;
    }
    return ok;
}

/* Class and score from the mean class probabilities of `views` views of box: the box,
   then shifted by SBR_RECOG_VIEW_SHIFT of its size right, left, down and up (views that
   cannot be sampled are left out). b->prob holds the box's own probabilities on entry.
   Returns the number of extra views classified. */
static uint32_t average_views(recog_hyp_t *h, const sbr_image_t *view,
                              const sbr_picto_model_t *pm, uint32_t views, const float box[4],
                              recog_picto_buf_t *b)
{
    static const float dir[SBR_RECOG_MAX_VIEWS - 1u][2] = {
        {1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, -1.0f}};
    const float dx = SBR_RECOG_VIEW_SHIFT * (box[2] - box[0]);
    const float dy = SBR_RECOG_VIEW_SHIFT * (box[3] - box[1]);
    float *mean = b->mean;
    float n = 1.0f;
    uint32_t v;
    uint32_t k;
    for (k = 0u; k < SBR_PICTO_OUTPUTS; k++) {
        mean[k] = b->prob[k];
    }
    for (v = 0u; v < (views - 1u); v++) {
        float vb[4];
        vb[0] = box[0] + (dir[v][0] * dx);
        vb[1] = box[1] + (dir[v][1] * dy);
        vb[2] = box[2] + (dir[v][0] * dx);
        vb[3] = box[3] + (dir[v][1] * dy);
        if (picto_box(view, pm, vb, b) != 0) {
            for (k = 0u; k < SBR_PICTO_OUTPUTS; k++) {
                mean[k] += b->prob[k];
            }
            n += 1.0f;
        }
    }
    for (k = 0u; k < SBR_PICTO_OUTPUTS; k++) {
        mean[k] /= n;
    }
    (void)take_class(h, mean);
    return (uint32_t)n - 1u;
}

/* Is GTSDB class c a danger sign (an upward red triangle: 11, 18..31)? */
static int danger_class(uint32_t c)
{
    return ((c == 11u) || ((c >= 18u) && (c <= 31u))) ? 1 : 0;
}

/* The danger classes' probability together. */
static float danger_mass(const float *prob)
{
    float m = 0.0f;
    uint32_t k;
    for (k = 0u; k < SBR_PICTO_BACKGROUND; k++) {
        if (danger_class(k) != 0) {
            m += prob[k];
        }
    }
    return m;
}

/* config.triangle_view: classify the inside of the triangle inscribed in box; its most
   probable sign class replaces the hypothesis's class and score when it is a danger sign
   and more probable than the current score. */
static void triangle_view(recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm,
                          const float box[4], recog_picto_buf_t *b)
{
    if ((sbr_picto_features_outline(view, box, (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE, b->feat,
                                    SBR_PICTO_FEATURES, b->ws, SBR_PICTO_WORKSPACE_SIZE) == SBR_OK) &&
        (sbr_picto_classify(pm, b->feat, SBR_PICTO_FEATURES, b->prob, SBR_PICTO_OUTPUTS, b->ws,
                            SBR_PICTO_WORKSPACE_SIZE) == SBR_OK)) {
        recog_hyp_t t = *h;
        (void)take_class(&t, b->prob);
        if ((danger_class(t.class_id) != 0) && (t.score > h->score)) {
            h->class_id = t.class_id;
            h->score = t.score;
            h->share = t.share;
        }
    }
}

/* The class stage on one hypothesis: classify its box; if the signs are at least
   refine_first_score probable, and then while they are at least refine_score probable
   (at most refine_steps times in all), move the box by the classifier's box regression
   and classify again there; the box is the last one, and so are class
   and score unless the candidate, still view_score likely, gets the mean of
   config.views views (average_views()).
   Returns 0 when the box cannot be sampled; counts refinements and extra views in *st. */
static int classify_hyp(recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm,
                        const sbr_recog_config_t *cfg, recog_picto_buf_t *b,
                        sbr_recog_stats_t *st)
{
    float box[4];
    float signs; /* the sign classes' probability at the current box */
    float danger; /* the danger classes' probability at the first box */
    uint32_t step = 0u;
    uint32_t steps = 0u;
    centre_box(h, box);
    if (picto_box(view, pm, box, b) == 0) {
        return 0;
    }
    danger = (cfg->triangle_view != 0u) ? danger_mass(b->prob) : 0.0f;
    signs = take_class(h, b->prob);
    if ((signs >= cfg->refine_first_score) && (pm->w3 != NULL)) {
        steps = cfg->refine_steps;
    }
    while (step < steps) {
        float nb[4];
        step++;
        if ((sbr_picto_refine(pm, b->feat, SBR_PICTO_FEATURES, box, nb, b->ws,
                              SBR_PICTO_WORKSPACE_SIZE) != SBR_OK) ||
            (picto_box(view, pm, nb, b) == 0)) {
            step = steps; /* the box left the image: keep the last one */
        } else {
            st->refined++;
            box[0] = nb[0];
            box[1] = nb[1];
            box[2] = nb[2];
            box[3] = nb[3];
            h->mx = 0.5f * (box[0] + box[2]);
            h->my = 0.5f * (box[1] + box[3]);
            h->mw = box[2] - box[0];
            h->mh = box[3] - box[1];
            signs = take_class(h, b->prob);
            if (signs < cfg->refine_score) {
                step = steps; /* no longer a likely sign: this was the last move */
            }
        }
    }
    if ((cfg->views > 1u) && (signs >= cfg->view_score)) {
        st->views += average_views(h, view, pm, cfg->views, box, b);
    }
    if ((cfg->triangle_view != 0u) && (danger >= cfg->triangle_score)) {
        triangle_view(h, view, pm, box, b);
    }
    return 1;
}

/* Does a candidate pass the class stage's gate (sbr_picto_model_t::gate)? A box the gate
   cannot look at (outside the domain of the class stage's boxes) does not. */
static int gate_passes(const recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm,
                       recog_picto_buf_t *pb)
{
    float box[4];
    float score = 0.0f;
    int pass = 0;
    centre_box(h, box);
    if ((sbr_picto_gate_features(view, box, pb->feat, SBR_PICTO_FEATURES, pb->ws,
                                 SBR_PICTO_WORKSPACE_SIZE) == SBR_OK) &&
        (sbr_picto_gate(pm, pb->feat, SBR_PICTO_FEATURES, &score) == SBR_OK) &&
        (score >= pm->gate_threshold)) {
        pass = 1;
    }
    return pass;
}

/* The class stage's colour check (sbr_picto_model_t::rim_floor): 1 when the model has one
   for the candidate's class and the rim of its box is less red against its inside than
   the class's threshold, or when it cannot be measured. */
static int rim_fails(const recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm)
{
    int fails = 0;
    if ((pm->rim_shape != NULL) && (pm->rim_floor != NULL) && (h->class_id < SBR_PICTO_CLASSES) &&
        (pm->rim_shape[h->class_id] != (uint8_t)SBR_PICTO_RIM_NONE)) {
        float box[4];
        float contrast = 0.0f;
        centre_box(h, box);
        if ((sbr_picto_rim_contrast(view, box, (uint32_t)pm->rim_shape[h->class_id], &contrast) !=
             SBR_OK) ||
            (contrast < pm->rim_floor[h->class_id])) {
            fails = 1;
        }
    }
    return fails;
}

sbr_status_t sbr_recog_detect(const sbr_image_t *img, const sbr_rect_t *roi,
                              const sbr_recog_config_t *cfg, const sbr_model_t *model,
                              void *workspace, size_t workspace_size, sbr_detection_t *dets,
                              uint32_t capacity, uint32_t *count, sbr_recog_stats_t *stats)
{
    recog_ctx_t c;
    recog_layout_t l;
    sbr_image_t view;
    sbr_fft_t fft_n;
    uint8_t *base;
    uint32_t ox = 0u;
    uint32_t oy = 0u;
    uint32_t i;
    uint32_t out = 0u;
    uint32_t kept;
    uint32_t t0 = 0u;
    int full = 0;
    sbr_status_t st;

    if ((img == NULL) || (cfg == NULL) || (model == NULL) || (dets == NULL) || (count == NULL)) {
        return SBR_ERR_NULL;
    }
    *count = 0u;
    st = sbr_recog_config_check(cfg);
    if (st != SBR_OK) {
        return st;
    }
    st = sbr_model_check(model);
    if (st != SBR_OK) {
        return st;
    }
    if ((model->fd_n != cfg->parts.fd_n) || (model->fd_m != cfg->parts.fd_m) ||
        (model->proto_count > cfg->max_model_protos)) {
        return SBR_ERR_RANGE;
    }
    if ((img->format != SBR_PIXEL_RGB888) && (img->format != SBR_PIXEL_BGR888)) {
        st = sbr_image_check(img);
        return (st != SBR_OK) ? st : SBR_ERR_RANGE;
    }
    if (roi != NULL) {
        st = sbr_image_roi(img, roi, &view);
        ox = roi->x;
        oy = roi->y;
    } else {
        st = sbr_image_check(img);
        view = *img;
    }
    if (st != SBR_OK) {
        return st;
    }
    if ((recog_layout(view.width, view.height, cfg, &l) == 0) || (capacity == 0u)) {
        return SBR_ERR_SIZE;
    }
    if ((workspace == NULL) || (workspace_size < l.total) ||
        (sbr_util_aligned(workspace, 8u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    (void)memset(&c, 0, sizeof c);
    if ((sbr_fft_init(&fft_n, cfg->parts.fd_n) != SBR_OK) ||
        (sbr_fft_init(&c.fft_p, cfg->match_p) != SBR_OK)) {
        return SBR_ERR_RANGE;
    }
    c.cfg = cfg;
    c.model = model;
    c.vote_error = (cfg->vote_error > 0.0f) ? cfg->vote_error : model->vote_error;
    c.score_floor = (model->picto.version != 0u) ? cfg->candidate_score : cfg->min_score;
    (void)sbr_fd_match_config_default(&c.mcfg);
    c.mcfg.mode = SBR_FD_ROTATION_COVARIANT;
    c.mcfg.max_rotation = cfg->max_rotation;
    c.vcfg = c.mcfg;
    c.mcfg.max_error = c.vote_error;   /* only matches up to these errors count */
    c.vcfg.max_error = cfg->verify_error;
    base = (uint8_t *)workspace;
    c.parts = (sbr_part_t *)(void *)&base[l.parts_ws];
    base = &base[l.parts_ws + l.parts];
    c.index = (recog_index_t *)(void *)base;
    base = &base[l.index];
    c.results = (sbr_fd_match_t *)(void *)base;
    base = &base[l.results];
    c.work = (sbr_complex_t *)(void *)base;
    c.work_len = cfg->match_p * 5u; /* SBR_FD_TABLE_WORK_LEN */
    base = &base[l.work];
    c.votes = (recog_vote_t *)(void *)base;
    base = &base[l.votes];
    c.hyps = (recog_hyp_t *)(void *)base;
    base = (uint8_t *)workspace;

    if (cfg->clock != NULL) {
        t0 = cfg->clock(cfg->clock_ctx);
    }

    /* 1. parts */
    st = sbr_parts_extract(&view, &cfg->parts, &fft_n, workspace, l.parts_ws, c.parts,
                           cfg->max_parts, &c.nparts, &c.st.parts_stats);
    if (st == SBR_ERR_CAPACITY) {
        c.st.capacity_hit |= 1u;
    } else if (st != SBR_OK) {
        return st;
    } else {
        /* all parts */
    }
    if (c.st.parts_stats.capacity_hit != 0u) {
        c.st.capacity_hit |= 8u;
    }
    c.st.parts = c.nparts;
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_PARTS, &t0);

    /* 2. votes */
    for (i = 0u; i < c.nparts; i++) {
        st = cast_votes(&c, i);
        if (st != SBR_OK) {
            return st;
        }
    }
    c.st.votes = c.nvotes;
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_VOTES, &t0);

    /* 3. hypotheses */
    heap_sort((uint8_t *)(void *)c.votes, c.nvotes, sizeof(recog_vote_t), vote_before, 0);
    group_votes(&c);
    c.st.hypotheses = c.nhyps;
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_GROUP, &t0);

    /* 4. evidence per class, cascade verification */
    heap_sort((uint8_t *)(void *)c.votes, c.nvotes, sizeof(recog_vote_t), vote_before, 1);
    index_parts(&c);
    score_hyps(&c);
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_VERIFY, &t0);

    /* 5. non-maximum suppression on part evidence, best first (with a class stage at
       candidate_iou, by default none: only empty boxes go) */
    kept = compact_sorted(&c);
    suppress(&c, kept, view.width, view.height,
             (model->picto.version != 0u) ? cfg->candidate_iou : cfg->nms_iou);
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_NMS, &t0);

    /* 6. class stage: the pictogram classifier scores and classifies the survivors, then
       suppression again on the new scores */
    if (model->picto.version != 0u) {
        uint32_t examined = 0u;
        float *feat = (float *)(void *)&base[l.total - l.picto];
        float *prob = &feat[SBR_PICTO_FEATURES];
        recog_picto_buf_t pb;
        pb.feat = feat;
        pb.prob = prob;
        pb.mean = &prob[SBR_PICTO_OUTPUTS];
        pb.ws = (void *)&prob[2u * SBR_PICTO_OUTPUTS];
        for (i = 0u; i < kept; i++) {
            recog_hyp_t *h = &c.hyps[i];
            if (h->keep == 0u) {
                continue;
            }
            h->keep = 0u;
            if (examined >= cfg->max_candidates) {
                c.st.capacity_hit |= 16u;
                continue;
            }
            examined++;
            if ((cfg->gate != 0u) && (model->picto.gate != NULL) &&
                (gate_passes(h, &view, &model->picto, &pb) == 0)) {
                c.st.gated++;
                continue;
            }
            if (classify_hyp(h, &view, &model->picto, cfg, &pb, &c.st) == 0) {
                continue;
            }
            if ((h->score >= cfg->min_score) && (rim_fails(h, &view, &model->picto) != 0)) {
                c.st.rim_rejected++;
            } else if (h->score >= cfg->min_score) {
                h->keep = 1u;
            } else {
                c.st.rejected++;
            }
        }
        c.st.classified = examined;
        kept = compact_sorted(&c);
        suppress(&c, kept, view.width, view.height, cfg->nms_iou);
    }
    stage_end(&c, (uint32_t)SBR_RECOG_STAGE_CLASS, &t0);

    /* 7. output, best first */
    for (i = 0u; i < kept; i++) {
        if (c.hyps[i].keep == 0u) {
            continue;
        }
        if (out >= capacity) {
            full = 1;
        } else {
            sbr_detection_t *d = &dets[out];
            float bi[4];
            hyp_box(&c.hyps[i], view.width, view.height, bi);
            d->box.x = ox + (uint32_t)bi[0];
            d->box.y = oy + (uint32_t)bi[1];
            d->box.width = (uint32_t)(bi[2] + 0.5f) - (uint32_t)bi[0];
            d->box.height = (uint32_t)(bi[3] + 0.5f) - (uint32_t)bi[1];
            d->score = c.hyps[i].score;
            d->class_share = c.hyps[i].share;
            d->class_id = c.hyps[i].class_id;
            d->parts = c.hyps[i].parts;
            out++;
        }
    }

    *count = out;
    if (stats != NULL) {
        *stats = c.st;
    }
    return (full != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}
