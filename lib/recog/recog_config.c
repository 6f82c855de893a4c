/* SPDX-License-Identifier: MIT */
/*
 * Recogniser: configuration, model check and workspace layout. See include/sbr/recog.h.
 */
#include "recog_internal.h"
#include "sbr/recog_strips.h"

#include <string.h>

void sbr_recog_config_default(sbr_recog_config_t *cfg)
{
    if (cfg != NULL) {
        /* every field's default is in the table (recog_fields.c); the clock is not a field */
        (void)memset(cfg, 0, sizeof *cfg);
        sbr_recog_priv_fields_default(cfg);
        cfg->clock = NULL;
        cfg->clock_ctx = NULL;
    }
}

void sbr_recog_config_strips(sbr_recog_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_recog_config_default(cfg);
        cfg->parts.mser.max_nodes = SBR_RECOG_STRIP_MAX_NODES;
        cfg->parts.mser.max_heap = SBR_RECOG_STRIP_MAX_HEAP;
        cfg->max_parts = SBR_RECOG_STRIP_MAX_PARTS;
        cfg->max_candidates = SBR_RECOG_STRIP_MAX_CANDIDATES;
        cfg->max_outline_candidates = SBR_RECOG_STRIP_MAX_OUTLINES;
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
    sbr_status_t st = SBR_ERR_NULL;
    if (cfg != NULL) {
        st = SBR_ERR_RANGE;
        /* the table's ranges and links; the part stage's own check agrees with them
           (tests/test_recog_fields.c) and stays as a second line */
        if ((sbr_recog_config_check_field(cfg) == SBR_RECOG_FIELD_NONE) &&
            (sbr_parts_config_check(&cfg->parts) == SBR_OK)) {
            st = SBR_OK;
        }
    }
    return st;
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

int sbr_recog_priv_layout(uint32_t width, uint32_t height, const sbr_recog_config_t *cfg,
                          recog_layout_t *l)
{
    const uint32_t work_len = SBR_FD_TABLE_WORK_LEN(cfg->match_p);
    size_t after_parts;
    /* after the part stage its block holds everything but the parts: the prototypes'
       magnitudes (the matcher's screening), the vote grouping's grid of hypotheses, the
       part index, the match results, the matcher's scratch, the votes and the hypotheses */
    l->mags = SBR_WS_ALIGN8((size_t)cfg->max_model_protos * ((2u * cfg->parts.fd_m) + 1u) *
                            sizeof(float));
    l->grid_cols = (width / 16u) + 2u;
    l->grid = SBR_WS_ALIGN8(((size_t)l->grid_cols + (2u * (size_t)cfg->max_hypotheses)) *
                            sizeof(uint32_t));
    l->index = SBR_WS_ALIGN8((size_t)cfg->max_parts * SBR_RECOG_INDEX_BYTES);
    l->results = SBR_WS_ALIGN8((size_t)cfg->max_model_protos * sizeof(sbr_fd_match_t));
    /* the table matcher's four-lane scratch */
    l->work = SBR_WS_ALIGN8((size_t)work_len * sizeof(sbr_complex_t));
    l->votes = SBR_WS_ALIGN8((size_t)cfg->max_votes * SBR_RECOG_VOTE_BYTES);
    l->hyps = SBR_WS_ALIGN8((size_t)cfg->max_hypotheses * SBR_RECOG_HYP_BYTES);
    after_parts = l->mags + l->grid + l->index + l->results + l->work + l->votes + l->hyps;
    l->parts_ws = SBR_WS_ALIGN8(sbr_parts_workspace_size(&cfg->parts, width, height));
    if (l->parts_ws == 0u) {
        return 0;
    }
    l->parts_ws = SBR_WS_MAX(l->parts_ws, after_parts);
    l->parts = SBR_WS_ALIGN8((size_t)cfg->max_parts * sizeof(sbr_part_t));
    l->picto = SBR_RECOG_CLASS_BYTES;
    l->total = l->parts_ws + l->parts + l->picto;
    return 1;
}

size_t sbr_recog_workspace_size(const sbr_recog_config_t *cfg, uint32_t width, uint32_t height)
{
    recog_layout_t l;
    if ((sbr_recog_config_check(cfg) != SBR_OK) || (width > SBR_IMAGE_MAX_DIM) ||
        (height > SBR_IMAGE_MAX_DIM) || (sbr_recog_priv_layout(width, height, cfg, &l) == 0)) {
        return 0u;
    }
    return l.total;
}
