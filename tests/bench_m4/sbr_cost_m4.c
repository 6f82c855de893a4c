/* SPDX-License-Identifier: MIT */
/*
 * sbr_cost_m4: instructions per frame of the recogniser on the emulated Cortex-M4F
 * (qemu mps2-an386 with -icount shift=0), for `./sbr.sh cost` (host_tools/bench_cost).
 *
 * The frame is read through semihosting from `frame.ppm` (binary PPM, P6, maxval 255) in
 * qemu's working folder into a buffer in the 4 MiB SRAM when it fits there (a 1360 x 800
 * RGB frame does), else into the board's 16 MiB PSRAM at 0x21000000 before the
 * workspace; the recogniser's workspace takes the PSRAM. When frame and workspace do not
 * fit, the largest band of full rows (centred vertically) that fits is processed and said
 * so. The recogniser runs with its defaults
 * and the built-in model (lib/models).
 *
 * Built with SBR_BENCH_STRIPS (sbr_cost_m4_strips.elf): the strip configuration
 * (sbr_recog_config_strips(), sbr_recog_detect_strips()) on the whole frame, the frame in
 * the PSRAM (a camera's frame buffer) and the workspace, SBR_RECOG_WORKSPACE_STRIP_SIZE
 * for frames up to 1360 wide, a static array in the SRAM (what an MCU-class ECU has).
 *
 * Either way its stage clock reads the CMSDK APB timer 0
 * (25 MHz, counting down). With -icount shift=0 qemu advances virtual time by 1 ns per
 * instruction, so a timer tick is a fixed number of instructions: it is calibrated at
 * start against a loop of known length (2 instructions per iteration) and every figure is
 * printed in instructions.
 *
 * Output lines (parsed by host_tools/bench_cost/sbr_cost.py):
 *   calibration: <instructions per tick>
 *   view: <x> <y> <w> <h> of <W> <H>
 *   workspace: <bytes>
 *   init: <instructions>               (sbr_recog_init: the one-time checks)
 *   status: <sbr_status_str>
 *   stage <k>: <instructions>          (k = 0 .. SBR_RECOG_STAGES - 1)
 *   total: <instructions>              (the whole sbr_recog_detect call, per frame)
 *   det: <left>;<top>;<right>;<bottom>;<class>;<score>
 * This is a bench image, not part of the core: it uses stdio (semihosting) and a timer.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "sbr_bench_timer.h"
#include "sbr/recog.h"
#include "sbr/models.h"
#include "sbr_bench_ppm.h"
#include "sbr/recog_strips.h"

#define PSRAM_BASE 0x21000000u
#define PSRAM_BYTES (16u * 1024u * 1024u)
/* Frames up to this size are read into SRAM (.bss; the rest of the 4 MiB SRAM holds the
   image's data, its heap and its stack). */
#define SRAM_FRAME_BYTES (3u * 1024u * 1024u + 512u * 1024u)

#if defined(SBR_BENCH_STRIPS)
#define BENCH_MAX_WIDTH 1360u
/* the strip configuration's workspace in the SRAM */
static uint64_t g_ws[(SBR_RECOG_WORKSPACE_STRIP_SIZE(BENCH_MAX_WIDTH) / 8u) + 1u];
#else
static uint8_t g_frame[SRAM_FRAME_BYTES];
#endif

/* The recogniser's stage clock: the bench timer (sbr_bench_timer.h). */
static uint32_t timer_clock(void *ctx)
{
    (void)ctx;
    return ticks_now();
}

