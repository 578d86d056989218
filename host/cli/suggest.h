/*
 * suggest.h - "did you mean": the closest of a list of names to one that was
 * mistyped (a command, an option, a method, a curve id, a list subject).
 *
 * Closeness is the optimal-string-alignment edit distance (insertions,
 * deletions, substitutions and swaps of two adjacent characters, case
 * ignored).  A name is suggested when it is at most 2 edits away and fewer
 * edits than the mistyped word has characters, or else when it is the only
 * name that begins with the word (two characters or more).  Callers keep
 * their message and append the note: "unknown method 'tiler' (did you mean
 * 'tiller'?)".
 */
#ifndef OB_SUGGEST_H
#define OB_SUGGEST_H

#include <stddef.h>

/* Purpose: the edit distance between a and b (see above), but at most
 *          cap + 1: any distance beyond cap, and any word longer than 256
 *          characters, gives cap + 1. */
int ob_edit_distance(const char *a, const char *b, int cap);

/* Purpose: the name among names[0..n-1] (NULL entries are skipped) to
 *          suggest for word: the closest within the rule above, the first
 *          in list order on a tie.  Returns it, or NULL when none is close. */
const char *ob_suggest(const char *word, const char *const *names, int n);

/* Purpose: " (did you mean 'NAME'?)" for ob_suggest's choice, or "" when
 *          there is none, into buf.  Returns buf. */
const char *ob_suggest_note(const char *word, const char *const *names, int n, char *buf, size_t len);

/* Purpose: the note for an unknown method, over the registered methods. */
const char *ob_suggest_method_note(const char *name, char *buf, size_t len);

/* Purpose: the note for an unknown command.  The commands are read from the
 *          program's usage text (each line "  ./offbench NAME ..."), so a
 *          command in the usage is a command suggested; "help" always is. */
const char *ob_suggest_command(const char *usage, const char *word, char *buf, size_t len);

#endif
