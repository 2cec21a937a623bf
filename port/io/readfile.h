/* SPDX-License-Identifier: MIT */
/*
 * readfile.h: a whole text input read once, front to back, with a cap on its size: transfer functions, knob
 * scripts and board files. Once, because the input may be a pipe or a FIFO (volfix-sim --tf <(...)), which gives
 * its bytes a single time; front to back with blocking reads, so that a FIFO with no writer yet waits as cat
 * does (and SIGINT or SIGTERM end the wait); capped, so that /dev/zero or a runaway generator is refused with a
 * message instead of filling memory. The caps are documented in docs/usage.md, "Input sizes".
 */
#ifndef VFP_READFILE_H
#define VFP_READFILE_H

#include <stddef.h>

#include "status.h"

#define VFP_CAP_TF (1u << 20)       /* a transfer-function file: 1 MiB (at most 1022 control points a file) */
#define VFP_CAP_BOARD (1u << 20)    /* a board file: 1 MiB (a few dozen keys) */
#define VFP_CAP_SCRIPT (16u << 20)  /* a knob script: 16 MiB (about 800,000 events) */

/* Read path (at most cap bytes) into *text, NUL-terminated (malloc'd; free it), its length in *len. `what` names
 * the kind of file for the cap's message ("transfer function"). Returns VFP_OK, or VFP_ERR with "PATH: ..." in err:
 * "PATH: cannot open: REASON", "PATH: cannot read: REASON", or "PATH: larger than N bytes, the cap on a WHAT". */
vfp_status_t vfp_read_text(const char *path, size_t cap, const char *what, char **text, size_t *len, char *err,
                           size_t errlen);

/* The line (from 1) of the first NUL byte in text[0..len), or 0 when there is none: a text file holds none. */
unsigned vfp_text_nul_line(const char *text, size_t len);

/* The next line of a NUL-terminated text in place: *cursor is where it starts (NULL: no more lines); the line's
 * '\n' becomes a NUL and *cursor moves past it. Returns the line, or NULL at the end. */
char *vfp_text_next_line(char **cursor);

#endif /* VFP_READFILE_H */
