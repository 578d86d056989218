/*
 * test_summary.c - the paper table of a run (host/summary/summary.h) on a
 * hand-made results.csv of 20 jobs whose medians, quartiles, counts and
 * times were worked out by hand (below, beside the data): the quantile
 * rule, the pivot's cells and order, the family and method statistics,
 * the filters and their errors, the baseline join, and the three formats.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/io/results_csv.h"
#include "host/summary/summary.h"

#define HDR "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family\n"

/* Family fam_a: pairs (c1, 0.5), (c1, -0.5), (c2, 1), (c3, 1); fam_b: (c4, 0.2).
 * m1 in fam_a at 0.1: ok 4, 7, 13, 10 -> sorted 4 7 10 13: median (h = 1.5)
 *   8.5, q1 (h = 0.75) 4 + 0.75 * 3 = 6.25, q3 (h = 2.25) 10 + 0.25 * 3 = 10.75.
 * m1 in fam_a at 0.01: ok 10, 20 (limit and fail left out, 2 non-ok):
 *   median 15, q1 (h = 0.25) 12.5, q3 (h = 0.75) 17.5.
 * m2 in fam_a at 0.1: ok 5, 5, 6 and a skip: median 5, q1 (h = 0.5) 5,
 *   q3 (h = 1.5) 5.5, 1 non-ok.  At 0.01: four fails, no ok job.
 * Times (fit_ns + eval_ns): m1's ten jobs 3000 1000 5000 2000 4000 10000
 *   6000 9000 7000 8000 -> median 5500, q1 (h = 2.25) 3250, q3 (h = 6.75)
 *   7750.  m2's nine jobs not skipped 100 ... 900 -> 500, 300, 700 (the
 *   skip's 5e6 ns is left out).
 * c1's rows at 0.5 list 0.01 before 0.1: tolerances still come out descending. */
static const char RUN[] = HDR
    "c1,0.5,m1,hausdorff,mid,0.01,10,3,3,0.001,ok,1000,0,,fam_a\n"
    "c1,0.5,m1,hausdorff,mid,0.1,4,1,3,0.01,ok,1000,2000,,fam_a\n"
    "c1,0.5,m2,hausdorff,mid,0.1,5,1,3,0.01,ok,100,0,,fam_a\n"
    "c1,0.5,m2,hausdorff,mid,0.01,0,0,0,,fail,0,200,singular,fam_a\n"
    "c1,-0.5,m1,hausdorff,mid,0.1,7,2,3,0.01,ok,5000,0,,fam_a\n"
    "c1,-0.5,m1,hausdorff,mid,0.01,20,6,3,0.001,ok,2000,0,,fam_a\n"
    "c1,-0.5,m2,hausdorff,mid,0.1,5,1,3,0.01,ok,300,0,,fam_a\n"
    "c1,-0.5,m2,hausdorff,mid,0.01,0,0,0,,fail,400,0,singular,fam_a\n"
    "c2,1,m1,hausdorff,mid,0.1,13,4,3,0.01,ok,4000,0,,fam_a\n"
    "c2,1,m1,hausdorff,mid,0.01,50,16,3,0.02,limit,10000,0,depth,fam_a\n"
    "c2,1,m2,hausdorff,mid,0.1,6,1,5,0.01,ok,500,0,,fam_a\n"
    "c2,1,m2,hausdorff,mid,0.01,0,0,0,,fail,600,0,singular,fam_a\n"
    "c3,1,m1,hausdorff,mid,0.1,10,3,3,0.01,ok,6000,0,,fam_a\n"
    "c3,1,m1,hausdorff,mid,0.01,0,0,0,,fail,9000,0,diverged,fam_a\n"
    "c3,1,m2,hausdorff,mid,0.1,0,0,0,,skip,5000000,0,rational,fam_a\n"
    "c3,1,m2,hausdorff,mid,0.01,0,0,0,,fail,700,0,singular,fam_a\n"
    "c4,0.2,m1,hausdorff,mid,0.1,3,1,3,0.01,ok,7000,0,,fam_b\n"
    "c4,0.2,m1,hausdorff,mid,0.01,9,3,3,0.001,ok,8000,0,,fam_b\n"
    "c4,0.2,m2,hausdorff,mid,0.1,0,0,0,,timeout,800,0,time,fam_b\n"
    "c4,0.2,m2,hausdorff,mid,0.01,11,2,5,0.001,ok,900,0,,fam_b\n";

/* The baseline, under another metric (joined all the same): c1 0.5 m1 0.1
 * has 5 (ratio 4/5 = 0.8), c2 m1 0.01 is ok with 40, and c4 m2 0.01 is
 * missing.  m1 fam_a at 0.1: 5 7 10 13 -> median 8.5, q1 5 + 0.75 * 2 =
 * 6.5, q3 10.75.  m2's times: 100 ... 800 (the 900 is the missing row) ->
 * median (h = 3.5) 450, ratio 500 / 450. */
