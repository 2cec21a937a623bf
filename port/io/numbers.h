/* SPDX-License-Identifier: MIT */
/*
 * numbers.h: the one parser of numbers on the command line, for volfix and volfix-sim alike (and the lighting
 * options both share), so that an option takes the same numbers in either program.
 *
 * A number is written in decimal: an optional sign, digits with an optional point and fraction, an optional
 * exponent ("30", "-2.5", "1e-3", ".5"). Nothing else is a number: no spaces, no hexadecimal, no "inf" or "nan",
 * and nothing after it ("30junk"). A value must also be finite once read ("1e999" is not). A list is numbers
 * separated by single commas, exactly as many as the option takes ("30,20" for AZ,EL; "30,20,10,5" is refused,
 * not cut short). Integers are decimal digits with an optional sign and are read with overflow checks
 * ("4294967297" is too large, never 1). Sizes are "WxH" with each side an integer.
 *
 * Every function returns 1 when the text is exactly what was asked for (and stores it), else 0 and leaves the
 * outputs alone; callers print "PROGRAM: OPTION VALUE: expected FORM" with the accepted form and range.
 */
#ifndef VFP_NUMBERS_H
#define VFP_NUMBERS_H

#include <stdint.h>

/* Between min_count and max_count finite numbers separated by commas; returns how many (0 when the text is not
 * such a list). */
int vfp_parse_list(const char *text, double *out, int min_count, int max_count);

/* Exactly one finite number in [lo, hi]. */
int vfp_parse_number(const char *text, double lo, double hi, double *out);

/* Exactly one integer in [lo, hi], overflow-checked. */
int vfp_parse_integer(const char *text, long long lo, long long hi, long long *out);

/* "WxH" (or "WXH"): two integers, each in [lo, hi], overflow-checked. */
int vfp_parse_size(const char *text, long long lo, long long hi, uint32_t *width, uint32_t *height);

/* Is text empty (a value given as '')? Both programs refuse empty values rather than fall back to a default. */
static inline int vfp_is_empty(const char *text)
{
    return text && !text[0];
}

#endif /* VFP_NUMBERS_H */
