/*
 * cliopts.c - the table-driven option parser.  See cliopts.h.
 *
 * getopt_long (glibc) does the lexing: "--opt value", "--opt=value",
 * abbreviations, and, with "-" leading the short-option string, positional
 * arguments returned in place (as option 1).  What it cannot know, the
 * tables say: which command takes an option, whether it may repeat, and the
 * help text.
 */
#define _GNU_SOURCE
#include "host/cli/cliopts.h"

#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/suggest.h"
#include "host/diag.h"

/* Whether the space-ended list names `name`. */
static int listed(const char *list, const char *name)
{
    const size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && p[n] == ' ')
            return 1;
    return 0;
}

/* Whether set s takes its flag f. */
static int takes(const ob_flagset *s, const ob_flag *f)
{
    return (!s->only || listed(s->only, f->name)) && !(s->skip && listed(s->skip, f->name));
}

int ob_cli_apply_dir(void *ctx, int id, const char *opt, const char *value)
{
    (void)id;
    if (!*value) {
        ob_error("%s: empty directory name", opt);
        return -1;
    }
    *(const char **)ctx = value;
    return 0;
}

void ob_cli_help(FILE *f, const char *cmd, const char *synopsis, const ob_flagset *sets, int nsets)
{
    fprintf(f, "usage: ./offbench %s %s\n", cmd, synopsis);
    for (int k = 0; k < nsets; k++) {
        fprintf(f, "\n%s:\n", sets[k].title);
        for (int i = 0; i < sets[k].nflags; i++) {
            const ob_flag *g = &sets[k].flags[i];
            if (!takes(&sets[k], g))
                continue;
            char lhs[64];
            snprintf(lhs, sizeof lhs, "--%s%s%s", g->name, g->value ? " " : "", g->value ? g->value : "");
            fprintf(f, "  %-26s %s%s\n", lhs, g->help, g->rule == OB_FLAG_REPEAT ? " (repeatable)" : "");
        }
    }
    if (nsets > 0)
        fputs("\nEvery option also takes the form --name=value.  See README.md for more.\n", f);
}

/* The flags the command takes, in table order, with where each came from. */
typedef struct {
    struct option *lo;   /* getopt_long's table, terminated by a zero entry */
    const ob_flag **flag;
    int *set, *seen;
    int n;
} flagindex;

static int index_flags(const ob_flagset *sets, int nsets, flagindex *x)
{
    int total = 0;
    for (int k = 0; k < nsets; k++)
        total += sets[k].nflags;
    x->lo = calloc((size_t)total + 2, sizeof *x->lo);
    x->flag = calloc((size_t)total + 1, sizeof *x->flag);
    x->set = calloc((size_t)total + 1, sizeof *x->set);
    x->seen = calloc((size_t)total + 1, sizeof *x->seen);
    x->n = 0;
    if (!x->lo || !x->flag || !x->set || !x->seen)
        return -1;
    for (int k = 0; k < nsets; k++)
        for (int i = 0; i < sets[k].nflags; i++) {
            const ob_flag *g = &sets[k].flags[i];
            if (!takes(&sets[k], g))
                continue;
            x->lo[x->n] = (struct option){g->name, !g->value ? no_argument : g->value[0] == '[' ? optional_argument : required_argument, NULL, 256 + x->n};
            x->flag[x->n] = g;
            x->set[x->n] = k;
            x->n++;
        }
    x->lo[x->n] = (struct option){"help", no_argument, NULL, 'h'};
    return 0;
}

static void free_index(flagindex *x)
{
    free(x->lo);
    free(x->flag);
    free(x->set);
    free(x->seen);
}

/* The option as written on the command line, up to any '=', for messages. */
static void written(const char *arg, char *buf, size_t len)
{
    const char *eq = strchr(arg, '=');
    snprintf(buf, len, "%.*s", eq ? (int)(eq - arg) : (int)strlen(arg), arg);
}

/* " (did you mean '--NAME'?)" for an unknown option, over the options the
 * command takes and --help, into buf (or ""). */
static const char *option_note(const char *opt, const flagindex *x, char *buf, size_t len)
{
    char(*full)[64] = malloc(((size_t)x->n + 1) * sizeof *full);
    const char **names = malloc(((size_t)x->n + 1) * sizeof *names);
    buf[0] = '\0';
    if (full && names) {
        for (int i = 0; i < x->n; i++) {
            snprintf(full[i], sizeof full[i], "--%s", x->flag[i]->name);
            names[i] = full[i];
        }
        names[x->n] = "--help";
        ob_suggest_note(opt, names, x->n + 1, buf, len);
    }
    free(full);
    free(names);
    return buf;
}

/* An option getopt_long did not take: unknown, or an abbreviation of several. */
static void report_unknown(const char *cmd, const char *opt, const flagindex *x)
{
    char which[512] = "";
    int n = 0;
    const size_t len = strlen(opt) > 2 ? strlen(opt) - 2 : 0;
    for (int i = 0; i < x->n && len > 0; i++)
        if (strncmp(x->flag[i]->name, opt + 2, len) == 0 && n++ < 8)
            snprintf(which + strlen(which), sizeof which - strlen(which), "%s--%s", n > 1 ? ", " : "",
                     x->flag[i]->name);
    if (strncmp(opt, "--", 2) == 0 && n > 1) {
        ob_error("%s: '%s' is ambiguous: %s", cmd, opt, which);
        return;
    }
    char note[96];
    ob_error("%s: unknown option '%s'%s", cmd, opt, option_note(opt, x, note, sizeof note));
}

