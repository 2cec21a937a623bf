/* SPDX-License-Identifier: MIT */
/* test_input_script.c: scripted input (port/input/input_script.c) and finding backends by name (port/input/input.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "fixtures.h"
#include "input/input.h"
#include "input/input_backends.h" /* the seam in port/input/input_script.c */

#define MS 1000000ull
#define START (5000 * MS) /* the scripts' time 0 */

/* A board with 2 knobs and 2 buttons, as host-headless but smaller. */
static vfp_board_t board_2x2(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.path, sizeof b.path, "test.board");
    snprintf(b.input, sizeof b.input, "script");
    b.knob_count = 2;
    b.button_count = 2;
    return b;
}

static int load(vfp_input_t *in, const char *text, char *err, size_t errlen)
{
    vfp_board_t b = board_2x2();
    err[0] = '\0';
    return vfp_script_load_string(in, &b, text, "s.script", START, err, errlen);
}

#define EXPECT_BAD(text, phrase) \
    do { \
        vfp_input_t in_; \
        char err_[256]; \
        CHECK_EQ(load(&in_, text, err_, sizeof err_), VFP_ERR); \
        CHECK_MSG(strncmp(err_, phrase, strlen(phrase)) == 0, "expected '%s', got '%s'", phrase, err_); \
        CHECK(in_.priv == NULL); \
    } while (0)

/* ---------------------------------------------------------------------------------------------------------- */

static void parses_and_delivers_on_time(void)
{
    static const char *text = "# a script\n"
                              "\n"
                              "0 turn 0 3\n"
                              "  100\tturn 1 -2   # down\n"
                              "100 press 1\n"
                              "250 release 1\n"
                              "1000 quit\n";
    vfp_input_t in;
    char err[256];
    CHECK_MSG(load(&in, text, err, sizeof err) == 0, "%s", err);
    CHECK(in.ops && strcmp(in.ops->name, "script") == 0);
    CHECK_EQ(in.ops->fd(&in), -1);
    vfp_event_t ev[8];

    CHECK_EQ(in.ops->deadline_ns(&in), START);
    CHECK_EQ(in.ops->read(&in, ev, 8, START - 1, err, sizeof err), 0); /* nothing before its time */
    CHECK_EQ(in.ops->read(&in, ev, 8, START, err, sizeof err), 1);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(ev[0].steps, 3);
    CHECK_EQ(ev[0].time_ns, START);

    CHECK_EQ(in.ops->deadline_ns(&in), START + 100 * MS);
    /* read late: both events of time 100 come, each with its scheduled time */
    CHECK_EQ(in.ops->read(&in, ev, 8, START + 200 * MS, err, sizeof err), 2);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(ev[0].steps, -2);
    CHECK_EQ(ev[0].time_ns, START + 100 * MS);
    CHECK_EQ(ev[1].type, VFP_EV_PRESS);
    CHECK_EQ(ev[1].control, 1);
    CHECK_EQ(ev[1].time_ns, START + 100 * MS);

    CHECK_EQ(in.ops->deadline_ns(&in), START + 250 * MS);
    CHECK_EQ(in.ops->read(&in, ev, 8, START + 999 * MS, err, sizeof err), 1);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(in.ops->read(&in, ev, 8, START + 1000 * MS, err, sizeof err), 1);
    CHECK_EQ(ev[0].type, VFP_EV_QUIT);
    CHECK_EQ(ev[0].time_ns, START + 1000 * MS);

    /* the end: no deadline, nothing more */
    CHECK_EQ(in.ops->deadline_ns(&in), 0);
    CHECK_EQ(in.ops->read(&in, ev, 8, START + 10000 * MS, err, sizeof err), 0);
    in.ops->close(&in);
    CHECK(in.priv == NULL);
    in.ops->close(&in); /* twice is harmless */
}

static void max_limits_a_read(void)
{
    vfp_input_t in;
    char err[256];
    CHECK_MSG(load(&in, "0 press 0\n0 release 0\n0 press 1\n0 release 1\n", err, sizeof err) == 0, "%s", err);
    vfp_event_t ev[4];
    CHECK_EQ(in.ops->read(&in, ev, 3, START, err, sizeof err), 3);
    CHECK_EQ(ev[2].type, VFP_EV_PRESS);
    CHECK_EQ(ev[2].control, 1);
    CHECK_EQ(in.ops->deadline_ns(&in), START); /* the rest is due already */
    CHECK_EQ(in.ops->read(&in, ev, 3, START, err, sizeof err), 1);
    CHECK_EQ(ev[0].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[0].control, 1);
    in.ops->close(&in);
}

