/* SPDX-License-Identifier: MIT */
/*
 * status.h: what a port-layer function that can fail returns (host-sim's functions return the same), and the
 * exit status a program makes of it.
 *
 * One error code, the reason in words. A function that fails writes one printable line into its caller's err
 * buffer, naming the file, option or device and what was expected ("data/x.nhdr:4: unknown type 'float32'
 * (expected int8, uint8, int16 or uint16)"), and returns VFP_ERR. Only an outcome that a caller handles
 * differently has a code of its own: a display that went away (close it, open it again later) and a --help that
 * was printed (stop, successfully). Kinds of failure (bad input, I/O, a device, memory) would change no caller:
 * every program exits with status 2 for all of them, as the README promises, so a test of a bad input checks one
 * thing everywhere, VFP_ERR or exit status 2, and then the message, which is where the kinds differ.
 *
 * The numbers are fixed: code that compares numbers rather than names (boards/mps2-an386/gen_scene.c reads 1 as
 * --help) relies on them, and VFP_ERR is also the exit status it ends in.
 */
#ifndef VFP_STATUS_H
#define VFP_STATUS_H

typedef enum vfp_status {
    VFP_OK = 0,
    VFP_HELP_SHOWN = 1,   /* an option parser printed the usage for --help: nothing more to do */
    VFP_ERR = 2,          /* failed: err holds one line saying what, and where */
    VFP_DISPLAY_LOST = 3, /* a display's present(): the device went away (an unplugged USB display) */
} vfp_status_t;

/* The programs' exit statuses. */
#define VFP_EXIT_OK 0
#define VFP_EXIT_ERR 2 /* any bad input or failed device (README) */

/* A status as the exit status of a program: VFP_EXIT_OK for VFP_OK and VFP_HELP_SHOWN, else VFP_EXIT_ERR. */
static inline int vfp_exit_status(vfp_status_t status)
{
    return status == VFP_OK || status == VFP_HELP_SHOWN ? VFP_EXIT_OK : VFP_EXIT_ERR;
}

#endif /* VFP_STATUS_H */