static const char BASE[] = HDR
    "c1,0.5,m1,bound,mid,0.1,5,1,3,0.01,ok,3000,0,,fam_a\n"
    "c1,0.5,m1,bound,mid,0.01,10,3,3,0.001,ok,1000,0,,fam_a\n"
    "c1,0.5,m2,bound,mid,0.1,5,1,3,0.01,ok,100,0,,fam_a\n"
    "c1,0.5,m2,bound,mid,0.01,0,0,0,,fail,200,0,singular,fam_a\n"
    "c1,-0.5,m1,bound,mid,0.1,7,2,3,0.01,ok,5000,0,,fam_a\n"
    "c1,-0.5,m1,bound,mid,0.01,20,6,3,0.001,ok,2000,0,,fam_a\n"
    "c1,-0.5,m2,bound,mid,0.1,5,1,3,0.01,ok,300,0,,fam_a\n"
    "c1,-0.5,m2,bound,mid,0.01,0,0,0,,fail,400,0,singular,fam_a\n"
    "c2,1,m1,bound,mid,0.1,13,4,3,0.01,ok,4000,0,,fam_a\n"
    "c2,1,m1,bound,mid,0.01,40,13,3,0.009,ok,10000,0,,fam_a\n"
    "c2,1,m2,bound,mid,0.1,6,1,5,0.01,ok,500,0,,fam_a\n"
    "c2,1,m2,bound,mid,0.01,0,0,0,,fail,600,0,singular,fam_a\n"
    "c3,1,m1,bound,mid,0.1,10,3,3,0.01,ok,6000,0,,fam_a\n"
    "c3,1,m1,bound,mid,0.01,0,0,0,,fail,9000,0,diverged,fam_a\n"
    "c3,1,m2,bound,mid,0.1,0,0,0,,skip,5000000,0,rational,fam_a\n"
    "c3,1,m2,bound,mid,0.01,0,0,0,,fail,700,0,singular,fam_a\n"
    "c4,0.2,m1,bound,mid,0.1,3,1,3,0.01,ok,7000,0,,fam_b\n"
    "c4,0.2,m1,bound,mid,0.01,9,3,3,0.001,ok,8000,0,,fam_b\n"
    "c4,0.2,m2,bound,mid,0.1,0,0,0,,timeout,800,0,time,fam_b\n";

static int parse(const char *text, ob_res_table *t)
{
    ob_err err;
    if (ob_res_parse(text, strlen(text), "t.csv", t, &err) != 0) {
        fprintf(stderr, "parse: %s\n", err.msg);
        return -1;
    }
    return 0;
}

