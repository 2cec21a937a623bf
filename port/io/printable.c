/* SPDX-License-Identifier: MIT */
/* printable.c: error messages made one printable line (printable.h). */
#include "printable.h"

void vfp_printable(char *text)
{
    if (!text)
        return;
    for (unsigned char *c = (unsigned char *)text; *c; c++)
        if (*c == '\t')
            *c = ' ';
        else if (*c < 0x20 || *c == 0x7f)
            *c = '?';
}
