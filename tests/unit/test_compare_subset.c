/*
 * test_compare_subset.c - `compare` of a smaller run against a larger
 * baseline (compare_subset.h): rows of BASE outside NEW's meta.json
 * "selection" are left out (exit 0, no quality change), rows inside it that
 * NEW lacks are missing (exit 1), another random seed is not comparable
 * (exit 3); no selection on NEW's side behaves as before (missing), said in
 * a note.  Also: the writer of "selection" (meta_selection.h) reads back,
 * and --random N:SEED is the first N curves of --random M:SEED (what makes
 * a smaller N of one seed a subset).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/compare/compare.h"
#include "host/compare/compare_subset.h"
#include "host/io/curvefile.h"
#include "host/io/meta_selection.h"
#include "host/io/random.h"
#include "host/run/options.h"

/* ---- the runs ---- */

static const char HDR[] =
    "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family\n";

/* BASE: every (curve, d) below x tiller, ahn x tol 0.1, 0.01: 24 rows. */
static const struct {
    const char *curve, *d;
} OFFSETS[] = {{"c1", "1"}, {"c1", "2"}, {"c2", "1"}, {"rnd7_000000", "0.1"}, {"rnd7_000001", "0.2"},
               {"rnd7_000002", "0.3"}};
enum { NOFF = sizeof OFFSETS / sizeof OFFSETS[0], NROWS = NOFF * 4 };
static const char *const METHODS[] = {"tiller", "ahn"};
static const char *const TOLS[] = {"0.1", "0.01"};

/* Which rows a side has: the (curve, d) index, method and tol index. */
typedef int (*keep_fn)(int off, const char *method, int tol);

static int keep_all(int off, const char *method, int tol)
{
    (void)off, (void)method, (void)tol;
    return 1;
}

static void rows(char *buf, size_t len, keep_fn keep)
{
    size_t used = (size_t)snprintf(buf, len, "%s", HDR);
    for (int k = 0; k < NOFF; k++)
        for (int m = 0; m < 2; m++)
            for (int t = 0; t < 2; t++)
                if (keep(k, METHODS[m], t))
                    used += (size_t)snprintf(buf + used, len - used, "%s,%s,%s,hausdorff,mid,%s,10,3,3,0.05,ok,0,"
                                             "2000000,,f\n", OFFSETS[k].curve, OFFSETS[k].d, METHODS[m], TOLS[t]);
}

/* NEW's selection (meta_selection.h) with each part replaceable; NULL: as BASE ran */
typedef struct {
    const char *curves, *random, *methods, *tols, *splits;
} sel_spec;

static void selection(char *buf, size_t len, const sel_spec *s)
{
    snprintf(buf, len, ", \"selection\": {\"curves\": %s, \"random\": %s, \"methods\": %s, \"metrics\": "
             "[\"hausdorff\"], \"splits\": %s, \"tols\": %s, \"doc\": \"t\"}",
             s->curves ? s->curves : "{\"c1\": [1, 2], \"c2\": [1]}",
             s->random ? s->random : "{\"n\": 3, \"seed\": 7, \"only\": null}",
             s->methods ? s->methods : "[\"tiller\", \"ahn\"]", s->splits ? s->splits : "[\"mid\"]",
             s->tols ? s->tols : "[0.1, 0.01]");
}

/* A side: its rows (text with header) and meta.json (seed, extra keys), or no meta.json (seed NULL). */
static void side(ob_cmp_side *s, const char *label, const char *text, const char *seed, const char *extra)
{
    char meta[4096];
    ob_err err = {""};
    memset(s, 0, sizeof *s);
    s->label = label;
    snprintf(s->results_path, sizeof s->results_path, "%s.csv", label);
    CHECK(ob_res_parse(text, strlen(text), s->results_path, &s->res, &err) == 0, "%s rows: %s", label, err.msg);
    if (!seed)
        return;
    snprintf(meta, sizeof meta, "{\"seed\": %s, \"samples_per_segment\": 256, \"max_depth\": 40, \"max_segments\": "
             "20000, \"inflection_split\": true%s}", seed, extra ? extra : "");
    CHECK(ob_json_flatten(meta, strlen(meta), "meta.json", &s->meta, &err) == 0, "%s meta: %s", label, err.msg);
    s->has_meta = 1;
}

