/* SPDX-License-Identifier: MIT */
/*
 * The part model (part_model.h): the prototype library's check and its groups.
 */
#include "sbr/part_model.h"

#include "sbr/mser.h"

/* Is v in [lo, hi] (false for NaN)? */
static int in_range(float v, float lo, float hi)
{
    int ok = 0;
    if ((v >= lo) && (v <= hi)) {
        ok = 1;
    }
    return ok;
}

uint32_t sbr_model_group(uint8_t map, uint8_t polarity)
{
    uint32_t g = SBR_MODEL_GROUPS;
    if (((polarity == (uint8_t)SBR_MSER_DARK) || (polarity == (uint8_t)SBR_MSER_BRIGHT)) &&
        ((uint32_t)map < (SBR_MODEL_GROUPS / 2u))) {
        g = ((uint32_t)map * 2u) + ((uint32_t)polarity - 1u);
    }
    return g;
}

static int proto_ok(const sbr_model_proto_t *p, uint32_t g, uint32_t class_count)
{
    uint32_t k;
    float sum = 0.0f;
    int ok = 1;
    if ((in_range(p->dx, -100.0f, 100.0f) == 0) || (in_range(p->dy, -100.0f, 100.0f) == 0) ||
        (in_range(p->w, 1.0e-3f, 100.0f) == 0) || (in_range(p->h, 1.0e-3f, 100.0f) == 0) ||
        (in_range(p->weight, 1.0e-6f, 1.0f) == 0) ||
        (sbr_model_group(p->map, p->polarity) != g)) { /* also a map or polarity out of range */
        ok = 0;
    }
    for (k = 0u; (k < SBR_MODEL_PROTO_CLASSES) && (ok != 0); k++) {
        if (p->class_id[k] == (uint8_t)SBR_MODEL_NO_CLASS) {
            if (p->class_p[k] != 0.0f) {
                ok = 0;
            }
        } else if (((uint32_t)p->class_id[k] >= class_count) ||
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

/* The class tables: the count in range (checked first), outlines in range, the cascade
   ranges ordered and their prototype indices in range. */
static int classes_ok(const sbr_model_t *model)
{
    uint32_t c;
    uint32_t i;
    int ok = 1;
    for (c = 0u; (c < model->class_count) && (ok != 0); c++) {
        if ((model->class_first[c + 1u] < model->class_first[c]) ||
            (model->class_outline[c] > (uint8_t)SBR_PICTO_RIM_TRIANGLE_DOWN)) {
            ok = 0;
        }
    }
    for (i = 0u; (ok != 0) && (i < model->class_first[model->class_count]); i++) {
        if (model->cascade[i] >= model->proto_count) {
            ok = 0;
        }
    }
    return ok;
}

sbr_status_t sbr_model_check(const sbr_model_t *model)
{
    uint32_t g;
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
        (model->class_count == 0u) || (model->class_count > SBR_RECOG_MAX_CLASSES) ||
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
            if ((proto_ok(&model->protos[i], g, model->class_count) == 0) || (model->fds[i].m != model->fd_m) ||
                (sbr_fd_check(&model->fds[i], &e) != SBR_OK) || (in_range(e, 0.99f, 1.01f) == 0) ||
                (in_range(model->fds[i].scale, SBR_MODEL_MIN_SCALE, SBR_MODEL_MAX_SCALE) == 0)) {
                return SBR_ERR_CORRUPT;
            }
        }
    }
    if (classes_ok(model) == 0) {
        return SBR_ERR_CORRUPT;
    }
    return SBR_OK;
}

