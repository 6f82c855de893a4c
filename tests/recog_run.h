/* SPDX-License-Identifier: MIT */
/* For the recogniser's tests: sbr_recog_init() and sbr_recog_detect() in one call, as a
   test that varies the configuration or the models from call to call needs them. */
#ifndef SBR_TESTS_RECOG_RUN_H
#define SBR_TESTS_RECOG_RUN_H

#include "sbr/recog.h"

/* init's status when it refuses; else detect's. */
static inline sbr_status_t recog_run(const sbr_image_t *img, const sbr_rect_t *roi,
                                     const sbr_recog_config_t *cfg, const sbr_model_t *model,
                                     const sbr_picto_model_t *picto, void *workspace,
                                     size_t workspace_size, sbr_detection_t *dets,
                                     uint32_t capacity, uint32_t *count, sbr_recog_stats_t *stats)
{
    sbr_recog_t rec;
    const sbr_status_t st = sbr_recog_init(&rec, cfg, model, picto, workspace, workspace_size);
    if (st != SBR_OK) {
        return st;
    }
    return sbr_recog_detect(&rec, img, roi, dets, capacity, count, stats);
}

#endif /* SBR_TESTS_RECOG_RUN_H */
