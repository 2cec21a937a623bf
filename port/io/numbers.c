/* SPDX-License-Identifier: MIT */
/* numbers.c: numbers, lists of numbers, integers and sizes from the command line (see numbers.h). */
#include "numbers.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The length of the decimal number at the start of p (sign, digits, point, fraction, exponent), or 0 when p does
 * not start with one. Only this form is handed to strtod, which would also take spaces, hexadecimal, "inf" and
 * "nan". */
static size_t decimal_length(const char *p)
{
    size_t n = 0, digits = 0;
    if (p[n] == '+' || p[n] == '-')
        n++;
    while (isdigit((unsigned char)p[n]))
        n++, digits++;
    if (p[n] == '.') {
        n++;
        while (isdigit((unsigned char)p[n]))
            n++, digits++;
    }
    if (digits == 0)
        return 0;
    if (p[n] == 'e' || p[n] == 'E') {
        size_t e = n + 1;
        if (p[e] == '+' || p[e] == '-')
            e++;
        if (!isdigit((unsigned char)p[e]))
            return n; /* "2e" is the number 2 followed by junk, which the caller refuses */
        while (isdigit((unsigned char)p[e]))
            e++;
        n = e;
    }
    return n;
}

/* One finite number at *p, which moves past it. */
static int one_number(const char **p, double *out)
{
    size_t n = decimal_length(*p);
    if (n == 0)
        return 0;
    char buf[64];
    if (n >= sizeof buf)
        return 0; /* longer than any number a person writes on a command line */
    memcpy(buf, *p, n);
    buf[n] = 0;
    char *end;
    double v = strtod(buf, &end);
    if (*end || !isfinite(v))
        return 0;
    *out = v;
    *p += n;
    return 1;
}

int vfp_parse_list(const char *text, double *out, int min_count, int max_count)
{
    if (!text || min_count < 1 || max_count < min_count)
        return 0;
    double v[16];
    int n = 0;
    const char *p = text;
    for (;;) {
        if (n == max_count || n == (int)(sizeof v / sizeof v[0]))
            return 0; /* more values than the option takes */
        if (!one_number(&p, &v[n]))
            return 0;
        n++;
        if (*p == 0)
            break;
        if (*p != ',')
            return 0;
        p++;
    }
    if (n < min_count)
        return 0;
    memcpy(out, v, sizeof v[0] * (size_t)n);
    return n;
}

int vfp_parse_number(const char *text, double lo, double hi, double *out)
{
    double v;
    if (vfp_parse_list(text, &v, 1, 1) != 1 || !(v >= lo && v <= hi))
        return 0;
    *out = v;
    return 1;
}

/* An integer at *p (optional sign, decimal digits), which moves past it; 0 on overflow. */
static int one_integer(const char **p, long long *out)
{
    const char *s = *p;
    size_t n = (*s == '+' || *s == '-') ? 1 : 0;
    if (!isdigit((unsigned char)s[n]))
        return 0;
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (errno == ERANGE)
        return 0;
    *out = v;
    *p = end;
    return 1;
}

int vfp_parse_integer(const char *text, long long lo, long long hi, long long *out)
{
    long long v;
    const char *p = text;
    if (!text || !one_integer(&p, &v) || *p || v < lo || v > hi)
        return 0;
    *out = v;
    return 1;
}

int vfp_parse_size(const char *text, long long lo, long long hi, uint32_t *width, uint32_t *height)
{
    long long w, h;
    const char *p = text;
    if (!text || *p == '+' || *p == '-' || !one_integer(&p, &w) || (*p != 'x' && *p != 'X'))
        return 0;
    p++;
    if (*p == '+' || *p == '-' || !one_integer(&p, &h) || *p)
        return 0;
    if (w < lo || w > hi || h < lo || h > hi || lo < 0 || hi > UINT32_MAX)
        return 0;
    *width = (uint32_t)w;
    *height = (uint32_t)h;
    return 1;
}
