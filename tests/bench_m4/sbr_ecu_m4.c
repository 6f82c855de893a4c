/* SPDX-License-Identifier: MIT */
/*
 * sbr_ecu_m4: the ECU's whole per-frame job on the emulated Cortex-M4F (qemu mps2-an386):
 * frames in, CAN frames out through the candump port, as `sbr_detect --sequence --canlog
 * LOG --canlog-fixed-time` does on the host (cmake/compare_ecu_log.py compares the logs
 * byte for byte).
 *
 * Frames `00000.ppm`, `00001.ppm`, ... (binary PPM, P6, maxval 255) are read through
 * semihosting from qemu's working folder until one is missing, one frame 100 ms after the
 * other from 1700000000 s (the host tools' CAN log clock). Each goes through
 * sbr_ecu_frame(): the recogniser (defaults, the built-in models, the score floor the host
 * uses: min(0.3, the class stage's operating point)), the sign tracking, the restrictions
 * and the CAN cycle, whose frames the candump port writes to `ecu.log`. The processing
 * time in the status frame is 0 (no clock), as with the host's --canlog-fixed-time.
 *
 * Memory: the frame in the SRAM, the recogniser's and the ECU's workspaces in the board's
 * 16 MiB PSRAM at 0x21000000.
 *
 * Output lines: "frame <n>: <status> <detections> <confirmed> <limit>" and "frames: <n>".
 * This is a test image, not part of the core: it uses stdio (semihosting).
 */
#include <stdint.h>
#include <stdio.h>

#include "sbr/ecu.h"
#include "sbr/models.h"
#include "sbr_bench_ppm.h"
#include "sbr_port_candump.h"

#define PSRAM_BASE 0x21000000u
#define PSRAM_BYTES (16u * 1024u * 1024u)
#define SRAM_FRAME_BYTES (3u * 1024u * 1024u + 512u * 1024u)
#define MAX_FRAMES 1000u
#define BASE_US 1700000000000000ull
#define PERIOD_US 100000u

static uint8_t g_frame[SRAM_FRAME_BYTES];

/* Frame k into g_frame; 0 when there is none, -1 when it is not a PPM that fits. */
static int read_frame(uint32_t k, uint32_t *w, uint32_t *h)
{
    char name[16];
    uint32_t maxval = 0u;
    FILE *f;
    (void)snprintf(name, sizeof name, "%05u.ppm", (unsigned)k);
    f = fopen(name, "rb");
    if (f == NULL) {
        return 0;
    }
    if ((fgetc(f) != 'P') || (fgetc(f) != '6') || !read_token(f, w) || !read_token(f, h) ||
        !read_token(f, &maxval) || (maxval != 255u) || (*w == 0u) || (*h == 0u) ||
        ((size_t)*w * *h * 3u > SRAM_FRAME_BYTES) ||
        (fread(g_frame, 1u, (size_t)*w * *h * 3u, f) != (size_t)*w * *h * 3u)) {
        (void)fclose(f);
        return -1;
    }
    (void)fclose(f);
    return 1;
}

int main(void)
{
    sbr_recog_config_t rc;
    sbr_model_t model;
    sbr_picto_model_t picto;
    sbr_recog_t rec;
    sbr_ecu_config_t ec;
    sbr_ecu_t ecu;
    sbr_port_candump_t port;
    sbr_image_t img;
    uint32_t w = 0u, h = 0u, k;
    size_t rws, ews;
    sbr_status_t st;
    FILE *log;

    if (read_frame(0u, &w, &h) != 1) {
        printf("error: cannot read 00000.ppm (binary PPM, maxval 255, at most %u bytes)\n",
               (unsigned)SRAM_FRAME_BYTES);
        return 1;
    }
    (void)sbr_model_gtsdb(&model);
    (void)sbr_picto_gtsdb(&picto);
    sbr_recog_config_default(&rc);
    rc.min_score = (picto.threshold < rc.min_score) ? picto.threshold : rc.min_score;
    rws = (sbr_recog_workspace_size(&rc, w, h) + 7u) & ~(size_t)7u;
    sbr_ecu_config_default(&ec);
    ec.signs.width = (float)w;
    ec.signs.height = (float)h;
    ec.signs.period_us = PERIOD_US;
    ec.min_score = picto.threshold;
    ews = sbr_ecu_workspace_size(&ec);
    if ((rws == 0u) || (ews == 0u) || (rws + ews > PSRAM_BYTES)) {
        printf("error: workspaces of %u + %u bytes do not fit the PSRAM\n", (unsigned)rws, (unsigned)ews);
        return 1;
    }
    st = sbr_recog_init(&rec, &rc, &model, &picto, (void *)PSRAM_BASE, rws);
    if (st == SBR_OK) {
        st = sbr_ecu_init(&ecu, &ec, (void *)(PSRAM_BASE + rws), ews);
    }
    log = fopen("ecu.log", "w");
    if ((st != SBR_OK) || (log == NULL)) {
        printf("error: set-up: %s\n", sbr_status_str(st));
        return 1;
    }
    port.file = log;
    port.ifname = "can0";
    port.written = 0u;
    img.data = g_frame;
    img.format = SBR_PIXEL_RGB888;
    for (k = 0u; k < MAX_FRAMES; k++) {
        sbr_ecu_result_t r;
        const int got = (k == 0u) ? 1 : read_frame(k, &w, &h);
        if (got == 0) {
            break;
        }
        img.width = w;
        img.height = h;
        img.stride = w * 3u;
        if (got < 0) {
            img.width = 0u; /* a frame that cannot be read: the recogniser refuses it */
        }
        port.time_us = BASE_US + (uint64_t)k * PERIOD_US;
        st = sbr_ecu_frame(&ecu, &rec, &img, port.time_us, 0u, &sbr_port_candump, &port, &r);
        printf("frame %u: %s %u %u %u\n", (unsigned)k, sbr_status_str(st), (unsigned)r.detections,
               (unsigned)r.confirmed, (unsigned)r.restrictions.speed_limit_kmh);
    }
    (void)fclose(log);
    printf("frames: %u\n", (unsigned)k);
    printf("can frames: %u\n", (unsigned)port.written);
    return 0;
}