/* The report in one format (0 md, 1 csv, 2 json), malloc'd. */
static char *report(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, const ob_cmp_result *r,
                    int format)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return NULL;
    const int rc = format == 0   ? ob_cmp_write_md(f, b, n, o, r)
                   : format == 1 ? ob_cmp_write_csv(f, b, n, o, r)
                                 : ob_cmp_write_json(f, b, n, o, r);
    fclose(f);
    CHECK(rc == 0, "report %d written", format);
    return text;
}

/* compare BASE (every row, seed 7) with NEW (rows kept by keep, its seed
 * and meta.json extra); the exit status, the result in *r (freed by the
 * caller with the sides in *bs, *ns). */
static int compare(ob_cmp_side *bs, ob_cmp_side *ns, ob_cmp_result *r, const char *base_seed, keep_fn keep,
                   const char *new_seed, const char *extra)
{
    static char bt[8192], nt[8192];
    ob_cmp_opts o = ob_cmp_defaults();
    ob_err err = {""};
    o.no_timing = 1;
    rows(bt, sizeof bt, keep_all);
    rows(nt, sizeof nt, keep);
    side(bs, "BASE", bt, base_seed, NULL);
    side(ns, "NEW", nt, new_seed, extra);
    memset(r, 0, sizeof *r);
    int rc = ob_cmp_context(bs, ns, &o, r, &err);
    if (rc == 0 && !r->incomparable.n)
        rc = ob_cmp_rows(bs, ns, &o, r, &err);
    CHECK(rc == 0, "comparison: %s", err.msg);
    for (int format = 0; format < 3; format++)  /* every report renders */
        free(report(bs, ns, &o, r, format));
    return ob_cmp_status(r);
}

/* compare with NEW's selection sel (selection()) and NEW's rows keep, both sides of seed 7 */
static int compare_sel(ob_cmp_side *b, ob_cmp_side *n, ob_cmp_result *r, const sel_spec *sel, keep_fn keep)
{
    char extra[1024];
    selection(extra, sizeof extra, sel);
    return compare(b, n, r, "7", keep, "7", extra);
}

static void done(ob_cmp_side *b, ob_cmp_side *n, ob_cmp_result *r)
{
    ob_cmp_result_free(r);
    ob_cmp_side_free(b);
    ob_cmp_side_free(n);
}

static int count_kind(const ob_cmp_result *r, ob_ch_kind k)
{
    int c = 0;
    for (int i = 0; i < r->nch; i++)
        c += r->ch[i].kind == k;
    return c;
}

static int has_note(const ob_strlist *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strstr(l->v[i], s))
            return 1;
    return 0;
}

static const char *text_or(const char *s)
{
    return s ? s : "(none)";
}

/* ---- left out: a subset chosen on purpose ---- */

static int tiller_only(int off, const char *method, int tol)
{
    (void)off, (void)tol;
    return strcmp(method, "tiller") == 0;
}

static int not_c2(int off, const char *method, int tol)
{
    (void)method, (void)tol;
    return strcmp(OFFSETS[off].curve, "c2") != 0;
}

static int not_c1_d2(int off, const char *method, int tol)
{
    (void)method, (void)tol;
    return off != 1;
}

static int tol_01(int off, const char *method, int tol)
{
    (void)off, (void)method;
    return tol == 0;
}

static int first_random(int off, const char *method, int tol)
{
    (void)method, (void)tol;
    return off < 4;  /* c1 d 1, 2, c2, rnd7_000000 */
}

static int random_1_only(int off, const char *method, int tol)
{
    (void)method, (void)tol;
    return off < 3 || off == 4;
}

/* a subset of the methods: the other methods' rows left out, exit 0, and
 * the joined rows' quality as before (no change, no method of the rows
 * left out in the per-method table) */
static void left_out_methods(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    int st = compare_sel(&b, &n, &r, &(sel_spec){.methods = "[\"tiller\"]"}, tiller_only);
    CHECK(st == 0 && r.n_left_out == 12 && r.n_missing == 0 && r.joined == 12 && r.q_reg == 0 && r.q_imp == 0,
          "methods subset: exit 0 (got %d), 12 left out (got %d), 0 missing (got %d)", st, r.n_left_out,
          r.n_missing);
    CHECK(count_kind(&r, OB_CH_LEFT_OUT) == 12 && count_kind(&r, OB_CH_MISSING) == 0, "listed as left out");
    CHECK(r.nms == 1 && strcmp(r.ms[0].method, "tiller") == 0, "the per-method table has tiller alone (%d)", r.nms);
    const char *t = ob_cmp_left_out_text(&r);
    CHECK(t && strstr(t, "method ahn") && strstr(t, ": 12 rows left out"), "summary: %s", text_or(t));
    done(&b, &n, &r);
}

