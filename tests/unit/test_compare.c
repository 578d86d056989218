/*
 * test_compare.c - `compare`: the Mann–Whitney U test against reference
 * values, the meta.json reader on good and malformed input, the results.csv
 * and samples.csv readers' errors, and the join / verdict rules.
 *
 * Reference p-values: the scipy.stats.mannwhitneyu documentation example
 * (males vs females: U = 17, exact p = 0.1111..., asymptotic p = 0.11134688...)
 * and values computed independently (enumerating every rank assignment for
 * the exact test; the normal formula with tie and continuity corrections).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/compare/compare.h"
#include "host/io/metajson.h"
#include "host/compare/ranktest.h"
#include "host/io/results_csv.h"

/* ---- rank test ---- */

static void test_ranktest(void)
{
    const double males[] = {19, 22, 16, 29, 24}, females[] = {20, 11, 17, 12};
    ob_mw_result r = ob_mann_whitney(males, 5, females, 4);
    CHECK(r.exact && r.u == 17, "scipy docs: exact, U = 17 (got %d, %g)", r.exact, r.u);
    CHECK_NEAR(r.p, 1.0 / 9, 1e-12, "scipy docs exact p");

    const double a[] = {1, 2, 3, 4}, b[] = {5, 6, 7, 8};
    r = ob_mann_whitney(a, 4, b, 4);
    CHECK(r.exact && r.u == 0, "1234 vs 5678: U = 0");
    CHECK_NEAR(r.p, 2.0 / 70, 1e-12, "{1,2,3,4} vs {5,6,7,8}: p = 2/70");
    CHECK_NEAR(ob_mann_whitney(b, 4, a, 4).p, 2.0 / 70, 1e-12, "symmetric");
    r = ob_mann_whitney(a, 3, b, 3);
    CHECK_NEAR(r.p, 0.1, 1e-12, "3 vs 3 separated: p = 0.1, the smallest possible");
    CHECK_NEAR(ob_mw_min_p(3, 3), 0.1, 1e-12, "min p 3 vs 3");
    CHECK_NEAR(ob_mw_min_p(4, 4), 2.0 / 70, 1e-12, "min p 4 vs 4");
    CHECK_NEAR(ob_mw_min_p(5, 5), 2.0 / 252, 1e-12, "min p 5 vs 5");

    const double x[] = {1.5, 3.2, 7.1, 4.4, 9.0}, y[] = {2.2, 5.5, 6.1, 8.8, 0.3, 10.5};
    r = ob_mann_whitney(x, 5, y, 6);
    CHECK(r.exact && r.u == 14, "interleaved U = 14 (got %g)", r.u);
    CHECK_NEAR(r.p, 0.9307359307359307, 1e-12, "interleaved exact p");

    /* the same pairs, large: 12 vs 10 exact */
    const double g1[] = {97.441, 105.114, 97.739, 96.849, 90.7,   97.867, 111.119, 104.241, 110.369,
                         102.489, 103.948, 101.853, 83.339, 108.553, 105.064, 104.988, 83.086, 82.561,
                         91.104, 95.318, 103.054, 99.541, 105.21, 93.578, 103.087};
    const double g2[] = {111.942, 101.389, 125.175, 113.566, 119.97,  101.797, 100.605, 104.56,
                         106.936, 114.321, 110.484, 103.526, 98.431,  102.794, 120.209, 99.921,
                         110.448, 112.265, 93.103,  108.485, 121.062, 87.856};
    r = ob_mann_whitney(g1, 12, g2, 10);
    CHECK(r.exact && r.u == 26, "12 vs 10: exact, U = 26 (got %g)", r.u);
    CHECK_NEAR(r.p, 0.024916260210377857, 1e-12, "12 vs 10 exact p");
    r = ob_mann_whitney(g1, 25, g2, 22);
    CHECK(!r.exact && r.u == 143, "25 vs 22: normal approximation, U = 143 (got %g)", r.u);
    CHECK_NEAR(r.p, 0.0050537216161704365, 1e-12, "25 vs 22 asymptotic p");

    /* ties: the normal approximation with the tie correction */
    const double t1[] = {1, 2, 2, 3, 5}, t2[] = {2, 3, 4, 4, 6, 7};
    r = ob_mann_whitney(t1, 5, t2, 6);
    CHECK(!r.exact && r.u == 6.5, "ties: approximation, U = 6.5 (got %g)", r.u);
    CHECK_NEAR(r.p, 0.13862587987892772, 1e-12, "ties p");

    const double same[] = {5, 5, 5};
    r = ob_mann_whitney(same, 3, same, 2);
    CHECK(r.p == 1, "all tied: p = 1 (got %g)", r.p);
    CHECK(isnan(ob_mann_whitney(a, 0, b, 4).p), "empty sample: p is NAN");
    const double withnan[] = {1, NAN};
    CHECK(isnan(ob_mann_whitney(withnan, 2, b, 4).p), "a NAN value: p is NAN");
    r = ob_mann_whitney(a, 1, b, 1);
    CHECK(r.exact && r.p == 1, "1 vs 1: p = 1");
}

/* ---- meta.json ---- */

static void expect_json_bad(const char *text, const char *where, const char *why)
{
    ob_json_flat f;
    ob_err err = {""};
    int rc = ob_json_flatten(text, strlen(text), "t.json", &f, &err);
    CHECK(rc == -1 && strstr(err.msg, where) && strstr(err.msg, why), "'%s': want '%s' '%s', got '%s'", text, where,
          why, err.msg);
    CHECK(f.n == 0 && f.v == NULL, "a failed parse leaves nothing");
    ob_json_free(&f);
}

