/* SPDX-License-Identifier: MIT */
#include "sbr_port_cortex_m.h"

#include <stddef.h>

/* Default hook: no driver, every frame refused. A board overrides it. */
__attribute__((weak)) int sbr_board_can_tx(uint32_t id, uint8_t dlc, const uint8_t data[8])
{
    (void)id;
    (void)dlc;
    (void)data;
    return -1;
}

static sbr_status_t cortex_m_send(void *ctx, const sbr_can_frame_t *frame)
{
    sbr_port_cortex_m_t *p = (sbr_port_cortex_m_t *)ctx;
    if ((p == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((frame->dlc > 8u) || (frame->id > 0x7FFu)) {
        return SBR_ERR_RANGE;
    }
    if (sbr_board_can_tx(frame->id, frame->dlc, frame->data) != 0) {
        p->dropped++;
        return SBR_ERR_CAPACITY;
    }
    p->sent++;
    return SBR_OK;
}

const sbr_can_port_t sbr_port_cortex_m = {"cortex_m", cortex_m_send};
