/* SPDX-License-Identifier: MIT */
/*
 * Traffic-sign recogniser: parts -> prototype matches -> star-model votes -> hypotheses
 * -> cascade verification -> NMS -> class stage. See include/sbr/recog.h; the stages
 * are in recog_votes.c, recog_nms.c and recog_class.c, the configuration in recog_config.c.
 */
#include "recog_internal.h"


#include <stddef.h>
#include <string.h>

/* Close a timed stage: ticks since *t0 go to stage `s`; *t0 moves on. */
static void stage_end(recog_ctx_t *c, uint32_t s, uint32_t *t0)
{
    if (c->cfg->clock != NULL) {
        const uint32_t t = c->cfg->clock(c->cfg->clock_ctx);
        c->st.stage_ticks[s] = t - *t0;
        *t0 = t;
    }
}

/* The view the recogniser works on (the ROI of img, or img) and the ROI's offset in img. */
static sbr_status_t detect_view(const sbr_image_t *img, const sbr_rect_t *roi, sbr_image_t *view,
                                uint32_t *ox, uint32_t *oy)
{
    sbr_status_t st;
    if (roi != NULL) {
        st = sbr_image_roi(img, roi, view);
        *ox = roi->x;
        *oy = roi->y;
    } else {
        st = sbr_image_check(img);
        *view = *img;
    }
    return st;
}

/* "RECO": an initialised recogniser. */
#define RECOG_MAGIC 0x5245434Fu

/* The integrity word over the bytes before it. */
static uint32_t recog_checksum(const sbr_recog_t *rec)
{
    return sbr_util_fnv1a(rec, offsetof(sbr_recog_t, check));
}

sbr_status_t sbr_recog_priv_begin(const sbr_recog_t *rec, const sbr_image_t *img,
                                  const sbr_detection_t *dets, uint32_t *count,
                                  sbr_recog_stats_t *stats)
{
    sbr_status_t st = SBR_ERR_NULL;
    if (stats != NULL) {
        (void)memset(stats, 0, sizeof *stats);
    }
    if ((rec != NULL) && (img != NULL) && (dets != NULL) && (count != NULL)) {
        *count = 0u;
        st = ((rec->magic == RECOG_MAGIC) && (rec->check == recog_checksum(rec))) ? SBR_OK
                                                                                  : SBR_ERR_STATE;
    }
    return st;
}

/* The configuration, the library and the class stage, checked against each other. */
static sbr_status_t init_check(const sbr_recog_config_t *cfg, const sbr_model_t *model,
                               const sbr_picto_model_t *picto)
{
    sbr_status_t st = sbr_recog_config_check(cfg);
    if (st == SBR_OK) {
        st = sbr_model_check(model);
    }
    if ((st == SBR_OK) &&
        ((model->fd_n != cfg->parts.fd_n) || (model->fd_m != cfg->parts.fd_m) ||
         (model->proto_count > cfg->max_model_protos))) {
        st = SBR_ERR_RANGE;
    }
    if ((st == SBR_OK) && (picto != NULL) && (picto->version != 0u) &&
        ((sbr_picto_check(picto) != SBR_OK) || (picto->classes != model->class_count))) {
        st = SBR_ERR_CORRUPT;
    }
    return st;
}

sbr_status_t sbr_recog_init(sbr_recog_t *rec, const sbr_recog_config_t *cfg,
                            const sbr_model_t *model, const sbr_picto_model_t *picto,
                            void *workspace, size_t workspace_size)
{
    sbr_status_t st;
    if (rec == NULL) {
        return SBR_ERR_NULL;
    }
    (void)memset(rec, 0, sizeof *rec);
    if ((cfg == NULL) || (model == NULL)) {
        return SBR_ERR_NULL;
    }
    st = init_check(cfg, model, picto);
    if (st != SBR_OK) {
        return st;
    }
    if ((workspace == NULL) || (workspace_size == 0u) || (sbr_util_aligned(workspace, 8u) == 0)) {
        return SBR_ERR_WORKSPACE;
    }
    /* the FFT instances of the descriptors (fd_n) and the correlation (match_p), once */
    if ((sbr_fft_init(&rec->fft_n, cfg->parts.fd_n) != SBR_OK) ||
        (sbr_fft_init(&rec->fft_p, cfg->match_p) != SBR_OK)) {
        (void)memset(rec, 0, sizeof *rec);
        return SBR_ERR_RANGE;
    }
    rec->cfg = *cfg;
    rec->model = *model;
    if ((picto != NULL) && (picto->version != 0u)) {
        rec->picto = *picto;
    }
    rec->workspace = workspace;
    rec->workspace_size = workspace_size;
    rec->vote_error = (cfg->vote_error > 0.0f) ? cfg->vote_error : model->vote_error;
    rec->magic = RECOG_MAGIC;
    rec->check = recog_checksum(rec);
    return SBR_OK;
}

/* The part extraction's options for this view: the configuration's, with only the
   intensity map, of grey_polarity, for a grey frame (::SBR_ERR_RANGE when the
   configuration has none). */