static void test_json(void)
{
    const char good[] = "\xef\xbb\xbf{\n"
                        "  \"git_commit\": \"abc\\\"d\\u00e9\\ud83d\\ude00\",\n"
                        "  \"git_dirty\": true,\n"
                        "  \"opencl\": {\"device\": \"cpu-x\", \"build\": {\"s\": -0.5e-3}},\n"
                        "  \"seed\": null,\n"
                        "  \"method_params\": {\"tiller.k\": 10, \"zhao-rational.npfac\": 8},\n"
                        "  \"argv\": [\"./offbench\", \"run\", {\"a\": [1, 2]}],\n"
                        "  \"empty\": {},\n"
                        "  \"n\": 0\n"
                        "}\n";
    ob_json_flat f;
    ob_err err = {""};
    CHECK(ob_json_flatten(good, strlen(good), "g.json", &f, &err) == 0, "good json: %s", err.msg);
    const ob_json_entry *e = ob_json_get(&f, "git_commit");
    CHECK(e && e->type == OB_JSON_STRING && strcmp(e->value, "abc\"d\xc3\xa9\xf0\x9f\x98\x80") == 0 && e->line == 2,
          "escapes decoded: '%s'", e ? e->value : "(none)");
    e = ob_json_get(&f, "git_dirty");
    CHECK(e && e->type == OB_JSON_BOOL && strcmp(e->value, "true") == 0, "bool");
    e = ob_json_get(&f, "opencl.device");
    CHECK(e && strcmp(e->value, "cpu-x") == 0 && e->line == 4, "nested key path");
    e = ob_json_get(&f, "opencl.build.s");
    CHECK(e && e->type == OB_JSON_NUMBER && strcmp(e->value, "-0.5e-3") == 0, "number text kept");
    e = ob_json_get(&f, "seed");
    CHECK(e && e->type == OB_JSON_NULL, "null");
    CHECK(ob_json_get(&f, "method_params.tiller.k") && ob_json_get(&f, "method_params.zhao-rational.npfac"),
          "dotted keys under method_params");
    e = ob_json_get(&f, "argv");
    CHECK(e && e->type == OB_JSON_ARRAY && strcmp(e->value, "[\"./offbench\", \"run\", {\"a\": [1, 2]}]") == 0,
          "array kept raw: %s", e ? e->value : "(none)");
    e = ob_json_get(&f, "empty");
    CHECK(e && e->type == OB_JSON_OBJECT && strcmp(e->value, "{}") == 0, "empty object kept");
    CHECK(!ob_json_get(&f, "opencl") && !ob_json_get(&f, "nosuch"), "objects are flattened, not entries");
    CHECK(f.n == 10, "10 entries, got %d", f.n);
    ob_json_free(&f);
    ob_json_free(&f);

    ob_json_entry n1 = {"a", "10", OB_JSON_NUMBER, 1}, n2 = {"a", "1e1", OB_JSON_NUMBER, 1};
    ob_json_entry s1 = {"a", "10", OB_JSON_STRING, 1};
    CHECK(ob_json_same(&n1, &n2) && !ob_json_same(&n1, &s1) && !ob_json_same(&n1, NULL) && ob_json_same(NULL, NULL),
          "same: numbers by value, types differ, absent");

    expect_json_bad("", "t.json:1", "empty");
    expect_json_bad("[1, 2]", "t.json:1", "expected a JSON object");
    expect_json_bad("{\"a\": 1,\n}", "t.json:2", "expected a key");
    expect_json_bad("{\"a\" 1}", "t.json:1", "expected ':'");
    expect_json_bad("{'a': 1}", "t.json:1", "expected a key");
    expect_json_bad("{\"a\": 01}", "t.json:1", "leading zero");
    expect_json_bad("{\"a\": 1.}", "t.json:1", "after '.'");
    expect_json_bad("{\"a\": 1e}", "t.json:1", "exponent");
    expect_json_bad("{\"a\": NaN}", "t.json:1", "expected a value");
    expect_json_bad("{\"a\": nul}", "t.json:1", "expected a value");
    expect_json_bad("{\n\"a\": \"x}", "t.json:2", "unterminated string");
    expect_json_bad("{\"a\": \"x\ty\"}", "t.json:1", "control character");
    expect_json_bad("{\"a\": \"\\x\"}", "t.json:1", "invalid escape");
    expect_json_bad("{\"a\": \"\\u12\"}", "t.json:1", "four hex digits");
    expect_json_bad("{\"a\": \"\\ud800x\"}", "t.json:1", "surrogate");
    expect_json_bad("{\"a\": \"\\u0000\"}", "t.json:1", "\\u0000");
    expect_json_bad("{\"a\": \"\xff\"}", "t.json:1", "UTF-8");
    expect_json_bad("{\"a\": [1, 2,]}", "t.json:1", "expected a value");
    expect_json_bad("{\"a\": [1 2]}", "t.json:1", "expected ',' or ']'");
    expect_json_bad("{\"a\": 1 \"b\": 2}", "t.json:1", "expected ',' or '}'");
    expect_json_bad("{\"a\": 1}\n\nx", "t.json:3", "text after");
    expect_json_bad("{\"a\": 1, // c\n\"b\": 2}", "t.json:1", "expected a key");
    expect_json_bad("{\"a\": 1,\n\"b\": 2,\n\"a\": 3}", "t.json:3", "given twice (first on line 1)");
    expect_json_bad("{\"o\": {\"k\": 1}, \"o.k\": 2}", "t.json:1", "given twice");
    expect_json_bad("{\"a\": {\"b\": 1", "t.json:1", "expected ',' or '}'");
    char deep[200];
    size_t k = 0;
    k += (size_t)snprintf(deep, sizeof deep, "{\"a\": ");
    for (int i = 0; i < 40; i++)
        deep[k++] = '[';
    deep[k] = '\0';
    expect_json_bad(deep, "t.json:1", "nested deeper than 32");

    CHECK(ob_json_load("/nonexistent/meta.json", &f, &err) == -1 &&
              strstr(err.msg, "/nonexistent/meta.json: cannot open"),
          "missing file: %s", err.msg);
    ob_json_free(&f);
}

/* ---- results.csv / samples.csv ---- */

static const char HDR[] =
    "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family\n";

static void expect_csv_bad(const char *body, const char *where, const char *why)
{
    char text[2048];
    ob_err err = {""};
    snprintf(text, sizeof text, "%s%s", HDR, body);
    ob_res_table t;
    int rc = ob_res_parse(text, strlen(text), "r.csv", &t, &err);
    CHECK(rc == -1 && strstr(err.msg, where) && strstr(err.msg, why), "'%s': want '%s' '%s', got '%s'", body, where,
          why, err.msg);
    CHECK(t.n == 0 && t.v == NULL && t.text == NULL, "a failed parse leaves an empty table");
    ob_res_free(&t);
}

