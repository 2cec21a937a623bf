/* SPDX-License-Identifier: MIT */
/* gpiod_v2.c: the GPIO backend's lines through libgpiod 2.x: a chip by label (found by walking /dev/gpiochip*),
 * one request for all the lines, one fd. Compiled only when the Makefile finds libgpiod 2.x (VFP_HAVE_GPIOD,
 * VFP_GPIOD_MAJOR == 2; make test-hw builds it against a private copy); gpiod_v1.c does the same with 1.6. The
 * interface is in gpiod_internal.h. */
#include "gpiod_internal.h"

#if defined(VFP_HAVE_GPIOD) && VFP_GPIOD_MAJOR == 2

#include <dirent.h>
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------------------------------------------------- */
/* Prototypes */

static int by_name(const void *a, const void *b);
static struct gpiod_chip *open_by_label(const char *label, char *err, size_t errlen);

/* ---------------------------------------------------------------------------------------------------------- */
/* Shared functions */

vfp_status_t vfpi_gpiod_hw_open(vfpi_gpiod_t *g, char *err, size_t errlen)
{
    vfp_status_t status = VFP_ERR;
    struct gpiod_chip *chip = open_by_label(g->label, err, errlen);
    struct gpiod_line_settings *settings = gpiod_line_settings_new();
    struct gpiod_line_config *line_cfg = gpiod_line_config_new();
    struct gpiod_request_config *req_cfg = gpiod_request_config_new();
    if (!chip)
        goto out;
    if (!settings || !line_cfg || !req_cfg || !(g->buffer = gpiod_edge_event_buffer_new(VFPI_GPIO_EDGE_BATCH))) {
        snprintf(err, errlen, "gpio chip '%s': out of memory", g->label);
        goto out;
    }
    gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_INPUT);
    gpiod_line_settings_set_edge_detection(settings, GPIOD_LINE_EDGE_BOTH);
    gpiod_line_settings_set_event_clock(settings, GPIOD_LINE_CLOCK_MONOTONIC);
    for (int i = 0; i < g->line_count; i++) {
        gpiod_line_settings_set_bias(settings, g->lines[i].pull == VFP_PULL_UP     ? GPIOD_LINE_BIAS_PULL_UP
                                               : g->lines[i].pull == VFP_PULL_DOWN ? GPIOD_LINE_BIAS_PULL_DOWN
                                                                                   : GPIOD_LINE_BIAS_DISABLED);
        /* the config keeps a copy of the settings for this offset */
        if (gpiod_line_config_add_line_settings(line_cfg, &g->lines[i].offset, 1, settings) < 0) {
            snprintf(err, errlen, "gpio chip '%s' line %u: %s", g->label, g->lines[i].offset, strerror(errno));
            goto out;
        }
    }
    gpiod_request_config_set_consumer(req_cfg, VFPI_GPIOD_CONSUMER);
    g->request = gpiod_chip_request_lines(chip, req_cfg, line_cfg);
    if (!g->request) {
        int e = errno;
        char lines[160] = "";
        size_t used = 0;
        for (int i = 0; i < g->line_count && used < sizeof lines; i++) {
            int n = snprintf(lines + used, sizeof lines - used, "%s%u", i ? ", " : "", g->lines[i].offset);
            used += n > 0 ? (size_t)n : 0;
        }
        snprintf(err, errlen, "gpio chip '%s' lines %s: %s%s", g->label, lines, strerror(e),
                 vfpi_gpiod_hint(e));
        goto out;
    }
    for (int i = 0; i < g->line_count; i++) {
        enum gpiod_line_value v = gpiod_line_request_get_value(g->request, g->lines[i].offset);
        if (v == GPIOD_LINE_VALUE_ERROR) {
            snprintf(err, errlen, "gpio chip '%s' line %u: %s", g->label, g->lines[i].offset, strerror(errno));
            goto out;
        }
        vfp_gpio_decoder_set_level(g->dec, g->lines[i].offset, v == GPIOD_LINE_VALUE_ACTIVE);
    }
    status = VFP_OK;
out:
    /* the request stands on its own: the chip and the configs are not needed after it */
    if (req_cfg)
        gpiod_request_config_free(req_cfg);
    if (line_cfg)
        gpiod_line_config_free(line_cfg);
    if (settings)
        gpiod_line_settings_free(settings);
    if (chip)
        gpiod_chip_close(chip);
    return status;
}

