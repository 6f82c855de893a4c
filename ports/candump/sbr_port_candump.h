/* SPDX-License-Identifier: MIT */
/* candump-log CAN port (host): writes each frame as a line of can-utils' log format,
     (1436509052.249713) can0 310#0102030405060708
   which `canplayer -I FILE` replays and cantools/python-can read. The caller sets the
   timestamp (microseconds since the epoch) before each cycle. */
#ifndef SBR_PORT_CANDUMP_H
#define SBR_PORT_CANDUMP_H

#include <stdio.h>

#include "sbr/can.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sbr_port_candump_s {
    FILE *file;          /* open for writing, owned by the caller */
    const char *ifname;  /* interface name written in each line, e.g. "can0" */
    uint64_t time_us;    /* timestamp of the next frames */
    uint32_t written;    /* frames written */
} sbr_port_candump_t;

extern const sbr_can_port_t sbr_port_candump;

/* One log line (without newline) for a frame into buf; returns its length, 0 on error. */
size_t sbr_candump_format(char *buf, size_t size, uint64_t time_us, const char *ifname,
                          const sbr_can_frame_t *frame);

#ifdef __cplusplus
}
#endif

#endif
