/* SPDX-License-Identifier: MIT */
/* Bare-metal CAN port template (Cortex-M). The board support package provides the
 * driver hook
 *
 *     int sbr_board_can_tx(uint32_t id, uint8_t dlc, const uint8_t data[8]);
 *
 * which puts one classical frame (11-bit id) into a free transmit mailbox / FIFO slot
 * and returns 0, or returns non-zero at once when none is free (it must not block: it
 * may be called from the cycle task). Typical bodies: bxCAN (STM32F4) writes TIxR,
 * TDTxR, TDLxR, TDHxR of an empty mailbox and sets TXRQ; FDCAN (STM32H7/G4) writes the
 * Tx FIFO element at the put index and sets TXBAR; a TCAN/MCP251x over SPI queues into
 * its TX FIFO. The default hook (weak) refuses every frame, so an image without a driver
 * links and reports every frame as dropped.
 *
 * Policy: a refused frame is dropped and counted; the sender stops the cycle there
 * (the frames are in priority order, lower ones would not fit either). */
#ifndef SBR_PORT_CORTEX_M_H
#define SBR_PORT_CORTEX_M_H

#include "sbr/can.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sbr_port_cortex_m_s {
    uint32_t sent;
    uint32_t dropped;
} sbr_port_cortex_m_t;

extern const sbr_can_port_t sbr_port_cortex_m;

int sbr_board_can_tx(uint32_t id, uint8_t dlc, const uint8_t data[8]);

#ifdef __cplusplus
}
#endif

#endif
