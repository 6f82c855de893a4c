/* SPDX-License-Identifier: MIT */
/*
 * Recogniser: configuration, model check and workspace layout. See include/sbr/recog.h.
 */
#include "recog_internal.h"

void sbr_recog_config_default(sbr_recog_config_t *cfg)
{
    if (cfg != NULL) {
        sbr_parts_config_default(&cfg->parts);
        /* finer than the MSER defaults: small, blurred signs need a smaller delta and a
           looser stability bound to come out as regions at all */
        cfg->parts.mser.delta = SBR_RECOG_DEFAULT_DELTA;
        cfg->parts.mser.max_variation = 0.5f;
        /* intensity, red and blue, each flooded where its signs are (docs/results/realtime.md):
           - intensity: bright regions only (white insides, pictograms on blue); its dark
             flood cost a third of the part stage and carried few signs the other maps miss;
           - red: bright regions from level 136 up (red rims, no-entry discs, stop signs):
             under 2 % of a scene's pixels are that red, so its flood costs a few per cent
             of a full one;
           - blue at half resolution (a quarter of the pixels; its signs are large enough),
             regions from 20 of its pixels (the outlines of signs from about 11 px; 40
             lost mandatory signs of 17-22 px, docs/results/crossval.md), bright ones
             (blue signs) and dark ones up to level 120 (the yellow of priority roads). */
        cfg->parts.maps = (1u << (uint32_t)SBR_MAP_INTENSITY) | (1u << (uint32_t)SBR_MAP_RED) |
                          (1u << (uint32_t)SBR_MAP_BLUE);
        cfg->parts.map_polarity[SBR_MAP_INTENSITY] = (uint32_t)SBR_MSER_BRIGHT;
        cfg->parts.map_polarity[SBR_MAP_RED] = (uint32_t)SBR_MSER_BRIGHT;
        cfg->parts.map_bright_min[SBR_MAP_RED] = 136u;
        cfg->parts.map_subsample[SBR_MAP_BLUE] = 2u;
        cfg->parts.map_min_area[SBR_MAP_BLUE] = 20u;
        cfg->parts.map_dark_max[SBR_MAP_BLUE] = 120u;
        /* a grey frame has its intensity map only: both polarities (grey_polarity) */
        cfg->grey_polarity = 0u;
        cfg->match_p = SBR_RECOG_DEFAULT_MATCH_P;
        cfg->max_parts = SBR_RECOG_DEFAULT_MAX_PARTS;
        cfg->max_votes = SBR_RECOG_DEFAULT_MAX_VOTES;
        cfg->max_hypotheses = SBR_RECOG_DEFAULT_MAX_HYPOTHESES;
        cfg->max_model_protos = SBR_RECOG_DEFAULT_MAX_MODEL_PROTOS;
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
        cfg->refine_first_score = 0.01f;
        cfg->grey_refine_first_score = 0.0003f;
        cfg->refine_score = 0.001f;
        cfg->views = 5u;
        cfg->view_score = 0.1f;
        cfg->triangle_view = 1u;
        cfg->triangle_score = 0.001f;
        cfg->max_extra_looks = SBR_RECOG_DEFAULT_MAX_EXTRA_LOOKS;
        cfg->min_score = 0.3f;
        cfg->nms_iou = 0.3f;
        cfg->candidate_iou = 1.0f;
        cfg->gate = 1u;
        cfg->outline_maps = (1u << (uint32_t)SBR_MAP_RED) | (1u << (uint32_t)SBR_MAP_BLUE);
        cfg->max_outline_candidates = SBR_RECOG_DEFAULT_MAX_OUTLINES;
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
        (cfg->gate > 1u) || (cfg->grey_polarity > (uint32_t)SBR_MSER_BOTH) ||
        (cfg->max_extra_looks > 1000000u) ||
        (cfg->outline_maps >= (1u << (uint32_t)SBR_MAP_KINDS)) ||
        (cfg->max_outline_candidates > 1000000u)) {
        return SBR_ERR_RANGE;
    }
    if ((in_range(cfg->vote_error, 0.0f, 4.0f) == 0) ||
        (in_range(cfg->verify_error, 1.0e-6f, 4.0f) == 0) ||
        (in_range(cfg->max_rotation, 1.0e-6f, SBR_PI_F) == 0) ||
        (in_range(cfg->min_size, 1.0f, 16384.0f) == 0) ||
        (in_range(cfg->max_size, cfg->min_size, 16384.0f) == 0) ||
        (in_range(cfg->centre_tol, 1.0e-6f, 10.0f) == 0) ||
        (in_range(cfg->size_tol, 0.0f, 10.0f) == 0) ||
        (in_range(cfg->min_score, 0.0f, 0.999999f) == 0) ||
        (in_range(cfg->candidate_score, 0.0f, 0.999999f) == 0) ||
        (in_range(cfg->refine_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->refine_first_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->grey_refine_first_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->view_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->triangle_score, 0.0f, 1.0f) == 0) ||
        (in_range(cfg->nms_iou, 1.0e-6f, 1.0f) == 0) ||
        (in_range(cfg->candidate_iou, 1.0e-6f, 1.0f) == 0)) {
        return SBR_ERR_RANGE;
    }
    return SBR_OK;
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
