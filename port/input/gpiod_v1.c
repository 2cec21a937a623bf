/* SPDX-License-Identifier: MIT */
/* gpiod_v1.c: the GPIO backend's lines through libgpiod 1.6 (Debian 12, Raspberry Pi OS bookworm): a chip by label,
 * one event request per line, one fd per line, and an epoll fd over them when there are several. Compiled only
 * when the Makefile finds libgpiod 1.x (VFP_HAVE_GPIOD, VFP_GPIOD_MAJOR == 1); gpiod_v2.c does the same with 2.x.
 * The interface is in gpiod_internal.h. */
#include "gpiod_internal.h"

#if defined(VFP_HAVE_GPIOD) && VFP_GPIOD_MAJOR == 1

#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <stdio.h>
#include <string.h>
#include <sys/epoll.h>
#include <time.h>
#include <unistd.h>

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static void list_labels(char *out, size_t size);

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

vfp_status_t vfpi_gpiod_hw_open(vfpi_gpiod_t *g, char *err, size_t errlen)
{
    /* harmless values before anything can fail: vfpi_gpiod_hw_close follows a failed open */
    g->epoll_fd = -1;
    for (int i = 0; i < VFPI_GPIO_MAX_LINES; i++)
        g->fds[i] = -1;
    g->chip = gpiod_chip_open_by_label(g->label);
    if (!g->chip) {
        char labels[512];
        int e = errno;
        list_labels(labels, sizeof labels);
        if (e == ENOENT)
            snprintf(err, errlen, "gpio chip '%s' not found (%s)", g->label, labels);
        else
            snprintf(err, errlen, "gpio chip '%s': %s%s (%s)", g->label, strerror(e), vfpi_gpiod_hint(e),
                     labels);
        return VFP_ERR;
    }
    if (g->line_count > 1) {
        g->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
        if (g->epoll_fd < 0) {
            snprintf(err, errlen, "epoll_create1: %s", strerror(errno));
            return VFP_ERR;
        }
    }
    for (int i = 0; i < g->line_count; i++) {
        unsigned off = g->lines[i].offset;
        int flags = g->lines[i].pull == VFP_PULL_UP     ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP
                    : g->lines[i].pull == VFP_PULL_DOWN ? GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN
                                                        : GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
        struct gpiod_line *line = gpiod_chip_get_line(g->chip, off);
        if (!line || gpiod_line_request_both_edges_events_flags(line, VFPI_GPIOD_CONSUMER, flags) < 0) {
            snprintf(err, errlen, "gpio chip '%s' line %u: %s%s", g->label, off, strerror(errno),
                     vfpi_gpiod_hint(errno));
            return VFP_ERR;
        }
        g->handles[i] = line;
        int level = gpiod_line_get_value(line);
        int fd = gpiod_line_event_get_fd(line);
        int fl = fd >= 0 ? fcntl(fd, F_GETFL) : -1;
        if (level < 0 || fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) < 0) {
            snprintf(err, errlen, "gpio chip '%s' line %u: %s", g->label, off, strerror(errno));
            return VFP_ERR;
        }
        g->fds[i] = fd;
        vfp_gpio_decoder_set_level(g->dec, off, level);
        struct epoll_event ev = {.events = EPOLLIN, .data.u32 = (uint32_t)i};
        if (g->epoll_fd >= 0 && epoll_ctl(g->epoll_fd, EPOLL_CTL_ADD, fd, &ev) < 0) {
            snprintf(err, errlen, "gpio chip '%s' line %u: epoll_ctl: %s", g->label, off, strerror(errno));
            return VFP_ERR;
        }
    }
    return VFP_OK;
}

int vfpi_gpiod_hw_fd(const vfpi_gpiod_t *g)
{
    return g->line_count == 1 ? g->fds[0] : g->epoll_fd;
}

/* Every line's fd, one after the other. *read_ns: the horizon for merging the lines (see
 * vfp_gpio_decoder_edges): when line 0 was found empty, or with a full batch just after its last edge read. */
int vfpi_gpiod_hw_collect(vfpi_gpiod_t *g, vfp_gpio_edge_t *edges, int max, uint64_t *read_ns, char *err,
                          size_t errlen)
{
    int n = 0;
    *read_ns = 0;
    for (int i = 0; i < g->line_count; i++) {
        struct gpiod_line_event ev[16];
        int drained = 0;
        while (n + 16 <= max) {
            int got = gpiod_line_event_read_fd_multiple(g->fds[i], ev, 16);
            if (got < 0 && errno == EINTR)
                continue;
            if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
                drained = 1;
                break;
            }
            if (got < 0) {
                if (errno == ENODEV)
                    snprintf(err, errlen, "gpio chip '%s': removed", g->label);
                else
                    snprintf(err, errlen, "gpio chip '%s' line %u: %s", g->label, g->lines[i].offset,
                             strerror(errno));
                return -1;
            }
            for (int j = 0; j < got; j++)
                edges[n++] = (vfp_gpio_edge_t){
                    .line = g->lines[i].offset,
                    .level = ev[j].event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                    .time_ns = (uint64_t)ev[j].ts.tv_sec * 1000000000u + (uint64_t)ev[j].ts.tv_nsec,
                };
        }
        if (i == 0 && g->line_count > 1) {
            struct timespec ts;
            clock_gettime(CLOCK_MONOTONIC, &ts);
            *read_ns = drained || n == 0 ? (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec
                                         : edges[n - 1].time_ns + VFPI_GPIO_HOLD_NS;
        }
    }
    return n;
}

void vfpi_gpiod_hw_close(vfpi_gpiod_t *g)
{
    if (g->epoll_fd >= 0)
        close(g->epoll_fd);
    for (int i = g->line_count - 1; i >= 0; i--)
        if (g->handles[i])
            gpiod_line_release(g->handles[i]);
    if (g->chip)
        gpiod_chip_close(g->chip);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

/* For the message when the label is not found: every chip's name and label. */
static void list_labels(char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    struct gpiod_chip_iter *iter = gpiod_chip_iter_new();
    if (!iter) {
        snprintf(out, size, "cannot list the chips: %s%s", strerror(errno), vfpi_gpiod_hint(errno));
        return;
    }
    struct gpiod_chip *chip;
    gpiod_foreach_chip(iter, chip) {
        int n = snprintf(out + used, size - used, "%s%s '%s'", used ? ", " : "chips here: ", gpiod_chip_name(chip),
                         gpiod_chip_label(chip));
        if (n < 0 || (size_t)n >= size - used)
            break;
        used += (size_t)n;
    }
    gpiod_chip_iter_free(iter);
    if (!used)
        snprintf(out, size, "no GPIO chips in /dev");
}

#endif /* VFP_HAVE_GPIOD && VFP_GPIOD_MAJOR == 1 */