static void expect_samples_bad(const ob_res_table *t0, const char *text, const char *where, const char *why)
{
    ob_res_table t = *t0;
    ob_err err = {""};
    int rc = ob_res_attach_samples(&t, text, strlen(text), "s.csv", &err);
    CHECK(rc == -1 && strstr(err.msg, where) && strstr(err.msg, why), "samples: want '%s' '%s', got '%s'", where, why,
          err.msg);
    CHECK(t.rep_t == t0->rep_t && t.maxrep == t0->maxrep, "a failed attach changes nothing");
}

/* results.csv: a good file read (columns in any order, quotes, CRLF), rows found by job. */
static void csv_good_rows(ob_res_table *tp)
{
    ob_res_table t;
    ob_err err = {""};
    const char good[] = "family,message,curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,"
                        "status,fit_ns,eval_ns,extra\r\n"
                        "published,,c1,1,tiller,hausdorff,mid,0.1,10,3,3,0.05,ok,100,2000000,x\r\n"
                        "\r\n"
                        "published,\"singular, \"\"really\"\"\nsecond line\",c1,1,ahn,hausdorff,mid,1e-05,0,0,6,nan,"
                        "fail,0,0,y\n"
                        "published,,c1,-1,ahn,hausdorff,mid,0.00001,0,0,6,,skip,0,0,z";
    CHECK(ob_res_parse(good, strlen(good), "g.csv", &t, &err) == 0 && t.n == 3, "good csv: %s", err.msg);
    if (t.n == 3) {
        CHECK(strcmp(t.v[0].curve, "c1") == 0 && t.v[0].ctrl_points == 10 && t.v[0].max_err == 0.05 &&
                  t.v[0].fit_ns + t.v[0].eval_ns == 2000100 && t.v[0].line == 2,
              "first row");
        CHECK(strcmp(t.v[1].message, "singular, \"really\"\nsecond line") == 0, "quoted message: '%s'",
              t.v[1].message);
        CHECK(isnan(t.v[1].max_err) && isnan(t.v[2].max_err), "nan and empty max_err");
        CHECK(!t.has_joints && isnan(t.v[0].max_gap) && strcmp(t.v[0].continuity, "") == 0,
              "a file without the joint columns is read: none");
        CHECK(t.v[1].line == 4 && t.v[2].line == 6, "line numbers %d %d", t.v[1].line, t.v[2].line);
        ob_res_row key = t.v[1];
        key.tol_text = "0.00001";
        key.tol = 0.00001;
        CHECK(ob_res_find(&t, &key) == &t.v[1], "tol 1e-05 == 0.00001");
        key.d = -1;
        CHECK(ob_res_find(&t, &key) == &t.v[2], "d -1 is another job");
        key.method = "cobb";
        CHECK(ob_res_find(&t, &key) == NULL, "no such job");
    }
    *tp = t;
}

/* samples.csv attached to the good table; bad samples change nothing. */
static void csv_samples(ob_res_table *tp)
{
    ob_res_table t = *tp;
    ob_err err = {""};
    /* samples */
    const char sgood[] = "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns\n"
                         "c1,1,tiller,hausdorff,mid,0.1,1,10,1000\n"
                         "c1,1,tiller,hausdorff,mid,1e-1,3,20,1000\n"
                         "c1,1,ahn,hausdorff,mid,0.00001,2,0,5\n";
    CHECK(ob_res_attach_samples(&t, sgood, strlen(sgood), "s.csv", &err) == 0 && t.maxrep == 3,
          "good samples: %s", err.msg);
    if (t.maxrep == 3) {
        CHECK(t.v[0].nsamples == 2 && t.v[0].rep_t[0] == 1010 && isnan(t.v[0].rep_t[1]) && t.v[0].rep_t[2] == 1020,
              "reps of row 1");
        CHECK(t.v[1].nsamples == 1 && t.v[1].rep_t[1] == 5 && t.v[2].nsamples == 0, "reps of rows 2 and 3");
    }
    const char *sh = "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns\n";
    char s[512];
    snprintf(s, sizeof s, "%sc1,1,tiller,hausdorff,mid,0.1,1,10,1000\nc9,1,tiller,hausdorff,mid,0.1,1,10,1000\n", sh);
    expect_samples_bad(&t, s, "s.csv:3", "not in results.csv");
    snprintf(s, sizeof s, "%sc1,1,tiller,hausdorff,mid,0.1,2,10,1000\nc1,1,tiller,hausdorff,mid,0.1,2,10,9\n", sh);
    expect_samples_bad(&t, s, "s.csv:3", "repetition 2 of this job given twice");
    snprintf(s, sizeof s, "%sc1,1,tiller,hausdorff,mid,0.1,0,10,1000\n", sh);
    expect_samples_bad(&t, s, "s.csv:2", "rep is not");
    snprintf(s, sizeof s, "%sc1,1,tiller,hausdorff,mid,0.1,1.5,10,1000\n", sh);
    expect_samples_bad(&t, s, "s.csv:2", "rep is not");
    snprintf(s, sizeof s, "%sc1,1,tiller,hausdorff,mid,0.1,1,-10,1000\n", sh);
    expect_samples_bad(&t, s, "s.csv:2", "fit_ns and eval_ns");
    expect_samples_bad(&t, "curve,d,method,metric,split,tol,fit_ns,eval_ns\n", "s.csv:1", "no column 'rep'");
    ob_res_free(&t);
    ob_res_free(&t);
}

