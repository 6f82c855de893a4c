/* SPDX-License-Identifier: MIT */
#include "sbr_port_mock.h"

#include <stddef.h>

static sbr_status_t mock_send(void *ctx, const sbr_can_frame_t *frame)
{
    sbr_port_mock_t *m = (sbr_port_mock_t *)ctx;
    uint32_t limit;
    if ((m == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    limit = m->capacity;
    if ((m->accept_limit != 0u) && (m->accept_limit < limit)) {
        limit = m->accept_limit;
    }
    if (m->count >= limit) {
        m->refused++;
        return SBR_ERR_CAPACITY;
    }
    m->frames[m->count] = *frame;
    m->count++;
    return SBR_OK;
}

const sbr_can_port_t sbr_port_mock = {"mock", mock_send};

void sbr_port_mock_init(sbr_port_mock_t *m, sbr_can_frame_t *storage, uint32_t capacity)
{
    if (m != NULL) {
        m->frames = storage;
        m->capacity = (storage != NULL) ? capacity : 0u;
        m->count = 0u;
        m->accept_limit = 0u;
        m->refused = 0u;
    }
}
