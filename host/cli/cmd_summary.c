/*
 * cmd_summary.c - ./offbench summary RUN_DIR [options]: the paper table of
 * one run (host/summary/summary.h): control points per curve and d and per
 * family, time and statuses per method, as Markdown, CSV or LaTeX.
 *
 * RUN_DIR is a run directory (its results.csv is read) or a results.csv.
 * Options: --format md|csv|latex (md), --out FILE (standard output; written
 * through FILE.tmp and a rename, never over an input), --methods LIST (these
 * methods, in this order), --curves LIST, --family LIST, --metric M, --split
 * S (needed when the run holds several), --sections LIST (curves, families,
 * methods; all by default), --baseline RUN_DIR2 (a second run's values
 * beside each cell, with new/base), --archive ARCHIVE (repeatable: archived
 * runs' other methods beside the run's, summary_archive.h; not with
 * --baseline).
 *
 * Exit status: 0; 2 bad input (an unreadable or malformed results.csv,
 * named FILE:LINE; an unknown option, method, curve, family, metric or
 * split, named with its option; --out over an input); 1 the output cannot
 * be written.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/diag.h"
#include "host/io/fsutil.h"
#include "host/io/results_csv.h"
#include "host/cli/summary_archive.h"
#include "host/summary/summary.h"

enum { SO_FORMAT, SO_OUT, SO_METHODS, SO_CURVES, SO_FAMILY, SO_METRIC, SO_SPLIT, SO_SECTIONS, SO_BASELINE, SO_ARCHIVE };

static const ob_flag summary_flags[] = {
    {"format", "md|csv|latex", "the tables' format (default md; latex: booktabs)", SO_FORMAT, OB_FLAG_ONCE},
    {"out", "FILE", "write them there (default: standard output)", SO_OUT, OB_FLAG_ONCE},
    {"methods", "LIST", "only these methods, in this order (default: all, in the run's order)", SO_METHODS, OB_FLAG_LIST},
    {"curves", "ID,...", "only these curves", SO_CURVES, OB_FLAG_LIST},
    {"family", "F,...", "only the curves of these families", SO_FAMILY, OB_FLAG_LIST},
    {"metric", "M", "only the rows of this metric (needed when the run has several)", SO_METRIC, OB_FLAG_ONCE},
    {"split", "RULE", "only the rows of this split rule (needed when the run has several)", SO_SPLIT, OB_FLAG_ONCE},
    {"sections", "LIST", "curves, families, methods (default: all three)", SO_SECTIONS, OB_FLAG_LIST},
    {"baseline", "RUN_DIR", "a second run: its value beside each cell, with new/base", SO_BASELINE, OB_FLAG_ONCE},
    {"archive", "ARCHIVE", "archived runs (a run, a results.csv or a directory of runs): their other methods "
     "beside the run's on its jobs", SO_ARCHIVE, OB_FLAG_REPEAT},
};

typedef struct {
    const char *run, *baseline, *out;
    int format;   /* 0 md, 1 csv, 2 latex */
    int sections;
    ob_sum_list methods, curves, families;
    ob_sum_list archives;         /* --archive, each as given (a path may hold a comma) */
    const char *metric, *split;
} cmd_opts;

/* Appends one --archive; 0, or -1 after ob_error(). */
static int archive_opt(cmd_opts *o, const char *v)
{
    char **a = *v ? realloc(o->archives.v, (size_t)(o->archives.n + 1) * sizeof *a) : NULL;
    if (a)
        o->archives.v = a;
    if (!a || !(a[o->archives.n] = strdup(v))) {
        ob_error(*v ? "--archive: out of memory" : "--archive: expected a run directory, results.csv or a directory "
                 "of runs");
        return -1;
    }
    o->archives.n++;
    return 0;
}

/* An option's comma list into l; 0, or -1 after ob_error(). */
static int list_opt(const char *opt, const char *v, ob_sum_list *l)
{
    ob_err err;
    if (ob_sum_list_parse(opt, v, l, &err) == 0)
        return 0;
    ob_error("%s", err.msg);
    return -1;
}

/* A non-empty value of opt; 0, or -1 after ob_error(). */
static int name_opt(const char *opt, const char *v, const char *what, const char **out)
{
    if (!*v) {
        ob_error("%s: expected %s", opt, what);
        return -1;
    }
    *out = v;
    return 0;
}

static int apply_summary_flag(void *ctx, int id, const char *opt, const char *v)
{
    cmd_opts *o = ctx;
    ob_err err;
    switch (id) {
    case SO_FORMAT:
        o->format = strcmp(v, "md") == 0 ? 0 : strcmp(v, "csv") == 0 ? 1 : strcmp(v, "latex") == 0 ? 2 : -1;
        if (o->format < 0) {
            ob_error("--format: expected md, csv or latex, got '%s'", v);
            return -1;
        }
        return 0;
    case SO_OUT: return name_opt(opt, v, "a file name", &o->out);
    case SO_METHODS: return list_opt(opt, v, &o->methods);
    case SO_CURVES: return list_opt(opt, v, &o->curves);
    case SO_FAMILY: return list_opt(opt, v, &o->families);
    case SO_METRIC: return name_opt(opt, v, "a metric", &o->metric);
    case SO_SPLIT: return name_opt(opt, v, "a split rule", &o->split);
    case SO_SECTIONS:
        if ((o->sections = ob_sum_sections_parse(v, &err)) < 0) {
            ob_error("%s", err.msg);
            return -1;
        }
        return 0;
    case SO_ARCHIVE: return archive_opt(o, v);
    default: return name_opt(opt, v, "a run directory or results.csv", &o->baseline);
    }
}