/* A subset of NEW's selection sel (NEW's rows: keep) against every row:
 * exit 0, rows left out, none missing, no quality change, and the summary
 * says `said`. */
static void expect_left_out(const char *what, const sel_spec *sel, keep_fn keep, int rows, const char *said)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    const int st = compare_sel(&b, &n, &r, sel, keep);
    const char *t = ob_cmp_left_out_text(&r);
    CHECK(st == 0 && r.n_left_out == rows && r.n_missing == 0 && r.q_reg == 0 && r.q_imp == 0 &&
              r.joined == NROWS - rows && t && strstr(t, said),
          "%s: exit 0 (got %d), %d left out (got %d), 0 missing (got %d), summary with '%s': %s", what, st, rows,
          r.n_left_out, r.n_missing, said, text_or(t));
    done(&b, &n, &r);
}

static void left_out_parts(void)
{
    expect_left_out("curves subset", &(sel_spec){.curves = "{\"c1\": [1, 2]}"}, not_c2, 4, "1 curve (c2)");
    expect_left_out("offsets subset", &(sel_spec){.curves = "{\"c1\": [1], \"c2\": [1]}"}, not_c1_d2, 4,
                    "1 offset (c1 d=2)");
    expect_left_out("tols subset", &(sel_spec){.tols = "[0.1]"}, tol_01, 12, "tol 0.01: 12 rows left out");
    /* --random 1:7 against a baseline of --random 3:7: curves 1 and 2 left out */
    expect_left_out("smaller random N, same seed", &(sel_spec){.random = "{\"n\": 1, \"seed\": 7, \"only\": null}"},
                    first_random, 8, "2 random curves (rnd7_000001 ... rnd7_000002): 8 rows left out");
    /* --curve rnd7_000001 with --random 3:7: the other random curves left out */
    expect_left_out("random ids chosen by --curve",
                    &(sel_spec){.random = "{\"n\": 3, \"seed\": 7, \"only\": [\"rnd7_000001\"]}"}, random_1_only, 8,
                    "2 random curves (rnd7_000000 ... rnd7_000002)");
}

/* every row in the selection: nothing left out, nothing said */
static void full_selection(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    int st = compare_sel(&b, &n, &r, &(sel_spec){0}, keep_all);
    CHECK(st == 0 && r.n_left_out == 0 && r.nch == 0 && !ob_cmp_left_out_text(&r) && r.notes.n == 0,
          "full run, full selection: exit 0, nothing left out, no note (%d notes)", r.notes.n);
    done(&b, &n, &r);
}

/* ---- still regressions ---- */

static int tiller_but_one(int off, const char *method, int tol)
{
    return tiller_only(off, method, tol) && !(off == 0 && tol == 0);
}

/* a row inside the selection that NEW lacks is missing: exit 1 */
static void missing_inside(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    int st = compare_sel(&b, &n, &r, &(sel_spec){.methods = "[\"tiller\"]"}, tiller_but_one);
    CHECK(st == 1 && r.n_missing == 1 && r.n_left_out == 12 && count_kind(&r, OB_CH_MISSING) == 1,
          "a row inside the selection lost: exit 1 (got %d), 1 missing (got %d), 12 left out (got %d)", st,
          r.n_missing, r.n_left_out);
    done(&b, &n, &r);
}

/* NEW without a selection (an older offbench) or without meta.json: every
 * missing row is a regression, as before, and a note says why */