/* The summary written by fn into a string (malloc'ed), or NULL. */
static char *render(int (*fn)(FILE *, const ob_summary *, int), const ob_summary *s, int sections)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    int rc = fn(f, s, sections);
    fclose(f);
    if (rc != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* The text holds line as a whole line. */
static int has_line(const char *text, const char *line)
{
    size_t n = strlen(line);
    for (const char *p = text; p && (p = strstr(p, line)); p++)
        if ((p == text || p[-1] == '\n') && (p[n] == '\n' || p[n] == '\0'))
            return 1;
    return 0;
}

static void test_quantiles(void)
{
    const double v[] = {1, 2, 3, 4};
    CHECK_NEAR(ob_sum_quantile7(v, 4, 0.25), 1.75, 1e-15, "q(0.25) of 1..4: h = 0.75");
    CHECK_NEAR(ob_sum_quantile7(v, 4, 0.5), 2.5, 1e-15, "median of 1..4");
    CHECK(ob_sum_quantile7(v, 4, 0) == 1 && ob_sum_quantile7(v, 4, 1) == 4, "the ends");
    CHECK(ob_sum_quantile7(v, 1, 0.75) == 1, "one value is every quantile");
    double w[] = {13, 4, 10, 7};
    ob_sum_quart q;
    ob_sum_quartiles(w, 4, &q);
    CHECK(q.n == 4 && q.median == 8.5 && q.q1 == 6.25 && q.q3 == 10.75, "4 7 10 13: %g [%g, %g]", q.median, q.q1,
          q.q3);
    CHECK(w[0] == 4 && w[3] == 13, "left sorted");
    ob_sum_quartiles(w, 0, &q);
    CHECK(q.n == 0 && isnan(q.median) && isnan(q.q1) && isnan(q.q3), "no values: NAN");
}

static void test_lists(void)
{
    ob_sum_list l = {0};
    ob_err err;
    CHECK(ob_sum_list_parse("--methods", "b,a", &l, &err) == 0 && l.n == 2 && !strcmp(l.v[0], "b") &&
              !strcmp(l.v[1], "a"),
          "a list in its order");
    ob_sum_list_free(&l);
    CHECK(ob_sum_list_parse("--methods", "a,a", &l, &err) == -1 && strstr(err.msg, "--methods") &&
              strstr(err.msg, "'a'") && strstr(err.msg, "twice"),
          "a value twice: %s", err.msg);
    CHECK(ob_sum_list_parse("--curves", "a,,b", &l, &err) == -1 && strstr(err.msg, "--curves") && strstr(err.msg, "empty"),
          "an empty value: %s", err.msg);
    CHECK(ob_sum_list_parse("--curves", "a,", &l, &err) == -1, "a trailing comma");
    CHECK(ob_sum_list_parse("--family", "", &l, &err) == -1 && strstr(err.msg, "--family"), "an empty list");
    ob_sum_list_free(&l);
    ob_sum_list_free(&l);
    CHECK(ob_sum_sections_parse("curves,methods", &err) == (OB_SUM_CURVES | OB_SUM_METHODS), "sections");
    CHECK(ob_sum_sections_parse("all", &err) == OB_SUM_ALL, "all sections");
    CHECK(ob_sum_sections_parse("tables", &err) == -1 && strstr(err.msg, "--sections") && strstr(err.msg, "tables"),
          "an unknown section: %s", err.msg);
}

static void test_family_fallback(void)
{
    ob_res_table t;
    const char *text = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message\n"
                       "rnd7_000013,0.1,m,hausdorff,mid,0.1,4,1,3,0.01,ok,1,1,\n"
                       "rnd7_x,0.1,m,hausdorff,mid,0.1,4,1,3,0.01,ok,1,1,\n"
                       "mine,0.1,m,hausdorff,mid,0.1,4,1,3,0.01,ok,1,1,\n";
    if (parse(text, &t) != 0) {
        CHECK(0, "the table without a family column parses");
        return;
    }
    CHECK(!t.has_family && !strcmp(t.v[0].family, ""), "no family column: family \"\"");
    CHECK(!strcmp(ob_sum_family(&t.v[0]), "tight"), "rnd7_000013: 13 mod 8 = 5, tight: %s", ob_sum_family(&t.v[0]));
    CHECK(!strcmp(ob_sum_family(&t.v[1]), "(none)") && !strcmp(ob_sum_family(&t.v[2]), "(none)"),
          "not a random id: (none)");
    ob_res_free(&t);
    if (parse(RUN, &t) == 0) {
        CHECK(t.has_family && !strcmp(ob_sum_family(&t.v[16]), "fam_b"), "the family column");
        ob_res_free(&t);
    }
}

static void test_pivot(const ob_summary *s)
{
    CHECK(s->nm == 2 && !strcmp(s->methods[0], "m1") && !strcmp(s->methods[1], "m2"), "methods in file order");
    CHECK(s->nt == 2 && s->tols[0] == 0.1 && s->tols[1] == 0.01 && !strcmp(s->tol_text[0], "0.1"),
          "tolerances descending");
    CHECK(s->np == 5 && !strcmp(s->pairs[1].curve, "c1") && s->pairs[1].d == -0.5 && !strcmp(s->pairs[4].d_text, "0.2"),
          "the (curve, d) pairs in file order");
    CHECK(s->nf == 2 && !strcmp(s->families[0], "fam_a") && s->fam_pairs[0] == 4 && s->fam_pairs[1] == 1 &&
              s->pairs[4].fam == 1,
          "families and their pairs");
    CHECK(s->ncurves == 4 && s->run.njobs == 20 && !strcmp(s->run.metric, "hausdorff") && !strcmp(s->run.split, "mid"),
          "4 curves, 20 jobs, the metric and split");
    const ob_res_row *c = s->run.cell[ob_sum_at(s, 0, 0, 0)];
    CHECK(c && c->ctrl_points == 4, "c1 0.5 m1 0.1: 4");
    c = s->run.cell[ob_sum_at(s, 2, 0, 1)];
    CHECK(c && !strcmp(c->status, "limit"), "c2 m1 0.01: limit");
    const ob_sum_fcell *f = &s->run.fam[ob_sum_fat(s, 0, 0, 0)];
    CHECK(f->q.n == 4 && f->nonok == 0 && f->q.median == 8.5 && f->q.q1 == 6.25 && f->q.q3 == 10.75,
          "fam_a m1 0.1: %d ok, %g [%g, %g]", f->q.n, f->q.median, f->q.q1, f->q.q3);
    f = &s->run.fam[ob_sum_fat(s, 0, 0, 1)];
    CHECK(f->q.n == 2 && f->nonok == 2 && f->q.median == 15 && f->q.q1 == 12.5 && f->q.q3 == 17.5,
          "fam_a m1 0.01: limit and fail left out: %g [%g, %g]", f->q.median, f->q.q1, f->q.q3);
    f = &s->run.fam[ob_sum_fat(s, 0, 1, 0)];
    CHECK(f->q.n == 3 && f->nonok == 1 && f->q.median == 5 && f->q.q1 == 5 && f->q.q3 == 5.5, "fam_a m2 0.1");
    f = &s->run.fam[ob_sum_fat(s, 0, 1, 1)];
    CHECK(f->q.n == 0 && f->nonok == 4 && isnan(f->q.median), "fam_a m2 0.01: no ok job");
    f = &s->run.fam[ob_sum_fat(s, 1, 1, 0)];
    CHECK(f->q.n == 0 && f->nonok == 1, "fam_b m2 0.1: the timeout");
    const ob_sum_mstat *m = &s->run.meth[0];
    CHECK(m->jobs == 10 && m->status[OB_SUM_OK] == 8 && m->status[OB_SUM_LIMIT] == 1 && m->status[OB_SUM_FAIL] == 1,
          "m1's statuses");
    CHECK(m->time_ns.n == 10 && m->time_ns.median == 5500 && m->time_ns.q1 == 3250 && m->time_ns.q3 == 7750,
          "m1's time per job: %g [%g, %g]", m->time_ns.median, m->time_ns.q1, m->time_ns.q3);
    m = &s->run.meth[1];
    CHECK(m->jobs == 10 && m->status[OB_SUM_OK] == 4 && m->status[OB_SUM_FAIL] == 4 && m->status[OB_SUM_SKIP] == 1 &&
              m->status[OB_SUM_TIMEOUT] == 1,
          "m2's statuses");
    CHECK(m->time_ns.n == 9 && m->time_ns.median == 500 && m->time_ns.q1 == 300 && m->time_ns.q3 == 700,
          "m2's time per job, the skip left out: %g [%g, %g]", m->time_ns.median, m->time_ns.q1, m->time_ns.q3);
}

static void test_formats(const ob_summary *s)
{
    char *md = render(ob_summary_write_md, s, OB_SUM_ALL);
    CHECK(md != NULL, "Markdown written");
    if (md) {
        CHECK(has_line(md, "| curve | d | tol | m1 | m2 |"), "curves header");
        CHECK(has_line(md, "| c1 | 0.5 | 0.1 | 4 | 5 |"), "c1 0.5 at 0.1");
        CHECK(has_line(md, "|  |  | 0.01 | 10 | fail |"), "the next tolerance: curve and d left blank");
        CHECK(has_line(md, "|  | -0.5 | 0.1 | 7 | 5 |"), "same curve, another d");
        CHECK(has_line(md, "| c3 | 1 | 0.1 | 10 | skip |"), "a skip");
        CHECK(has_line(md, "| family | pairs | tol | m1 | m2 |"), "families header");
        CHECK(has_line(md, "| fam_a | 4 | 0.1 | 8.5 [6.25, 10.75] | 5 [5, 5.5] (1 non-ok) |"), "fam_a at 0.1");
        CHECK(has_line(md, "|  |  | 0.01 | 15 [12.5, 17.5] (2 non-ok) | - (4 non-ok) |"), "fam_a at 0.01");
        CHECK(has_line(md, "| fam_b | 1 | 0.1 | 3 [3, 3] | - (1 non-ok) |"), "fam_b at 0.1");
        CHECK(has_line(md, "| method | jobs | ok | limit | fail | skip | timeout | time/job (ms) |"), "methods header");
        CHECK(has_line(md, "| m1 | 10 | 8 | 1 | 1 | 0 | 0 | 0.0055 [0.00325, 0.00775] |"), "m1's line");
        CHECK(has_line(md, "| m2 | 10 | 4 | 0 | 4 | 1 | 1 | 0.0005 [0.0003, 0.0007] |"), "m2's line");
        CHECK(strstr(md, "type 7") != NULL, "the quantile rule is stated");
        if (check_failed)
            fprintf(stderr, "%s", md);
        free(md);
    }
    md = render(ob_summary_write_md, s, OB_SUM_FAMILIES);
    CHECK(md && !strstr(md, "| curve |") && !strstr(md, "| method |") && strstr(md, "| family |"),
          "--sections families: that table only");
    free(md);
    char *csv = render(ob_summary_write_csv, s, OB_SUM_ALL);
    CHECK(csv != NULL, "CSV written");
    if (csv) {
        CHECK(!strncmp(csv,
                       "section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,base_status,base_value,base_q1,"
                       "base_q3,base_n,ratio\n",
                       strlen("section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,base_status,base_value,"
                              "base_q1,base_q3,base_n,ratio\n")),
              "CSV header");
        CHECK(has_line(csv, "curve,fam_a,c1,0.5,m1,0.1,ok,4,,,,,,,,,,"), "a curve cell");
        CHECK(has_line(csv, "curve,fam_a,c1,0.5,m2,0.01,fail,,,,,,,,,,,"), "a failed cell: no value");
        CHECK(has_line(csv, "family,fam_a,,,m1,0.1,,8.5,6.25,10.75,4,0,,,,,,"), "a family cell");
        CHECK(has_line(csv, "family,fam_a,,,m2,0.01,,,,,0,4,,,,,,"), "a family cell without ok jobs");
        CHECK(has_line(csv, "time,,,,m1,,,5500,3250,7750,10,,,,,,,"), "m1's time in ns");
        CHECK(has_line(csv, "status,,,,m2,,timeout,1,,,,,,,,,,"), "m2's timeouts");
        CHECK(has_line(csv, "status,,,,m1,,timeout,0,,,,,,,,,,"), "zero counts are written");
        free(csv);
    }
    char *tex = render(ob_summary_write_latex, s, OB_SUM_ALL);
    CHECK(tex != NULL, "LaTeX written");
    if (tex) {
        CHECK(strstr(tex, "\\toprule") && strstr(tex, "\\midrule") && strstr(tex, "\\bottomrule") &&
                  strstr(tex, "\\begin{tabular}") && strstr(tex, "\\end{tabular}"),
              "booktabs rules");
        CHECK(has_line(tex, "fam\\_a & 4 & 0.1 & 8.5 [6.25, 10.75] & 5 [5, 5.5] (1 non-ok) \\\\"), "a family row, _ escaped");
        CHECK(!strstr(tex, "fam_a"), "no bare underscore");
        CHECK(has_line(tex, " &  & 0.01 & 15 [12.5, 17.5] (2 non-ok) & -- (4 non-ok) \\\\"), "none: an en dash");
        free(tex);
    }
}

static void test_filters(const ob_res_table *t)
{
    ob_summary s;
    ob_err err;
    ob_sum_list methods = {0}, curves = {0}, fam = {0};
    ob_sum_filter f = {&methods, NULL, NULL, NULL, NULL};
    if (ob_sum_list_parse("--methods", "m2,m1", &methods, &err) == 0) {
        CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == 0 && s.nm == 2 && !strcmp(s.methods[0], "m2"),
              "--methods m2,m1: that order");
        ob_summary_free(&s);
    }
    ob_sum_list_free(&methods);
    ob_sum_list_parse("--methods", "m1,nosuch", &methods, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "--methods") &&
              strstr(err.msg, "unknown method 'nosuch'"),
          "an unknown method: %s", err.msg);
    ob_sum_list_free(&methods);
    ob_sum_list_parse("--methods", "tiller", &methods, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "no rows of method 'tiller'") &&
              strstr(err.msg, "t.csv"),
          "a method of the build that the run lacks: %s", err.msg);
    ob_sum_list_free(&methods);
    f.methods = NULL;
    f.curves = &curves;
    ob_sum_list_parse("--curves", "c4", &curves, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == 0 && s.np == 1 && s.nf == 1 && !strcmp(s.families[0], "fam_b") &&
              s.run.njobs == 4,
          "--curves c4");
    ob_summary_free(&s);
    ob_sum_list_free(&curves);
    ob_sum_list_parse("--curves", "c9", &curves, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "--curves") && strstr(err.msg, "c9"),
          "an unknown curve: %s", err.msg);
    ob_sum_list_free(&curves);
    f.curves = NULL;
    f.families = &fam;
    ob_sum_list_parse("--family", "fam_a", &fam, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == 0 && s.np == 4 && s.nf == 1 && s.run.njobs == 16,
          "--family fam_a");
    ob_summary_free(&s);
    ob_sum_list_free(&fam);
    ob_sum_list_parse("--family", "fam_z", &fam, &err);
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "--family") && strstr(err.msg, "fam_z"),
          "an unknown family: %s", err.msg);
    ob_sum_list_free(&fam);
    f.families = NULL;
    f.metric = "radial";
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "--metric") && strstr(err.msg, "radial"),
          "a metric the run lacks: %s", err.msg);
    f.metric = "hausdorff";
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == 0 && s.run.njobs == 20, "--metric hausdorff");
    ob_summary_free(&s);
    f.metric = NULL;
    f.split = "greedy";
    CHECK(ob_summary_build(t, "t.csv", &f, &s, &err) == -1 && strstr(err.msg, "--split"), "a split the run lacks");
    /* two metrics in one file: --metric chooses */
    ob_res_table two;
    char *text = malloc(sizeof RUN + 200);
    snprintf(text, sizeof RUN + 200, "%s%s", RUN, "c1,0.5,m1,bound,mid,0.1,4,1,3,0.01,ok,1,1,,fam_a\n");
    if (text && parse(text, &two) == 0) {
        f.split = NULL;
        CHECK(ob_summary_build(&two, "two.csv", &f, &s, &err) == -1 && strstr(err.msg, "--metric") &&
                  strstr(err.msg, "bound") && strstr(err.msg, "hausdorff"),
              "two metrics and no --metric: %s", err.msg);
        f.metric = "bound";
        CHECK(ob_summary_build(&two, "two.csv", &f, &s, &err) == 0 && s.run.njobs == 1, "--metric bound: its one row");
        ob_summary_free(&s);
        ob_sum_list_parse("--curves", "c1,c2", &curves, &err);
        f.curves = &curves;
        CHECK(ob_summary_build(&two, "two.csv", &f, &s, &err) == -1 && strstr(err.msg, "--curves") &&
                  strstr(err.msg, "'c2'") && strstr(err.msg, "left out"),
              "a curve whose rows are all of another metric: %s", err.msg);
        f.curves = NULL;
        ob_sum_list_free(&curves);
        ob_res_free(&two);
    }
    free(text);
}

