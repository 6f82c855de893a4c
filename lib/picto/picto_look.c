/* SPDX-License-Identifier: MIT */
/* The class stage's looks at boxes: features and classifier with their buffers in one
   workspace whose layout stays here (picto.h, sbr_picto_look()). */
#include "sbr/picto.h"

#include "picto_internal.h"

#include "../common/sbr_util.h"

#include <string.h>

/* "LOOK": the workspace holds a successful look's box and features. */
#define LOOK_TAG 0x4C4F4F4Bu

/* The workspace's head; the features follow at SBR_PICTO_LOOK_HEAD_BYTES, the
   classifier's scratch after them. */
typedef struct look_head_s {
    uint32_t tag;
    uint32_t hidden; /* the look's model's hidden units: their values lead its scratch */
    float box[4];
} look_head_t;

typedef char look_head_fits[(sizeof(look_head_t) <= SBR_PICTO_LOOK_HEAD_BYTES) ? 1 : -1];
/* The scratch starts 8-byte aligned. */
typedef char look_scratch_aligned[((((size_t)SBR_PICTO_LOOK_HEAD_BYTES +
                                     (SBR_PICTO_FEATURES * sizeof(float))) % 8u) == 0u)
                                      ? 1
                                      : -1];
/* The gate's features and scratch fit a look's feature vector and scratch. */
typedef char look_gate_fits[((SBR_PICTO_GATE_FEATURES <= SBR_PICTO_FEATURES) &&
                             (SBR_PICTO_GATE_WORKSPACE_SIZE <= SBR_PICTO_WORKSPACE_SIZE))
                                ? 1
                                : -1];

/* The parts of a look's workspace (checked: present, large enough, 8-byte aligned). */
typedef struct look_ws_s {
    look_head_t *head;
    float *feat;
    void *scratch;
} look_ws_t;

static sbr_status_t look_ws(void *workspace, size_t workspace_size, look_ws_t *w)
{
    uint8_t *base = (uint8_t *)workspace;
    if ((workspace == NULL) || (workspace_size < SBR_PICTO_LOOK_WORKSPACE_SIZE) ||
        (sbr_util_aligned(workspace, 8u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    w->head = (look_head_t *)workspace;
    w->feat = (float *)(void *)&base[SBR_PICTO_LOOK_HEAD_BYTES];
    w->scratch = (void *)&base[SBR_PICTO_LOOK_HEAD_BYTES + (SBR_PICTO_FEATURES * sizeof(float))];
    return SBR_OK;
}

/* The start of a look or a gate: its pointers present, the workspace checked, and no
   look held from here on (until this one succeeds). */
static sbr_status_t look_start(const sbr_picto_model_t *model, const sbr_image_t *img,
                               const float *box, const float *out, void *workspace,
                               size_t workspace_size, look_ws_t *w)
{
    sbr_status_t st = SBR_ERR_NULL;
    if ((model != NULL) && (img != NULL) && (box != NULL) && (out != NULL)) {
        st = look_ws(workspace, workspace_size, w);
    }
    if (st == SBR_OK) {
        w->head->tag = 0u;
    }
    return st;
}

sbr_status_t sbr_picto_look(const sbr_picto_model_t *model, const sbr_image_t *img,
                            const float box[4], uint32_t outline, float *prob, uint32_t nprob,
                            void *workspace, size_t workspace_size)
{
    look_ws_t w;
    sbr_status_t st = look_start(model, img, box, prob, workspace, workspace_size, &w);
    if (st != SBR_OK) {
        return st;
    }
    st = sbr_picto_features_outline(img, box, outline, w.feat, SBR_PICTO_FEATURES, w.scratch,
                                    SBR_PICTO_WORKSPACE_SIZE);
    if (st == SBR_OK) {
        st = sbr_picto_classify(model, w.feat, SBR_PICTO_FEATURES, prob, nprob, w.scratch,
                                SBR_PICTO_WORKSPACE_SIZE);
    }
    if (st == SBR_OK) {
        (void)memcpy(w.head->box, box, sizeof w.head->box);
        w.head->hidden = model->hidden;
        w.head->tag = LOOK_TAG;
    }
    return st;
}

sbr_status_t sbr_picto_look_refine(const sbr_picto_model_t *model, float refined[4],
                                   void *workspace, size_t workspace_size)
{
    look_ws_t w;
    sbr_status_t st;
    if ((model == NULL) || (refined == NULL)) {
        return SBR_ERR_NULL;
    }
    st = look_ws(workspace, workspace_size, &w);
    if (st != SBR_OK) {
        return st;
    }
    if ((w.head->tag != LOOK_TAG) || (w.head->hidden != model->hidden)) {
        return SBR_ERR_STATE;
    }
    /* the classifier left the rectified hidden units at the start of its scratch (the
       regression's inputs, as sbr_picto_refine() would compute them again); without a
       hidden layer the features are the inputs */
    return sbr_picto_priv_refine_from(model, (model->hidden > 0u) ? (const float *)w.scratch : w.feat,
                                      w.head->box, refined);
}

sbr_status_t sbr_picto_look_gate(const sbr_picto_model_t *model, const sbr_image_t *img,
                                 const float box[4], float *score, void *workspace,
                                 size_t workspace_size)
{
    look_ws_t w;
    sbr_status_t st = look_start(model, img, box, score, workspace, workspace_size, &w);
    if (st != SBR_OK) {
        return st;
    }
    st = sbr_picto_gate_features(img, box, w.feat, SBR_PICTO_FEATURES, w.scratch,
                                 SBR_PICTO_WORKSPACE_SIZE);
    if (st == SBR_OK) {
        st = sbr_picto_gate(model, w.feat, SBR_PICTO_FEATURES, score);
    }
    return st;
}
