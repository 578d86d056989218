/*
 * commands.h - the subcommands of ./offbench.  Each takes the arguments after
 * the program name (argv[0] is the subcommand) and returns the exit status:
 * 0 success, 1 a run-time failure (e.g. output not writable), 2 bad input.
 */
#ifndef OB_COMMANDS_H
#define OB_COMMANDS_H

int ob_cmd_run(int argc, char **argv, int full_argc, char **full_argv);
int ob_cmd_list(int argc, char **argv);
int ob_cmd_bench(int argc, char **argv);

/* Creates dir and its parents (mode 0777 & umask); 0 or -1 (errno set). */
int ob_mkdir_p(const char *dir);

#endif