static void test_baseline(const ob_res_table *t)
{
    ob_res_table b;
    if (parse(BASE, &b) != 0) {
        CHECK(0, "the baseline parses");
        return;
    }
    ob_summary s;
    ob_err err;
    ob_sum_filter f = {NULL, NULL, NULL, NULL, NULL};
    if (ob_summary_build(t, "t.csv", &f, &s, &err) != 0 || ob_summary_join(&s, &b, "b.csv", &f, &err) != 0) {
        CHECK(0, "summary with a baseline: %s", err.msg);
        ob_res_free(&b);
        return;
    }
    CHECK(s.has_base && s.base.njobs == 19 && !strcmp(s.base.metric, "bound"), "19 of 20 jobs joined, metric bound");
    const ob_res_row *c = s.base.cell[ob_sum_at(&s, 0, 0, 0)];
    CHECK(c && c->ctrl_points == 5, "the baseline's c1 0.5 m1 0.1");
    CHECK(s.base.cell[ob_sum_at(&s, 4, 1, 1)] == NULL, "c4 m2 0.01: not in the baseline");
    const ob_sum_fcell *fc = &s.base.fam[ob_sum_fat(&s, 0, 0, 0)];
    CHECK(fc->q.median == 8.5 && fc->q.q1 == 6.5 && fc->q.q3 == 10.75, "baseline fam_a m1 0.1: %g [%g, %g]",
          fc->q.median, fc->q.q1, fc->q.q3);
    CHECK(s.base.meth[1].time_ns.median == 450 && s.base.meth[0].status[OB_SUM_OK] == 9, "baseline method stats");
    char *md = render(ob_summary_write_md, &s, OB_SUM_ALL);
    CHECK(md != NULL, "Markdown with a baseline");
    if (md) {
        CHECK(has_line(md, "| curve | d | tol | m1 | base | new/base | m2 | base | new/base |"), "curves header");
        CHECK(has_line(md, "| c1 | 0.5 | 0.1 | 4 | 5 | 0.8 | 5 | 5 | 1 |"), "ratios of control points");
        CHECK(has_line(md, "|  |  | 0.01 | limit | 40 | - | fail | fail | - |"), "statuses beside");
        CHECK(has_line(md, "|  |  | 0.01 | 9 | 9 | 1 | 11 | - | - |"), "a job the baseline lacks");
        CHECK(has_line(md, "| fam_a | 4 | 0.1 | 8.5 [6.25, 10.75] | 8.5 [6.5, 10.75] | 1 | 5 [5, 5.5] (1 non-ok) | "
                           "5 [5, 5.5] (1 non-ok) | 1 |"),
              "family medians beside");
        CHECK(has_line(md, "| method | jobs | ok | limit | fail | skip | timeout | time/job (ms) | base ok | "
                           "base time/job (ms) | new/base |"),
              "methods header");
        CHECK(has_line(md, "| m2 | 10 | 4 | 0 | 4 | 1 | 1 | 0.0005 [0.0003, 0.0007] | 3 | 0.00045 [0.000275, 0.000625] | "
                           "1.11 |"),
              "m2 with its baseline");
        CHECK(strstr(md, "b.csv") && strstr(md, "19 of 20"), "the baseline named, with the jobs joined");
        if (check_failed)
            fprintf(stderr, "%s", md);
        free(md);
    }
    char *csv = render(ob_summary_write_csv, &s, OB_SUM_ALL);
    if (csv) {
        CHECK(has_line(csv, "curve,fam_a,c1,0.5,m1,0.1,ok,4,,,,,ok,5,,,,0.8"), "CSV: the baseline's cell and ratio");
        CHECK(has_line(csv, "curve,fam_b,c4,0.2,m2,0.01,ok,11,,,,,missing,,,,,"), "CSV: a missing baseline row");
        CHECK(has_line(csv, "family,fam_a,,,m1,0.1,,8.5,6.25,10.75,4,0,,8.5,6.5,10.75,4,1"), "CSV: family beside");
        free(csv);
    }
    char *tex = render(ob_summary_write_latex, &s, OB_SUM_CURVES);
    if (tex) {
        CHECK(strstr(tex, "\\multicolumn{3}{c}{m1}") && strstr(tex, "\\cmidrule(lr){4-6}"),
              "LaTeX: a method spans its three columns");
        free(tex);
    }
    ob_summary_free(&s);
    ob_summary_free(&s);
    ob_res_free(&b);
}

