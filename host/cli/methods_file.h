/*
 * methods_file.h - `--methods-file FILE`, taken by every command as
 * --external is (docs/external-methods.md "A methods file"): external
 * methods named in a small file, each registered when its program is
 * there, and otherwise remembered as unavailable with how to get it, so
 * that `list methods` shows it and --methods names the install line.
 *
 * The file: sections [NAME], each with the keys
 *   command = COMMAND   (required; as for --external NAME=COMMAND)
 *   build   = TEXT      (optional: how to build the program, e.g. make occt-worker)
 *   needs   = TEXT      (optional: what the build needs, e.g. an apt-get line)
 * '#' starts a comment line; blank lines are ignored.  A command whose
 * program (its first word: a path with '/', relative to the directory
 * offbench runs in, or a name looked up in PATH) is not an executable file
 * makes the method unavailable; a program that is there but does not speak
 * the protocol is an error.
 */
#ifndef OB_METHODS_FILE_H
#define OB_METHODS_FILE_H

#include <stddef.h>

/* Purpose: take every --methods-file FILE (or --methods-file=FILE) out of
 *          argv[1 .. *argc) and register or note each method it names.
 * Returns: 0, or -1 after an error naming FILE:LINE or the option. */
int ob_methods_file_args(int *argc, char **argv);

/* The k-th method a methods file named whose program is missing (k from
 * 0), or NULL past the last: its name, why, and how to get it (build and
 * needs may be ""). */
typedef struct {
    char name[64], why[256], build[256], needs[512], file[256];
} ob_unavailable;
const ob_unavailable *ob_methods_file_unavailable(int k);

/* The note for an unknown method name that a methods file named:
 * ": it is unavailable, named in FILE: WHY; build it with BUILD, which
 * needs: NEEDS", written into buf; NULL when name is no such method. */
const char *ob_methods_file_note(const char *name, char *buf, size_t len);

#endif
