/*
 * summary_archive.c - `summary RUN --archive ARCHIVE`: the methods of
 * committed runs beside the run's own, on the run's jobs (summary.h,
 * ob_summary_archive).  The archive's numbers are read, never rerun, so a
 * column is only as good as the join: every row that could not join is
 * counted by reason, for the report to say (s->alines).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/summary/summary_impl.h"

const char *ob_sum_label(const ob_summary *s, int m)
{
    return s->mlabel && s->mlabel[m] ? s->mlabel[m] : s->methods[m];
}

void ob_sum_archive_free(ob_summary *s)
{
    for (int m = 0; s->mlabel && m < s->nm; m++)
        free(s->mlabel[m]);
    free(s->mlabel);
    free(s->msrc);
    free(s->arch_hit);
    ob_strlist_free(&s->alines);
}

/* The map (curve, d) -> pair index of s, for the archive's lookups. */
static int pair_map(const ob_summary *s, ob_strmap *map)
{
    memset(map, 0, sizeof *map);
    for (int p = 0; p < s->np; p++) {
        ob_res_row key;
        memset(&key, 0, sizeof key);
        key.curve = s->pairs[p].curve;
        key.d = s->pairs[p].d;
        if (ob_sum_pair_lookup(map, &key, p) == -2)
            return -1;
    }
    return 0;
}

/* The run has job (p, k) under one of its own methods. */
static int run_has_job(const ob_summary *s, int p, int k)
{
    const int nrun = s->has_archive ? s->nm_run : s->nm;
    for (int m = 0; m < nrun; m++)
        if (s->run.cell[ob_sum_at(s, p, m, k)])
            return 1;
    return 0;
}

/* The cell of row r (its pair and tol), or -1 when the run has no such job. */
static long job_of(const ob_summary *s, ob_strmap *map, const ob_res_row *r, int *p, int *k)
{
    const long got = ob_sum_pair_lookup(map, r, -1);
    if (got < 0)
        return got == -2 ? -2 : -1;
    *p = (int)got;
    *k = ob_sum_find_tol(s, r->tol);
    return *k >= 0 && run_has_job(s, *p, *k) ? 0 : -1;
}

int ob_summary_archive_shared(const ob_summary *s, const ob_res_table *a)
{
    ob_strmap map;
    int n = 0, p, k;
    if (pair_map(s, &map) == 0)
        for (int i = 0; i < a->n; i++)
            n += job_of(s, &map, &a->v[i], &p, &k) == 0;
    ob_strmap_free(&map);
    return n;
}

/* The row counts in the archive's columns: its metric and split are the
 * run's (another metric's numbers do not mean the same). */
static int same_measure(const ob_summary *s, const ob_res_row *r)
{
    return strcmp(r->metric, s->run.metric) == 0 && strcmp(r->split, s->run.split) == 0;
}

/* Appends column `method` from archive `name`; 0, or -1 out of memory. */
static int add_column(ob_summary *s, const char *method, const char *name)
{
    const size_t n = (size_t)s->nm + 1;
    const char **mv = realloc(s->methods, n * sizeof *mv);
    if (mv)
        s->methods = mv;
    const char **src = realloc(s->msrc, n * sizeof *src);
    if (src)
        s->msrc = src;
    char **lab = realloc(s->mlabel, n * sizeof *lab);
    if (lab)
        s->mlabel = lab;
    if (!mv || !src || !lab)
        return -1;
    const size_t len = strlen(method) + sizeof " (archive)";
    if (!(lab[s->nm] = malloc(len)))
        return -1;
    snprintf(lab[s->nm], len, "%s (archive)", method);
    mv[s->nm] = method;
    src[s->nm] = name;
    s->nm++;
    return 0;
}

/* The run's cells in a side of the new shape (nm grew from old_nm). */
static int relayout(ob_summary *s, int old_nm)
{
    ob_sum_side side = s->run;
    if (ob_sum_side_alloc(s, &side)) {
        free(side.cell);
        free(side.fam);
        free(side.meth);
        return -1;
    }
    for (int p = 0; p < s->np; p++)
        for (int m = 0; m < old_nm; m++)
            for (int k = 0; k < s->nt; k++)
                side.cell[ob_sum_at(s, p, m, k)] = s->run.cell[(p * old_nm + m) * s->nt + k];
    free(s->run.cell);
    free(s->run.fam);
    free(s->run.meth);
    s->run = side;
    return 0;
}

/* The first use: the run's columns get no source and no mark. */
static int archive_init(ob_summary *s)
{
    if (s->has_archive)
        return 0;
    s->nm_run = s->nm;
    s->msrc = calloc((size_t)s->nm + 1, sizeof *s->msrc);
    s->mlabel = calloc((size_t)s->nm + 1, sizeof *s->mlabel);
    s->arch_hit = calloc((size_t)s->np * (size_t)s->nt + 1, 1);
    s->has_archive = 1;
    return s->msrc && s->mlabel && s->arch_hit ? 0 : -1;
}

/* Adds a column for every method of a (of the run's metric and split, on
 * a job of the run) that no column has yet; *added: how many. */