int main(void)
{
    FILE *f = fopen("frame.ppm", "rb");
    uint32_t w = 0u, h = 0u, maxval = 0u;
    uint8_t *frame = (uint8_t *)PSRAM_BASE;
    sbr_recog_config_t cfg;
    sbr_model_t model;
    sbr_picto_model_t picto;
    sbr_recog_t rec;
    sbr_image_t img;
    sbr_rect_t roi;
    sbr_recog_stats_t stats;
    static sbr_detection_t dets[64];
    uint32_t n = 0u, k, band, t0, t1;
    size_t frame_bytes, ws_bytes = 0u, ws_off;
    float per_tick;
    sbr_status_t st;

    per_tick = bench_timer_start();
    printf("calibration: %.3f\n", (double)per_tick);

    if ((f == NULL) || (fgetc(f) != 'P') || (fgetc(f) != '6') || !read_token(f, &w) ||
        !read_token(f, &h) || !read_token(f, &maxval) || (maxval != 255u) || (w == 0u) ||
        (h == 0u) || (w > 4096u) || (h > 4096u)) {
        printf("error: cannot read frame.ppm (binary PPM, maxval 255)\n");
        return 1;
    }
    frame_bytes = (size_t)w * h * 3u;
#if !defined(SBR_BENCH_STRIPS)
    if (frame_bytes <= SRAM_FRAME_BYTES) {
        frame = g_frame;
    }
#endif
    if ((frame_bytes >= PSRAM_BYTES) || (fread(frame, 1u, frame_bytes, f) != frame_bytes)) {
        printf("error: frame.ppm too large or short\n");
        return 1;
    }
    (void)fclose(f);

    (void)sbr_model_gtsdb(&model);
    (void)sbr_picto_gtsdb(&picto);
    img.data = frame;
    img.width = w;
    img.height = h;
    img.stride = w * 3u;
    img.format = SBR_PIXEL_RGB888;
#if defined(SBR_BENCH_STRIPS)
    sbr_recog_config_strips(&cfg);
    cfg.clock = timer_clock;
    ws_bytes = sbr_recog_strip_workspace_size(&cfg, w, h, SBR_RECOG_STRIP_ROWS);
    if ((ws_bytes == 0u) || (ws_bytes > sizeof g_ws)) {
        printf("error: the strip configuration of a %u-wide frame needs %u bytes, the bench has %u\n",
               (unsigned)w, (unsigned)ws_bytes, (unsigned)sizeof g_ws);
        return 1;
    }
    printf("view: strips of %u rows overlapping by %u, %u x %u in SRAM\n", (unsigned)SBR_RECOG_STRIP_ROWS,
           (unsigned)SBR_RECOG_STRIP_OVERLAP, (unsigned)w, (unsigned)h);
    printf("workspace: %u\n", (unsigned)ws_bytes);
    t0 = ticks_now();
    st = sbr_recog_init(&rec, &cfg, &model, &picto, g_ws, ws_bytes);
    t1 = ticks_now();
    printf("init: %.0f\n", (double)((float)(t1 - t0) * per_tick));
    if (st != SBR_OK) {
        printf("status: %s\n", sbr_status_str(st));
        return 1;
    }
    (void)band;
    (void)roi;
    (void)ws_off;
    t0 = ticks_now();
    st = sbr_recog_detect_strips(&rec, &img, SBR_RECOG_STRIP_ROWS, SBR_RECOG_STRIP_OVERLAP, dets, 64u, &n,
                                 &stats);
    t1 = ticks_now();
#else
    sbr_recog_config_default(&cfg);
    cfg.clock = timer_clock;
    ws_off = (frame == g_frame) ? 0u : ((frame_bytes + 7u) & ~(size_t)7u);
    /* the largest band of full rows whose workspace fits beside the frame */
    for (band = h; band >= 16u; band -= 8u) {
        ws_bytes = sbr_recog_workspace_size(&cfg, w, band);
        if ((ws_bytes != 0u) && (ws_off + ws_bytes <= PSRAM_BYTES)) {
            break;
        }
    }
    if (band < 16u) {
        printf("error: no band of the frame fits in the PSRAM\n");
        return 1;
    }
    roi.x = 0u;
    roi.y = (h - band) / 2u;
    roi.width = w;
    roi.height = band;
    printf("view: %u %u %u %u of %u %u\n", (unsigned)roi.x, (unsigned)roi.y, (unsigned)roi.width,
           (unsigned)roi.height, (unsigned)w, (unsigned)h);
    printf("workspace: %u\n", (unsigned)ws_bytes);

    t0 = ticks_now();
    st = sbr_recog_init(&rec, &cfg, &model, &picto, (void *)(PSRAM_BASE + ws_off), ws_bytes);
    t1 = ticks_now();
    printf("init: %.0f\n", (double)((float)(t1 - t0) * per_tick));
    if (st != SBR_OK) {
        printf("status: %s\n", sbr_status_str(st));
        return 1;
    }
    t0 = ticks_now();
    st = sbr_recog_detect(&rec, &img, (band == h) ? NULL : &roi, dets, 64u, &n, &stats);
    t1 = ticks_now();
#endif
    printf("status: %s\n", sbr_status_str(st));
    for (k = 0u; k < (uint32_t)SBR_RECOG_STAGES; k++) {
        printf("stage %u: %.0f\n", (unsigned)k, (double)((float)stats.stage_ticks[k] * per_tick));
    }
    printf("total: %.0f\n", (double)((float)(t1 - t0) * per_tick));
    for (k = 0u; k < n; k++) {
        const sbr_detection_t *d = &dets[k];
        printf("det: %u;%u;%u;%u;%u;%.4f\n", (unsigned)d->box.x, (unsigned)d->box.y,
               (unsigned)(d->box.x + d->box.width - 1u), (unsigned)(d->box.y + d->box.height - 1u),
               (unsigned)d->class_id, (double)d->score);
    }
    return ((st == SBR_OK) || (st == SBR_ERR_CAPACITY)) ? 0 : 1;
}
