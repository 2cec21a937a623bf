/* SPDX-License-Identifier: MIT */
/*
 * check.h: the smallest test framework that does the job. A test file lists its cases in a table and calls
 * check_main; each case prints "ok - suite/name" or "not ok - suite/name: file:line: what failed", and the
 * runner (tests/run.sh) counts those lines.
 */
#ifndef CHECK_H
#define CHECK_H

#include <stdio.h>
#include <stddef.h>
#include <stdint.h>

typedef struct check_case {
    const char *name;
    void (*fn)(void);
} check_case_t;

/* Set by the CHECK macros when the running case fails. */
extern int check_failed;
void check_fail(const char *file, int line, const char *fmt, ...);
int check_main(const char *suite, const check_case_t *cases, int count, int argc, char **argv);

/* Random numbers a test can repeat (xorshift64*): the same sequence on every machine from the seed the test keeps
 * in *state. check_below: one in [0, n), from the high bits. */
static inline uint64_t check_rand64(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return *state * 0x2545F4914F6CDD1Du;
}

static inline uint32_t check_below(uint64_t *state, uint32_t n)
{
    return (uint32_t)((check_rand64(state) >> 33) % n);
}

/* check_mod: one in [0, n) from the low bits, the draw the older core suites' random cases come from (their
 * measured bounds are for those cases, so they keep it). */
static inline uint32_t check_mod(uint64_t *state, uint32_t n)
{
    return (uint32_t)(check_rand64(state) % n);
}

/* A sample volume: NAME in the folder $VOLFIX_DATA (make test sets it; the Makefile names the default). Writes
 * its path into path and returns path; when the variable is unset or the file is not there, writes why instead
 * (naming VOLFIX_DATA) and returns NULL, for the test to fail with. */
const char *check_data(const char *name, char *path, size_t len);

#define CHECK_CASES(...) static const check_case_t check_cases_[] = {__VA_ARGS__}
/* One entry of CHECK_CASES: a case named as its function is. */
#define CHECK_CASE(fn) {#fn, fn}
#define CHECK_RUN(suite) \
    int main(int argc, char **argv) \
    { \
        return check_main(suite, check_cases_, (int)(sizeof check_cases_ / sizeof check_cases_[0]), argc, argv); \
    }

#define CHECK(cond) \
    do { \
        if (!(cond)) { \
            check_fail(__FILE__, __LINE__, "%s", #cond); \
            return; \
        } \
    } while (0)

#define CHECK_MSG(cond, ...) \
    do { \
        if (!(cond)) { \
            check_fail(__FILE__, __LINE__, __VA_ARGS__); \
            return; \
        } \
    } while (0)

#define CHECK_EQ(a, b) \
    do { \
        long long check_a_ = (long long)(a), check_b_ = (long long)(b); \
        if (check_a_ != check_b_) { \
            check_fail(__FILE__, __LINE__, "%s == %s (%lld != %lld)", #a, #b, check_a_, check_b_); \
            return; \
        } \
    } while (0)

#define CHECK_NEAR(a, b, tol) \
    do { \
        double check_a_ = (double)(a), check_b_ = (double)(b), check_t_ = (double)(tol); \
        if (!(check_a_ - check_b_ <= check_t_ && check_b_ - check_a_ <= check_t_)) { \
            check_fail(__FILE__, __LINE__, "%s ~ %s (%.9g vs %.9g, tolerance %.3g)", #a, #b, check_a_, check_b_, \
                       check_t_); \
            return; \
        } \
    } while (0)

#endif