static int add_columns(ob_summary *s, const ob_res_table *a, const char *name, ob_strmap *map, int *added)
{
    const int old_nm = s->nm;
    int p, k;
    *added = 0;
    for (int i = 0; i < a->n; i++) {
        const ob_res_row *r = &a->v[i];
        if (!same_measure(s, r) || ob_sum_find_name(s->methods, s->nm, r->method) >= 0)
            continue;
        const long j = job_of(s, map, r, &p, &k);
        if (j == -2 || (j == 0 && add_column(s, r->method, name)))
            return -1;
        *added += j == 0;
    }
    return *added ? relayout(s, old_nm) : 0;
}

/* Why the rows of one archive did or did not join (the report's lines). */
typedef struct {
    int joined, other_measure, not_run, own, dup;
    char own_names[512];          /* the run's methods the archive also has */
} join_counts;

/* An archive row of one of the run's own methods: counted, not shown (the
 * run's own values are the ones to show); the method named once. */
static void count_own(const ob_res_row *r, join_counts *c)
{
    char word[300], have[520];
    c->own++;
    snprintf(word, sizeof word, ",%s,", r->method);
    snprintf(have, sizeof have, ",%s,", c->own_names);
    const size_t n = strlen(c->own_names);
    if (!strstr(have, word) && n + strlen(r->method) + 2 < sizeof c->own_names)
        snprintf(c->own_names + n, sizeof c->own_names - n, "%s%s", n ? "," : "", r->method);
}

/* One row of the archive into its cell, or into a count of why not. */
static int join_row(ob_summary *s, ob_strmap *map, const ob_res_row *r, join_counts *c)
{
    int p, k;
    if (!same_measure(s, r)) {
        c->other_measure++;
        return 0;
    }
    const long j = job_of(s, map, r, &p, &k);
    if (j == -2)
        return -1;
    if (j == 0)
        s->arch_hit[p * s->nt + k] = 1;
    const int m = ob_sum_find_name(s->methods, s->nm, r->method);
    if (m >= 0 && m < s->nm_run)
        count_own(r, c);
    else if (j < 0 || m < 0)
        c->not_run++;
    else if (s->run.cell[ob_sum_at(s, p, m, k)])
        c->dup++;
    else {
        s->run.cell[ob_sum_at(s, p, m, k)] = r;
        c->joined++;
    }
    return 0;
}

/* The report's lines for one archive. */
static int archive_lines(ob_summary *s, const char *name, int added, const join_counts *c)
{
    int rc = ob_strlist_addf(&s->alines, "Archive: %s (metric %s, split %s): %d methods beside the run's, %d rows "
                                     "joined.", name, s->run.metric, s->run.split, added, c->joined);
    if (c->not_run)
        rc |= ob_strlist_addf(&s->alines, "Not joined: %d archive rows are on jobs RUN did not run (curve, d, tol) "
                                      "in %s.", c->not_run, name);
    if (c->own)
        rc |= ob_strlist_addf(&s->alines, "Not joined: %d archive rows are of methods RUN ran itself (%s): RUN's "
                                      "values shown (%s).", c->own, c->own_names, name);
    if (c->other_measure)
        rc |= ob_strlist_addf(&s->alines, "Not joined: %d archive rows are of another metric or split than RUN's "
                                      "(%s, %s): not comparable (%s).", c->other_measure, s->run.metric,
                                      s->run.split, name);
    if (c->dup)
        rc |= ob_strlist_addf(&s->alines, "Not joined: %d archive rows repeat a job an earlier archive gave: the "
                                      "first kept (%s).", c->dup, name);
    return rc;
}

int ob_summary_archive(ob_summary *s, const ob_res_table *a, const char *name, ob_err *err)
{
    ob_strmap map;
    join_counts c;
    memset(&c, 0, sizeof c);
    int added = 0, rc = archive_init(s) || pair_map(s, &map);
    if (!rc)
        rc = add_columns(s, a, name, &map, &added);
    for (int i = 0; !rc && i < a->n; i++)
        rc = join_row(s, &map, &a->v[i], &c);
    ob_strmap_free(&map);
    if (!rc)
        rc = ob_sum_side_stats(s, &s->run) || archive_lines(s, name, added, &c);
    if (rc)
        return ob_fail(err, "%s: out of memory", name);
    if (s->nm + 3 > 64)
        return ob_fail(err, "%s: %d method columns: more than a table holds (64 columns); choose the run's with "
                       "--methods or fewer archives", name, s->nm);
    return 0;
}

int ob_summary_archive_done(ob_summary *s)
{
    int n = 0, ntols = 0;
    char tols[512] = "";
    if (!s->has_archive)
        return 0;  /* no archive shared a job: each is named already */
    /* the control points are the same numbers anywhere; a time is its machine's */
    if (ob_strlist_addf(&s->alines, "The archived methods' time/job is the archive's own (its machine and backend, "
                                "in its meta.json): ./offbench compare says whether times compare."))
        return -1;
    for (int k = 0; k < s->nt; k++) {
        int nk = 0;
        for (int p = 0; p < s->np; p++)
            for (int m = 0; !s->arch_hit[p * s->nt + k] && m < s->nm_run; m++)
                nk += s->run.cell[ob_sum_at(s, p, m, k)] != NULL;
        const size_t used = strlen(tols);
        if (nk && used + 40 < sizeof tols)
            snprintf(tols + used, sizeof tols - used, "%s%s", ntols++ ? ", " : "", s->tol_text[k]);
        n += nk;
    }
    if (!n)
        return 0;
    return ob_strlist_addf(&s->alines, "Not joined: %d RUN rows have no archived job (curve, d, tol); at tolerances "
                                   "%s.", n, tols);
}
