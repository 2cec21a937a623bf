/* SPDX-License-Identifier: MIT */
/*
 * semihost.h: text out and exit through Arm semihosting: a `bkpt 0xab` that the debugger, or qemu run with
 * -semihosting, serves on the host. The firmware has no UART driver and no libc; this is its only output.
 * (On a board without a debugger attached, bkpt 0xab faults: semihosting is for the emulator and the bench.)
 */
#ifndef SEMIHOST_H
#define SEMIHOST_H

#include <stdint.h>

/* SYS_WRITE0: a NUL-terminated string to the host's console. */
void sh_puts(const char *text);

/* Numbers for the report, without printf: unsigned decimal, and 64 bits as 16 hex digits. */
void sh_putu(uint32_t value);
void sh_puthex64(uint64_t value);

/* SYS_EXIT_EXTENDED: end the program with an exit status that qemu returns as its own. */
__attribute__((noreturn)) void sh_exit(uint32_t status);

#endif