/* results.csv: the joint columns, optional, all three or none, values checked. */
static void csv_joint_columns(void)
{
    ob_res_table t;
    ob_err err = {""};
    /* the joint columns: optional, all three or none, values checked */
    const char jhdr[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,"
                        "eval_ns,message,family,offset_degree,offset_rational,max_gap,max_kink,continuity\n";
    char jt[1024];
    snprintf(jt, sizeof jt, "%sc1,1,zhao,hausdorff,mid,0.1,8,2,3,0.05,ok,1,1,,f,10,no,0.031,2.06,open\n"
             "c1,1,cobb,hausdorff,mid,0.1,4,1,3,0.05,ok,1,1,,f,10,no,,,\n", jhdr);
    CHECK(ob_res_parse(jt, strlen(jt), "j.csv", &t, &err) == 0 && t.n == 2 && t.has_joints,
          "joint columns: %s", err.msg);
    if (t.n == 2)
        CHECK(t.v[0].max_gap == 0.031 && t.v[0].max_kink == 2.06 && strcmp(t.v[0].continuity, "open") == 0 &&
                  isnan(t.v[1].max_gap) && isnan(t.v[1].max_kink) && strcmp(t.v[1].continuity, "") == 0,
              "joint values");
    ob_res_free(&t);
    struct { const char *row, *why; } jbad[] = {
        {"c1,1,zhao,hausdorff,mid,0.1,8,2,3,0.05,ok,1,1,,f,10,no,0.03,1,C2\n", "continuity is not"},
        {"c1,1,zhao,hausdorff,mid,0.1,8,2,3,0.05,ok,1,1,,f,10,no,-1,1,open\n", "max_gap and max_kink"},
        {"c1,1,zhao,hausdorff,mid,0.1,8,2,3,0.05,ok,1,1,,f,10,no,0.1,x,open\n", "max_gap and max_kink"},
    };
    for (size_t k = 0; k < sizeof jbad / sizeof jbad[0]; k++) {
        snprintf(jt, sizeof jt, "%s%s", jhdr, jbad[k].row);
        CHECK(ob_res_parse(jt, strlen(jt), "j.csv", &t, &err) == -1 && strstr(err.msg, "j.csv:2") &&
                  strstr(err.msg, jbad[k].why),
              "'%s': %s", jbad[k].row, err.msg);
        ob_res_free(&t);
    }
    const char half[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,"
                        "eval_ns,message,max_gap\nc1,1,zhao,hausdorff,mid,0.1,8,2,3,0.05,ok,1,1,,0.1\n";
    CHECK(ob_res_parse(half, strlen(half), "h.csv", &t, &err) == -1 && strstr(err.msg, "h.csv:1") &&
              strstr(err.msg, "come together"),
          "only max_gap: %s", err.msg);
    ob_res_free(&t);
}

/* results.csv: bad rows, bad headers, empty, garbage and missing files, each named. */
static void csv_bad(void)
{
    ob_res_table t;
    ob_err err = {""};
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.05,ok,1,1,,f\nc,1,m,hausdorff,mid,0.1,10,3,3\n", "r.csv:3",
                   "9 fields, the header has 15");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.05,ok,1,1,\"oops,f\n", "r.csv:2", "unterminated quote");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.05,ok,1,1,\"a\"b,f\n", "r.csv:2", "after the closing quote");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.05,ok,1,1,a\"b,f\n", "r.csv:2", "quote inside");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,ten,3,3,0.05,ok,1,1,,f\n", "r.csv:2", "ctrl_points");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,-1,3,3,0.05,ok,1,1,,f\n", "r.csv:2", "ctrl_points");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,big,ok,1,1,,f\n", "r.csv:2", "max_err");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,-0.5,ok,1,1,,f\n", "r.csv:2", "max_err");
    expect_csv_bad("c,x,m,hausdorff,mid,0.1,10,3,3,0.5,ok,1,1,,f\n", "r.csv:2", "d is not");
    expect_csv_bad("c,1,m,hausdorff,mid,inf,10,3,3,0.5,ok,1,1,,f\n", "r.csv:2", "tol is not");
    expect_csv_bad(",1,m,hausdorff,mid,0.1,10,3,3,0.5,ok,1,1,,f\n", "r.csv:2", "must not be empty");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.5,good,1,1,,f\n", "r.csv:2", "status");
    /* an error that is not finite is never ok (ob_err_can_pass); other statuses may carry one */
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,inf,ok,1,1,,f\n", "r.csv:2", "status ok with a max_err");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.05,ok,1,1,,f\nc,-1,m,hausdorff,mid,0.1,10,3,3,Infinity,ok,1,1,,f\n",
                   "r.csv:3", "status ok with a max_err");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,nan,ok,1,1,,f\n", "r.csv:2", "never ok");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,,ok,1,1,,f\n", "r.csv:2", "never ok");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,1e999,ok,1,1,,f\n", "r.csv:2", "never ok");
    {
        const char lim[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,"
                           "eval_ns,message,family\nc,1,m,hausdorff,mid,0.1,10,3,3,inf,limit,1,1,,f\n"
                           "c,2,m,hausdorff,mid,0.1,0,0,0,,fail,1,1,,f\nc,3,m,hausdorff,mid,0.1,0,0,0,nan,skip,1,1,,f\n";
        CHECK(ob_res_parse(lim, strlen(lim), "l.csv", &t, &err) == 0 && t.n == 3 && isinf(t.v[0].max_err),
              "limit with inf, fail and skip without an error are read: %s", err.msg);
        ob_res_free(&t);
    }
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.5,ok,1,,,f\n", "r.csv:2", "fit_ns and eval_ns");
    expect_csv_bad("c,1,m,hausdorff,mid,0.1,10,3,3,0.5,ok,1,1,,f\n\nc,1.0,m,hausdorff,mid,1e-1,9,3,3,0.5,ok,1,1,,f\n",
                   "r.csv:4", "duplicate job c,1.0,m,hausdorff,mid,1e-1 (first on line 2)");
    const char nocol[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,status,fit_ns,eval_ns,"
                         "message\n";
    CHECK(ob_res_parse(nocol, strlen(nocol), "h.csv", &t, &err) == -1 && strstr(err.msg, "h.csv:1") &&
              strstr(err.msg, "'max_err'"),
          "missing column: %s", err.msg);
    const char twice[] = "curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,"
                         "eval_ns,message,tol\n";
    CHECK(ob_res_parse(twice, strlen(twice), "h.csv", &t, &err) == -1 && strstr(err.msg, "appears twice"),
          "repeated column: %s", err.msg);
    CHECK(ob_res_parse("", 0, "e.csv", &t, &err) == -1 && strstr(err.msg, "e.csv:1: empty"), "empty: %s", err.msg);
    const char garbage[] = "\x7f" "ELF\x02\x01\x01\n\x00\x01garbage";
    CHECK(ob_res_parse(garbage, sizeof garbage - 1, "b.csv", &t, &err) == -1 && strstr(err.msg, "b.csv:1"),
          "garbage: %s", err.msg);
    CHECK(ob_res_parse(HDR, strlen(HDR), "h.csv", &t, &err) == 0 && t.n == 0, "header only: no rows");
    ob_res_free(&t);
    CHECK(ob_res_load("/nonexistent/results.csv", &t, &err) == -1 && strstr(err.msg, "cannot open"),
          "missing file: %s", err.msg);
}

/* results.csv and samples.csv, read and refused. */
static void test_csv(void)
{
    ob_res_table t;
    csv_good_rows(&t);
    csv_samples(&t);
    csv_joint_columns();
    csv_bad();
}


/* ---- join and verdicts ---- */

static const char META[] =
    "{\"compiler\": \"gcc 12\", \"cflags\": \"-O2\", \"backend\": \"cpu\", \"opencl\": null, \"omp_threads\": 2,"
    " \"seed\": null, \"samples_per_segment\": %d, \"max_depth\": 40, \"max_segments\": 20000,"
    " \"inflection_split\": true, \"method_params\": {\"tiller.k\": %s, \"zhao.n\": %s},"
    " \"method_versions\": {\"tiller\": %d, \"ahn\": 1}, \"reps\": 1,"
    " \"machine\": {\"name\": \"m\", \"id\": \"%s\", \"logical_cores\": 2, \"memory_mib\": %ld},"
    " \"host\": {\"cores_used\": 2, \"loadavg_max\": %.2f}}";

/* A meta.json (META): machine_id NULL is 00000000000000aa, memory_mib 0
 * is 1000 (MiB), load the largest load average (on 2 cores). */
typedef struct {
    int samples, tiller_version;
    const char *tiller_k, *zhao_n, *compiler;
    const char *machine_id;
    long memory_mib;
    double load;
} meta_spec;

static void load(ob_cmp_side *s, const char *label, const char *rows, const meta_spec *m, const char *samples)
{
    char text[8192];
    ob_err err = {""};
    memset(s, 0, sizeof *s);
    s->label = label;
    snprintf(s->results_path, sizeof s->results_path, "%s.csv", label);
    snprintf(text, sizeof text, "%s%s", HDR, rows);
    CHECK(ob_res_parse(text, strlen(text), s->results_path, &s->res, &err) == 0, "rows: %s", err.msg);
    if (m) {
        snprintf(text, sizeof text, META, m->samples, m->tiller_k, m->zhao_n, m->tiller_version,
                 m->machine_id ? m->machine_id : "00000000000000aa", m->memory_mib ? m->memory_mib : 1000L, m->load);
        if (m->compiler) {
            char *c = strstr(text, "gcc 12");
            memcpy(c, m->compiler, 6);
        }
        CHECK(ob_json_flatten(text, strlen(text), "meta.json", &s->meta, &err) == 0, "meta: %s", err.msg);
        s->has_meta = 1;
    }
    if (samples) {
        snprintf(text, sizeof text, "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns\n%s", samples);
        CHECK(ob_res_attach_samples(&s->res, text, strlen(text), "samples.csv", &err) == 0, "samples: %s",
              err.msg);
        s->has_samples = s->res.maxrep > 0;
    }
}

/* Runs a comparison; returns the exit status and keeps the result in *r. */
static int run(const ob_cmp_side *b, const ob_cmp_side *n, const ob_cmp_opts *o, ob_cmp_result *r)
{
    ob_err err = {""};
    memset(r, 0, sizeof *r);
    int rc = ob_cmp_context(b, n, o, r, &err);
    if (rc == 0 && r->incomparable.n == 0)
        rc = ob_cmp_rows(b, n, o, r, &err);
    CHECK(rc == 0, "comparison: %s", err.msg);
    /* both reports render */
    FILE *devnull = fopen("/dev/null", "w");
    if (devnull) {
        CHECK(ob_cmp_write_md(devnull, b, n, o, r) == 0 && ob_cmp_write_csv(devnull, b, n, o, r) == 0, "reports");
        fclose(devnull);
    }
    return ob_cmp_status(r);
}

static const ob_change *find_change(const ob_cmp_result *r, ob_ch_kind k, const char *field, const char *method)
{
    for (int i = 0; i < r->nch; i++) {
        const ob_res_row *row = r->ch[i].base ? r->ch[i].base : r->ch[i].nw;
        if (r->ch[i].kind == k && strcmp(r->ch[i].field, field) == 0 && strcmp(row->method, method) == 0)
            return &r->ch[i];
    }
    return NULL;
}

static int has_text(const ob_strlist *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strstr(l->v[i], s))
            return 1;
    return 0;
}