/* Abbreviations of one or two letters are refused: getopt takes any
 * unique prefix, and so `run --d -1` (measure's and draw's offset option)
 * silently meant --device there, the only run option beginning with d.  A
 * prefix of three letters or more (`--thr 2`) is taken as documented.
 * Option li of x was matched by the word before optind (or the one before
 * that, when its value was the next word). */
static int short_abbreviation(const char *cmd, char **argv, int li, const flagindex *x)
{
    if (li < 0 || li >= x->n)
        return OB_CLI_OK;
    const char *word = optarg && optind >= 2 && optarg == argv[optind - 1] ? argv[optind - 2] : argv[optind - 1];
    if (!word || strncmp(word, "--", 2) != 0)
        return OB_CLI_OK;
    const char *name = word + 2, *eq = strchr(name, '=');
    const size_t n = eq ? (size_t)(eq - name) : strlen(name), full = strlen(x->flag[li]->name);
    if (n >= full || n >= 3)
        return OB_CLI_OK;
    ob_error("%s: '--%.*s' is too short to abbreviate --%s (an abbreviation needs three letters): write --%s",
             cmd, (int)n, name, x->flag[li]->name, x->flag[li]->name);
    return OB_CLI_ERROR;
}

/* An option's value given as the next word must not be '--' (it ends the
 * options) nor look like an option ("--out --force" forgot the value);
 * --name=VALUE takes any value. */
static int check_value(const char *opt, const char *word, char **argv, int optind_now)
{
    if (!word || word != argv[optind_now - 1] || strncmp(word, "--", 2) != 0)
        return OB_CLI_OK;
    if (!word[2])
        ob_error("%s: missing value ('--' ends the options; write %s=-- for a value '--')", opt, opt);
    else
        ob_error("%s: missing value (the next word '%s' is an option; write %s=VALUE for a value that begins "
                 "with '--')",
                 opt, word, opt);
    return OB_CLI_ERROR;
}

/* Applies option c (getopt_long's return) of x; 0, or OB_CLI_ERROR. */
static int apply_one(const ob_flagset *sets, flagindex *x, int c, char **argv)
{
    const int i = c - 256;
    const ob_flag *g = x->flag[i];
    char opt[80];
    snprintf(opt, sizeof opt, "--%s", g->name);
    if (x->seen[i]++ && g->rule != OB_FLAG_REPEAT) {
        ob_error("%s: given twice (give each option once%s)", opt,
                 g->rule == OB_FLAG_LIST ? "; list all values in one comma list" : "");
        return OB_CLI_ERROR;
    }
    if (g->value && check_value(opt, optarg, argv, optind) != OB_CLI_OK)
        return OB_CLI_ERROR;
    const ob_flagset *s = &sets[x->set[i]];
    return s->apply(s->ctx, g->id, opt, g->value ? optarg : NULL) ? OB_CLI_ERROR : OB_CLI_OK;
}

/* Takes arg as the next operand; 0, or OB_CLI_ERROR naming it when the
 * command takes no more (after '--' too: nothing is dropped). */
static int take_operand(const char *cmd, const char *arg, int after_dashes, int npos_max, char **pos, int *np)
{
    if (*np < npos_max) {
        pos[(*np)++] = (char *)arg;
        return OB_CLI_OK;
    }
    const char *why = after_dashes ? "after '--' every argument is an operand" : "options are --NAME VALUE";
    if (npos_max == 0)
        ob_error("%s: unexpected argument '%s' (%s takes no operands; %s)", cmd, arg, cmd, why);
    else
        ob_error("%s: unexpected argument '%s' (%s takes at most %d operand%s; %s)", cmd, arg, cmd, npos_max,
                 npos_max > 1 ? "s" : "", why);
    return OB_CLI_ERROR;
}

int ob_cli_parse(const char *synopsis, const ob_flagset *sets, int nsets, int argc, char **argv, int npos_max,
                 char **pos, int *npos)
{
    const char *cmd = argv[0];
    flagindex x;
    if (index_flags(sets, nsets, &x) != 0) {
        free_index(&x);
        ob_error("%s: out of memory", cmd);
        return OB_CLI_ERROR;
    }
    int rc = OB_CLI_OK, np = 0, c;
    char buf[256];
    opterr = 0;
    optind = 0; /* glibc: a full restart (the parser may run more than once) */
    int li = -1;
    while (rc == OB_CLI_OK && (c = getopt_long(argc, argv, "-:h", x.lo, &li)) != -1) {
        if (c == 'h') {
            ob_cli_help(stdout, cmd, synopsis, sets, nsets);
            rc = OB_CLI_HELP;
        } else if (c == 1) {
            rc = take_operand(cmd, optarg, 0, npos_max, pos, &np);
        } else if (c == ':') {
            written(argv[optind - 1], buf, sizeof buf);
            ob_error("%s: missing value", buf);
            rc = OB_CLI_ERROR;
        } else if (c == '?') {
            written(argv[optind - 1], buf, sizeof buf);
            if (optopt >= 256) /* a flag without value given one */
                ob_error("%s: takes no value", buf);
            else
                report_unknown(cmd, buf, &x);
            rc = OB_CLI_ERROR;
        } else if ((rc = short_abbreviation(cmd, argv, li, &x)) == OB_CLI_OK) {
            rc = apply_one(sets, &x, c, argv);
        }
    }
    /* getopt_long stops at the first '--': what follows is all operands */
    for (int i = optind; rc == OB_CLI_OK && i < argc; i++)
        rc = take_operand(cmd, argv[i], 1, npos_max, pos, &np);
    free_index(&x);
    if (npos)
        *npos = np;
    return rc;
}

int ob_cli_no_options(const char *synopsis, int argc, char **argv)
{
    return ob_cli_parse(synopsis, NULL, 0, argc, argv, 0, NULL, NULL);
}