static void empty_script(void)
{
    vfp_input_t in;
    char err[256];
    CHECK_MSG(load(&in, "# nothing\n\n   \n", err, sizeof err) == 0, "%s", err);
    vfp_event_t ev[1];
    CHECK_EQ(in.ops->deadline_ns(&in), 0);
    CHECK_EQ(in.ops->read(&in, ev, 1, START, err, sizeof err), 0);
    in.ops->close(&in);
    /* time 0 at clock 0 is still a deadline (0 means none) */
    vfp_board_t b = board_2x2();
    CHECK_EQ(vfp_script_load_string(&in, &b, "0 quit", "z", 0, err, sizeof err), 0);
    CHECK_EQ(in.ops->deadline_ns(&in), 1);
    CHECK_EQ(in.ops->read(&in, ev, 1, 0, err, sizeof err), 1);
    in.ops->close(&in);
}

static void bad_lines(void)
{
    EXPECT_BAD("0 turn 0 1\nabc turn 0 1\n", "s.script:2: expected a time in milliseconds (0 to 1000000000) first, "
                                               "found 'abc'");
    EXPECT_BAD("-5 quit\n", "s.script:1: expected a time in milliseconds");
    EXPECT_BAD("100 turn 0 1\n# c\n50 turn 0 1\n", "s.script:3: time 50 is before the previous event's 100 "
                                                     "(times must not decrease)");
    EXPECT_BAD("0 spin 0 1\n", "s.script:1: unknown event 'spin' (expected turn, press, release or quit)");
    EXPECT_BAD("10\n", "s.script:1: unknown event ''");
    EXPECT_BAD("0 turn 0\n", "s.script:1: expected 'TIME_MS turn KNOB STEPS'");
    EXPECT_BAD("0 turn 0 1 2\n", "s.script:1: expected 'TIME_MS turn KNOB STEPS'");
    EXPECT_BAD("0 turn 2 1\n", "s.script:1: turn: expected a knob from 0 to 1, found '2'");
    EXPECT_BAD("0 turn -1 1\n", "s.script:1: turn: expected a knob from 0 to 1, found '-1'");
    EXPECT_BAD("0 turn 0 0\n", "s.script:1: turn: expected detents, a non-zero number from -1000 to 1000, found '0'");
    EXPECT_BAD("0 turn 0 1001\n", "s.script:1: turn: expected detents");
    EXPECT_BAD("0 turn 0 two\n", "s.script:1: turn: expected detents");
    EXPECT_BAD("\n\n0 press 5\n", "s.script:3: press: expected a button from 0 to 1, found '5'");
    EXPECT_BAD("0 release\n", "s.script:1: expected 'TIME_MS release BUTTON'");
    EXPECT_BAD("0 quit now\n", "s.script:1: expected 'TIME_MS quit'");
    EXPECT_BAD("0 press 0 1 2 3 4 5 6\n", "s.script:1: expected 'TIME_MS press BUTTON'");
    /* A control byte quoted from the script becomes '?': the message stays one printable line (found by
     * tests/fuzz: "quit\x1a" came back with its byte). */
    EXPECT_BAD("2000 quit\032\n", "s.script:1: unknown event 'quit?' (expected turn, press, release or quit)");
    EXPECT_BAD("0 turn \033[2J 1\n", "s.script:1: turn: expected a knob from 0 to 1, found '?[2J'");

    /* a board without knobs says so */
    vfp_board_t b = board_2x2();
    b.knob_count = 0;
    vfp_input_t in;
    char err[256];
    CHECK_EQ(vfp_script_load_string(&in, &b, "0 turn 0 1", "k.script", 0, err, sizeof err), VFP_ERR);
    CHECK_MSG(strcmp(err, "k.script:1: turn: the board has no knobs") == 0, "%s", err);
}

