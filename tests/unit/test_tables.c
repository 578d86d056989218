/*
 * test_tables.c - the published-figure parser (every malformed input gets
 * FILE:LINE and a reason), the protocol of each published column, and the
 * match / close / differs rules of `./offbench tables`.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/tables/published.h"
#include "host/tables/tables.h"

static const char HDR[] = "source,table,curve,d,tol,method,label,value,unit\n";

static void expect_bad(const char *body, const char *line, const char *why)
{
    char text[1024];
    ob_err err = {""};
    snprintf(text, sizeof text, "%s%s", HDR, body);
    ob_pub_set s;
    int rc = ob_pub_parse(text, strlen(text), "t.csv", &s, &err);
    CHECK(rc == -1 && strstr(err.msg, line) && strstr(err.msg, why), "'%s': got '%s'", body, err.msg);
    CHECK(s.v == NULL && s.n == 0, "failed parse leaves an empty set");
    ob_pub_free(&s);
}

static void test_parser(void)
{
    ob_pub_set s;
    ob_err err = {""};
    const char ok[] = "source,table,curve,d,tol,method,label,value,unit\r\n"
                      "liu2002,1,liu2002_ex1,1.0,1e-1,tiller,Til,10,ctrl_points\r\n"
                      "\n"
                      "zhao2017,text,zhao2017_septic,0.5,,interp500,\"interpolating, 500 \"\"samples\"\"\",0.0371,max_err\n";
    CHECK(ob_pub_parse(ok, strlen(ok), "ok.csv", &s, &err) == 0 && s.n == 2, "good file: %s", err.msg);
    if (s.n == 2) {
        CHECK(strcmp(s.v[1].label, "interpolating, 500 \"samples\"") == 0, "quoted label: %s", s.v[1].label);
        CHECK(isnan(s.v[1].tol) && s.v[1].value == 0.0371 && strcmp(s.v[1].value_text, "0.0371") == 0,
              "empty tol, value kept as text");
        CHECK(s.v[0].line == 2 && s.v[1].line == 4, "line numbers %d %d", s.v[0].line, s.v[1].line);
    }
    ob_pub_free(&s);
    ob_pub_free(&s); /* twice is safe */

    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,\"10,ctrl_points\n", "t.csv:2", "unterminated quote");
    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,10\n", "t.csv:2", "8 fields");
    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,ten,ctrl_points\n", "t.csv:2", "value");
    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,nan,ctrl_points\n", "t.csv:2", "value");
    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,-3,ctrl_points\n", "t.csv:2", "value");
    expect_bad("liu2002,1,c,inf,1e-1,tiller,Til,3,ctrl_points\n", "t.csv:2", "d is not");
    expect_bad("liu2002,1,c,1,0,tiller,Til,3,ctrl_points\n", "t.csv:2", "tol");
    expect_bad("liu2002,1,c,1,,tiller,Til,3,ctrl_points\n", "t.csv:2", "needs a tolerance");
    expect_bad("liu2002,1,c,1,1e-1,tiller,Til,3,points\n", "t.csv:2", "unit");
    expect_bad("liu2002,1,,1,1e-1,tiller,Til,3,ctrl_points\n", "t.csv:2", "must not be empty");
    expect_bad("a,1,c,1,1e-1,m,L,3,ctrl_points\nb,1,c,1,1e-1,m,L,3,ctrl_points,x\n", "t.csv:3", "10 fields");
    expect_bad("", "t.csv", "no figures");
    const char nocol[] = "source,table,curve,d,tol,method,label,value\n";
    CHECK(ob_pub_parse(nocol, strlen(nocol), "h.csv", &s, &err) == -1 && strstr(err.msg, "h.csv:1") &&
              strstr(err.msg, "'unit'"),
          "missing column: %s", err.msg);
    CHECK(ob_pub_parse("", 0, "e.csv", &s, &err) == -1 && strstr(err.msg, "e.csv:1"), "empty: %s", err.msg);

    /* the real file: every published table */
    CHECK(ob_pub_load(&s, &err) == 0, "load: %s", err.msg);
    CHECK(s.n == 237, "237 published cells, got %d", s.n);
    int liu1 = 0, ahn1 = 0, zhao = 0;
    for (int i = 0; i < s.n; i++) {
        liu1 += strcmp(s.v[i].source, "liu2002") == 0 && strcmp(s.v[i].table, "1") == 0;
        ahn1 += strcmp(s.v[i].source, "ahn2023") == 0 && strcmp(s.v[i].table, "1") == 0;
        zhao += strcmp(s.v[i].source, "zhao2017") == 0;
    }
    CHECK(liu1 == 35 && ahn1 == 35 && zhao == 12, "table sizes %d %d %d", liu1, ahn1, zhao);
    ob_pub_free(&s);
}