static void no_selection(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    int st = compare(&b, &n, &r, "7", tiller_only, "7", NULL);
    CHECK(st == 1 && r.n_missing == 12 && r.n_left_out == 0 && has_note(&r.notes, "records no selection"),
          "NEW's meta.json without a selection: missing rows are regressions, said: exit %d, %d missing", st,
          r.n_missing);
    done(&b, &n, &r);
    st = compare(&b, &n, &r, "7", tiller_only, NULL, NULL);
    CHECK(st == 1 && r.n_missing == 12 && has_note(&r.notes, "NEW has no meta.json"),
          "NEW without meta.json: missing rows are regressions, said: exit %d", st);
    done(&b, &n, &r);
    st = compare_sel(&b, &n, &r, &(sel_spec){.tols = "[\"0.1\"]"}, tol_01);
    CHECK(st == 1 && r.n_missing == 12 && has_note(&r.notes, "selection.tols"),
          "a selection that cannot be read is not used, said: exit %d", st);
    done(&b, &n, &r);
    st = compare_sel(&b, &n, &r, &(sel_spec){.random = "{\"n\": 3, \"seed\": \"7\", \"only\": null}"}, tol_01);
    CHECK(st == 1 && r.n_missing == 12 && has_note(&r.notes, "selection.random"),
          "a random set whose seed is not a number is not read: exit %d", st);
    done(&b, &n, &r);
    st = compare(&b, &n, &r, "7", keep_all, "7", NULL);
    CHECK(st == 0 && r.notes.n == 0, "nothing missing: no note (the output of a full run does not move)");
    done(&b, &n, &r);
}

/* another seed: not comparable, exit 3 (meta.json's seed; a BASE without
 * meta.json: the seed of its random curves' ids) */
static void another_seed(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    char extra[1024];
    selection(extra, sizeof extra, &(sel_spec){.random = "{\"n\": 3, \"seed\": 8, \"only\": null}"});
    int st = compare(&b, &n, &r, "7", first_random, "8", extra);
    CHECK(st == 3 && has_note(&r.incomparable, "seed"), "another seed: exit 3 (got %d)", st);
    done(&b, &n, &r);
    st = compare(&b, &n, &r, NULL, first_random, "8", extra);
    CHECK(st == 3 && has_note(&r.incomparable, "seed 7") && r.n_left_out == 0,
          "another seed, BASE without meta.json: exit 3 (got %d)", st);
    done(&b, &n, &r);
    selection(extra, sizeof extra, &(sel_spec){.random = "null"});
    st = compare(&b, &n, &r, NULL, first_random, "null", extra);
    CHECK(st == 3 && has_note(&r.incomparable, "seed 7"), "no random set against random curves: exit 3 (got %d)",
          st);
    done(&b, &n, &r);
}

/* ---- the reports ---- */

static void reports(void)
{
    ob_cmp_side b, n;
    ob_cmp_result r;
    ob_cmp_opts o = ob_cmp_defaults();
    o.no_timing = 1;
    compare_sel(&b, &n, &r, &(sel_spec){.methods = "[\"tiller\"]"}, tiller_only);
    char *md = report(&b, &n, &o, &r, 0), *csv = report(&b, &n, &o, &r, 1), *json = report(&b, &n, &o, &r, 2);
    int lines = 0;
    for (const char *p = csv; p && (p = strstr(p, "\nleft_out,")); p++)
        lines++;
    CHECK(md && strstr(md, "\nLeft out: method ahn: 12 rows left out") && strstr(md, "| c1 | 1 | ahn |"),
          "md: the summary line and the rows left out");
    CHECK(lines == 12 && strstr(csv, "\ncontext,,,,,,,left_out,method ahn: 12 rows left out,"),
          "csv: 12 left_out lines (got %d) and the summary", lines);
    CHECK(json && strstr(json, "\"left_out\": {\"rows\": 12, \"summary\": \"method ahn: 12 rows left out\"") &&
              strstr(json, "\"kind\": \"left_out\""),
          "json: the count, the rows and the summary");
    free(md);
    free(csv);
    free(json);
    done(&b, &n, &r);
}

/* ---- the writer, and what makes a smaller random N a subset ---- */

static const char CURVES[] = "curve c1\n  bezier 1\n  point 0 0 1\n  point 1 0 1\n  offset 1 2\nend\n"
                             "curve c2\n  bezier 1\n  point 0 0 1\n  point 0 1 1\n  offset 1\nend\n";

/* NEW's rows of the run below, but for tiller on c1 d 1 at 0.1 (lost) */
static int written_but_one(int off, const char *method, int tol)
{
    return (off == 1 || off == 4) && strcmp(method, "tiller") == 0 && tol == 0;
}