/* A run with certificates (run --certify): m1 has two certified within
 * tol (0.0009 <= 0.001; 0.01 <= 0.01 exactly), one not (0.0011 > 0.001),
 * one unbounded (inf: not), and a fail without one; m2's one job has none.
 * cert_ns of m1's four: 1e6 2e6 3e6 4e6 -> median 2.5e6, q1 (h = 0.75)
 * 1.75e6, q3 (h = 2.25) 3.25e6. */
#define HDRC "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message," \
             "family,err_upper,err_lower,certified,cert_ns\n"
static const char CERT[] = HDRC
    "c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,0.0009,yes,1000000\n"
    "c1,1,m1,hausdorff,mid,0.01,4,1,3,0.009,ok,10,0,,f,0.01,0.009,yes,2000000\n"
    "c2,1,m1,hausdorff,mid,0.001,10,3,3,0.00099,ok,10,0,,f,0.0011,0.00099,no,3000000\n"
    "c2,1,m1,hausdorff,mid,0.01,13,4,3,0.02,limit,10,0,depth,f,inf,0.02,no,4000000\n"
    "c3,1,m1,hausdorff,mid,0.001,0,0,0,,fail,10,0,singular,f,,,,\n"
    "c3,1,m2,hausdorff,mid,0.001,4,1,3,0.0001,ok,10,0,,f,,,,\n";

