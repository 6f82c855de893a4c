/* SPDX-License-Identifier: MIT */
/* SocketCAN port (Linux): a raw CAN socket bound to one interface, non-blocking.
 *
 * Full-queue policy: when the kernel refuses a frame (EAGAIN/EWOULDBLOCK: socket send
 * buffer full, or ENOBUFS: the interface's queue is full), the port waits up to
 * `retry_wait_ms` for the socket to become writable and tries again, at most `retries`
 * times; then it drops the frame, counts it in `dropped` and returns SBR_ERR_CAPACITY so
 * that the sender stops this cycle (later, lower-priority frames would not fit either).
 * Every refusal is counted in `busy` (EAGAIN) or `nobufs` (ENOBUFS). */
#ifndef SBR_PORT_SOCKETCAN_H
#define SBR_PORT_SOCKETCAN_H

#include "sbr/can.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sbr_port_socketcan_s {
    int fd;                  /* -1 when closed */
    uint32_t retries;        /* default 3 */
    uint32_t retry_wait_ms;  /* default 1 */
    uint32_t sent;
    uint32_t dropped;
    uint32_t busy;
    uint32_t nobufs;
} sbr_port_socketcan_t;

extern const sbr_can_port_t sbr_port_socketcan;

/* Open a raw CAN socket on `ifname` (e.g. "vcan0"). SBR_OK; SBR_ERR_NULL; SBR_ERR_STATE
   when the kernel has no CAN support (AF_CAN unavailable) or the interface is missing;
   *os_error gets errno (may be NULL). */
sbr_status_t sbr_port_socketcan_open(sbr_port_socketcan_t *p, const char *ifname, int *os_error);

/* Receive one frame if one is waiting: SBR_OK; SBR_ERR_CAPACITY when none is waiting
   (non-blocking); SBR_ERR_STATE on a socket error. */
sbr_status_t sbr_port_socketcan_recv(sbr_port_socketcan_t *p, sbr_can_frame_t *frame,
                                     uint32_t wait_ms);

void sbr_port_socketcan_close(sbr_port_socketcan_t *p);

#ifdef __cplusplus
}
#endif

#endif
