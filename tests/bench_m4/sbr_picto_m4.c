/* SPDX-License-Identifier: MIT */
/*
 * sbr_picto_m4: instructions of one class-stage look on the emulated Cortex-M4F (qemu
 * mps2-an386 with -icount shift=0), for `./sbr.sh cost` (host_tools/bench_cost): the
 * features of a box (sbr_picto_features_outline()) and the built-in classifier
 * (sbr_picto_classify()), apart, per box side. A look's features cost grows with the
 * box (its resampling takes up to 4 x 4 samples a patch pixel), the classifier's does
 * not; sbr_cost_m4 gives the class stage per frame, this bench where a look's
 * instructions go.
 *
 * The frame is synthetic (a fixed LCG's pixels, 200 x 200 RGB): the work of a look does
 * not depend on what the box holds, except for a few branches of the orientation bins.
 * The timer and its calibration: sbr_bench_timer.h, as sbr_cost_m4's.
 *
 * Output lines (parsed by host_tools/bench_cost/sbr_cost.py):
 *   calibration: <instructions per tick>
 *   look <side> <outline>: features <instructions> classify <instructions>
 *   mean: features <instructions> classify <instructions>   (over the looks above)
 * This is a bench image, not part of the core: it uses stdio (semihosting) and a timer.
 */
#include <stdint.h>
#include <stdio.h>

#include "sbr_bench_timer.h"
#include "sbr/picto.h"
#include "sbr/models.h"

#define FRAME_SIDE 200u

static uint8_t g_frame[FRAME_SIDE * FRAME_SIDE * 3u];
static float g_feat[SBR_PICTO_FEATURES];
static float g_prob[SBR_PICTO_MAX_OUTPUTS];
static uint64_t g_ws[(SBR_PICTO_WORKSPACE_SIZE + 7u) / 8u];

int main(void)
{
    sbr_picto_model_t model;
    sbr_image_t img;
    uint32_t seed = 12345u;
    uint32_t i;
    uint32_t side;
    uint32_t looks = 0u;
    float per_tick;
    float sum_f = 0.0f;
    float sum_c = 0.0f;

    per_tick = bench_timer_start();
    printf("calibration: %.3f\n", (double)per_tick);

    for (i = 0u; i < sizeof g_frame; i++) {
        seed = (seed * 1664525u) + 1013904223u;
        g_frame[i] = (uint8_t)(seed >> 24);
    }
    if (sbr_picto_gtsdb(&model) != SBR_OK) {
        printf("error: built-in class stage\n");
        return 1;
    }
    img.data = g_frame;
    img.width = FRAME_SIDE;
    img.height = FRAME_SIDE;
    img.stride = FRAME_SIDE * 3u;
    img.format = SBR_PIXEL_RGB888;
    /* box sides of 1 to 4 samples a patch pixel each way (SBR_PICTO_SIZE = 36), both
       outlines, at a fractional position */
    for (side = 16u; side <= 144u; side += 16u) {
        uint32_t outline;
        for (outline = 0u; outline <= (uint32_t)SBR_PICTO_OUTLINE_TRIANGLE; outline++) {
            const float box[4] = {10.3f, 20.6f, 10.3f + (float)side, 20.6f + (1.05f * (float)side)};
            uint32_t t0;
            uint32_t t1;
            uint32_t t2;
            sbr_status_t st;
            t0 = ticks_now();
            st = sbr_picto_features_outline(&img, box, outline, g_feat, SBR_PICTO_FEATURES, g_ws,
                                            sizeof g_ws);
            t1 = ticks_now();
            if (st == SBR_OK) {
                st = sbr_picto_classify(&model, g_feat, SBR_PICTO_FEATURES, g_prob,
                                        SBR_PICTO_MAX_OUTPUTS, g_ws, sizeof g_ws);
            }
            t2 = ticks_now();
            if (st != SBR_OK) {
                printf("error: %s\n", sbr_status_str(st));
                return 1;
            }
            printf("look %u %u: features %.0f classify %.0f\n", (unsigned)side, (unsigned)outline,
                   (double)((float)(t1 - t0) * per_tick), (double)((float)(t2 - t1) * per_tick));
            sum_f += (float)(t1 - t0) * per_tick;
            sum_c += (float)(t2 - t1) * per_tick;
            looks++;
        }
    }
    printf("mean: features %.0f classify %.0f\n", (double)(sum_f / (float)looks),
           (double)(sum_c / (float)looks));
    return 0;
}
