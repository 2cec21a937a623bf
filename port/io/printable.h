/* SPDX-License-Identifier: MIT */
/*
 * printable.h: every error message the port layer gives is one printable line.
 *
 * Messages quote what they found in a file (a header value, a board key, a script verb), and a file can hold
 * anything: a line break, a tab, a terminal escape. A message printed as one line must not carry them along, so
 * each reader passes its message through here before returning it (tests/fuzz checks this for every parser).
 */
#ifndef VFP_PRINTABLE_H
#define VFP_PRINTABLE_H

/* In place: a tab becomes a space, any other control byte (below 0x20, and 0x7f) a '?'. NULL is ignored. */
void vfp_printable(char *text);

#endif /* VFP_PRINTABLE_H */
