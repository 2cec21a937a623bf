/* SPDX-License-Identifier: MIT */
/*
 * startup.c: the vector table and the reset handler, in C, with no libc. At reset the Cortex-M4 loads its stack
 * pointer from word 0 and jumps to word 1; the handler paints the stack (to measure it later), copies .data's
 * initial values from code memory, zeroes .bss, runs main and ends the program with main's status through
 * semihosting. A fault ends it too, with status 3 and a line that says which.
 */
#include <stdint.h>

#include "semihost.h"
#include "startup.h"

#define STACK_PAINT 0x5EEDC0DEu

/* From the linker script (mps2-an386.ld). */
extern uint32_t __stack_limit[], __stack_top[];
extern uint32_t __data_start[], __data_end[], __data_load[];
extern uint32_t __bss_start[], __bss_end[];

int main(void);
void Reset_Handler(void);
static void fault(void);

typedef void (*handler_t)(void);

/* The Armv7-M exception vectors: the initial stack pointer, then reset, NMI, HardFault, MemManage, BusFault,
 * UsageFault, four reserved, SVCall, DebugMonitor, reserved, PendSV, SysTick. No interrupt is enabled, so
 * the external interrupt vectors that would follow are left out. */
__attribute__((section(".vectors"), used)) static const handler_t vectors[16] = {
    (handler_t)(uintptr_t)__stack_top, Reset_Handler, fault, fault, fault, fault, fault, 0, 0, 0, 0,
    fault, fault, 0, fault, fault,
};

/* Word by word; -fno-tree-loop-distribute-patterns (Makefile) keeps these loops from becoming memset and memcpy
 * calls, which this firmware does not have. */
void Reset_Handler(void)
{
    /* Paint the stack below this function's own frame: everything under the stack pointer is unused yet. */
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (uint32_t *p = __stack_limit; p < sp; p++)
        *p = STACK_PAINT;
    for (uint32_t *dst = __data_start, *src = __data_load; dst < __data_end;)
        *dst++ = *src++;
    for (uint32_t *p = __bss_start; p < __bss_end; p++)
        *p = 0;
    sh_exit((uint32_t)main());
}

size_t startup_stack_size(void)
{
    return (size_t)((uintptr_t)__stack_top - (uintptr_t)__stack_limit);
}

size_t startup_stack_used(void)
{
    const uint32_t *p = __stack_limit;
    while (p < __stack_top && *p == STACK_PAINT)
        p++;
    return (size_t)((uintptr_t)__stack_top - (uintptr_t)p);
}

/* Any fault: the configurable fault status register says which kind (MemManage, BusFault, UsageFault bits). */
static void fault(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    sh_puts("fault: exception ");
    sh_putu(ipsr & 0x1FFu);
    sh_puts(", CFSR ");
    sh_puthex64(*(volatile const uint32_t *)0xE000ED28u);
    sh_puts("\n");
    sh_exit(3);
}
