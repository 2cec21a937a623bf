/* SPDX-License-Identifier: MIT */
/* startup.h: what the reset code tells main: how much stack there is and how much of it has been touched. */
#ifndef STARTUP_H
#define STARTUP_H

#include <stddef.h>

size_t startup_stack_size(void);
/* Bytes of stack written since reset: the painted words no longer holding the paint, counted from the
 * bottom (a deepest call that wrote the paint value itself would go unseen, which a word-sized pattern makes
 * unlikely). */
size_t startup_stack_used(void);

#endif