/* Two rows: tiller and ahn at tol 0.1; each field overridable. */
static void rows2(char *buf, size_t len, const char *t_status, int t_cp, const char *t_err, int t_ns,
                  const char *a_status, int a_cp, const char *a_err, int a_ns)
{
    snprintf(buf, len,
             "c1,1,tiller,hausdorff,mid,0.1,%d,3,3,%s,%s,0,%d,,f\n"
             "c1,1,ahn,hausdorff,mid,0.1,%d,2,6,%s,%s,0,%d,,f\n",
             t_cp, t_err, t_status, t_ns, a_cp, a_err, a_status, a_ns);
}

/* compare: identical results give 0 and geometric means 1. */
static void verdicts_identical(const ob_cmp_side *b, const char *rb, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    load(&n, "NEW", rb, m, NULL);
    CHECK(run(b, &n, &o, &r) == 0 && r.joined == 2 && r.nch == 0 && r.checked && r.timing, "identical: 0");
    CHECK(r.nms == 2 && r.ms[0].gm_cp == 1 && r.ms[0].gm_t == 1 && r.t_judged == 2 && r.t_threshold_only == 2,
          "identical: geometric means 1, timings judged by threshold");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: ctrl_points up is a regression, down with a larger error an improvement. */
static void verdicts_ctrl_points(const ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    char rn[1024];

    /* more control points: a regression */
    rows2(rn, sizeof rn, "ok", 11, "0.05", 2000000, "ok", 13, "0.04", 3000000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.q_reg == 1 && find_change(&r, OB_CH_REGRESSION, "ctrl_points", "tiller"),
          "ctrl_points 10 -> 11: regression");
    CHECK(r.ms[0].regressions == 1 && fabs(r.ms[0].gm_cp - 1.1) < 1e-12, "tiller gm ctrl_points 1.1");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);

    /* fewer control points with a larger error: an improvement */
    rows2(rn, sizeof rn, "ok", 9, "0.09", 2000000, "ok", 13, "0.04", 3000000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 0 && r.q_imp == 1 && find_change(&r, OB_CH_IMPROVEMENT, "ctrl_points", "tiller"),
          "ctrl_points 10 -> 9 with a larger error: improvement");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: max_err beyond the tolerance, within it, --err-rtol, smaller. */
static void verdicts_max_err(const ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    char rn[1024];

    /* max_err: beyond the tolerance, within it */
    rows2(rn, sizeof rn, "ok", 10, "0.0500001", 2000000, "ok", 13, "0.04000000000000001", 3000000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.q_reg == 1 && find_change(&r, OB_CH_REGRESSION, "max_err", "tiller") &&
              r.nch == 1,
          "max_err up by 2e-6 relative: regression; by 2.5e-16: nothing");
    ob_cmp_result_free(&r);
    o.err_rtol = 1e-3;
    CHECK(run(b, &n, &o, &r) == 0 && r.nch == 0, "--err-rtol 1e-3: no change");
    ob_cmp_result_free(&r);
    o = ob_cmp_defaults();
    ob_cmp_side_free(&n);
    rows2(rn, sizeof rn, "ok", 10, "0.04", 2000000, "ok", 13, "0.04", 3000000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 0 && find_change(&r, OB_CH_IMPROVEMENT, "max_err", "tiller"), "smaller max_err");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: status changes; the base side is reloaded here and freed. */
static void verdicts_status(ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    char rn[1024], rs[1024];

    /* status changes */
    rows2(rn, sizeof rn, "fail", 0, "", 2000000, "limit", 13, "0.04", 3000000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.q_reg == 2 && find_change(&r, OB_CH_REGRESSION, "status", "tiller") &&
              find_change(&r, OB_CH_REGRESSION, "status", "ahn") && r.t_judged == 0,
          "ok -> fail and ok -> limit: regressions, timings not judged");
    ob_cmp_result_free(&r);
    CHECK(run(&n, b, &o, &r) == 0 && r.q_imp == 2, "fail -> ok, limit -> ok: improvements");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(b);
    rows2(rs, sizeof rs, "skip", 0, "", 2000000, "fail", 0, "", 3000000);
    load(b, "BASE", rs, m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.q_reg == 2, "skip -> fail, fail -> limit: other changes are regressions");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
    load(&n, "NEW", rs, m, NULL);
    CHECK(run(b, &n, &o, &r) == 0 && r.nch == 0, "skip -> skip, fail -> fail: nothing");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(b);
    ob_cmp_side_free(&n);
}

/* compare: a missing row is 1, a new row is reported. */
static void verdicts_missing_new(const ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;

    /* missing and new rows */
    load(&n, "NEW", "c1,1,tiller,hausdorff,mid,0.1,10,3,3,0.05,ok,0,2000000,,f\n"
                    "c1,1,tiller,hausdorff,mid,0.01,31,3,3,0.005,ok,0,2000000,,f\n", m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.n_missing == 1 && r.n_new == 1 && r.joined == 1 &&
              find_change(&r, OB_CH_MISSING, "status", "ahn") && find_change(&r, OB_CH_NEW, "status", "tiller"),
          "a missing row: 1; a new row is reported");
    ob_cmp_result_free(&r);
    CHECK(run(&n, b, &o, &r) == 1 && r.n_missing == 1 && r.n_new == 1, "reversed: still one missing");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: timing without samples: the threshold, the floor, --no-timing. */
static void verdicts_timing_threshold(const ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    char rn[1024];

    /* timing without samples: the threshold decides; the floor; */
    rows2(rn, sizeof rn, "ok", 10, "0.05", 2300000, "ok", 13, "0.04", 2500000);
    load(&n, "NEW", rn, m, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && r.t_reg == 1 && r.t_imp == 1 && r.t_threshold_only == 2 &&
              find_change(&r, OB_CH_REGRESSION, "time", "tiller") && find_change(&r, OB_CH_IMPROVEMENT, "time", "ahn"),
          "timing +15%%: regression, -17%%: improvement");
    CHECK(r.m_reg == 1 && r.ms[0].verdict == 1 && r.m_imp == 1 && r.ms[1].verdict == -1, "per method verdicts");
    ob_cmp_result_free(&r);
    o.time_threshold = 0.2;
    CHECK(run(b, &n, &o, &r) == 0 && r.nch == 0, "--time-threshold 0.2: no change");
    ob_cmp_result_free(&r);
    o = ob_cmp_defaults();
    o.time_floor_ns = 2500000;
    CHECK(run(b, &n, &o, &r) == 0 && r.t_judged == 1 && isnan(r.ms[0].gm_t), "below the floor: not judged");
    ob_cmp_result_free(&r);
    o = ob_cmp_defaults();
    o.no_timing = 1;
    CHECK(run(b, &n, &o, &r) == 0 && r.t_judged == 0 && !r.timing, "--no-timing");
    ob_cmp_result_free(&r);
    o = ob_cmp_defaults();
    ob_cmp_side_free(&n);
}

/* compare: a different timing context leaves quality compared, timings not. */
static void verdicts_timing_context(const ob_cmp_side *b, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    char rn[1024];

    /* timing context differs: timings not compared, quality still is */
    meta_spec m1 = *m;
    m1.compiler = "gcc 13";
    rows2(rn, sizeof rn, "ok", 11, "0.05", 9000000, "ok", 13, "0.04", 3000000);
    load(&n, "NEW", rn, &m1, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && !r.timing && r.t_judged == 0 && r.q_reg == 1 &&
              has_text(&r.timing_diffs, "compiler: gcc 12 vs gcc 13"),
          "compiler differs: only quality compared");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: not comparable (3) or comparable with a note, every reason named. */
static void verdicts_incomparable(const ob_cmp_side *b, const char *rb, const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;

    /* not comparable */
    meta_spec m2 = *m;
    m2.samples = 64;
    load(&n, "NEW", rb, &m2, NULL);
    CHECK(run(b, &n, &o, &r) == 3 && has_text(&r.incomparable, "samples_per_segment 256 vs 64"),
          "samples_per_segment differs: 3");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
    m2 = *m;
    m2.tiller_k = "12";
    m2.tiller_version = 2;
    load(&n, "NEW", rb, &m2, NULL);
    CHECK(run(b, &n, &o, &r) == 3 && has_text(&r.incomparable, "method_params.tiller.k 10 vs 12") &&
              has_text(&r.incomparable, "method_versions.tiller 1 vs 2") && r.incomparable.n == 2,
          "a parameter and a version of a method both ran: 3, every reason");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
    m2 = *m;
    m2.zhao_n = "16";
    load(&n, "NEW", rb, &m2, NULL);
    CHECK(run(b, &n, &o, &r) == 0 && has_text(&r.notes, "1 method_params key(s) differ for methods not run"),
          "a parameter of a method neither ran: comparable, with a note");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
    load(&n, "NEW", "c1,1,tiller,hausdorff,mid,0.1,10,3,3,0.05,ok,0,2000000,,f\n", NULL, NULL);
    CHECK(run(b, &n, &o, &r) == 1 && !r.checked && has_text(&r.notes, "no meta.json beside NEW") && !r.timing &&
              r.tstate == OB_TIMING_MACHINE && has_text(&r.timing_diffs, "NEW has no meta.json: the machine is unknown"),
          "no meta.json on one side: quality compared, with a note; timings not judged (the machine is unknown)");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
    load(&n, "NEW", "c1,1,tiller,radial,mid,0.1,10,3,3,0.05,ok,0,2000000,,f\n"
                    "c1,1,ahn,radial,greedy,0.1,10,3,3,0.05,ok,0,2000000,,f\n", m, NULL);
    CHECK(run(b, &n, &o, &r) == 3 && has_text(&r.incomparable, "metric differs: hausdorff vs radial") &&
              !has_text(&r.incomparable, "split differs"),
          "no metric in common: 3 (splits share mid)");
    ob_cmp_result_free(&r);
    ob_cmp_side_free(&n);
}

/* compare: timing with 3 and 5 repetitions: the rank test decides. */
static void verdicts_rank_test(const meta_spec *m)
{
    ob_cmp_opts o = ob_cmp_defaults();
    ob_cmp_side n;
    ob_cmp_result r;
    ob_cmp_side b;
    char rb[1024], rn[1024];

    /* timing with repetitions: the rank test decides */
    char sb[2048], sn[2048];
    const char *key[2] = {"c1,1,tiller,hausdorff,mid,0.1", "c1,1,ahn,hausdorff,mid,0.1"};
    for (int reps = 3; reps <= 5; reps += 2) {
        size_t kb = 0, kn = 0;
        for (int j = 0; j < 2; j++)
            for (int i = 1; i <= reps; i++) {
                /* tiller: new clearly slower; ahn: new 20% slower but noisy, overlapping */
                double tb = j == 0 ? 2000000 + 1000 * i : 3000000 + 900000 * (i % 2);
                double tn = j == 0 ? 2500000 + 1000 * i : 3600000 + 900000 * (i % 2) - 1000 * i;
                kb += (size_t)snprintf(sb + kb, sizeof sb - kb, "%s,%d,0,%.0f\n", key[j], i, tb);
                kn += (size_t)snprintf(sn + kn, sizeof sn - kn, "%s,%d,0,%.0f\n", key[j], i, tn);
            }
        rows2(rb, sizeof rb, "ok", 10, "0.05", 2000000, "ok", 13, "0.04", 3000000);
        rows2(rn, sizeof rn, "ok", 10, "0.05", 2500000, "ok", 13, "0.04", 3600000);
        load(&b, "BASE", rb, m, sb);
        load(&n, "NEW", rn, m, sn);
        int st = run(&b, &n, &o, &r);
        const ob_change *c = find_change(&r, OB_CH_REGRESSION, "time", "tiller");
        if (reps == 5) {
            CHECK(st == 1 && r.t_tested == 2 && r.t_reg == 1 && c && fabs(c->p - 2.0 / 252) < 1e-12 &&
                      !find_change(&r, OB_CH_REGRESSION, "time", "ahn"),
                  "5 reps: tiller slower (p = 2/252), ahn's 20%% not significant");
            CHECK(r.ms[0].reps_base == 5 && fabs(r.ms[0].p - 2.0 / 252) < 1e-12 && r.ms[0].verdict == 1 &&
                      r.ms[1].verdict == 0 && r.ms[1].p > 0.05,
                  "per-method rank test on the totals per repetition");
            CHECK(!has_text(&r.notes, "repetition") && r.tstate == OB_TIMING_JUDGED, "no note with 5 reps");
            const ob_method_sum *t = &r.ms[0], *a = &r.ms[1];
            CHECK(strcmp(t->timing, "slower") == 0 && t->ci_lo <= t->t_est && t->t_est <= t->ci_hi &&
                      fabs(t->t_est - 2502000.0 / 2002000.0) < 0.01 && t->t_base == 2003000 && t->t_new == 2503000,
                  "tiller: the HL estimate (about 1.25) inside its own interval, the medians of the totals");
            CHECK(strcmp(a->timing, "noisy") == 0 && a->ci_lo < 1 && a->t_est > 1.1 && a->not_judged,
                  "ahn: 20%% up but its interval reaches below 1: noisy, not judged");
        } else {
            CHECK(st == 3 && r.t_tested == 0 && r.t_reg == 0 && r.tstate == OB_TIMING_FEW_REPS && r.need_reps == 4 &&
                      has_text(&r.strict, "too few repetitions to judge timing: need 4 per side"),
                  "3 reps: nothing could be significant: exit 3, saying how many are needed");
        }
        ob_cmp_result_free(&r);
        ob_cmp_side_free(&b);
        ob_cmp_side_free(&n);
    }
}

/* compare: timings are judged only between runs of one machine (id, cores,
 * memory within 5 %), whatever their load (a note says it); quality is
 * judged whatever the machine. */
static void verdicts_machine(const ob_cmp_side *b, const meta_spec *m)
{
    static const struct {
        const char *id;
        long mem;
        double load;
        ob_timing_state st;
        const char *why;
    } c[] = {
        {NULL, 0, 0, OB_TIMING_JUDGED, NULL},
        {"00000000000000bb", 0, 0, OB_TIMING_MACHINE, "baseline from machine 'm' (id 00000000000000aa), this is 'm' "
                                                      "(id 00000000000000bb)"},
        {NULL, 1040, 0, OB_TIMING_JUDGED, NULL},
        {NULL, 1100, 0, OB_TIMING_MACHINE, "machine 'm' changed: memory_mib 1000 vs 1100"},
        {NULL, 0, 2.0, OB_TIMING_JUDGED, NULL},
        /* a load above the cores no longer refuses (issue 46): judged, noted */
        {NULL, 0, 2.5, OB_TIMING_JUDGED, NULL},
    };
    char rn[1024];
    rows2(rn, sizeof rn, "ok", 11, "0.05", 9000000, "ok", 13, "0.04", 3000000);
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        ob_cmp_opts o = ob_cmp_defaults();
        ob_cmp_side n;
        ob_cmp_result r;
        meta_spec mn = *m;
        mn.machine_id = c[i].id;
        mn.memory_mib = c[i].mem;
        mn.load = c[i].load;
        load(&n, "NEW", rn, &mn, NULL);
        const int st = run(b, &n, &o, &r);
        CHECK(st == 1 && r.q_reg == 1 && r.tstate == c[i].st && r.timing == (c[i].st == OB_TIMING_JUDGED) &&
                  (!c[i].why || has_text(&r.timing_diffs, c[i].why)) && (c[i].why || r.t_reg == 1),
              "machine case %zu: quality judged, timing state %d (want %d) %s", i, (int)r.tstate, (int)c[i].st,
              c[i].why ? c[i].why : "");
        char text[2048];
        ob_cmp_timing_text(b, &n, &o, &r, 0, text, sizeof text);
        CHECK(c[i].why ? strstr(text, c[i].why) && strncmp(text, "not judged", 10) == 0
                       : strncmp(text, "judged: the same machine 'm' (id 00000000000000aa)", 50) == 0,
              "machine case %zu: the timing line: %s", i, text);
        CHECK(!(c[i].load > 2) || has_text(&r.notes, "NEW's load average reached 2.50 on its 2 cores: timings judged"),
              "machine case %zu: the load is a note", i);
        ob_cmp_result_free(&r);
        ob_cmp_side_free(&n);
    }
}

/* compare --methods: the selection is by whole names. */
static void test_method_selection(void)
{
    ob_cmp_opts o = ob_cmp_defaults();
    CHECK(ob_cmp_method_selected(&o, "tiller"), "no --methods: every method");
    o.methods = "tiller,ahn";
    CHECK(ob_cmp_method_selected(&o, "tiller") && ob_cmp_method_selected(&o, "ahn") &&
              !ob_cmp_method_selected(&o, "till") && !ob_cmp_method_selected(&o, "tiller,ahn") &&
              !ob_cmp_method_selected(&o, "zhao"),
          "--methods tiller,ahn: those two, whole names only");
}

/* A side with the cubic-opt row rows and the meta.json whose method_params
 * are params (a JSON object body). */
static void load_params(ob_cmp_side *s, const char *label, const char *params)
{
    char text[2048];
    ob_err err = {""};
    load(s, label, "c1,1,cubic-opt,hausdorff,greedy,0.01,7,2,3,0.002,ok,0,2000000,,f\n", NULL, NULL);
    snprintf(text, sizeof text,
             "{\"compiler\": \"gcc 12\", \"cflags\": \"-O2\", \"backend\": \"cpu\", \"opencl\": null,"
             " \"omp_threads\": 2, \"seed\": null, \"samples_per_segment\": 256, \"max_depth\": 40,"
             " \"max_segments\": 20000, \"inflection_split\": true, \"method_params\": {%s},"
             " \"method_versions\": {\"cubic-opt\": 1}, \"reps\": 1}",
             params);
    CHECK(ob_json_flatten(text, strlen(text), "meta.json", &s->meta, &err) == 0, "meta: %s", err.msg);
    s->has_meta = 1;
}

/* compare: a parameter that one run's meta.json does not have (a parameter
 * added since that run) is that parameter's default in this build: equal
 * to it, comparable with a note; any other value, or a key this build does
 * not know, not comparable. */
static void test_param_added(void)
{
    static const struct {
        const char *base, *nw;
        int status;
        const char *text;
    } c[] = {
        {"\"cubic-opt.samples\": 24", "\"cubic-opt.samples\": 24, \"cubic-opt.split\": 0", 0,
         "method_params.cubic-opt.split is absent in BASE: taken as its default 0"},
        {"\"cubic-opt.samples\": 24, \"cubic-opt.split\": 0", "\"cubic-opt.samples\": 24", 0,
         "method_params.cubic-opt.split is absent in NEW: taken as its default 0"},
        {"\"cubic-opt.samples\": 24", "\"cubic-opt.samples\": 24, \"cubic-opt.split\": 1", 3,
         "method_params.cubic-opt.split (absent) vs 1"},
        {"\"cubic-opt.samples\": 24", "\"cubic-opt.samples\": 24, \"cubic-opt.nosuch\": 0", 3,
         "method_params.cubic-opt.nosuch (absent) vs 0"},
    };
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        ob_cmp_opts o = ob_cmp_defaults();
        ob_cmp_side b, n;
        ob_cmp_result r;
        load_params(&b, "BASE", c[i].base);
        load_params(&n, "NEW", c[i].nw);
        const int st = run(&b, &n, &o, &r);
        CHECK(st == c[i].status && has_text(c[i].status ? &r.incomparable : &r.notes, c[i].text),
              "parameter on one side only, case %zu: status %d (want %d), \"%s\"", i, st, c[i].status, c[i].text);
        ob_cmp_result_free(&r);
        ob_cmp_side_free(&n);
        ob_cmp_side_free(&b);
    }
}

/* compare: the verdicts, case by case; the base side is shared as it was loaded. */
static void test_verdicts(void)
{
    const meta_spec m0 = {256, 1, "10", "8", NULL, NULL, 0, 0};
    ob_cmp_side b;
    char rb[1024];

    rows2(rb, sizeof rb, "ok", 10, "0.05", 2000000, "ok", 13, "0.04", 3000000);
    load(&b, "BASE", rb, &m0, NULL);
    verdicts_identical(&b, rb, &m0);
    verdicts_ctrl_points(&b, &m0);
    verdicts_max_err(&b, &m0);
    verdicts_status(&b, &m0);
    rows2(rb, sizeof rb, "ok", 10, "0.05", 2000000, "ok", 13, "0.04", 3000000);
    load(&b, "BASE", rb, &m0, NULL);
    verdicts_missing_new(&b, &m0);
    verdicts_timing_threshold(&b, &m0);
    verdicts_timing_context(&b, &m0);
    verdicts_machine(&b, &m0);
    verdicts_incomparable(&b, rb, &m0);
    ob_cmp_side_free(&b);
    verdicts_rank_test(&m0);
}

int main(void)
{
    test_ranktest();
    test_json();
    test_csv();
    test_verdicts();
    test_param_added();
    test_method_selection();
    return check_done();
}
