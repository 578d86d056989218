/*
 * cliopts.h - one table-driven parser of command-line options, shared by the
 * commands (getopt_long underneath: "--opt value" and "--opt=value", and
 * unambiguous abbreviations, as every GNU tool takes them).
 *
 * A command describes its options in flag tables: its own, and any it takes
 * from another command (draw, trace and tables take run's), each table with
 * the function that applies its options to that table's context.  The parser
 * owns the rules every command shares: an unknown option, a missing value,
 * an option given twice (unless the table says it repeats) and a stray
 * argument (before or after '--') are errors that name the option or the
 * argument; --help (or -h) prints the tables to stdout.
 */
#ifndef OB_CLIOPTS_H
#define OB_CLIOPTS_H

#include <stdio.h>

typedef enum {
    OB_FLAG_ONCE = 0,    /* given at most once */
    OB_FLAG_LIST,        /* at most once, its values in one comma list */
    OB_FLAG_REPEAT,      /* any number of times, each applied in order */
} ob_flag_rule;

typedef struct {
    const char *name;    /* without the leading "--" */
    const char *value;   /* what its value is, for --help ("N", "FILE"); NULL: no value;
                            "[...]": an optional value, given only as --name=VALUE */
    const char *help;    /* one line for --help */
    int id;              /* passed to the table's apply function */
    ob_flag_rule rule;
} ob_flag;

/* Applies option id (opt: "--name", for messages) with its value (NULL for
 * a flag without one) to ctx.  Returns 0, or -1 after ob_error(). */
typedef int (*ob_flag_apply)(void *ctx, int id, const char *opt, const char *value);

typedef struct {
    const ob_flag *flags;
    int nflags;
    const char *only;    /* NULL, or the only names of this table the command
                            takes, space-separated and space-ended ("threads ") */
    const char *skip;    /* NULL, or the names of this table the command does not
                            take, in the same form ("tols out ") */
    const char *title;   /* heading of the table in --help */
    ob_flag_apply apply;
    void *ctx;
} ob_flagset;

enum { OB_CLI_OK = 0, OB_CLI_HELP = 1, OB_CLI_ERROR = 2 };

/* Purpose: parse argv[1..argc-1] (argv[0]: the command's name) against the
 *          flag tables, applying each option in command-line order.
 * Inputs:  synopsis: what --help prints after "usage: ./offbench CMD ";
 *          npos_max: how many positional arguments (operands) the command
 *          takes (they may come before, between or after the options, and
 *          every argument after the first '--' is one, even one that looks
 *          like an option or is '--'); pos receives them (may be NULL when
 *          npos_max is 0).  One operand more is an error naming it: nothing
 *          on the command line is ever ignored.  An option's value given as
 *          the next word may not be '--' or begin with '--' (--name=VALUE
 *          may).
 * Outputs: *npos: the positional arguments found (may be NULL).
 * Returns: OB_CLI_OK; OB_CLI_HELP after printing the help to stdout (the
 *          command then exits 0); OB_CLI_ERROR after ob_error() naming the
 *          option or argument (exit 2), or when an apply function failed. */
int ob_cli_parse(const char *synopsis, const ob_flagset *sets, int nsets, int argc, char **argv, int npos_max,
                 char **pos, int *npos);

/* Purpose: parse the arguments of a command that takes neither options nor
 *          operands (list methods, --version): --help, '--' and the refusal
 *          of anything else are the shared parser's.
 * Inputs:  synopsis as for ob_cli_parse; argv[0] the command's name.
 * Returns: as ob_cli_parse. */
int ob_cli_no_options(const char *synopsis, int argc, char **argv);

/* An ob_flag_apply for a directory (ctx: a const char **): refuses an empty
 * name. */
int ob_cli_apply_dir(void *ctx, int id, const char *opt, const char *value);

/* The help of the tables (what --help prints) on f. */
void ob_cli_help(FILE *f, const char *cmd, const char *synopsis, const ob_flagset *sets, int nsets);

#endif