/* Returns 0, 1 after printing the help (--help), or -1 after ob_error(). */
static int parse_opts(int argc, char **argv, cmd_opts *o)
{
    const ob_flagset flags = {summary_flags, (int)(sizeof summary_flags / sizeof summary_flags[0]), NULL, NULL,
                              "options", apply_summary_flag, o};
    char *pos[1];
    int npos = 0;
    const int rc = ob_cli_parse("RUN_DIR [options]   (the paper table of a run: control points per curve and d and "
                                "per family, time and failures per method)",
                                &flags, 1, argc, argv, 1, pos, &npos);
    if (rc != OB_CLI_OK)
        return rc == OB_CLI_HELP ? 1 : -1;
    if (npos != 1) {
        ob_error("summary: expected RUN_DIR (a run directory or its results.csv)");
        return -1;
    }
    o->run = pos[0];
    if (o->baseline && o->archives.n) {
        ob_error("summary: --archive and --baseline: one at a time (--baseline puts a run's own methods beside "
                 "themselves, --archive other methods beside them)");
        return -1;
    }
    return 0;
}

/* The results.csv of a run: path itself, or path/results.csv for a
 * directory. */
static void results_path(const char *path, char *buf, size_t len)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        snprintf(buf, len, "%s%sresults.csv", path, path[strlen(path) - 1] == '/' ? "" : "/");
    else
        snprintf(buf, len, "%s", path);
}

typedef struct {
    const ob_summary *s;
    int format, sections;
} write_ctx;

static int write_summary(FILE *f, void *ctx)
{
    const write_ctx *w = ctx;
    if (w->format == 1)
        return ob_summary_write_csv(f, w->s, w->sections);
    if (w->format == 2)
        return ob_summary_write_latex(f, w->s, w->sections);
    return ob_summary_write_md(f, w->s, w->sections);
}

/* To stdout, or to --out FILE through FILE.tmp and a rename.  0, or the
 * exit status after ob_error(). */
static int emit(const char *out, write_ctx *w)
{
    if (!out) {
        const int rc = write_summary(stdout, w);
        if (fflush(stdout) != 0 || rc != 0) {
            ob_error("summary: cannot write to standard output");
            return 1;
        }
        return 0;
    }
    const char *slash = strrchr(out, '/');
    if (slash && !slash[1]) {
        ob_error("--out: '%s' is a directory name, expected a file", out);
        return 2;
    }
    char dir[4096];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s", slash == out ? 1 : (int)(slash - out), out);
    return ob_write_atomically(dir, slash ? slash + 1 : out, write_summary, w) == 0 ? 0 : 1;
}

/* Loads the run and the baseline and pivots them: 0, or 2 after ob_error(). */
static int load(const cmd_opts *o, const ob_sum_filter *f, char (*path)[4200], ob_res_table *t, ob_res_table *b,
                ob_summary *s)
{
    ob_err err;
    results_path(o->run, path[0], sizeof path[0]);
    if (ob_res_load(path[0], t, &err) || ob_summary_build(t, path[0], f, s, &err)) {
        ob_error("summary: %s", err.msg);
        return 2;
    }
    if (!o->baseline)
        return 0;
    results_path(o->baseline, path[1], sizeof path[1]);
    if (ob_res_load(path[1], b, &err) || ob_summary_join(s, b, path[1], f, &err)) {
        ob_error("summary: --baseline: %s", err.msg);
        return 2;
    }
    return 0;
}

int ob_cmd_summary(int argc, char **argv)
{
    cmd_opts o;
    memset(&o, 0, sizeof o);
    o.sections = OB_SUM_ALL;
    int status = 2;
    ob_res_table t, b;
    ob_summary s;
    ob_sum_archives arch;
    memset(&arch, 0, sizeof arch);
    memset(&t, 0, sizeof t);
    memset(&b, 0, sizeof b);
    memset(&s, 0, sizeof s);
    const int prc = parse_opts(argc, argv, &o);
    if (prc) {
        status = prc > 0 ? 0 : 2;
        goto done;
    }
    const ob_sum_filter f = {&o.methods, &o.curves, &o.families, o.metric, o.split};
    char path[2][4200] = {"", ""};
    if ((status = load(&o, &f, path, &t, &b, &s)) != 0 ||
        (o.archives.n && (status = ob_sum_archives_join(&s, o.run, &o.archives, &arch)) != 0))
        goto done;
    for (int i = 0; o.format == 1 && i < s.alines.n; i++)  /* CSV has no prose: what did not join, said here */
        ob_info("summary: %s", s.alines.v[i]);
    const char *const inputs[] = {path[0], o.baseline ? path[1] : NULL};
    if (o.out && ob_check_out_not_input("summary", o.out, 0, inputs, 2) != 0) {
        status = 2;
        goto done;
    }
    write_ctx w = {&s, o.format, o.sections};
    status = emit(o.out, &w);
done:
    ob_summary_free(&s);
    ob_res_free(&t);
    ob_res_free(&b);
    ob_sum_archives_free(&arch);
    ob_sum_list_free(&o.archives);
    ob_sum_list_free(&o.methods);
    ob_sum_list_free(&o.curves);
    ob_sum_list_free(&o.families);
    return status;
}
