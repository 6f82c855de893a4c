/* SPDX-License-Identifier: MIT */
/*
 * Recogniser: the class stage (pictogram classifier) on the candidates. See
 * include/sbr/recog.h.
 */
#include "recog_internal.h"

#include <string.h>

/* Class and score of one classified box: class = the most probable sign class, score = its
   probability, share = its share of the sign classes' probability. Returns the sign
   classes' total probability. */
static float take_class(recog_hyp_t *h, const float *prob, uint32_t classes)
{
    float signs = 0.0f;
    uint32_t best = 0u;
    uint32_t k;
    for (k = 0u; k < classes; k++) {
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
/* The box of a hypothesis's centre and size, x0, y0, x1, y1 (unclipped). */
static void centre_box(const recog_hyp_t *h, float box[4])
{
    box[0] = h->mx - (0.5f * h->mw);
    box[1] = h->my - (0.5f * h->mh);
    box[2] = h->mx + (0.5f * h->mw);
    box[3] = h->my + (0.5f * h->mh);
}

/* Class probabilities of one box (a look, whose features stay for the box regression);
   0 when it cannot be sampled. */
static int picto_box(const sbr_image_t *view, const sbr_picto_model_t *pm, const float box[4],
                     recog_picto_buf_t *b)
{
    int ok = 0;
    if (sbr_picto_look(pm, view, box, (uint32_t)SBR_PICTO_OUTLINE_BOX, b->prob,
                       SBR_PICTO_MAX_OUTPUTS, b->look, SBR_PICTO_LOOK_WORKSPACE_SIZE) == SBR_OK) {
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
    /* (the caller checks the extra-look budget for views - 1 looks) */
    static const float dir[SBR_RECOG_MAX_VIEWS - 1u][2] = {
        {1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, -1.0f}};
    const float dx = SBR_RECOG_VIEW_SHIFT * (box[2] - box[0]);
    const float dy = SBR_RECOG_VIEW_SHIFT * (box[3] - box[1]);
    float *mean = b->mean;
    const uint32_t outputs = b->classes + 1u;
    float n = 1.0f;
    uint32_t v;
    uint32_t k;
    for (k = 0u; k < outputs; k++) {
        mean[k] = b->prob[k];
    }
    for (v = 0u; v < (views - 1u); v++) {
        float vb[4];
        vb[0] = box[0] + (dir[v][0] * dx);
        vb[1] = box[1] + (dir[v][1] * dy);
        vb[2] = box[2] + (dir[v][0] * dx);
        vb[3] = box[3] + (dir[v][1] * dy);
        if (picto_box(view, pm, vb, b) != 0) {
            for (k = 0u; k < outputs; k++) {
                mean[k] += b->prob[k];
            }
            n += 1.0f;
        }
    }
    for (k = 0u; k < outputs; k++) {
        mean[k] /= n;
    }
    (void)take_class(h, mean, b->classes);
    return (uint32_t)n - 1u;
}

/* Is class c's sign an upward triangle (the model's outlines; GTSDB's danger signs)? */
static int triangle_class(const recog_picto_buf_t *b, uint32_t c)
{
    return (b->outline[c] == (uint8_t)SBR_PICTO_RIM_TRIANGLE) ? 1 : 0;
}

/* The upward-triangle classes' probability together. */
static float triangle_mass(const recog_picto_buf_t *b)
{
    float m = 0.0f;
    uint32_t k;
    for (k = 0u; k < b->classes; k++) {
        if (triangle_class(b, k) != 0) {
            m += b->prob[k];
        }
    }
    return m;
}

/* config.triangle_view: classify the inside of the triangle inscribed in box; its most
   probable sign class replaces the hypothesis's class and score when its sign is an upward
   triangle and it is more probable than the current score. */
static void triangle_view(recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm,
                          const float box[4], recog_picto_buf_t *b)
{
    if (sbr_picto_look(pm, view, box, (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE, b->prob,
                       SBR_PICTO_MAX_OUTPUTS, b->look, SBR_PICTO_LOOK_WORKSPACE_SIZE) == SBR_OK) {
        recog_hyp_t t = *h;
        (void)take_class(&t, b->prob, b->classes);
        if ((triangle_class(b, t.class_id) != 0) && (t.score > h->score)) {
            h->class_id = t.class_id;
            h->score = t.score;
            h->share = t.share;
        }
    }
}

/* One extra look from the frame's budget (config.max_extra_looks): 1 if there were
   n left (otherwise none is taken and the bound is marked reached). */
static int spend_look(sbr_recog_stats_t *st, uint32_t budget, uint32_t n)
{
    int ok = 0;
    if ((st->extra_looks <= budget) && (n <= (budget - st->extra_looks))) {
        st->extra_looks += n;
        ok = 1;
    } else {
        st->capacity_hit |= SBR_RECOG_HIT_LOOKS;
    }
    return ok;
}

/* The class stage on one hypothesis: classify its box; if the signs are at least
   refine_first_score probable (grey_refine_first_score on a grey frame; the thresholds
   are the class stage's, pm->looks), and then while they are at least refine_score
   probable (at most refine_steps times in all), move the
   box by the classifier's box regression
   and classify again there; the box is the last one, and so are class
   and score unless the candidate, still view_score likely, gets the mean of
   config.views views (average_views()).
   Each look after the first takes from the frame's budget (spend_look()).
   Returns 0 when the box cannot be sampled; counts refinements and extra views in *st. */
static int classify_hyp(recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm,
                        const sbr_recog_config_t *cfg, recog_picto_buf_t *b,
                        sbr_recog_stats_t *st)
{
    float box[4];
    float signs; /* the sign classes' probability at the current box */
    float danger; /* the upward-triangle classes' probability at the first box */
    const sbr_picto_looks_t *lk = &pm->looks;
    const float first = (view->format == SBR_PIXEL_GRAY8) ? lk->grey_refine_first_score
                                                          : lk->refine_first_score;
    uint32_t step = 0u;
    uint32_t steps = 0u;
    centre_box(h, box);
    if (picto_box(view, pm, box, b) == 0) {
        return 0;
    }
    danger = (cfg->triangle_view != 0u) ? triangle_mass(b) : 0.0f;
    signs = take_class(h, b->prob, b->classes);
    if ((signs >= first) && (pm->w3 != NULL)) {
        steps = cfg->refine_steps;
    }
    while (step < steps) {
        float nb[4];
        step++;
        if ((sbr_picto_look_refine(pm, nb, b->look, SBR_PICTO_LOOK_WORKSPACE_SIZE) != SBR_OK) ||
            (spend_look(st, cfg->max_extra_looks, 1u) == 0) || (picto_box(view, pm, nb, b) == 0)) {
            step = steps; /* the box left the image, or the frame's extra looks are spent:
                             keep the last one */
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
            signs = take_class(h, b->prob, b->classes);
            if (signs < lk->refine_score) {
                step = steps; /* no longer a likely sign: this was the last move */
            }
        }
    }
    if ((cfg->views > 1u) && (signs >= lk->view_score) &&
        (spend_look(st, cfg->max_extra_looks, cfg->views - 1u) != 0)) {
        st->views += average_views(h, view, pm, cfg->views, box, b);
    }
    if ((cfg->triangle_view != 0u) && (danger >= lk->triangle_score) &&
        (spend_look(st, cfg->max_extra_looks, 1u) != 0)) {
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
    if ((sbr_picto_look_gate(pm, view, box, &score, pb->look, SBR_PICTO_LOOK_WORKSPACE_SIZE) ==
         SBR_OK) &&
        (score >= pm->gate_threshold)) {
        pass = 1;
    }
    return pass;
}

/* The class stage's colour check (sbr_picto_model_t::rim_floor): 1 when the model has one
   for the candidate's class and the rim of its box is less red against its inside than
   the class's threshold, or when it cannot be measured. A grey frame has no colour to
   check: 0. */
static int rim_fails(const recog_hyp_t *h, const sbr_image_t *view, const sbr_picto_model_t *pm)
{
    int fails = 0;
    if ((view->format != SBR_PIXEL_GRAY8) && (pm->rim_shape != NULL) && (pm->rim_floor != NULL) && ((uint32_t)h->class_id < pm->classes) &&
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

/* The class stage's verdict on one candidate: gated away, not classifiable, colour check
   failed, below min_score, or kept (h->keep). */
static void class_verdict(recog_ctx_t *c, recog_hyp_t *h, const sbr_image_t *view,
                          recog_picto_buf_t *pb)
{
    const sbr_recog_config_t *cfg = c->cfg;
    const sbr_picto_model_t *pm = c->picto;
    h->keep = 0u;
    if ((cfg->gate != 0u) && (pm->gate != NULL) && (gate_passes(h, view, pm, pb) == 0)) {
        c->st.gated++;
    } else if (classify_hyp(h, view, pm, cfg, pb, &c->st) == 0) {
        /* the box cannot be sampled */
    } else if ((h->score >= cfg->min_score) && (rim_fails(h, view, pm) != 0)) {
        c->st.rim_rejected++;
    } else if (h->score >= cfg->min_score) {
        h->keep = 1u;
    } else {
        c->st.rejected++;
    }
}

/* The box of an outline candidate's part, x0, y0, x1, y1, if it is one (config.outline_maps,
   its size and proportions); 0 otherwise. */
static int outline_box(const sbr_part_t *p, const sbr_recog_config_t *cfg, float b[4])
{
    const float w = (float)p->bbox.width;
    const float h = (float)p->bbox.height;
    const float big = sbr_util_maxf(w, h);
    int ok = 0;
    if (((uint32_t)p->map < (uint32_t)SBR_MAP_KINDS) &&
        (((cfg->outline_maps >> (uint32_t)p->map) & 1u) != 0u) &&
        (p->polarity == (uint8_t)SBR_MSER_BRIGHT) && (big >= cfg->min_size) &&
        (big <= cfg->max_size) && (big <= (SBR_RECOG_OUTLINE_ASPECT * sbr_util_minf(w, h)))) {
        b[0] = (float)p->bbox.x;
        b[1] = (float)p->bbox.y;
        b[2] = b[0] + w;
        b[3] = b[1] + h;
        ok = 1;
    }
    return ok;
}

uint32_t sbr_recog_priv_outline_candidates(recog_ctx_t *c, uint32_t kept)
{
    const sbr_recog_config_t *cfg = c->cfg;
    uint32_t end = kept;
    uint32_t i;
    int full = 0;
    for (i = 0u; (i < c->nparts) && (cfg->outline_maps != 0u) && (full == 0); i++) {
        float b[4];
        if (outline_box(&c->parts[i], cfg, b) != 0) {
            uint32_t j;
            int nested = 0;
            for (j = kept; (j < end) && (nested == 0); j++) {
                float o[4];
                centre_box(&c->hyps[j], o);
                if (sbr_util_box_iou(b, o) > SBR_RECOG_OUTLINE_IOU) {
                    nested = 1;
                }
            }
            if (nested != 0) {
                /* the same box as an earlier one */
            } else if (((end - kept) >= cfg->max_outline_candidates) ||
                       (end >= cfg->max_hypotheses)) {
                c->st.capacity_hit |= SBR_RECOG_HIT_OUTLINES;
                full = 1;
            } else {
                recog_hyp_t *h = &c->hyps[end];
                (void)memset(h, 0, sizeof *h);
                h->mx = 0.5f * (b[0] + b[2]);
                h->my = 0.5f * (b[1] + b[3]);
                h->mw = b[2] - b[0];
                h->mh = b[3] - b[1];
                h->keep = 1u;
                end++;
            }
        }
    }
    c->nhyps = end;
    c->st.outlines = end - kept;
    return end;
}

void sbr_recog_priv_class_stage(recog_ctx_t *c, const sbr_image_t *view, uint32_t kept,
                                uint32_t end, recog_picto_buf_t *pb)
{
    uint32_t examined = 0u;
    uint32_t i;
    for (i = 0u; i < kept; i++) {
        recog_hyp_t *h = &c->hyps[i];
        if (h->keep == 0u) {
            /* suppressed on part evidence */
        } else if (examined >= c->cfg->max_candidates) {
            h->keep = 0u;
            c->st.capacity_hit |= SBR_RECOG_HIT_CANDIDATES;
        } else {
            examined++;
            class_verdict(c, h, view, pb);
        }
    }
    for (i = kept; i < end; i++) {
        class_verdict(c, &c->hyps[i], view, pb);
    }
    c->st.classified = examined + (end - kept);
}
