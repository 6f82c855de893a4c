/* SPDX-License-Identifier: MIT */
/* SocketCAN port on a real kernel interface: frames sent through sbr's port arrive on a
 * second socket bound to the same interface (vcan0 by default, or argv[1]).
 * Skips itself (exit 77) with a message only where the kernel has no CAN support
 * (EAFNOSUPPORT) or the interface does not exist (ENODEV); any other error fails. Create
 * the interface with:
 *   sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "sbr/can.h"
#include "sbr_port_socketcan.h"

int main(int argc, char **argv)
{
    const char *ifname = (argc > 1) ? argv[1] : "vcan0";
    sbr_port_socketcan_t tx;
    sbr_port_socketcan_t rx;
    sbr_can_e2e_tx_t e2e;
    sbr_can_frame_t frames[4];
    sbr_can_detection_t d = {14u, 80.0f, 700.0f, 300.0f, 40.0f, 40.0f, 5u};
    uint32_t sent = 0u;
    uint32_t i;
    int err = 0;

    if (sbr_port_socketcan_open(&rx, ifname, &err) != SBR_OK) {
        /* only the documented causes skip: no AF_CAN in the kernel, or no such interface;
           any other failure (a bug in the port included) fails */
        if ((err == EAFNOSUPPORT) || (err == ENODEV)) {
            printf("SKIP: SocketCAN not available here (%s: %s)%s\n", ifname, strerror(err),
                   (err == EAFNOSUPPORT) ? " - the kernel has no CAN support (AF_CAN)"
                                         : " - no such interface");
            return 77;
        }
        printf("FAIL: opening %s: %s (errno %d)\n", ifname, strerror(err), err);
        return 1;
    }
    if (sbr_port_socketcan_open(&tx, ifname, &err) != SBR_OK) {
        printf("FAIL: second socket on %s: %s\n", ifname, strerror(err));
        return 1;
    }
    sbr_can_e2e_tx_init(&e2e);
    for (i = 0u; i < 4u; i++) {
        d.center_x = 100.0f + 10.0f * (float)i;
        if ((sbr_can_pack_detection(&d, &frames[i]) != SBR_OK) ||
            (sbr_can_e2e_protect(&e2e, &frames[i]) != SBR_OK)) {
            printf("FAIL: pack\n");
            return 1;
        }
    }
    if (sbr_can_send(&sbr_port_socketcan, &tx, frames, 4u, &sent) != SBR_OK || sent != 4u) {
        printf("FAIL: sent %u of 4 (busy %u, nobufs %u, dropped %u)\n", sent, tx.busy, tx.nobufs,
               tx.dropped);
        return 1;
    }
    for (i = 0u; i < 4u; i++) {
        sbr_can_frame_t got;
        if (sbr_port_socketcan_recv(&rx, &got, 1000u) != SBR_OK) {
            printf("FAIL: frame %u not received\n", i);
            return 1;
        }
        if ((got.id != frames[i].id) || (got.dlc != 8u) || (memcmp(got.data, frames[i].data, 8u) != 0)) {
            printf("FAIL: frame %u differs\n", i);
            return 1;
        }
    }
    sbr_port_socketcan_close(&tx);
    sbr_port_socketcan_close(&rx);
    printf("OK: 4 frames sent and received on %s\n", ifname);
    return 0;
}
