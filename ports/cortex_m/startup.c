/* SPDX-License-Identifier: MIT */
/*
 * Minimal Cortex-M4F start-up for sbr's test images (qemu mps2-an386) and template for an
 * ECU project: vector table, reset handler (FPU on, .data copied, .bss zeroed), newlib
 * semihosting set-up, then exit(main()).
 *
 * On a real ECU, replace initialise_monitor_handles() and exit() with the project's own
 * start-up; sbr's core needs nothing from here (no heap, no stdio, no static data).
 */
#include <stdint.h>
#include <stdlib.h>

extern int main(void);
extern void initialise_monitor_handles(void);

/* Linker script symbols. */
extern uint32_t _sidata;
extern uint32_t _sdata;
extern uint32_t _edata;
extern uint32_t _sbss;
extern uint32_t _ebss;
extern uint32_t _estack;

void Reset_Handler(void);
void Fault_Handler(void);
void _init(void);
void _fini(void);

/* With -nostartfiles there is no crti/crtn: newlib's __libc_init_array still calls these. */
void _init(void) {}
void _fini(void) {}

void Reset_Handler(void)
{
    volatile uint32_t *const cpacr = (volatile uint32_t *)0xE000ED88u;
    uint32_t *src = &_sidata;
    uint32_t *dst = &_sdata;

    /* Full access to CP10/CP11 (the FPU) before any float instruction runs. */
    *cpacr |= (0xFu << 20);
    __asm volatile("dsb\n\tisb" ::: "memory");

    while (dst < &_edata) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss; dst++) {
        *dst = 0u;
    }
    initialise_monitor_handles();
    exit(main());
}

/* Any fault ends the emulated run with a distinct exit code instead of hanging. */
void Fault_Handler(void)
{
    _Exit(99);
}

typedef void (*vector_t)(void);

__attribute__((section(".isr_vector"), used))
const vector_t sbr_vector_table[16] = {
    (vector_t)(uintptr_t)&_estack, /* initial stack pointer */
    Reset_Handler,
    Fault_Handler, /* NMI */
    Fault_Handler, /* HardFault */
    Fault_Handler, /* MemManage */
    Fault_Handler, /* BusFault */
    Fault_Handler, /* UsageFault */
    0, 0, 0, 0,
    Fault_Handler, /* SVCall */
    Fault_Handler, /* DebugMonitor */
    0,
    Fault_Handler, /* PendSV */
    Fault_Handler, /* SysTick */
};
