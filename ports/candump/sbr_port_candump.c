/* SPDX-License-Identifier: MIT */
#include "sbr_port_candump.h"

size_t sbr_candump_format(char *buf, size_t size, uint64_t time_us, const char *ifname,
                          const sbr_can_frame_t *frame)
{
    int n;
    int k;
    uint32_t i;
    if ((buf == NULL) || (ifname == NULL) || (frame == NULL) || (frame->dlc > 8u) ||
        (frame->id > 0x7FFu)) {
        return 0u;
    }
    n = snprintf(buf, size, "(%llu.%06llu) %s %03X#", (unsigned long long)(time_us / 1000000u),
                 (unsigned long long)(time_us % 1000000u), ifname, (unsigned)frame->id);
    for (i = 0u; (n > 0) && (i < frame->dlc); i++) {
        if ((size_t)n >= size) {
            return 0u;
        }
        k = snprintf(&buf[n], size - (size_t)n, "%02X", (unsigned)frame->data[i]);
        n = (k > 0) ? n + k : -1;
    }
    if ((n <= 0) || ((size_t)n >= size)) {
        return 0u;
    }
    return (size_t)n;
}

static sbr_status_t candump_send(void *ctx, const sbr_can_frame_t *frame)
{
    sbr_port_candump_t *p = (sbr_port_candump_t *)ctx;
    char line[64];
    if ((p == NULL) || (p->file == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if (sbr_candump_format(line, sizeof line, p->time_us, p->ifname ? p->ifname : "can0",
                           frame) == 0u) {
        return SBR_ERR_RANGE;
    }
    if (fprintf(p->file, "%s\n", line) < 0) {
        return SBR_ERR_STATE;
    }
    p->written++;
    return SBR_OK;
}

const sbr_can_port_t sbr_port_candump = {"candump", candump_send};