static sbr_status_t view_parts(const sbr_recog_config_t *cfg, const sbr_image_t *view,
                               sbr_parts_config_t *out)
{
    *out = cfg->parts;
    if (view->format == SBR_PIXEL_GRAY8) {
        out->maps &= 1u << (uint32_t)SBR_MAP_INTENSITY;
        out->map_polarity[SBR_MAP_INTENSITY] = cfg->grey_polarity;
    }
    return (out->maps != 0u) ? SBR_OK : SBR_ERR_RANGE;
}

/* The context of one call: matchers, and the arrays in the workspace (layout l). */
static sbr_status_t ctx_init(recog_ctx_t *c, const sbr_recog_t *rec, const recog_layout_t *l)
{
    const sbr_recog_config_t *cfg = &rec->cfg;
    uint8_t *base;
    (void)memset(c, 0, sizeof *c);
    c->fft_p = &rec->fft_p;
    c->cfg = cfg;
    c->model = &rec->model;
    c->picto = (rec->picto.version != 0u) ? &rec->picto : NULL;
    c->vote_error = rec->vote_error;
    c->score_floor = (c->picto != NULL) ? cfg->candidate_score : cfg->min_score;
    sbr_fd_match_config_default(&c->mcfg);
    c->mcfg.mode = SBR_FD_ROTATION_COVARIANT;
    c->mcfg.max_rotation = cfg->max_rotation;
    c->vcfg = c->mcfg;
    c->mcfg.max_error = c->vote_error;   /* only matches up to these errors count */
    c->vcfg.max_error = cfg->verify_error;
    base = (uint8_t *)rec->workspace;
    c->parts = (sbr_part_t *)(void *)&base[l->parts_ws];
    /* the part stage's block, after that stage: the prototypes' magnitudes, the vote
       grouping's grid, the index, the results, the scratch, the votes, the hypotheses */
    c->pmag = (float *)(void *)base;
    base = &base[l->mags];
    c->grid_head = (uint32_t *)(void *)base;
    c->grid_cols = l->grid_cols;
    c->grid_next = &c->grid_head[c->grid_cols];
    c->grid_prev = &c->grid_next[cfg->max_hypotheses];
    base = &base[l->grid];
    c->index = (recog_index_t *)(void *)base;
    base = &base[l->index];
    c->results = (sbr_fd_match_t *)(void *)base;
    base = &base[l->results];
    c->work = (sbr_complex_t *)(void *)base;
    c->work_len = cfg->match_p * 5u; /* SBR_FD_TABLE_WORK_LEN */
    base = &base[l->work];
    c->votes = (recog_vote_t *)(void *)base;
    base = &base[l->votes];
    c->hyps = (recog_hyp_t *)(void *)base;
    return SBR_OK;
}

/* Stages 1-4: parts, votes, hypotheses, evidence per class with cascade verification. */
static sbr_status_t evidence_stages(recog_ctx_t *c, const sbr_image_t *view,
                                    const sbr_fft_t *fft_n, void *workspace, size_t parts_ws,
                                    uint32_t *t0)
{
    const sbr_recog_config_t *cfg = c->cfg;
    uint32_t i;
    const uint32_t stride = (2u * c->model->fd_m) + 1u;
    sbr_status_t st = sbr_parts_extract(view, &c->parts_cfg, fft_n, workspace, parts_ws, c->parts,
                                        cfg->max_parts, &c->nparts, &c->st.parts_stats);
    if (st == SBR_ERR_CAPACITY) {
        c->st.capacity_hit |= SBR_RECOG_HIT_PARTS;
    } else if (st != SBR_OK) {
        return st;
    } else {
        /* all parts */
    }
    if (c->st.parts_stats.capacity_hit != 0u) {
        c->st.capacity_hit |= SBR_RECOG_HIT_MSER;
    }
    c->st.parts = c->nparts;
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_PARTS, t0);

    /* the model's prototypes as a prepared table: checked and their screening magnitudes
       computed once per frame instead of once per pair */
    st = sbr_fd_table_init(&c->table, c->model->fds, c->model->proto_count, c->pmag,
                           (size_t)c->model->proto_count * stride);
    if (st != SBR_OK) {
        return st;
    }

    for (i = 0u; i < c->nparts; i++) {
        st = sbr_recog_priv_cast_votes(c, i);
        if (st != SBR_OK) {
            return st;
        }
    }
    c->st.votes = c->nvotes;
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_VOTES, t0);

    sbr_recog_priv_sort_votes(c, 0);
    sbr_recog_priv_group_votes(c);
    c->st.hypotheses = c->nhyps;
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_GROUP, t0);

    sbr_recog_priv_sort_votes(c, 1);
    sbr_recog_priv_index_parts(c);
    sbr_recog_priv_score_hyps(c);
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_VERIFY, t0);
    return SBR_OK;
}