int vfpi_gpiod_hw_fd(const vfpi_gpiod_t *g)
{
    return gpiod_line_request_get_fd(g->request);
}

int vfpi_gpiod_hw_collect(vfpi_gpiod_t *g, vfp_gpio_edge_t *edges, int max, uint64_t *read_ns, char *err,
                          size_t errlen)
{
    *read_ns = 0; /* one request: the kernel queues every line's edges in one queue, in time order */
    int n = 0;
    while (n < max) {
        int ready = gpiod_line_request_wait_edge_events(g->request, 0);
        if (ready == 0)
            break;
        int got = ready < 0 ? -1 : gpiod_line_request_read_edge_events(g->request, g->buffer, (size_t)(max - n));
        if (got < 0) {
            if (errno == EINTR)
                continue;
            if (errno == ENODEV)
                snprintf(err, errlen, "gpio chip '%s': removed", g->label);
            else
                snprintf(err, errlen, "gpio chip '%s': %s", g->label, strerror(errno));
            return -1;
        }
        for (int j = 0; j < got; j++) {
            struct gpiod_edge_event *ev = gpiod_edge_event_buffer_get_event(g->buffer, (unsigned long)j);
            edges[n++] = (vfp_gpio_edge_t){
                .line = gpiod_edge_event_get_line_offset(ev),
                .level = gpiod_edge_event_get_event_type(ev) == GPIOD_EDGE_EVENT_RISING_EDGE,
                .time_ns = gpiod_edge_event_get_timestamp_ns(ev),
            };
        }
    }
    return n;
}

void vfpi_gpiod_hw_close(vfpi_gpiod_t *g)
{
    if (g->request)
        gpiod_line_request_release(g->request);
    if (g->buffer)
        gpiod_edge_event_buffer_free(g->buffer);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Static functions */

static int by_name(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* 2.x opens chips by path only: try /dev/gpiochip* in name order. NULL with err (naming the labels there are)
 * when no chip has this label. */
static struct gpiod_chip *open_by_label(const char *label, char *err, size_t errlen)
{
    char *names[64];
    int count = 0, first_errno = 0;
    DIR *dir = opendir("/dev");
    if (dir) {
        struct dirent *de;
        while ((de = readdir(dir)) && count < 64)
            if (strncmp(de->d_name, "gpiochip", 8) == 0 && (names[count] = strdup(de->d_name)))
                count++;
        closedir(dir);
    }
    qsort(names, (size_t)count, sizeof names[0], by_name);

    struct gpiod_chip *found = NULL;
    char labels[512] = "";
    size_t used = 0;
    for (int i = 0; i < count; i++) {
        char path[300];
        snprintf(path, sizeof path, "/dev/%s", names[i]);
        if (found || !gpiod_is_gpiochip_device(path))
            continue;
        struct gpiod_chip *chip = gpiod_chip_open(path);
        if (!chip) {
            if (!first_errno)
                first_errno = errno;
            continue;
        }
        struct gpiod_chip_info *info = gpiod_chip_get_info(chip);
        const char *this = info ? gpiod_chip_info_get_label(info) : "?";
        if (strcmp(this, label) == 0) {
            found = chip;
        } else {
            int n = snprintf(labels + used, sizeof labels - used, "%s%s '%s'", used ? ", " : "chips here: ",
                             names[i], this);
            if (n > 0 && (size_t)n < sizeof labels - used)
                used += (size_t)n;
            gpiod_chip_close(chip);
        }
        if (info)
            gpiod_chip_info_free(info);
    }
    for (int i = 0; i < count; i++)
        free(names[i]);
    if (!found) {
        if (!used)
            snprintf(labels, sizeof labels, "%s", count ? "no GPIO chip could be opened" : "no GPIO chips in /dev");
        snprintf(err, errlen, "gpio chip '%s' not found (%s)%s", label, labels,
                 first_errno ? vfpi_gpiod_hint(first_errno) : "");
    }
    return found;
}

#endif /* VFP_HAVE_GPIOD && VFP_GPIOD_MAJOR == 2 */
