/* SPDX-License-Identifier: MIT */
/*
 * The bench images' clock (sbr_cost_m4.c, sbr_picto_m4.c): the CMSDK APB timer 0 of qemu
 * mps2-an386 (25 MHz, counting down), started free-running and calibrated against a loop
 * of known length. With -icount shift=0 qemu advances virtual time by 1 ns per
 * instruction, so a tick is a fixed number of instructions (40). Bench code only, not
 * part of the core.
 */
#ifndef SBR_BENCH_TIMER_H
#define SBR_BENCH_TIMER_H

#include <stdint.h>

#define SBR_BENCH_TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define SBR_BENCH_TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define SBR_BENCH_TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)

/* Ticks since the timer started. */
static inline uint32_t ticks_now(void)
{
    return 0xFFFFFFFFu - SBR_BENCH_TIMER0_VALUE;
}

/* Ticks for a loop of 2 * n instructions (subs + bne per iteration). */
static inline uint32_t loop_ticks(uint32_t n)
{
    const uint32_t t0 = ticks_now();
    __asm volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
    return ticks_now() - t0;
}

/* Starts the timer free-running; returns instructions per tick. */
static inline float bench_timer_start(void)
{
    SBR_BENCH_TIMER0_CTRL = 0u;
    SBR_BENCH_TIMER0_RELOAD = 0xFFFFFFFFu;
    SBR_BENCH_TIMER0_VALUE = 0xFFFFFFFFu;
    SBR_BENCH_TIMER0_CTRL = 1u;
    return (float)(2u * 2000000u) / (float)loop_ticks(2000000u);
}

#endif
