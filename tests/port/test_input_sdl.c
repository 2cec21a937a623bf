/* SPDX-License-Identifier: MIT */
/* test_input_sdl.c: the SDL keys backend (port/input/input_sdl.c) on SDL's dummy video driver, with key events pushed
 * into SDL's queue: boards/host-sdl.board's keys turn its knobs and press its buttons. Without SDL in the build,
 * only that the backend is reported as not compiled in. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "input/input.h"

#ifdef VFP_HAVE_SDL
#include <SDL.h>

static uint64_t monotonic_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void key(int type, SDL_Keycode sym, int repeat)
{
    SDL_Event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = (Uint32)type;
    ev.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
    ev.key.repeat = (Uint8)repeat;
    ev.key.keysym.sym = sym;
    SDL_PushEvent(&ev);
}

static int open_host_sdl(vfp_board_t *b, vfp_input_t *in, char *err, size_t errlen)
{
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    if (vfp_board_load(b, "boards/host-sdl.board", err, errlen))
        return 2;
    const vfp_input_ops_t *ops = vfp_input_find(NULL, b, err, errlen);
    if (!ops)
        return 2;
    return ops->open(in, b, NULL, err, errlen);
}

static void keys_turn_and_press(void)
{
    vfp_board_t b;
    vfp_input_t in;
    char err[512] = "";
    CHECK_MSG(open_host_sdl(&b, &in, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(in.ops->fd(&in), -1);
    CHECK_EQ(in.ops->deadline_ns(&in), 1); /* look at once */
    vfp_event_t ev[8];
    uint64_t now = monotonic_ns();
    (void)in.ops->read(&in, ev, 8, now, err, sizeof err); /* whatever SDL queued at start */

    key(SDL_KEYDOWN, SDLK_RIGHT, 0);
    key(SDL_KEYDOWN, SDLK_RIGHT, 1); /* auto-repeat keeps turning */
    key(SDL_KEYDOWN, SDLK_RIGHT, 1);
    key(SDL_KEYUP, SDLK_RIGHT, 0);
    key(SDL_KEYDOWN, SDLK_LEFT, 0);
    key(SDL_KEYDOWN, SDLK_PAGEUP, 0);
    key(SDL_KEYDOWN, SDLK_SPACE, 0);
    key(SDL_KEYDOWN, SDLK_SPACE, 1); /* a held button is still one press */
    key(SDL_KEYUP, SDLK_SPACE, 0);
    key(SDL_KEYDOWN, SDLK_q, 0); /* no control */
    now = monotonic_ns();
    int n = in.ops->read(&in, ev, 8, now, err, sizeof err);
    CHECK_EQ(n, 4);
    CHECK_EQ(ev[0].type, VFP_EV_TURN);
    CHECK_EQ(ev[0].control, 0);
    CHECK_EQ(ev[0].steps, 2); /* three right, one left: one event */
    CHECK_EQ(ev[0].time_ns, now);
    CHECK_EQ(ev[1].type, VFP_EV_TURN);
    CHECK_EQ(ev[1].control, 2);
    CHECK_EQ(ev[1].steps, 1);
    CHECK_EQ(ev[2].type, VFP_EV_PRESS);
    CHECK_EQ(ev[2].control, 0);
    CHECK_EQ(ev[3].type, VFP_EV_RELEASE);
    CHECK_EQ(ev[3].control, 0);
    /* the next look is due 10 ms after this read, and stays put while nothing reads */
    uint64_t due = in.ops->deadline_ns(&in);
    CHECK(due > now && due <= monotonic_ns() + 10000000u);
    CHECK_EQ(in.ops->deadline_ns(&in), due);

    /* up and down in one read cancel; Escape is the quit button; closing the window is QUIT */
    key(SDL_KEYDOWN, SDLK_UP, 0);
    key(SDL_KEYDOWN, SDLK_DOWN, 0);
    key(SDL_KEYDOWN, SDLK_ESCAPE, 0);
    SDL_Event q;
    memset(&q, 0, sizeof q);
    q.type = SDL_QUIT;
    SDL_PushEvent(&q);
    n = in.ops->read(&in, ev, 8, monotonic_ns(), err, sizeof err);
    CHECK_EQ(n, 2);
    CHECK_EQ(ev[0].type, VFP_EV_PRESS);
    CHECK_EQ(ev[0].control, 4);
    CHECK_EQ(b.buttons[4].action, VFP_ACT_QUIT);
    CHECK_EQ(ev[1].type, VFP_EV_QUIT);
    in.ops->close(&in);
    CHECK(in.priv == NULL);
}

static void small_max_leaves_the_rest_queued(void)
{
    vfp_board_t b;
    vfp_input_t in;
    char err[512] = "";
    CHECK_MSG(open_host_sdl(&b, &in, err, sizeof err) == 0, "%s", err);
    vfp_event_t ev[4];
    (void)in.ops->read(&in, ev, 4, monotonic_ns(), err, sizeof err);
    key(SDL_KEYDOWN, SDLK_m, 0);
    key(SDL_KEYDOWN, SDLK_o, 0);
    key(SDL_KEYDOWN, SDLK_r, 0);
    CHECK_EQ(in.ops->read(&in, ev, 2, monotonic_ns(), err, sizeof err), 2);
    CHECK_EQ(ev[0].control, 1);
    CHECK_EQ(ev[1].control, 2);
    CHECK_EQ(in.ops->read(&in, ev, 2, monotonic_ns(), err, sizeof err), 1);
    CHECK_EQ(ev[0].control, 3);
    in.ops->close(&in);
}

CHECK_CASES({"keys_turn_and_press", keys_turn_and_press},
            {"small_max_leaves_the_rest_queued", small_max_leaves_the_rest_queued});

#else

static void not_compiled_in(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    char err[256] = "";
    CHECK(vfp_input_find("sdl", &b, err, sizeof err) == NULL);
    CHECK(strstr(err, "input 'sdl' is not compiled in") != NULL);
}

CHECK_CASES({"not_compiled_in", not_compiled_in});

#endif

CHECK_RUN("input_sdl")