static ob_pub_cell cell(const char *source, const char *table, const char *curve, const char *method,
                        const char *label, const char *unit, double tol)
{
    ob_pub_cell c;
    memset(&c, 0, sizeof c);
    snprintf(c.source, sizeof c.source, "%s", source);
    snprintf(c.table, sizeof c.table, "%s", table);
    snprintf(c.curve, sizeof c.curve, "%s", curve);
    snprintf(c.method, sizeof c.method, "%s", method);
    snprintf(c.label, sizeof c.label, "%s", label);
    snprintf(c.unit, sizeof c.unit, "%s", unit);
    c.tol = tol;
    c.d = 1.0;
    return c;
}

static void test_protocols(void)
{
    ob_tab_spec s;
    ob_err err = {""};
    ob_pub_cell c = cell("liu2002", "1", "liu2002_ex1", "tiller", "Til", "ctrl_points", 1e-3);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_BOUND &&
              s.split == OB_SPLIT_MID && s.d_factor == 1.0 && s.tol == 1e-3 && !s.single_piece,
          "Til: bound, mid");
    c = cell("liu2002", "2", "liu2002_ex2", "liu", "Liu", "ctrl_points", 1e-3);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_RADIAL &&
              s.split == OB_SPLIT_MAXERR && s.inflections,
          "Liu: radial, maxerr, inflections");
    CHECK(ob_tab_resolve(&c, OB_PROTO_RIGOROUS, &s, &err) == 0 && s.metric == OB_METRIC_HAUSDORFF &&
              s.split == OB_SPLIT_MID,
          "rigorous: hausdorff, mid");
    CHECK(ob_tab_resolve(&c, OB_PROTO_BEST, &s, &err) == 0 && s.metric == OB_METRIC_HAUSDORFF &&
              s.split == OB_SPLIT_OPTIMAL,
          "best: hausdorff, optimal (issue 19: the fewest pieces, errors equalized)");
    c = cell("ahn2023", "1", "liu2002_ex1", "ahn", "Our method", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_RADIAL &&
              s.d_factor == -1.0,
          "Ahn: radial, his normal points right");
    CHECK(ob_tab_resolve(&c, OB_PROTO_BEST, &s, &err) == 0 && s.d_factor == -1.0,
          "the sign of d is kept by the other protocols");
    c = cell("ahn2023", "1", "liu2002_ex1", "hoschek", "Hos", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_HAUSDORFF,
          "a method not parameterized like the base is not measured radially");
    /* the columns of Lee, Kim & Elber 1996 (Liu-Wang's [13], Ahn's [11]) */
    const ob_method *lsq = ob_method_find("bspline-lsq");
    static const struct {
        const char *source, *table, *method;
    } lee_lst[] = {{"liu2002", "1", "lstsq"}, {"liu2002", "2", "lstsq"}, {"ahn2023", "1", "hoschek"},
                   {"ahn2023", "2", "hoschek"}};
    for (int k = 0; k < 4; k++) {
        c = cell(lee_lst[k].source, lee_lst[k].table, "liu2002_ex1", lee_lst[k].method, "Lst", "ctrl_points", 1e-2);
        CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && lsq && s.method == lsq &&
                  s.metric == OB_METRIC_BOUND && s.split == OB_SPLIT_MID && !s.inflections &&
                  strstr(s.note, "Lee, Kim & Elber 1996"),
              "%s T%s Lst: Lee et al.'s least-squares B-spline, its own bound, no inflection split (%s)",
              lee_lst[k].source, lee_lst[k].table, s.note ? s.note : "");
        CHECK(ob_tab_resolve(&c, OB_PROTO_RIGOROUS, &s, &err) == 0 && s.method == lsq &&
                  s.metric == OB_METRIC_HAUSDORFF,
              "%s T%s Lst: the other protocols measure the same method", lee_lst[k].source, lee_lst[k].table);
    }
    c = cell("ahn2023", "2", "liu2002_ex2", "lee", "M2", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_RADIAL &&
              s.d_factor == -1.0 && !s.inflections,
          "Ahn's M2 (Lee et al.'s runs): his measure, no inflection split");
    c = cell("ahn2023", "2", "liu2002_ex2", "kim2018", "[26]", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.inflections,
          "Ahn's other columns: inflections first");
    c = cell("liu2002", "3", "liu2002_ex3", "lstsq", "Lst", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.method == ob_method_find("lstsq") &&
              s.metric == OB_METRIC_RADIAL && s.inflections,
          "Liu-Wang T3 Lst (their own runs): their normal-LSQ variant, their protocol");
    static const char *const lee_cols[] = {"Til", "Cob", "Coq", "Elb"};
    for (int k = 0; k < 4; k++)
        for (int t = 1; t <= 3; t++) {
            char tab[2] = {(char)('0' + t), 0};
            c = cell("liu2002", tab, "liu2002_ex1", "tiller", lee_cols[k], "ctrl_points", 1e-2);
            CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.metric == OB_METRIC_BOUND &&
                      s.inflections == (t == 3),
                  "Liu-Wang T%d %s: %s inflection split", t, lee_cols[k], t == 3 ? "their" : "no (IRIT's runs)");
        }
    c = cell("ahn2023", "1", "liu2002_ex1", "cl", "CL", "ctrl_points", 1e-2);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.method == NULL, "CL: no method");
    c = cell("zhao2017", "1", "zhao2017_quintic/C1", "zhao-rational", "Ours", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.single_piece && s.piece_a == 0.0 &&
              s.piece_b == 0.5 && strcmp(s.curve, "zhao2017_quintic") == 0 && s.metric == OB_METRIC_PARAM &&
              s.nset == 1 && s.set_value[0] == 4,
          "Zhao C1: one piece, first half, the error at the given parameter, four iterations");
    CHECK(ob_tab_resolve(&c, OB_PROTO_BEST, &s, &err) == 0 && s.split == OB_SPLIT_MID &&
              s.metric == OB_METRIC_HAUSDORFF,
          "error tables: best = rigorous");
    c = cell("zhao2017", "text", "zhao2017_septic", "zhao-rational/iter2", "2nd", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.nset == 1 &&
              strcmp(s.set_name[0], "iterations") == 0 && s.set_value[0] == 2 && s.metric == OB_METRIC_PARAM,
          "iter2 variant, the error at the given parameter");
    c = cell("zhao2017", "1", "zhao2017_quintic/C1@0.4", "lee", "Lee", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.piece_a == 0.0 && s.piece_b == 0.4,
          "C1@0.4: the first part cut at t = 0.4 (%s)", err.msg);
    c = cell("zhao2017", "1", "zhao2017_quintic/C2@0.7", "lee", "Lee", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == 0 && s.piece_a == 0.7 && s.piece_b == 1.0,
          "C2@0.7: the second part from t = 0.7 (%s)", err.msg);
    static const char *const bad_cuts[] = {"zhao2017_quintic/C1@1", "zhao2017_quintic/C2@0", "zhao2017_quintic/C1@x",
                                           "zhao2017_quintic/C1@0.5x", "zhao2017_quintic/C@0.5"};
    for (int k = 0; k < 5; k++) {
        c = cell("zhao2017", "1", bad_cuts[k], "lee", "Lee", "max_err", NAN);
        CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == -1 && strstr(err.msg, "piece"),
              "%s refused: %s", bad_cuts[k], err.msg);
    }
    c = cell("zhao2017", "1", "zhao2017_quintic/C9", "lee", "Lee", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == -1 && strstr(err.msg, "C9"), "unknown piece: %s",
          err.msg);
    c = cell("zhao2017", "text", "zhao2017_septic", "zhao-rational/turbo", "x", "max_err", NAN);
    CHECK(ob_tab_resolve(&c, OB_PROTO_PAPER, &s, &err) == -1 && strstr(err.msg, "turbo"),
          "unknown variant: %s", err.msg);
}