/* The certificate in the tables (issue 47): err_upper beside the control
 * points of an ok job ("!" over tol, "no verdict" timed out), the jobs
 * certified within tol per method and tol, the ok jobs not certified
 * within tol listed; in all three formats. */
static void test_certified_tables(const ob_summary *s)
{
    char *md = render(ob_summary_write_md, s, OB_SUM_ALL);
    CHECK(md && has_line(md, "| c1 | 1 | 0.01 | 4 (0.01) | - |") && has_line(md, "|  |  | 0.001 | 7 (0.0009) | - |"),
          "the curves table: err_upper beside the control points: %s", md ? md : "");
    CHECK(md && has_line(md, "| c2 | 1 | 0.01 | limit | - |") && has_line(md, "|  |  | 0.001 | 10 (0.0011 !) | - |"),
          "over tol marked; a limit job as before");
    CHECK(md && has_line(md, "| c3 | 1 | 0.01 | - | - |") && has_line(md, "|  |  | 0.001 | fail | 4 |"),
          "an ok job without a certificate: its control points alone");
    CHECK(md && strstr(md, "## Certified within tol per tolerance") &&
              has_line(md, "| method | 0.01 | 0.001 |") && has_line(md, "| m1 | 1 of 1 | 1 of 2 |") &&
              has_line(md, "| m2 | - | - |"),
          "certified within tol per method and tol (of the ok jobs with a certificate)");
    CHECK(md && strstr(md, "## Ok but not certified within tol") &&
              has_line(md, "| curve | d | method | tol | ctrl_points | max_err | err_upper | err_lower | why |") &&
              has_line(md, "| c2 | 1 | m1 | 0.001 | 10 | 0.00099 | 0.0011 | 0.00099 | over tol |"),
          "the ok jobs not certified within tol listed");
    free(md);
    char *csv = render(ob_summary_write_csv, s, OB_SUM_ALL);
    CHECK(csv && strncmp(csv, "section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,base_status,base_value,"
                              "base_q1,base_q3,base_n,ratio,err_upper,err_lower,certified\n", 145) == 0,
          "the CSV's header: the certificate's columns at the end");
    CHECK(csv && strstr(csv, "\ncurve,f,c2,1,m1,0.001,ok,10,,,,,,,,,,,0.0011,0.00099,no\n") &&
              strstr(csv, "\ncurve,f,c3,1,m1,0.001,fail,,,,,,,,,,,,,,\n"),
          "CSV curve rows with their certificates: %s", csv ? csv : "");
    CHECK(csv && strstr(csv, "\ncertified_tol,,,,m1,0.001,,1,,,2,,,,,,,,,,\n") &&
              strstr(csv, "\ncertified_tol,,,,m1,0.01,,1,,,1,,,,,,,,,,\n"),
          "CSV rows certified_tol: yes in value, of n");
    CHECK(csv && strstr(csv, "\nnot_certified,f,c2,1,m1,0.001,over tol,10,,,,,,,,,,,0.0011,0.00099,no\n"),
          "CSV rows not_certified");
    free(csv);
    char *tex = render(ob_summary_write_latex, s, OB_SUM_ALL);
    CHECK(tex && strstr(tex, "10 (0.0011 !)") && strstr(tex, "m1 & 1 of 1 & 1 of 2 \\\\") &&
              strstr(tex, "c2 & 1 & m1 & 0.001 & 10 & 0.00099 & 0.0011 & 0.00099 & over tol \\\\"),
          "LaTeX: the same tables");
    free(tex);
}

