/* SPDX-License-Identifier: MIT */
/* version.c: the library's version as text, from volfix.h's numbers, so that the two cannot disagree. */
#include "volfix.h"

#define VERSION_TEXT_(major, minor, patch) #major "." #minor "." #patch
#define VERSION_TEXT(major, minor, patch) VERSION_TEXT_(major, minor, patch)

const char *vf_version(void)
{
    return VERSION_TEXT(VF_VERSION_MAJOR, VF_VERSION_MINOR, VF_VERSION_PATCH);
}