/* One row over one finished job. */
static int status_of(const char *unit, const char *pub, ob_status st, long ctrl, double err, double *ours)
{
    ob_tab_plan pl;
    memset(&pl, 0, sizeof pl);
    ob_tab_slot slot;
    memset(&slot, 0, sizeof slot);
    slot.job.status = st;
    slot.job.ctrl_points = ctrl;
    slot.job.max_err = err;
    pl.slots = &slot;
    pl.nslots = 1;
    ob_pub_cell c = cell("s", "1", "c", "m", "L", unit, 1e-2);
    snprintf(c.value_text, sizeof c.value_text, "%s", pub);
    c.value = atof(pub);
    ob_tab_row r;
    memset(&r, 0, sizeof r);
    r.cell = &c;
    r.slot = 0;
    return ob_tab_row_status(&pl, &r, ours);
}

static void test_status_rules(void)
{
    double v;
    CHECK(status_of("ctrl_points", "31", OB_OK, 31, 0, &v) == OB_TAB_MATCH && v == 31, "equal count");
    CHECK(status_of("ctrl_points", "31", OB_OK, 34, 0, &v) == OB_TAB_CLOSE, "34 vs 31: within 10 %%");
    CHECK(status_of("ctrl_points", "31", OB_OK, 35, 0, &v) == OB_TAB_DIFFERS, "35 vs 31: differs");
    CHECK(status_of("ctrl_points", "31", OB_LIMIT, 31, 0, &v) == OB_TAB_DIFFERS && v == 31,
          "a job stopped at a limit never matches");
    CHECK(status_of("ctrl_points", "31", OB_FAIL, 0, 0, &v) == OB_TAB_DIFFERS && isnan(v), "failed job: no figure");
    CHECK(status_of("max_err", "0.1030", OB_OK, 0, 0.10304, &v) == OB_TAB_MATCH, "0.10304 prints as 0.1030");
    CHECK(status_of("max_err", "0.1030", OB_OK, 0, 0.10306, &v) == OB_TAB_CLOSE, "0.10306 does not");
    CHECK(status_of("max_err", "2.9199e-5", OB_LIMIT, 0, 2.91994e-5, &v) == OB_TAB_MATCH,
          "exponent form; a one-piece job over its tolerance still has its error");
    CHECK(status_of("max_err", "1.24", OB_OK, 0, 1.5, &v) == OB_TAB_DIFFERS, "1.5 vs 1.24 differs");
}