/* A certificate stopped by --job-timeout (cert_ns alone): no verdict, not
 * certified within tol, listed. */
static void test_cert_timeout(void)
{
    static const char text[] = HDRC "c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,0.0009,yes,1000000\n"
                                    "c2,1,m1,hausdorff,mid,0.001,9,2,3,0.0009,ok,10,0,,f,,,,5000000\n";
    ob_res_table t;
    ob_summary s;
    ob_err err;
    ob_sum_filter f = {NULL, NULL, NULL, NULL, NULL};
    if (parse(text, &t) != 0 || ob_summary_build(&t, "c.csv", &f, &s, &err) != 0) {
        CHECK(0, "a run with a timed-out certificate parses and summarizes");
        ob_res_free(&t);
        return;
    }
    CHECK(t.v[1].cert_done == 2 && isnan(t.v[1].err_upper) && t.v[1].cert_ns == 5e6, "read: timed out, its time");
    CHECK(s.run.meth[0].cert_yes == 1 && s.run.meth[0].cert_no == 1, "counted not certified");
    char *md = render(ob_summary_write_md, &s, OB_SUM_ALL);
    CHECK(md && has_line(md, "| c2 | 1 | 0.001 | 9 (no verdict) |") && has_line(md, "| m1 | 1 of 2 |") &&
              has_line(md, "| c2 | 1 | m1 | 0.001 | 9 | 0.0009 |  |  | timed out |"),
          "shown as no verdict, listed as timed out: %s", md ? md : "");
    free(md);
    ob_summary_free(&s);
    ob_res_free(&t);
}

/* A file name's whole text (malloc'ed), or NULL. */
static char *slurp_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0, n;
    char chunk[4096];
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (len + n + 1 > cap) {
            cap = 2 * (len + n + 1);
            char *b = realloc(buf, cap);
            if (!b) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = b;
        }
        memcpy(buf + len, chunk, n);
        len += n;
    }
    fclose(f);
    if (buf)
        buf[len] = '\0';
    return buf;
}

/* Runs without certificates: the summary byte for byte as before the
 * certificate's tables (tests/data/summary/: written by the build before
 * them), in every format, with and without a baseline, also when the four
 * columns are there but empty. */
static void test_no_cert_unchanged(void)
{
    /* RUN with the certificate's four columns, empty */
    static char empty4[sizeof RUN + 64 * 21];
    size_t at = 0;
    for (const char *p = RUN; *p; p++) {
        if (*p == '\n')
            at += (size_t)snprintf(empty4 + at, sizeof empty4 - at, "%s",
                                   p == strchr(RUN, '\n') ? ",err_upper,err_lower,certified,cert_ns" : ",,,,");
        empty4[at++] = *p;
    }
    empty4[at] = '\0';
    const char *const runs[2] = {RUN, empty4};
    static const char *const ext[3] = {"md", "csv", "tex"};
    int (*const fn[3])(FILE *, const ob_summary *, int) = {ob_summary_write_md, ob_summary_write_csv,
                                                           ob_summary_write_latex};
    for (int r = 0; r < 2; r++) {
        ob_res_table t, b;
        ob_summary s;
        ob_err err;
        ob_sum_filter f = {NULL, NULL, NULL, NULL, NULL};
        if (parse(runs[r], &t) != 0 || parse(BASE, &b) != 0) {
            CHECK(0, "the run parses (%d)", r);
            return;
        }
        for (int base = 0; base < 2; base++) {
            if (ob_summary_build(&t, "t.csv", &f, &s, &err) != 0 ||
                (base && ob_summary_join(&s, &b, "b.csv", &f, &err) != 0)) {
                CHECK(0, "summary: %s", err.msg);
                continue;
            }
            for (int k = 0; k < 3; k++) {
                char path[128];
                snprintf(path, sizeof path, "tests/data/summary/run%s.%s", base ? "_base" : "", ext[k]);
                char *want = slurp_file(path), *got = render(fn[k], &s, OB_SUM_ALL);
                CHECK(want && got && strcmp(want, got) == 0, "%s (%s): as before, byte for byte:\n%s", path,
                      r ? "empty certificate columns" : "none", got ? got : "(nothing)");
                free(want);
                free(got);
            }
            ob_summary_free(&s);
        }
        ob_res_free(&t);
        ob_res_free(&b);
    }
}

