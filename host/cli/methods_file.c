/*
 * methods_file.c - the --methods-file option of every command
 * (methods_file.h).
 */
#include "host/cli/methods_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/cli/external_opt.h"
#include "host/diag.h"
#include "methods/external/ext.h"

enum { MAX_UNAVAILABLE = 16 };
static ob_unavailable missing[MAX_UNAVAILABLE];
static int nmissing;

const ob_unavailable *ob_methods_file_unavailable(int k)
{
    return k >= 0 && k < nmissing ? &missing[k] : NULL;
}

const char *ob_methods_file_note(const char *name, char *buf, size_t len)
{
    for (int k = 0; k < nmissing; k++)
        if (strcmp(missing[k].name, name) == 0) {
            const ob_unavailable *u = &missing[k];
            snprintf(buf, len, ": it is unavailable, named in %s: %s%s%s%s%s", u->file, u->why,
                     u->build[0] ? "; build it with " : "", u->build, u->needs[0] ? ", which needs: " : "", u->needs);
            return buf;
        }
    return NULL;
}

/* One method of the file, read so far. */
typedef struct {
    char name[64], command[1024], build[256], needs[512];
    int line;   /* of its [NAME] */
} entry;

/* 1 when the command's program is an executable file; else 0 with why. */
static int program_there(const char *command, char *why, size_t wl)
{
    char prog[200];
    const size_t n = strcspn(command, " \t");
    snprintf(prog, sizeof prog, "%.*s", (int)(n < sizeof prog ? n : sizeof prog - 1), command);
    struct stat st;
    if (strchr(prog, '/')) {
        if (stat(prog, &st) == 0 && S_ISREG(st.st_mode) && access(prog, X_OK) == 0)
            return 1;
        snprintf(why, wl, "%.200s is not there (or not an executable file)", prog);
        return 0;
    }
    const char *path = getenv("PATH");
    for (const char *p = path ? path : ""; *p;) {
        const size_t k = strcspn(p, ":");
        char full[2200];
        snprintf(full, sizeof full, "%.*s/%s", (int)k, p, prog);
        if (k && stat(full, &st) == 0 && S_ISREG(st.st_mode) && access(full, X_OK) == 0)
            return 1;
        p += k + (p[k] == ':');
    }
    snprintf(why, wl, "no program %.200s in PATH", prog);
    return 0;
}

/* Registers the entry, or notes it unavailable; 0, or -1 after the error. */
static int take_entry(const char *file, const entry *e)
{
    char why[256], msg[512];
    if (!e->command[0]) {
        ob_error("%s:%d: [%s] has no command = ...", file, e->line, e->name);
        return -1;
    }
    if (!program_there(e->command, why, sizeof why)) {
        if (nmissing == MAX_UNAVAILABLE) {
            ob_error("%s:%d: more than %d unavailable methods", file, e->line, MAX_UNAVAILABLE);
            return -1;
        }
        ob_unavailable *u = &missing[nmissing++];
        snprintf(u->name, sizeof u->name, "%s", e->name);
        snprintf(u->why, sizeof u->why, "%s", why);
        snprintf(u->build, sizeof u->build, "%s", e->build);
        snprintf(u->needs, sizeof u->needs, "%s", e->needs);
        snprintf(u->file, sizeof u->file, "%s", file);
        return 0;
    }
    if (ob_ext_register(e->name, e->command, msg, sizeof msg) != 0) {
        ob_error("%s:%d: [%s]: %s", file, e->line, e->name, msg);
        return -1;
    }
    return 0;
}

/* The text of s without the blanks at both ends, in place. */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
        s[--n] = '\0';
    return s;
}

/* One "key = value" line into e; 0, or -1 after the error. */
static int key_line(const char *file, int line, char *s, entry *e)
{
    char *eq = strchr(s, '=');
    if (!e->name[0] || !eq) {
        ob_error("%s:%d: expected [NAME] or KEY = VALUE", file, line);
        return -1;
    }
    *eq = '\0';
    const char *k = trim(s), *v = trim(eq + 1);
    char *dst = strcmp(k, "command") == 0 ? e->command : strcmp(k, "build") == 0 ? e->build
              : strcmp(k, "needs") == 0 ? e->needs : NULL;
    const size_t cap = dst == e->command ? sizeof e->command : dst == e->build ? sizeof e->build : sizeof e->needs;
    if (!dst || dst[0] || !v[0] || strlen(v) >= cap) {
        ob_error("%s:%d: %s", file, line, !dst ? "unknown key (command, build, needs)" : dst[0] ? "key given twice"
                                          : !v[0] ? "empty value" : "value too long");
        return -1;
    }
    memcpy(dst, v, strlen(v) + 1);
    return 0;
}

/* "[NAME]": a new entry; 0, or -1 after the error. */
static int section_line(const char *file, int line, char *s, entry *e)
{
    static const char word[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-";
    const size_t n = strlen(s);
    if (n < 3 || s[n - 1] != ']' || n - 2 >= sizeof e->name || strspn(s + 1, word) != n - 2) {
        ob_error("%s:%d: a section is [NAME] (letters, digits, '_', '-'; at most 63)", file, line);
        return -1;
    }
    memset(e, 0, sizeof *e);
    memcpy(e->name, s + 1, n - 2);
    e->line = line;
    return 0;
}

static int read_file(const char *file)
{
    FILE *f = fopen(file, "r");
    if (!f) {
        ob_error("--methods-file %s: cannot open it", file);
        return -1;
    }
    char buf[2048];
    entry e;
    memset(&e, 0, sizeof e);
    int line = 0, rc = 0;
    while (rc == 0 && fgets(buf, sizeof buf, f)) {
        line++;
        if (!strchr(buf, '\n') && !feof(f)) {
            ob_error("%s:%d: line longer than %zu bytes", file, line, sizeof buf - 2);
            rc = -1;
            break;
        }
        char *s = trim(buf);
        if (!*s || *s == '#')
            continue;
        if (*s == '[')
            rc = (e.name[0] ? take_entry(file, &e) : 0) || section_line(file, line, s, &e) ? -1 : 0;
        else
            rc = key_line(file, line, s, &e);
    }
    if (rc == 0 && e.name[0])
        rc = take_entry(file, &e);
    else if (rc == 0 && line == 0)
        ob_warn("--methods-file %s: empty: no methods", file);
    fclose(f);
    return rc;
}

int ob_methods_file_args(int *argc, char **argv)
{
    return ob_take_global_option(argc, argv, "--methods-file", "FILE", read_file);
}
