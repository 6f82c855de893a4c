/* SPDX-License-Identifier: MIT */
/*
 * Recogniser: ordering and non-maximum suppression of hypotheses. See
 * include/sbr/recog.h.
 */
#include "recog_internal.h"

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

void sbr_recog_priv_hyp_box(const recog_hyp_t *h, uint32_t vw, uint32_t vh, float b[4])
{
    const float hw = 0.5f * h->mw;
    const float hh = 0.5f * h->mh;
    b[0] = sbr_util_maxf(0.0f, h->mx - hw);
    b[1] = sbr_util_maxf(0.0f, h->my - hh);
    b[2] = sbr_util_minf((float)vw, h->mx + hw);
    b[3] = sbr_util_minf((float)vh, h->my + hh);
}

uint32_t sbr_recog_priv_compact(recog_ctx_t *c)
{
    uint32_t kept = 0u;
    uint32_t i;
    for (i = 0u; i < c->nhyps; i++) {
        if (c->hyps[i].keep != 0u) {
            c->hyps[kept] = c->hyps[i];
            kept++;
        }
    }
    sbr_util_heap_sort((uint8_t *)(void *)c->hyps, kept, sizeof(recog_hyp_t), hyp_before, 0);
    c->nhyps = kept;
    return kept;
}

void sbr_recog_priv_suppress(recog_ctx_t *c, uint32_t n, uint32_t vw, uint32_t vh, float iou)
{
    uint32_t i;
    for (i = 0u; i < n; i++) {
        float bi[4];
        uint32_t j;
        uint32_t earlier = 0u; /* the better hypotheses to compare with */
        int suppressed = 0;
        sbr_recog_priv_hyp_box(&c->hyps[i], vw, vh, bi);
        if (iou < 1.0f) {
            earlier = i;
        }
        for (j = 0u; (j < earlier) && (suppressed == 0); j++) {
            if (c->hyps[j].keep != 0u) {
                float bj[4];
                sbr_recog_priv_hyp_box(&c->hyps[j], vw, vh, bj);
                if (sbr_util_box_iou(bi, bj) > iou) {
                    suppressed = 1;
                }
            }
        }
        if ((suppressed != 0) || (bi[2] <= bi[0]) || (bi[3] <= bi[1])) {
            c->hyps[i].keep = 0u;
        }
    }
}
