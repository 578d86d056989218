/*
 * external_opt.h - `--external NAME=COMMAND`, taken by every command
 * (docs/external-methods.md): registers an external method before the
 * command parses its own options, so that --methods, --param, `list
 * methods` and the run's plan see it like a built-in.
 */
#ifndef OB_EXTERNAL_OPT_H
#define OB_EXTERNAL_OPT_H

/* Purpose: register every --external NAME=COMMAND (or --external=...) in
 *          argv[1 .. *argc) and remove them from argv.
 * Returns: 0, or -1 after an error naming the option. */
int ob_external_args(int *argc, char **argv);

/* Purpose: take every OPT VALUE (or OPT=VALUE) of an option every command
 *          takes out of argv[1 .. *argc), calling take(VALUE) on each in
 *          order (--external, --methods-file: methods_file.h).
 * Returns: 0; -1 after take failed or "OPT: expected WHAT after it". */
int ob_take_global_option(int *argc, char **argv, const char *opt, const char *what, int (*take)(const char *));

#endif
