/* SPDX-License-Identifier: MIT */
/* commands.h: volfix-sim's commands; each takes the arguments after its name and returns the program's exit
 * status: VFP_EXIT_OK, SIM_EXIT_DIFFERENT when a check the user asked for failed, or VFP_EXIT_ERR for bad input
 * or usage (status.h). */
#ifndef SIM_COMMANDS_H
#define SIM_COMMANDS_H

#include "status.h"

/* volfix-sim diff --max N: the images differ by more than N levels. */
#define SIM_EXIT_DIFFERENT 1

int sim_cmd_render(int argc, char **argv);
int sim_cmd_compare(int argc, char **argv);
int sim_cmd_bench(int argc, char **argv);
int sim_cmd_tables(int argc, char **argv);
int sim_cmd_tables_order2(int argc, char **argv); /* volfix-sim tables --order 2 (cmd_tables2.c) */
int sim_cmd_ray(int argc, char **argv);
int sim_cmd_study(int argc, char **argv);
int sim_cmd_diff(int argc, char **argv);

#endif