/* meta.json's selection as run writes it reads back: --curve c1,rnd7_000001 --random 3:7 --methods tiller
 * --tols 0.1, compared with BASE: c2, rnd7_000000 and 000002, ahn and tol 0.01 left out */
static void writer_reads_back(void)
{
    char *argv[] = {"run", "--curve", "c1,rnd7_000001", "--random", "3:7", "--methods", "tiller", "--tols", "0.1"};
    ob_run_opts o;
    ob_curveset set = {0};
    ob_err err = {""};
    CHECK(ob_run_opts_parse(9, argv, &o) == OB_CLI_OK, "options");
    CHECK(ob_curves_parse(CURVES, strlen(CURVES), "t.curves", &set, &err) == 0 &&
              ob_random_append(&set, 7, 3, o.curve_ids, o.ncurve_ids, &err) == 0, "curves: %s", err.msg);
    char *line = NULL, extra[4096];
    size_t len = 0;
    FILE *f = open_memstream(&line, &len);
    ob_meta_write_selection(f, &o, &set);
    fclose(f);
    CHECK(line && strncmp(line, "  \"selection\": {", 16) == 0 && strchr(line, '\n') == line + len - 1,
          "one line: %s", line ? line : "");
    snprintf(extra, sizeof extra, ", %.*s", (int)(len > 4 ? len - 4 : 0), line ? line + 2 : "");  /* no ",\n" */
    ob_cmp_side b, n;
    ob_cmp_result r;
    int st = compare(&b, &n, &r, "7", written_but_one, "7", extra);
    const char *t = ob_cmp_left_out_text(&r);
    CHECK(st == 1 && r.n_missing == 1 && r.n_left_out == 21 && t && strstr(t, "1 curve (c2)") && strstr(t, "2 random curves") &&
              strstr(t, "method ahn") && strstr(t, "tol 0.01"),
          "read back: exit %d (the one tiller c1 row at 0.1 that NEW lacks is missing), %s", st, text_or(t));
    done(&b, &n, &r);
    free(line);
    ob_curveset_free(&set);
    ob_run_opts_free(&o);
}

static int same_curve(const ob_curve *a, const ob_curve *b)
{
    if (strcmp(a->id, b->id) || a->nseg != b->nseg || a->nd != b->nd ||
        memcmp(a->d, b->d, (size_t)a->nd * sizeof *a->d))
        return 0;
    for (int s = 0; s < a->nseg; s++)
        if (a->seg[s].deg != b->seg[s].deg ||
            memcmp(a->seg[s].h, b->seg[s].h, (size_t)(a->seg[s].deg + 1) * sizeof a->seg[s].h[0]))
            return 0;
    return 1;
}

/* --random 2:2026 (a small nightly) is the first two curves of --random
 * 250:2026 (the committed baseline): the same ids, control points and
 * offsets; and 20:2026 (the small baseline) likewise */
static void random_prefix(void)
{
    ob_curveset small = {0}, big = {0};
    ob_err err = {""};
    CHECK(ob_random_append(&small, 2026, 20, NULL, 0, &err) == 0 && ob_random_append(&big, 2026, 250, NULL, 0, &err) == 0,
          "generate: %s", err.msg);
    int same = small.n == 20 && big.n == 250;
    for (int i = 0; same && i < small.n; i++)
        same = same_curve(&small.v[i], &big.v[i]);
    CHECK(same, "--random 20:2026 is a prefix of --random 250:2026");
    uint64_t seed = 0;
    long index = -1;
    CHECK(ob_random_id_parse(big.v[249].id, &seed, &index) == 0 && seed == 2026 && index == 249,
          "ids read back: %s", big.n ? big.v[249].id : "");
    CHECK(ob_random_id_parse("rnd2026_42", &seed, &index) == -1 && ob_random_id_parse("c1", &seed, &index) == -1 &&
              ob_random_id_parse("rnd_000001", &seed, &index) == -1 &&
              ob_random_id_parse("rnd7_0000001", &seed, &index) == -1,
          "only the canonical spelling is a random id");
    ob_curveset_free(&small);
    ob_curveset_free(&big);
}

int main(void)
{
    full_selection();
    left_out_methods();
    left_out_parts();
    missing_inside();
    no_selection();
    another_seed();
    reports();
    writer_reads_back();
    random_prefix();
    return check_done();
}