static void test_certified(void)
{
    ob_res_table t;
    ob_summary s;
    ob_err err;
    ob_sum_filter f = {NULL, NULL, NULL, NULL, NULL};
    if (parse(CERT, &t) != 0 || ob_summary_build(&t, "c.csv", &f, &s, &err) != 0) {
        CHECK(0, "the certified run parses and summarizes");
        ob_res_free(&t);
        return;
    }
    CHECK(t.has_cert && t.v[0].cert_done && !t.v[4].cert_done && isinf(t.v[3].err_upper), "rows read with and without");
    CHECK(s.has_cert && s.run.meth[0].cert_yes == 2 && s.run.meth[0].cert_no == 2, "m1: 2 certified within tol, 2 not");
    CHECK(s.run.meth[1].cert_yes == 0 && s.run.meth[1].cert_no == 0 && s.run.meth[1].cert_ns.n == 0, "m2: none");
    CHECK_NEAR(s.run.meth[0].cert_ns.median, 2.5e6, 1e-6, "m1 cert_ns median");
    CHECK_NEAR(s.run.meth[0].cert_ns.q1, 1.75e6, 1e-6, "m1 cert_ns q1");
    char *md = render(ob_summary_write_md, &s, OB_SUM_METHODS);
    CHECK(md && has_line(md, "| method | jobs | ok | limit | fail | skip | timeout | time/job (ms) | certified | "
                             "not certified | cert/job (ms) |"), "methods header with the certificate's columns");
    CHECK(md && has_line(md, "| m1 | 5 | 3 | 1 | 1 | 0 | 0 | 1e-05 [1e-05, 1e-05] | 2 | 2 | 2.5 [1.75, 3.25] |"),
          "m1's row: %s", md ? md : "");
    free(md);
    char *csv = render(ob_summary_write_csv, &s, OB_SUM_METHODS);
    CHECK(csv && strstr(csv, "certified,,,,m1,,yes,2,") && strstr(csv, "certified,,,,m1,,no,2,") &&
          strstr(csv, "cert_time,,,,m1,,,2500000,"), "CSV rows certified and cert_time");
    free(csv);
    test_certified_tables(&s);
    ob_summary_free(&s);
    ob_res_free(&t);
    /* a run without them: no such columns */
    if (parse(RUN, &t) == 0 && ob_summary_build(&t, "t.csv", &f, &s, &err) == 0) {
        char *m = render(ob_summary_write_md, &s, OB_SUM_METHODS);
        CHECK(!s.has_cert && m && !strstr(m, "certified"), "no certificates: no certified columns");
        free(m);
        ob_summary_free(&s);
    }
    ob_res_free(&t);
    /* the reader refuses a certificate that contradicts itself, naming the line */
    static const char *const bad[][2] = {
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0011,0.0009,yes,1\n", "certified must be yes exactly"},
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,0.001,yes,1\n", "err_lower is not a finite"},
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,0.0009,yes,\n", "all empty or all set"},
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,0.0009,maybe,1\n", "certified is not"},
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,nan,0.0009,no,1\n", "err_upper is not"},
        /* issue 48: err_lower nan is not below err_upper; a row without an approximation has no certificate */
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0009,nan,yes,1\n", "err_lower is not a finite"},
        {"c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,inf,nan,no,1\n", "err_lower is not a finite"},
        {"c1,1,m1,hausdorff,mid,0.001,0,0,0,,skip,0,0,,f,0.0009,0.0009,yes,1\n", "status skip has no approximation"},
        {"c1,1,m1,hausdorff,mid,0.001,0,0,0,,fail,0,0,,f,0.0011,0.0009,no,1\n", "status fail has no approximation"},
        {"c1,1,m1,hausdorff,mid,0.001,0,0,0,,timeout,0,0,,f,0.0009,0.0009,yes,1\n", "status timeout has no approx"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "%s%s", HDRC, bad[i][0]);
        const int rc = ob_res_parse(text, strlen(text), "c.csv", &t, &err);
        CHECK(rc == -1 && strstr(err.msg, "c.csv:2:") && strstr(err.msg, bad[i][1]), "bad certificate %zu: %s", i,
              rc ? err.msg : "accepted");
        ob_res_free(&t);
    }
    /* still read: verdict mode (err_upper inf, err_lower over tol); a sampled max_err over err_upper */
    static const char *const good[] = {
        "c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,limit,10,0,,f,inf,0.002,no,1\n",
        "c1,1,m1,hausdorff,mid,0.001,7,2,3,0.0009,ok,10,0,,f,0.0008,0.0007,yes,1\n",
        "c1,1,m1,hausdorff,mid,0.001,0,0,0,,skip,0,0,,f,,,,\n",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text, "%s%s", HDRC, good[i]);
        const int rc = ob_res_parse(text, strlen(text), "c.csv", &t, &err);
        CHECK(rc == 0, "good certificate %zu: %s", i, rc ? err.msg : "read");
        ob_res_free(&t);
    }
    static const char three[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,"
                                "fit_ns,eval_ns,message,err_upper,err_lower,certified\n";
    CHECK(ob_res_parse(three, strlen(three), "c.csv", &t, &err) == -1 && strstr(err.msg, "come together"),
          "three of the four columns: refused");
    ob_res_free(&t);
}

int main(void)
{
    test_certified();
    test_cert_timeout();
    test_no_cert_unchanged();
    test_quantiles();
    test_lists();
    test_family_fallback();
    ob_res_table t;
    if (parse(RUN, &t) != 0) {
        CHECK(0, "the hand-made run parses");
        return check_done();
    }
    ob_summary s;
    ob_err err;
    ob_sum_filter f = {NULL, NULL, NULL, NULL, NULL};
    if (ob_summary_build(&t, "t.csv", &f, &s, &err) == 0) {
        test_pivot(&s);
        test_formats(&s);
        ob_summary_free(&s);
    } else {
        CHECK(0, "summary of the hand-made run: %s", err.msg);
    }
    test_filters(&t);
    test_baseline(&t);
    ob_res_free(&t);
    return check_done();
}
