/* SPDX-License-Identifier: MIT */
/* Mock CAN port: records frames in a caller array, for tests. It can refuse frames after
   a given number to exercise the sender's full-queue path. */
#ifndef SBR_PORT_MOCK_H
#define SBR_PORT_MOCK_H

#include "sbr/can.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sbr_port_mock_s {
    sbr_can_frame_t *frames; /* storage */
    uint32_t capacity;
    uint32_t count;          /* frames recorded */
    uint32_t accept_limit;   /* refuse (::SBR_ERR_CAPACITY) once count reaches this; 0 = capacity */
    uint32_t refused;        /* frames refused */
} sbr_port_mock_t;

/* The port's function table; its context is an sbr_port_mock_t. */
extern const sbr_can_port_t sbr_port_mock;

/* Start recording into `storage`. */
void sbr_port_mock_init(sbr_port_mock_t *m, sbr_can_frame_t *storage, uint32_t capacity);

#ifdef __cplusplus
}
#endif

#endif
