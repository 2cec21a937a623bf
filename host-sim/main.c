/* SPDX-License-Identifier: MIT */
/*
 * main.c: volfix-sim, the host simulator: renders with the fixed-point core, checks it against a
 * double-precision reference of the same algorithm, and times it.
 */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "volfix.h"

static const char usage[] =
    "usage: volfix-sim COMMAND [options]   (volfix-sim COMMAND --help for its options)\n"
    "  render    render one image with the fixed-point core (or the double reference, or the truth) to PNG\n"
    "  compare   render with the core and the double reference (or the truth) and report the difference\n"
    "  bench     time 90 frames of a 180-degree turn (Schulze et al.'s protocol)\n"
    "  tables    build a pre-integrated table with each builder: time, error, picture\n"
    "  ray       one ray's signal and its order 0, 1, 2 reconstructions (El Hajjar et al.): CSV, plot\n"
    "  study     the fixed-point precision study: errors, plots, report.md\n"
    "  diff      two PNG images compared pixel by pixel\n"
    "volfix-sim --version prints the version.\n";

/* The commands in the order the usage lists them. */
static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
} commands[] = {
    {"render", sim_cmd_render}, {"compare", sim_cmd_compare}, {"bench", sim_cmd_bench}, {"tables", sim_cmd_tables},
    {"ray", sim_cmd_ray},       {"study", sim_cmd_study},     {"diff", sim_cmd_diff},
};

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? VFP_EXIT_ERR : VFP_EXIT_OK;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--version") == 0) {
        printf("volfix-sim %s\n", vf_version());
        return VFP_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(cmd, commands[i].name) == 0)
            return commands[i].run(argc - 2, argv + 2);
    fprintf(stderr, "volfix-sim: unknown command '%s' (expected render, compare, bench, tables, ray, study or diff; "
                    "see --help)\n", cmd);
    return VFP_EXIT_ERR;
}