/* Stages 5-6: non-maximum suppression on part evidence, best first (with a class stage at
   candidate_iou, by default none: only empty boxes go); then the class stage (the
   pictogram classifier scores and classifies the survivors, then the outline candidates)
   and suppression again on the new scores. The class stage's buffers are the workspace's last l->picto bytes
   (SBR_RECOG_CLASS_BYTES: the looks' workspace, then the probabilities). Returns
   the number of hypotheses left (sorted, kept ones marked). */
static uint32_t decide_stages(recog_ctx_t *c, const sbr_image_t *view, void *workspace,
                              const recog_layout_t *l, uint32_t *t0)
{
    const sbr_recog_config_t *cfg = c->cfg;
    int picto = 0;
    uint32_t kept;
    if (c->picto != NULL) {
        picto = 1;
    }
    kept = sbr_recog_priv_compact(c);
    sbr_recog_priv_suppress(c, kept, view->width, view->height,
                            (picto != 0) ? cfg->candidate_iou : cfg->nms_iou);
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_NMS, t0);
    if (picto != 0) {
        uint8_t *base = (uint8_t *)workspace;
        const size_t look = SBR_WS_ALIGN8(SBR_PICTO_LOOK_WORKSPACE_SIZE);
        recog_picto_buf_t pb;
        pb.look = (void *)&base[l->total - l->picto];
        pb.prob = (float *)(void *)&base[(l->total - l->picto) + look];
        pb.mean = &pb.prob[SBR_PICTO_MAX_OUTPUTS];
        pb.classes = c->model->class_count;
        pb.outline = c->model->class_outline;
        sbr_recog_priv_class_stage(c, view, kept, sbr_recog_priv_outline_candidates(c, kept),
                                   &pb);
        kept = sbr_recog_priv_compact(c);
        sbr_recog_priv_suppress(c, kept, view->width, view->height, cfg->nms_iou);
    }
    stage_end(c, (uint32_t)SBR_RECOG_STAGE_CLASS, t0);
    return kept;
}

/* Stage 7: the kept hypotheses among the first n, best first, as detections in image
   coordinates (offset ox, oy). Returns 1 if some did not fit in capacity. */
static int write_detections(const recog_ctx_t *c, uint32_t n, const sbr_image_t *view,
                            uint32_t ox, uint32_t oy, sbr_detection_t *dets, uint32_t capacity,
                            uint32_t *count)
{
    uint32_t out = 0u;
    uint32_t i;
    int full = 0;
    for (i = 0u; i < n; i++) {
        if (c->hyps[i].keep == 0u) {
            /* suppressed or rejected */
        } else if (out >= capacity) {
            full = 1;
        } else {
            sbr_detection_t *d = &dets[out];
            float bi[4];
            sbr_recog_priv_hyp_box(&c->hyps[i], view->width, view->height, bi);
            d->box.x = ox + (uint32_t)bi[0];
            d->box.y = oy + (uint32_t)bi[1];
            d->box.width = (uint32_t)(bi[2] + 0.5f) - (uint32_t)bi[0];
            d->box.height = (uint32_t)(bi[3] + 0.5f) - (uint32_t)bi[1];
            d->score = c->hyps[i].score;
            d->class_share = c->hyps[i].share;
            d->class_id = c->hyps[i].class_id;
            d->parts = c->hyps[i].parts;
            out++;
        }
    }
    *count = out;
    return full;
}

sbr_status_t sbr_recog_detect(sbr_recog_t *rec, const sbr_image_t *img, const sbr_rect_t *roi,
                              sbr_detection_t *dets, uint32_t capacity, uint32_t *count,
                              sbr_recog_stats_t *stats)
{
    recog_ctx_t c;
    recog_layout_t l;
    sbr_image_t view;
    uint32_t ox = 0u;
    uint32_t oy = 0u;
    uint32_t kept;
    uint32_t t0 = 0u;
    int full;
    sbr_status_t st;

    st = sbr_recog_priv_begin(rec, img, dets, count, stats);
    if (st != SBR_OK) {
        return st;
    }
    st = detect_view(img, roi, &view, &ox, &oy);
    if (st != SBR_OK) {
        return st;
    }
    if ((sbr_recog_priv_layout(view.width, view.height, &rec->cfg, &l) == 0) || (capacity == 0u)) {
        return SBR_ERR_SIZE;
    }
    if (rec->workspace_size < l.total) {
        return SBR_ERR_WORKSPACE;
    }
    if ((ctx_init(&c, rec, &l) != SBR_OK) ||
        (view_parts(&rec->cfg, &view, &c.parts_cfg) != SBR_OK)) {
        return SBR_ERR_RANGE;
    }
    if (rec->cfg.clock != NULL) {
        t0 = rec->cfg.clock(rec->cfg.clock_ctx);
    }
    st = evidence_stages(&c, &view, &rec->fft_n, rec->workspace, l.parts_ws, &t0);
    if (st != SBR_OK) {
        return st;
    }
    kept = decide_stages(&c, &view, rec->workspace, &l, &t0);
    full = write_detections(&c, kept, &view, ox, oy, dets, capacity, count);
    if (stats != NULL) {
        *stats = c.st;
    }
    return (full != 0) ? SBR_ERR_CAPACITY : SBR_OK;
}
