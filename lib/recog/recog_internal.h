/* SPDX-License-Identifier: MIT */
/* Private to lib/recog: the recogniser's working types and the functions its files share
   (config, votes + cascade, suppression, class stage, detect). Not installed. */
#ifndef SBR_RECOG_INTERNAL_H
#define SBR_RECOG_INTERNAL_H

#include "sbr/recog.h"

#include "../common/sbr_util.h"


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

/* The workspace macros (recog.h) count these sizes. */
typedef char recog_vote_size_check[(sizeof(recog_vote_t) == SBR_RECOG_VOTE_BYTES) ? 1 : -1];
typedef char recog_hyp_size_check[(sizeof(recog_hyp_t) == SBR_RECOG_HYP_BYTES) ? 1 : -1];

/* An entry of the part index: the parts of each group (map, polarity) in order of their
   centre's x, so that the cascade looks only at parts near a predicted position. */
typedef struct recog_index_s {
    float cx;
    uint32_t part;
    uint32_t group;
} recog_index_t;

typedef char recog_index_size_check[(sizeof(recog_index_t) == SBR_RECOG_INDEX_BYTES) ? 1 : -1];

/* Width in pixels of the columns the vote grouping indexes hypotheses by. */
#define RECOG_GRID_CELL 16.0f

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
    size_t mags;        /* in the part stage's block after that stage, in this order: the
                           prototypes' magnitudes, the vote grouping's grid, the index,
                           the results, the scratch, the votes, the hypotheses */
    size_t grid;
    uint32_t grid_cols; /* the grid's columns: width / 16 + 2 (the last one also takes
                           what lies right of the view) */
} recog_layout_t;


/* Everything one call works with. */
typedef struct recog_ctx_s {
    const sbr_recog_config_t *cfg;
    const sbr_model_t *model;
    const sbr_picto_model_t *picto; /* the class stage; NULL: none */
    sbr_parts_config_t parts_cfg; /* cfg->parts, the intensity map alone on a grey frame */
    const sbr_fft_t *fft_p; /* the recogniser's correlation FFT (match_p) */
    sbr_fd_match_config_t mcfg;  /* votes: screened at the vote error */
    sbr_fd_match_config_t vcfg;  /* cascade: screened at the verification error */
    sbr_part_t *parts;
    uint32_t nparts;
    recog_index_t *index;                          /* [nparts] */
    uint32_t group_first[SBR_MODEL_GROUPS + 1u];   /* each group's first index entry */
    sbr_fd_match_t *results;
    sbr_complex_t *work;
    uint32_t work_len;
    float *pmag; /* the model's prototypes' coefficient magnitudes, 2 fd_m + 1 each */
    sbr_fd_table_t table; /* the model's prototypes with pmag (sbr_fd_table_init()) */
    uint32_t *grid_head; /* [grid_cols] the hypotheses by column (recog_votes.c) */
    uint32_t *grid_next; /* [max_hypotheses] */
    uint32_t *grid_prev; /* [max_hypotheses] */
    uint32_t grid_cols;
    recog_vote_t *votes;
    uint32_t nvotes;
    recog_hyp_t *hyps;
    uint32_t nhyps;
    float vote_error;
    float score_floor; /* part-evidence floor: min_score, or candidate_score before the
                          class stage */
    sbr_recog_stats_t st;
} recog_ctx_t;

/* The class stage's buffers in the workspace. */
typedef struct recog_picto_buf_s {
    void *look;  /* the looks' workspace (sbr_picto_look()), SBR_PICTO_LOOK_WORKSPACE_SIZE */
    float *prob;
    float *mean; /* averaged probabilities of several views */
    uint32_t classes;       /* the model's class count (outputs: classes + 1) */
    const uint8_t *outline; /* the model's class outlines (sbr_model_t::class_outline) */
} recog_picto_buf_t;

/* recog_config.c */

/* The workspace layout of a width x height view; 0 if the parts stage cannot run on it. */
int sbr_recog_priv_layout(uint32_t width, uint32_t height, const sbr_recog_config_t *cfg,
                          recog_layout_t *l);

/* recog_votes.c: votes, hypotheses, evidence and cascade verification */

/* Match part pi against its group and cast its votes. */
sbr_status_t sbr_recog_priv_cast_votes(recog_ctx_t *c, uint32_t pi);

/* Sort the votes: by weight, descending (mode 0), or by hypothesis, part, then weight
   descending (mode 1). */
void sbr_recog_priv_sort_votes(recog_ctx_t *c, int mode);

/* Group the votes (sorted by weight) into hypotheses. */
void sbr_recog_priv_group_votes(recog_ctx_t *c);

/* Build the part index and each group's first entry. */
void sbr_recog_priv_index_parts(recog_ctx_t *c);

/* Score every hypothesis (votes sorted by hypothesis and part). */
void sbr_recog_priv_score_hyps(recog_ctx_t *c);

/* recog_nms.c: suppression */

/* Box of a hypothesis in view pixels, clamped to the view: x0, y0, x1, y1 (exclusive). */
void sbr_recog_priv_hyp_box(const recog_hyp_t *h, uint32_t vw, uint32_t vh, float b[4]);

/* Move the kept hypotheses to the front, sorted best first; returns their count. */
/* The checks a detect call starts with, in sbr_recog_detect()'s documented order: stats
   zeroed, SBR_ERR_NULL for a missing pointer (else *count = 0), SBR_ERR_STATE unless rec
   comes from a successful sbr_recog_init() and is unchanged since. */
sbr_status_t sbr_recog_priv_begin(const sbr_recog_t *rec, const sbr_image_t *img,
                                  const sbr_detection_t *dets, uint32_t *count,
                                  sbr_recog_stats_t *stats);
uint32_t sbr_recog_priv_compact(recog_ctx_t *c);

/* Greedy non-maximum suppression over the first n (sorted) hypotheses: one overlapping
   a better kept one by more than iou, or with an empty box, is dropped (iou 1: only the
   empty boxes, as no IoU exceeds 1). */
void sbr_recog_priv_suppress(recog_ctx_t *c, uint32_t n, uint32_t vw, uint32_t vh, float iou);

/* recog_class.c: the class stage */

/* The outline candidates (config.outline_maps) after the first `kept` hypotheses: the
   parts that qualify, in order, at most max_outline_candidates and up to max_hypotheses
   in all, each at its own box and kept. Returns the hypotheses' new count (c->nhyps). */
uint32_t sbr_recog_priv_outline_candidates(recog_ctx_t *c, uint32_t kept);

/* The class stage over the first `kept` hypotheses (sorted best first) and then the
   outline candidates kept .. end - 1: each kept one is gated, classified and
   colour-checked; it stays kept when its class score reaches min_score. At most
   max_candidates of the first are examined. */
void sbr_recog_priv_class_stage(recog_ctx_t *c, const sbr_image_t *view, uint32_t kept,
                                uint32_t end, recog_picto_buf_t *pb);

/* Every field of the table (recog_fields.c) at its default. */
void sbr_recog_priv_fields_default(sbr_recog_config_t *cfg);

#endif /* SBR_RECOG_INTERNAL_H */
