/* commands.h: volfix-sim's commands; each takes the arguments after its name and returns the exit status
 * (0 success, 1 a check failed, 2 bad input or usage). */
#ifndef SIM_COMMANDS_H
#define SIM_COMMANDS_H

int sim_cmd_render(int argc, char **argv);
int sim_cmd_compare(int argc, char **argv);
int sim_cmd_bench(int argc, char **argv);
int sim_cmd_tables(int argc, char **argv);
int sim_cmd_ray(int argc, char **argv);
int sim_cmd_study(int argc, char **argv);
int sim_cmd_diff(int argc, char **argv);

#endif
