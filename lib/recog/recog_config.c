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

sbr_status_t sbr_recog_config_check(const sbr_recog_config_t *cfg)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (cfg != NULL) {
        st = SBR_ERR_RANGE;
        /* the table's ranges and links; the part stage's own check agrees with them
           (tests/test_recog_fields.c) and stays as a second line */
        if ((sbr_recog_config_check_field(cfg) == SBR_FIELD_NONE) &&
            (sbr_parts_config_check(&cfg->parts) == SBR_OK)) {
            st = SBR_OK;
        }
    }
    return st;
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
