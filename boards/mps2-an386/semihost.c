/* SPDX-License-Identifier: MIT */
/* semihost.c: Arm semihosting calls (see semihost.h) and the two number formatters the report needs. */
#include "semihost.h"

/* Operation numbers and the exit reason, from Arm's semihosting specification. */
#define SYS_WRITE0 0x04u
#define SYS_EXIT_EXTENDED 0x20u             /* SYS_EXIT (0x18) cannot carry a status on 32-bit Arm */
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u

/* The call: operation in r0, argument (a pointer to a string or a parameter block) in r1; the result comes
 * back in r0. "memory": the host reads what r1 points at, so earlier stores must have happened. */
static uint32_t call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void sh_puts(const char *text)
{
    call(SYS_WRITE0, text);
}

void sh_putu(uint32_t value)
{
    char text[11];
    int at = (int)sizeof text - 1;
    text[at] = 0;
    do {
        text[--at] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value);
    sh_puts(text + at);
}

void sh_puthex64(uint64_t value)
{
    char text[17];
    for (int i = 15; i >= 0; i--, value >>= 4)
        text[i] = "0123456789abcdef"[value & 15u];
    text[16] = 0;
    sh_puts(text);
}

void sh_exit(uint32_t status)
{
    const uint32_t block[2] = {ADP_STOPPED_APPLICATION_EXIT, status};
    call(SYS_EXIT_EXTENDED, block);
    for (;;) /* without a host to stop us: stay here */
        __asm__ volatile("wfi");
}