/* The tables.md of three cells of one published table (tables --certify):
 * one certified within tol, one over tol, one whose certificate timed out.
 * md: the tables.md text (malloc'ed). */
static char *cert_md(void)
{
    static ob_pub_cell c[3];
    static const char *const label[3] = {"Til", "Cob", "Coq"};
    for (int k = 0; k < 3; k++) {
        c[k] = cell("liu2002", "1", "liu2002_ex1", label[k], label[k], "ctrl_points", 1e-3);
        snprintf(c[k].tol_text, sizeof c[k].tol_text, "1e-3");
        snprintf(c[k].value_text, sizeof c[k].value_text, "31");
        c[k].value = 31;
    }
    ob_pub_set pub = {c, 3, "test"};
    ob_tab_slot slot[3];
    ob_tab_row row[3];
    memset(slot, 0, sizeof slot);
    memset(row, 0, sizeof row);
    const double up[3] = {0.00090012, 0.0011, NAN};
    for (int k = 0; k < 3; k++) {
        slot[k].job.status = OB_OK;
        slot[k].job.ctrl_points = 31;
        slot[k].job.tol = 1e-3;
        slot[k].job.max_err = 0.0009;
        slot[k].job.cert_done = k < 2 ? OB_CERT_DONE : OB_CERT_TIMEOUT;
        slot[k].job.err_upper = up[k];
        slot[k].job.err_lower = k < 2 ? 0.0009 : NAN;
        row[k].cell = &c[k];
        row[k].proto = OB_PROTO_PAPER;
        row[k].slot = k;
        row[k].d_run = 1.0;
        row[k].spec.note = "the paper's reading";
    }
    ob_tab_plan *pl = calloc(1, sizeof *pl);
    pl->slots = slot;
    pl->nslots = 3;
    pl->rows = row;
    pl->nrows = 3;
    ob_tab_out out = {pl, &pub, "test", NULL, 0.0};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    CHECK(f && ob_tab_write_md(f, &out) == 0, "tables.md written");
    if (f)
        fclose(f);
    free(pl);
    return buf;
}

/* tables --certify: err_upper beside ours in the reproduced tables, the
 * counts, and the ok cells not certified within tol listed. */
static void test_cert_md(void)
{
    char *md = cert_md();
    CHECK(md && strstr(md, "| 1e-3 | 31 / 31 (0.000901) = | 31 / 31 (0.0011 !) = | 31 / 31 (no verdict) = |"),
          "err_upper (rounded up) beside ours; ! over tol; no verdict timed out: %s", md ? md : "");
    CHECK(md && strstr(md, "paper 1 of 3"), "counted: 1 of the 3 ok cells certified within tol");
    CHECK(md && strstr(md, "| source | table | column | row | protocol | ours | err_upper | err_lower | why |") &&
              strstr(md, "| liu2002 | 1 | Cob | 1e-3 | paper | 31 | 0.0011 | 0.0009 | over tol |") &&
              strstr(md, "| liu2002 | 1 | Coq | 1e-3 | paper | 31 |  |  | timed out |") &&
              !strstr(md, "| liu2002 | 1 | Til |"),
          "the ok cells not certified within tol listed");
    free(md);
}

int main(void)
{
    test_cert_md();
    test_parser();
    test_protocols();
    test_status_rules();
    return check_done();
}
