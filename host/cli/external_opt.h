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

#endif