static void open_from_file(void)
{
    const char *path = fx_write("demo.script", "0 turn 1 4\n20 press 0\n", NULL, 0);

    vfp_board_t b = board_2x2();
    char err[256] = "";
    const vfp_input_ops_t *ops = vfp_input_find("script", &b, err, sizeof err);
    CHECK_MSG(ops, "%s", err);
    vfp_input_t in;
    /* the --script argument wins over the board's input.script */
    snprintf(b.script, sizeof b.script, "/nonexistent.script");
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    uint64_t before = (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
    vfp_status_t status = ops->open(&in, &b, path, err, sizeof err);
    CHECK_MSG(status == VFP_OK, "%s", err);
    uint64_t t0 = ops->deadline_ns(&in);
    CHECK(t0 >= before);
    vfp_event_t ev[4];
    CHECK_EQ(ops->read(&in, ev, 4, t0 + 20 * MS, err, sizeof err), 2);
    CHECK_EQ(ev[0].steps, 4);
    CHECK_EQ(ev[1].time_ns, t0 + 20 * MS);
    ops->close(&in);

    /* the board's script when no --script; a missing file is named */
    CHECK_EQ(ops->open(&in, &b, NULL, err, sizeof err), VFP_ERR);
    CHECK_MSG(strcmp(err, "/nonexistent.script: cannot open: No such file or directory") == 0, "%s", err);
    b.script[0] = '\0';
    CHECK_EQ(ops->open(&in, &b, "", err, sizeof err), VFP_ERR);
    CHECK_MSG(strcmp(err, "test.board: input = script needs a script (input.script in the board file, or --script "
                          "FILE)") == 0, "%s", err);
}

static void shipped_script_plays(void)
{
    /* boards/host-headless.script against its board */
    vfp_board_t b;
    char err[512] = "";
    CHECK_MSG(vfp_board_load(&b, "boards/host-headless.board", err, sizeof err) == 0, "%s", err);
    const vfp_input_ops_t *ops = vfp_input_find(NULL, &b, err, sizeof err);
    CHECK_MSG(ops && strcmp(ops->name, "script") == 0, "%s", err);
    vfp_input_t in;
    CHECK_MSG(ops->open(&in, &b, NULL, err, sizeof err) == 0, "%s", err);
    vfp_event_t ev[64];
    int n = ops->read(&in, ev, 64, UINT64_MAX, err, sizeof err);
    ops->close(&in);
    CHECK(n >= 3);
    CHECK_EQ(ev[n - 1].type, VFP_EV_QUIT);
}

static void find_backends(void)
{
    char err[256] = "";
    vfp_board_t b = board_2x2();
    CHECK(vfp_input_find("script", &b, err, sizeof err) != NULL);
    CHECK(vfp_input_find("evdev", &b, err, sizeof err) != NULL);
    CHECK(vfp_input_find("mouse", &b, err, sizeof err) == NULL);
    CHECK_MSG(strcmp(err, "test.board: unknown input 'mouse' (expected gpiod, evdev, sdl or script)") == 0, "%s", err);
#ifdef VFP_HAVE_GPIOD
    CHECK(vfp_input_find("gpiod", &b, err, sizeof err) != NULL);
#else
    CHECK(vfp_input_find("gpiod", &b, err, sizeof err) == NULL);
    CHECK_MSG(strcmp(err, "test.board: input 'gpiod' is not compiled in: install libgpiod-dev and rebuild") == 0, "%s",
              err);
#endif
#ifdef VFP_HAVE_SDL
    CHECK(vfp_input_find("sdl", &b, err, sizeof err) != NULL);
#else
    CHECK(vfp_input_find("sdl", &b, err, sizeof err) == NULL);
    CHECK(strstr(err, "input 'sdl' is not compiled in: install libsdl2-dev and rebuild") != NULL);
#endif
    /* the list is NULL-terminated and names are distinct */
    int n = 0;
    while (vfp_inputs[n])
        n++;
    CHECK(n >= 2);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            CHECK(strcmp(vfp_inputs[i]->name, vfp_inputs[j]->name) != 0);
}

CHECK_CASES({"parses_and_delivers_on_time", parses_and_delivers_on_time}, {"max_limits_a_read", max_limits_a_read},
            {"empty_script", empty_script}, {"bad_lines", bad_lines}, {"open_from_file", open_from_file},
            {"shipped_script_plays", shipped_script_plays}, {"find_backends", find_backends});
CHECK_RUN("input_script")
