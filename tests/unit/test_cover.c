/*
 * test_cover.c - what `measure` requires of an approximation and what it
 * measures of the whole (issue 36):
 *   - the coverage check (host/measure/cover.c) on approximations made by
 *     real jobs (jobview + ob_approx_from_job, as --export makes them):
 *     every method's valid approximation passes, with read links exactly
 *     and matched by projection; the variants fail or are noted where they
 *     are: one piece of many, one piece 50 times, a piece missing in the
 *     middle, a piece twice, two pieces swapped, the list reversed, an
 *     overlap, a joint pulled apart (beyond and within the tolerance),
 *     pieces reversed, pieces of another curve, a link to a segment the
 *     curve lacks;
 *   - the whole-vs-whole Hausdorff distance (host/measure/whole.c) against
 *     an independent brute force written here (dense polylines of both
 *     wholes, the nearest chord over all of them refined on the curve by
 *     golden section, the curves evaluated by testlib's Bernstein sums,
 *     not the library's), and
 *     against the per-piece maximum, which bounds it from above; a
 *     constructed case where the two differ by construction;
 *   - param does not apply to pieces matched by projection.
 * Run with -v for the figures.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"
#include "host/io/approx.h"
#include "host/measure/measure.h"
#include "host/view/jobview.h"
#include "methods/driver/joints.h"
#include "tests/testlib.h"

static int verbose;

/* ---- jobs ------------------------------------------------------------------------ */

typedef struct {
    ob_jobview v;
    ob_approx ap;
} jobap;

/* Runs one job (hausdorff, mid, CPU, one thread) and takes its pieces with
 * their links, as --export does.  0 when it produced an approximation. */
static int job_open(jobap *j, const char *curve, double d, const char *method, const char *tol)
{
    const char *argv[] = {"test", "--curve", curve, "--methods", method, "--tols", tol, "--metric", "hausdorff",
                          "--split", "mid", "--backend", "cpu", "--threads", "1", NULL};
    memset(j, 0, sizeof *j);
    int rc = ob_run_opts_parse((int)(sizeof argv / sizeof *argv) - 1, (char **)argv, &j->v.o) ? 2
             : ob_jobview_open(&j->v, "test", 1, d);
    if (rc == 0)
        rc = ob_jobview_run(&j->v);
    ob_err err;
    if (rc == 0 && ob_jobview_has_approx(&j->v))
        rc = ob_approx_from_job(&j->v.job, &j->v.spans, &j->ap, &err);
    else
        rc = -1;
    CHECK(rc == 0 && j->ap.n > 0, "%s d = %g %s %s: the job runs and gives pieces", curve, d, method, tol);
    for (int k = 0; k < j->ap.n; k++)
        j->ap.v[k].line = 100 + k;
    return rc;
}

static void job_close(jobap *j)
{
    ob_approx_free(&j->ap);
    ob_jobview_close(&j->v);
}

/* dst = the pieces idx[0..n) of src (a fresh approximation). */
static void pick(const ob_approx *src, const int *idx, int n, ob_approx *dst)
{
    memset(dst, 0, sizeof *dst);
    dst->same_param = src->same_param;
    for (int i = 0; i < n; i++) {
        ob_apiece *p = ob_approx_add(dst);
        *p = src->v[idx[i]];
        p->line = 100 + i;
    }
}

/* A copy of src. */
static void copy(const ob_approx *src, ob_approx *dst)
{
    int *idx = malloc((size_t)src->n * sizeof *idx);
    for (int i = 0; i < src->n; i++)
        idx[i] = i;
    pick(src, idx, src->n, dst);
    free(idx);
}

/* Drops every link and matches the pieces by projection, as for a CAD
 * file; returns ob_approx_match's status. */
static int unlink_match(const ob_curve *c, double d, ob_approx *a)
{
    for (int k = 0; k < a->n; k++) {
        a->v[k].has_base = 0;
        a->v[k].seg = 0;
        a->v[k].a = a->v[k].b = a->v[k].t0 = a->v[k].t1 = 0.0;
    }
    a->same_param = 0;
    ob_err err;
    return ob_approx_match(c, d, a, "m.json", &err);
}

/* The cover of a, with its return status. */
static int cover(const ob_curve *c, double d, const ob_approx *a, ob_cover *cv)
{
    ob_err err = {""};
    memset(cv, 0, sizeof *cv);
    const int rc = ob_approx_cover(c, d, a, 256, "t.json", cv, &err);
    if (rc != 0 && verbose)
        printf("  cover: %s\n", err.msg);
    return rc;
}

static void print_issues(const ob_cover *cv, const ob_approx *a)
{
    char buf[512];
    for (int i = 0; i < cv->nfail; i++) {
        ob_cover_text(&cv->fail[i], a, "t.json", buf, sizeof buf);
        printf("    %s\n", buf);
    }
    for (int i = 0; i < cv->nnote; i++) {
        ob_cover_text(&cv->note[i], a, "t.json", buf, sizeof buf);
        printf("    %s\n", buf);
    }
}

static double lo_of(const ob_apiece *p) { return ob_apiece_base_t(p, 0.0); }
static double hi_of(const ob_apiece *p) { return ob_apiece_base_t(p, 1.0); }

/* tiller's one-piece fit of the offset of segment seg of c over [u0, u1]. */
static int tiller_piece(const ob_curve *c, int seg, double u0, double u1, double d, ob_bez *out)
{
    const ob_method *m = ob_method_find("tiller");
    ob_bez sub;
    ob_fit fit;
    char msg[160];
    void *work = malloc(m->work_size ? m->work_size : 1);
    ob_bez_subsegment(&c->seg[seg], u0, u1, &sub);
    const ob_fit_args args = {d, 1e-3, NULL};
    const int rc = m->fit(&sub, &args, work, &fit, msg, sizeof msg) == OB_FIT_OK && fit.n == 1 ? 0 : -1;
    free(work);
    if (rc == 0)
        *out = fit.seg[0];
    return rc;
}

/* ---- valid approximations ----------------------------------------------------------- */

/* The tiles of a passing cover: in the base's order, each segment from 0 to
 * 1, consecutive tiles meeting exactly; for read links each tile is its
 * piece's range. */
static int tiles_ok(const ob_curve *c, const ob_approx *a, const ob_cover *cv)
{
    int ok = 1, seg = 0;
    double at = 0.0;
    for (int i = 0; i < a->n; i++) {
        const int k = cv->order[i];
        const ob_apiece *p = &a->v[k];
        if (p->seg != seg) {
            ok &= at == 1.0 && p->seg == seg + 1;
            seg = p->seg;
            at = 0.0;
        }
        ok &= cv->lo[k] == at && cv->hi[k] > cv->lo[k];
        if (!p->matched)
            ok &= cv->lo[k] == lo_of(p) && cv->hi[k] == hi_of(p);
        at = cv->hi[k];
    }
    return ok && seg == c->nseg - 1 && at == 1.0;
}

typedef struct {
    const char *curve;
    double d;
    const char *method, *tol;
    int matched_too; /* the offset has no loops: projection finds the base pieces */
} job_spec;

static const job_spec valid_jobs[] = {
    {"liu2002_ex1", -1.0, "tiller", "1e-3", 1},   {"liu2002_ex1", -1.0, "lee", "1e-3", 1},
    {"liu2002_ex1", -1.0, "hoschek", "1e-3", 1},  {"liu2002_ex1", -1.0, "bspline-lsq", "1e-3", 1},
    {"liu2002_ex1", -1.0, "zhao-rational", "1e-3", 1}, {"liu2002_ex1", -1.0, "elber", "1e-3", 1},
    {"liu2002_ex1", -1.0, "sisl", "1e-3", 1},     {"liu2002_ex1", 1.0, "tiller", "1e-3", 0},
    {"liu2002_ex1", 1.0, "interp", "1e-3", 0},    {"liu2002_ex1", 1.0, "bspline-lsq", "1e-3", 0},
    {"liu2002_ex1", 1.0, "ahn", "1e-3", 0},       {"liu2002_ex2", 0.5, "tiller", "1e-3", 1},
    {"liu2002_ex2", 0.5, "cobb", "1e-3", 1},      {"liu2002_ex2", 0.5, "bspline-lsq", "1e-3", 0},
    {"liu2002_ex2", 0.5, "zhao", "1e-3", 0},      {"zhao2017_septic", 0.5, "cubic-opt", "1e-3", 0},
};

static void test_valid(void)
{
    for (size_t i = 0; i < sizeof valid_jobs / sizeof *valid_jobs; i++) {
        const job_spec *s = &valid_jobs[i];
        jobap j;
        if (job_open(&j, s->curve, s->d, s->method, s->tol) != 0) {
            job_close(&j);
            continue;
        }
        const ob_curve *c = j.v.curve;
        ob_cover cv;
        int rc = cover(c, s->d, &j.ap, &cv);
        int inorder = 1;
        for (int k = 0; k < j.ap.n && rc == 0; k++)
            inorder &= cv.order[k] == k;
        CHECK(rc == 0 && ob_cover_fails(&cv) == 0 && cv.nnote == 0 && inorder && tiles_ok(c, &j.ap, &cv),
              "%s d = %g %s %s (%d pieces, read links): the cover passes exactly, in order (%d problems)", s->curve,
              s->d, s->method, s->tol, j.ap.n, rc == 0 ? ob_cover_fails(&cv) : -1);
        if (verbose || (rc == 0 && ob_cover_fails(&cv)))
            print_issues(&cv, &j.ap);
        ob_cover_free(&cv);
        if (s->matched_too) {
            ob_approx m;
            copy(&j.ap, &m);
            const int mr = unlink_match(c, s->d, &m);
            rc = mr == 0 ? cover(c, s->d, &m, &cv) : -1;
            CHECK(mr == 0 && rc == 0 && ob_cover_fails(&cv) == 0 && cv.count[OB_COVER_ORDER] == 0 &&
                      tiles_ok(c, &m, &cv),
                  "%s d = %g %s %s: matched by projection, the cover passes (match %d, %d problems)", s->curve, s->d,
                  s->method, s->tol, mr, rc == 0 ? ob_cover_fails(&cv) : -1);
            if (verbose || (rc == 0 && ob_cover_fails(&cv)))
                print_issues(&cv, &m);
            ob_cover_free(&cv);
            ob_approx_free(&m);
        }
        job_close(&j);
    }
}

/* ---- the variants ----------------------------------------------------------------- */

/* Checks one variant's counts: fails of each kind and notes. */
static void expect(const char *what, const ob_curve *c, double d, const ob_approx *a, int gaps, int overlaps,
                   int dups, int order, ob_cover *cv)
{
    const int rc = cover(c, d, a, cv);
    CHECK(rc == 0 && cv->count[OB_COVER_GAP] == gaps && cv->count[OB_COVER_OVERLAP] == overlaps &&
              cv->count[OB_COVER_DUPLICATE] == dups && cv->count[OB_COVER_ORDER] == order,
          "%s: rc %d, %d gaps, %d overlaps, %d duplicates, %d out of order (expected %d, %d, %d, %d)", what, rc,
          cv->count[OB_COVER_GAP], cv->count[OB_COVER_OVERLAP], cv->count[OB_COVER_DUPLICATE],
          cv->count[OB_COVER_ORDER], gaps, overlaps, dups, order);
    CHECK(ob_cover_fails(cv) == gaps + overlaps + dups, "%s: ob_cover_fails", what);
    const int notes = cv->count[OB_COVER_ORDER] + cv->count[OB_COVER_NEAR_GAP] + cv->count[OB_COVER_NEAR_OVERLAP];
    CHECK(cv->nfail == (gaps + overlaps + dups < OB_COVER_KEEP ? gaps + overlaps + dups : OB_COVER_KEEP) &&
              cv->nnote == (notes < OB_COVER_KEEP ? notes : OB_COVER_KEEP),
          "%s: the first %d problems and %d notes kept (%d, %d)", what, OB_COVER_KEEP, OB_COVER_KEEP, cv->nfail,
          cv->nnote);
    if (verbose) {
        printf("  %s:\n", what);
        print_issues(cv, a);
    }
}

/* The position (segment, parameter) of an issue's ends equals the range
 * [lo of piece x, hi of piece y] (tol 0: exactly). */
static int range_is(const ob_cover_issue *is, const ob_apiece *x, int x_end, const ob_apiece *y, int y_end,
                    double tol)
{
    const double a = x_end ? hi_of(x) : lo_of(x), b = y_end ? hi_of(y) : lo_of(y);
    return is->seg0 == x->seg && is->seg1 == y->seg && fabs(is->t0 - a) <= tol && fabs(is->t1 - b) <= tol;
}

/* Every variant on the pieces of one job, with read links (matched 0) or
 * matched by projection (matched 1). */
static void variants(const jobap *j, double d, int matched)
{
    const ob_curve *c = j->v.curve;
    ob_approx base;
    copy(&j->ap, &base);
    if (matched && unlink_match(c, d, &base) != 0) {
        CHECK(0, "%s: matching the job's own pieces", c->id);
        ob_approx_free(&base);
        return;
    }
    const double tol = matched ? 1e-12 : 0.0;
    const int n = base.n, m = n / 2;
    CHECK(n >= 6, "%s: enough pieces for the variants (%d)", c->id, n);
    char what[160];
    const char *kind = matched ? "matched" : "read links";
    int *idx = malloc((size_t)(n + 64) * sizeof *idx);
    ob_approx v;
    ob_cover cv;

    /* one piece of n */
    idx[0] = m;
    pick(&base, idx, 1, &v);
    snprintf(what, sizeof what, "%s (%s): piece %d alone", c->id, kind, m);
    expect(what, c, d, &v, 2, 0, 0, 0, &cv);
    ob_apiece first = {.has_base = 1, .seg = 0, .a = 0, .b = 1, .t0 = 0, .t1 = 1};
    ob_apiece last = first;
    last.seg = c->nseg - 1;
    CHECK(cv.nfail == 2 && cv.fail[0].kind == OB_COVER_GAP && cv.fail[0].piece == 0 &&
              range_is(&cv.fail[0], &first, 0, &base.v[m], 0, tol) && cv.fail[1].piece == 0 &&
              range_is(&cv.fail[1], &base.v[m], 1, &last, 1, tol),
          "%s: the gaps before and after it, from the curve's start and to its end", what);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* one piece 50 times */
    for (int i = 0; i < 50; i++)
        idx[i] = m;
    pick(&base, idx, 50, &v);
    snprintf(what, sizeof what, "%s (%s): piece %d 50 times", c->id, kind, m);
    expect(what, c, d, &v, 2, 0, 49, 0, &cv);
    CHECK(cv.fail[1].kind == OB_COVER_DUPLICATE && cv.fail[1].piece == 1 && cv.fail[1].other == 0 &&
              range_is(&cv.fail[1], &base.v[m], 0, &base.v[m], 1, tol),
          "%s: the second copy is a duplicate of the first, over its range", what);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* a piece missing in the middle */
    for (int i = 0, k = 0; i < n; i++)
        if (i != m)
            idx[k++] = i;
    pick(&base, idx, n - 1, &v);
    snprintf(what, sizeof what, "%s (%s): piece %d missing", c->id, kind, m);
    expect(what, c, d, &v, 1, 0, 0, 0, &cv);
    CHECK(cv.fail[0].piece == m && cv.fail[0].other == m - 1 &&
              range_is(&cv.fail[0], &base.v[m - 1], 1, &base.v[m + 1], 0, tol) &&
              range_is(&cv.fail[0], &base.v[m], 0, &base.v[m], 1, tol + (matched ? 1e-9 : 0.0)),
          "%s: the gap is the missing piece's range, seen at the piece after it", what);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* a piece twice: the copy at the end */
    for (int i = 0; i < n; i++)
        idx[i] = i;
    idx[n] = m;
    pick(&base, idx, n + 1, &v);
    snprintf(what, sizeof what, "%s (%s): piece %d again at the end", c->id, kind, m);
    expect(what, c, d, &v, 0, 0, 1, 1, &cv);
    CHECK(cv.fail[0].piece == n && cv.fail[0].other == m && cv.note[0].piece == n,
          "%s: the duplicate is the last piece, of piece %d, and out of order", what, m);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* two pieces swapped: a permutation of a cover passes, noted */
    for (int i = 0; i < n; i++)
        idx[i] = i;
    idx[m] = m + 1;
    idx[m + 1] = m;
    pick(&base, idx, n, &v);
    snprintf(what, sizeof what, "%s (%s): pieces %d and %d swapped", c->id, kind, m, m + 1);
    expect(what, c, d, &v, 0, 0, 0, 1, &cv);
    CHECK(cv.note[0].piece == m + 1 && cv.note[0].other == m && cv.order[m] == m + 1 && cv.order[m + 1] == m &&
              tiles_ok(c, &v, &cv),
          "%s: noted at the second, measured in the base's order", what);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* the list reversed */
    for (int i = 0; i < n; i++)
        idx[i] = n - 1 - i;
    pick(&base, idx, n, &v);
    snprintf(what, sizeof what, "%s (%s): the list reversed", c->id, kind);
    expect(what, c, d, &v, 0, 0, 0, n - 1, &cv);
    CHECK(tiles_ok(c, &v, &cv), "%s: tiles in the base's order", what);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    /* an overlap: piece o reaches into piece o + 1's range (both on one segment) */
    int o = m;
    while (o + 2 < n && base.v[o].seg != base.v[o + 1].seg)
        o++;
    copy(&base, &v);
    if (matched) { /* piece o + 1 refitted from the middle of piece o's range */
        const double u0 = 0.5 * (lo_of(&v.v[o]) + hi_of(&v.v[o])), u1 = hi_of(&v.v[o + 1]);
        CHECK(tiller_piece(c, v.v[o].seg, u0, u1, d, &v.v[o + 1].approx) == 0, "%s: tiller fits [%g, %g]", c->id,
              u0, u1);
        v.v[o + 1].has_base = 0;
        CHECK(ob_approx_match(c, d, &v, "t.json", &(ob_err){""}) == 0, "%s: the extended piece matches", c->id);
    } else {
        const double lo = lo_of(&v.v[o]), hi = 0.5 * (lo_of(&v.v[o + 1]) + hi_of(&v.v[o + 1]));
        v.v[o].a = lo, v.v[o].b = hi, v.v[o].t0 = 0.0, v.v[o].t1 = 1.0;
    }
    snprintf(what, sizeof what, "%s (%s): piece %d reaches into piece %d", c->id, kind, o, o + 1);
    expect(what, c, d, &v, 0, 1, 0, 0, &cv);
    CHECK(cv.fail[0].kind == OB_COVER_OVERLAP && cv.fail[0].piece == o + 1 && cv.fail[0].other == o &&
              range_is(&cv.fail[0], &v.v[o + 1], 0, &v.v[o], 1, 0.0),
          "%s: the overlap from piece %d's start to piece %d's end", what, o + 1, o);
    ob_cover_free(&cv);
    ob_approx_free(&v);

    if (matched) {
        /* a joint pulled apart along the offset: a third of the piece is
         * a gap; 1e-6 of it is within the pieces' accuracy (tiller's
         * errors here are some 1e-4), 1e-15 is round-off */
        const double cut[3] = {1.0 / 3.0, 1e-6, 1e-15};
        for (int i = 0; i < 3; i++) {
            copy(&base, &v);
            ob_bez sub;
            ob_bez_subsegment(&v.v[m + 1].approx, cut[i], 1.0, &sub);
            v.v[m + 1].approx = sub;
            v.v[m + 1].has_base = 0;
            CHECK(ob_approx_match(c, d, &v, "t.json", &(ob_err){""}) == 0, "%s: the shortened piece matches", c->id);
            snprintf(what, sizeof what, "%s (matched): piece %d starts %g later", c->id, m + 1, cut[i]);
            expect(what, c, d, &v, i == 0, 0, 0, 0, &cv);
            CHECK(cv.count[OB_COVER_NEAR_GAP] == (i == 1), "%s: %d small gaps noted (%d)", what, i == 1,
                  cv.count[OB_COVER_NEAR_GAP]);
            ob_cover_free(&cv);
            ob_approx_free(&v);
        }
        /* each piece reversed: the match turns it back */
        copy(&base, &v);
        for (int k = 0; k < n; k++) {
            const ob_bez r = reversed(&v.v[k].approx);
            v.v[k].approx = r;
        }
        snprintf(what, sizeof what, "%s (matched): every piece reversed", c->id);
        CHECK(unlink_match(c, d, &v) == 0, "%s: matches", what);
        expect(what, c, d, &v, 0, 0, 0, 0, &cv);
        ob_cover_free(&cv);
        ob_approx_free(&v);
    }
    free(idx);
    ob_approx_free(&base);
}

static void test_variants(void)
{
    static const job_spec jobs[] = {{"liu2002_ex1", -1.0, "tiller", "1e-3", 1}, {"liu2002_ex2", 0.5, "tiller", "1e-3", 1},
                                    {"liu2002_ex1", -1.0, "bspline-lsq", "1e-4", 1}};
    for (size_t i = 0; i < sizeof jobs / sizeof *jobs; i++) {
        jobap j;
        if (job_open(&j, jobs[i].curve, jobs[i].d, jobs[i].method, jobs[i].tol) == 0) {
            variants(&j, jobs[i].d, 0);
            if (i < 2)
                variants(&j, jobs[i].d, 1);
        }
        job_close(&j);
    }
}

/* Pieces of another curve, a link to a segment the curve lacks, an empty
 * approximation's text. */
static void test_foreign(void)
{
    jobap a, b;
    const int ra = job_open(&a, "liu2002_ex1", -1.0, "tiller", "1e-3");
    const int rb = job_open(&b, "liu2002_ex2", 0.5, "tiller", "1e-3");
    if (ra == 0 && rb == 0) {
        /* liu2002_ex2's pieces (read links: segments 0..3) against liu2002_ex1 (one segment) */
        ob_cover cv;
        ob_err err = {""};
        memset(&cv, 0, sizeof cv);
        CHECK(ob_approx_cover(a.v.curve, -1.0, &b.ap, 256, "t.json", &cv, &err) != 0 &&
                  strstr(err.msg, "t.json:") && strstr(err.msg, "is not a piece of curve 'liu2002_ex1'"),
              "pieces linked to segments liu2002_ex1 lacks: %s", err.msg);
        ob_cover_free(&cv);
        /* matched by projection: the match refuses, or the cover fails */
        ob_approx m;
        copy(&b.ap, &m);
        const int mr = unlink_match(a.v.curve, -1.0, &m);
        int fails = -1;
        if (mr == 0 && cover(a.v.curve, -1.0, &m, &cv) == 0)
            fails = ob_cover_fails(&cv);
        CHECK(mr != 0 || fails > 0, "liu2002_ex2's pieces matched against liu2002_ex1: refused (match %d, %d problems)",
              mr, fails);
        if (verbose && mr == 0)
            print_issues(&cv, &m);
        ob_cover_free(&cv);
        ob_approx_free(&m);
        /* and liu2002_ex1's against liu2002_ex2 */
        copy(&a.ap, &m);
        const int mr2 = unlink_match(b.v.curve, 0.5, &m);
        fails = -1;
        if (mr2 == 0 && cover(b.v.curve, 0.5, &m, &cv) == 0)
            fails = ob_cover_fails(&cv);
        CHECK(mr2 != 0 || fails > 0, "liu2002_ex1's pieces matched against liu2002_ex2: refused (match %d, %d problems)",
              mr2, fails);
        ob_cover_free(&cv);
        ob_approx_free(&m);
    }
    job_close(&a);
    job_close(&b);
}

/* The text of each kind names the file, line, piece and range. */
static void test_text(void)
{
    ob_approx a = {0};
    for (int k = 0; k < 2; k++) {
        ob_apiece *p = ob_approx_add(&a);
        p->line = 10 + 5 * k;
    }
    char buf[512];
    const struct { ob_cover_issue is; const char *want; } t[] = {
        {{OB_COVER_GAP, 1, 0, 0, 0, 0.25, 0.5}, "f.json:15: piece 1: gap: nothing covers base segment 0 from t = 0.25 to t = 0.5 (after piece 0, line 10)"},
        {{OB_COVER_GAP, 0, -1, 0, 1, 0, 0.5}, "f.json:10: piece 0: gap: nothing covers base segment 0 t = 0 to segment 1 t = 0.5 (before this piece, the first on the base)"},
        {{OB_COVER_GAP, 1, 1, 2, 2, 0.75, 1}, "f.json:15: piece 1: gap: nothing covers base segment 2 from t = 0.75 to t = 1 (after this piece, the last on the base)"},
        {{OB_COVER_OVERLAP, 1, 0, 0, 0, 0.25, 0.5}, "f.json:15: piece 1: overlap: base segment 0 from t = 0.25 to t = 0.5 is covered by piece 0 (line 10) too"},
        {{OB_COVER_DUPLICATE, 1, 0, 0, 0, 0.25, 0.5}, "f.json:15: piece 1: duplicate of piece 0 (line 10): base segment 0 from t = 0.25 to t = 0.5"},
        {{OB_COVER_ORDER, 1, 0, 3, 3, 0.25, 0.5}, "f.json:15: piece 1: out of order: it lies before piece 0 (line 10) on the base (segment 3 from t = 0.25 to t = 0.5)"},
    };
    for (size_t i = 0; i < sizeof t / sizeof *t; i++) {
        ob_cover_text(&t[i].is, &a, "f.json", buf, sizeof buf);
        CHECK(strcmp(buf, t[i].want) == 0, "text:\n  got  %s\n  want %s", buf, t[i].want);
    }
    ob_approx_free(&a);
}

/* ---- the whole-vs-whole Hausdorff distance ------------------------------------------- */

/* The brute-force reference.  Each curve (a piece of the approximation, a
 * whole base segment's offset) is a polyline of NT chords; the distance from
 * a point to a whole is found at the nearest of all chords of all its
 * curves (chords in blocks of BLK with bounding boxes; a block whose box is
 * farther than the best so far cannot hold a nearer chord and is skipped,
 * which changes nothing but the work), then refined on the curve by golden
 * section over that chord and its neighbours (a chord strays from the
 * curve by h^2 k / 8: 1e-7 on liu2002_ex1's offset, too much beside
 * errors of 1e-5).  Each side's supremum: NQ + 1 query samples per curve,
 * then around the MAXP largest, two nested grids of 41 points over +- one
 * spacing. */
enum { NT = 6000, BLK = 50, NQ = 400, MAXP = 8 };

typedef struct {
    double (*p)[2]; /* points: ncurves x (NT + 1) */
    int ncurves;
    double (*box)[4]; /* per block: x0, y0, x1, y1 */
} whole_poly;

typedef struct {
    const ob_bez *segs;   /* curves */
    const ob_bez *const *ptrs;
    int n;
    double d;             /* 0: the curves themselves; else their offsets */
} curves;

static const ob_bez *cur(const curves *c, int i) { return c->ptrs ? c->ptrs[i] : &c->segs[i]; }

static void ref_pt(const curves *c, int i, double t, double p[2])
{
    if (c->d == 0.0)
        ref_point(cur(c, i), t, p);
    else
        ref_offset(cur(c, i), t, c->d, p);
}

static void poly_make(const curves *c, whole_poly *w)
{
    w->ncurves = c->n;
    w->p = malloc((size_t)c->n * (NT + 1) * sizeof *w->p);
    w->box = malloc((size_t)c->n * (NT / BLK) * sizeof *w->box);
    for (int i = 0; i < c->n; i++) {
        for (int k = 0; k <= NT; k++)
            ref_pt(c, i, (double)k / NT, w->p[i * (NT + 1) + k]);
        for (int b = 0; b < NT / BLK; b++) {
            double *bx = w->box[i * (NT / BLK) + b];
            bx[0] = bx[1] = INFINITY;
            bx[2] = bx[3] = -INFINITY;
            for (int k = b * BLK; k <= (b + 1) * BLK; k++) {
                const double *q = w->p[i * (NT + 1) + k];
                bx[0] = fmin(bx[0], q[0]), bx[1] = fmin(bx[1], q[1]);
                bx[2] = fmax(bx[2], q[0]), bx[3] = fmax(bx[3], q[1]);
            }
        }
    }
}

static void poly_free(whole_poly *w)
{
    free(w->p);
    free(w->box);
}

static double seg_dist(const double q[2], const double a[2], const double b[2])
{
    const double vx = b[0] - a[0], vy = b[1] - a[1], wx = q[0] - a[0], wy = q[1] - a[1];
    const double vv = vx * vx + vy * vy;
    double s = vv > 0.0 ? (wx * vx + wy * vy) / vv : 0.0;
    s = s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
    return hypot(wx - s * vx, wy - s * vy);
}

static double box_dist(const double q[2], const double *bx)
{
    const double dx = q[0] < bx[0] ? bx[0] - q[0] : q[0] > bx[2] ? q[0] - bx[2] : 0.0;
    const double dy = q[1] < bx[1] ? bx[1] - q[1] : q[1] > bx[3] ? q[1] - bx[3] : 0.0;
    return hypot(dx, dy);
}

/* Least distance from q to the chords of w; *ci, *ck: the chord (curve,
 * index). */
static double poly_dist(const whole_poly *w, const double q[2], int *ci, int *ck)
{
    const int nb = w->ncurves * (NT / BLK);
    double best = INFINITY;
    for (int pass = 0; pass < 2; pass++) { /* the nearest box first, then the rest */
        int b0 = 0;
        if (pass == 0)
            for (int b = 1; b < nb; b++)
                b0 = box_dist(q, w->box[b]) < box_dist(q, w->box[b0]) ? b : b0;
        for (int b = pass ? 0 : b0; b < (pass ? nb : b0 + 1); b++) {
            if (!(box_dist(q, w->box[b]) < best))
                continue;
            const int i = b / (NT / BLK), k0 = (b % (NT / BLK)) * BLK;
            const double(*p)[2] = w->p + i * (NT + 1);
            for (int k = k0; k < k0 + BLK; k++) {
                const double e = seg_dist(q, p[k], p[k + 1]);
                if (e < best)
                    best = e, *ci = i, *ck = k;
            }
        }
    }
    return best;
}

/* The distance from q to the curves c (polyline w of them): the nearest
 * chord, then golden section on the curve itself over it and its two
 * neighbours (the distance to a curve point: never below the true one). */
static double ref_dist(const curves *c, const whole_poly *w, const double q[2])
{
    int i = 0, k = 0;
    poly_dist(w, q, &i, &k);
    double lo = fmax(0.0, (k - 1.0) / NT), hi = fmin(1.0, (k + 2.0) / NT), p[2];
    const double g = 0.6180339887498949;
    for (int it = 0; it < 80 && hi - lo > 1e-15; it++) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        double p1[2], p2[2];
        ref_pt(c, i, x1, p1);
        ref_pt(c, i, x2, p2);
        if (dist2d(q, p1) < dist2d(q, p2))
            hi = x2;
        else
            lo = x1;
    }
    ref_pt(c, i, 0.5 * (lo + hi), p);
    return dist2d(q, p);
}

typedef struct {
    double e;
    int i, k;
} peak;

/* sup over the query curves q of the distance to the target curves t
 * (polyline w of them). */
static double ref_side(const curves *q, const curves *t, const whole_poly *w)
{
    peak top[MAXP];
    int ntop = 0;
    for (int i = 0; i < q->n; i++)
        for (int k = 0; k <= NQ; k++) {
            double p[2];
            ref_pt(q, i, (double)k / NQ, p);
            const peak e = {ref_dist(t, w, p), i, k};
            int at = ntop < MAXP ? ntop++ : MAXP - 1;
            if (at == MAXP - 1 && ntop == MAXP && !(e.e > top[at].e))
                continue;
            top[at] = e;
            for (; at > 0 && top[at].e > top[at - 1].e; at--) {
                const peak x = top[at];
                top[at] = top[at - 1];
                top[at - 1] = x;
            }
        }
    double best = ntop ? top[0].e : 0.0;
    for (int j = 0; j < ntop; j++) {
        double u = (double)top[j].k / NQ, h = 1.0 / NQ;
        for (int level = 0; level < 2; level++) {
            double bu = u, be = -1.0;
            for (int g = 0; g <= 40; g++) {
                const double x = fmin(1.0, fmax(0.0, u - h + 2.0 * h * g / 40));
                double p[2];
                ref_pt(q, top[j].i, x, p);
                const double e = ref_dist(t, w, p);
                if (e > be) {
                    be = e;
                    bu = x;
                }
            }
            best = fmax(best, be);
            u = bu;
            h /= 20;
        }
    }
    return best;
}

/* The reference two-sided distance between the pieces of a and the offset
 * of c's whole segments. */
static double ref_whole(const ob_curve *c, double d, const ob_approx *a)
{
    const ob_bez **ptrs = malloc((size_t)a->n * sizeof *ptrs);
    for (int k = 0; k < a->n; k++)
        ptrs[k] = &a->v[k].approx;
    const curves A = {NULL, ptrs, a->n, 0.0}, O = {c->seg, NULL, c->nseg, d};
    whole_poly wa, wo;
    poly_make(&A, &wa);
    poly_make(&O, &wo);
    const double h = fmax(ref_side(&A, &O, &wo), ref_side(&O, &A, &wa));
    poly_free(&wa);
    poly_free(&wo);
    free(ptrs);
    return h;
}

/* whole for a (linked or matched) and its per-piece hausdorff maximum. */
static int measure_whole(const ob_curve *c, double d, const ob_approx *a, double *whole, double *piece)
{
    ob_cover cv;
    ob_err err = {""};
    ob_mres r;
    int rc = cover(c, d, a, &cv);
    rc = rc || ob_cover_fails(&cv) || ob_approx_hausdorff_whole(c, d, a, &cv, 256, &r, &err);
    *whole = rc ? NAN : r.err;
    ob_cover_free(&cv);
    rc = rc || ob_approx_measure(c, d, a, OB_METRIC_HAUSDORFF, 256, "t.json", &r, &err);
    *piece = rc ? NAN : r.err;
    return rc;
}

static void test_whole(void)
{
    static const job_spec jobs[] = {
        {"liu2002_ex1", -1.0, "tiller", "1e-2", 1}, {"liu2002_ex1", -1.0, "lee", "1e-2", 1},
        {"liu2002_ex1", 1.0, "tiller", "1e-2", 0},  {"liu2002_ex1", 1.0, "interp", "1e-3", 0},
        {"liu2002_ex1", 1.0, "hoschek", "1e-2", 0}, {"liu2002_ex2", 0.5, "cobb", "1e-2", 1},
        {"liu2002_ex2", 0.5, "zhao", "1e-2", 0},
        /* the default job's exports where the two differ most: 0.16, 0.23 */
        {"atlas_parabola", 0.125, "lee", "1e-5", 0},   {"zhao2017_septic", 0.5, "interp", "1e-1", 0},
    };
    for (size_t i = 0; i < sizeof jobs / sizeof *jobs; i++) {
        const job_spec *s = &jobs[i];
        jobap j;
        if (job_open(&j, s->curve, s->d, s->method, s->tol) != 0) {
            job_close(&j);
            continue;
        }
        const ob_curve *c = j.v.curve;
        double whole, piece;
        const int rc = measure_whole(c, s->d, &j.ap, &whole, &piece);
        const double ref = ref_whole(c, s->d, &j.ap);
        /* the reference's own error (golden section on the curves, query
         * grids 6e-6 apart at the end): some 1e-10 relative here */
        const double tol = 1e-7 * ref + 1e-13;
        CHECK(rc == 0 && fabs(whole - ref) <= tol, "%s d = %g %s %s: whole %.9g, brute force %.9g (tol %.2g)",
              s->curve, s->d, s->method, s->tol, whole, ref, tol);
        CHECK(rc == 0 && whole <= piece * (1.0 + 1e-12), "%s d = %g %s %s: whole %.17g <= per piece %.17g",
              s->curve, s->d, s->method, s->tol, whole, piece);
        if (verbose)
            printf("%-12s d = %4g %-8s %s %3d pieces: per piece %.9e  whole %.9e  brute force %.9e\n", s->curve,
                   s->d, s->method, s->tol, j.ap.n, piece, whole, ref);
        if (s->matched_too) { /* the same two sets, matched by projection: the same distance */
            ob_approx m;
            copy(&j.ap, &m);
            double mw, mp;
            const int mr = unlink_match(c, s->d, &m) || measure_whole(c, s->d, &m, &mw, &mp);
            CHECK(mr == 0 && fabs(mw - ref) <= tol, "%s d = %g %s %s, matched: whole %.9g, brute force %.9g",
                  s->curve, s->d, s->method, s->tol, mw, ref);
            if (verbose)
                printf("%-12s d = %4g %-8s %s matched:   per piece %.9e  whole %.9e\n", s->curve, s->d, s->method,
                       s->tol, mp, mw);
            ob_approx_free(&m);
        }
        job_close(&j);
    }
}

/* A straight base from (0, 0) to (2, 0), d = 0.5, two pieces on the exact
 * offset line y = 0.5, linked to [0, 0.5] and [0.5, 1], the first running
 * on to x = 1.5: per piece, its end is 0.5 from its base piece's offset
 * (which ends at x = 1); as wholes the two are the same line: 0. */
static void test_whole_constructed(void)
{
    ob_bez seg;
    const double base[2][2] = {{0, 0}, {2, 0}};
    ob_bez_from_points(&seg, 1, base);
    ob_curve c;
    memset(&c, 0, sizeof c);
    snprintf(c.id, sizeof c.id, "line");
    c.nseg = 1;
    c.seg = &seg;
    ob_approx a = {0};
    const double p0[2][2] = {{0, 0.5}, {1.5, 0.5}}, p1[2][2] = {{1, 0.5}, {2, 0.5}};
    ob_apiece *p = ob_approx_add(&a);
    ob_bez_from_points(&p->approx, 1, p0);
    p->has_base = 1, p->a = 0.0, p->b = 0.5, p->t0 = 0.0, p->t1 = 1.0, p->line = 1;
    p = ob_approx_add(&a);
    ob_bez_from_points(&p->approx, 1, p1);
    p->has_base = 1, p->a = 0.5, p->b = 1.0, p->t0 = 0.0, p->t1 = 1.0, p->line = 2;
    double whole, piece;
    const int rc = measure_whole(&c, 0.5, &a, &whole, &piece);
    CHECK(rc == 0 && whole <= 1e-15 && fabs(piece - 0.5) <= 1e-12,
          "an overshooting piece: per piece %.17g (0.5), whole %.17g (0)", piece, whole);
    /* the same pieces without links: the overshoot (half the next piece) is an overlap */
    CHECK(unlink_match(&c, 0.5, &a) == 0, "the constructed pieces match");
    ob_cover cv;
    expect("the overshooting piece matched by projection", &c, 0.5, &a, 0, 1, 0, 0, &cv);
    ob_cover_free(&cv);
    ob_approx_free(&a);
}

/* Many pieces at many samples: more tables than whole.c keeps (64 MiB per
 * side: 248 of 4,096 samples), so that tables are dropped and filled
 * again; the result is the brute force's, and that of 256 samples. */
static void test_whole_many(void)
{
    jobap j;
    if (job_open(&j, "liu2002_ex1", -1.0, "tiller", "1e-1") != 0) {
        job_close(&j);
        return;
    }
    const ob_curve *c = j.v.curve;
    enum { N = 260 };
    ob_approx a = {0};
    int ok = 1;
    for (int i = 0; i < N && ok; i++) {
        ob_apiece *p = ob_approx_add(&a);
        *p = (ob_apiece){.has_base = 1, .seg = 0, .a = (double)i / N, .b = (double)(i + 1) / N, .t0 = 0, .t1 = 1,
                         .line = i + 1};
        ok = tiller_piece(c, 0, p->a, p->b, -1.0, &p->approx) == 0;
    }
    a.v[N - 1].b = 1.0;
    ob_cover cv;
    ob_err err = {""};
    ob_mres r256, r4096;
    int rc = !ok || cover(c, -1.0, &a, &cv) || ob_cover_fails(&cv);
    rc = rc || ob_approx_hausdorff_whole(c, -1.0, &a, &cv, 256, &r256, &err) ||
         ob_approx_hausdorff_whole(c, -1.0, &a, &cv, 4096, &r4096, &err);
    const double ref = rc ? NAN : ref_whole(c, -1.0, &a);
    CHECK(rc == 0 && fabs(r4096.err - ref) <= 1e-7 * ref + 1e-13 && fabs(r4096.err - r256.err) <= 1e-7 * ref + 1e-13,
          "%d pieces: whole at 4096 samples %.9g, at 256 %.9g, brute force %.9g", N, r4096.err, r256.err, ref);
    if (verbose)
        printf("%d tiller pieces: whole at 4096 samples %.9e, at 256 %.9e, brute force %.9e\n", N, r4096.err, r256.err,
               ref);
    ob_cover_free(&cv);
    ob_approx_free(&a);
    job_close(&j);
}

/* param applies to read links (also of a method not in the base's
 * parameter: the run measured it so), not to matched pieces. */
static void test_param(void)
{
    static const char *const methods[] = {"tiller", "hoschek"};
    for (int i = 0; i < 2; i++) {
        jobap j;
        if (job_open(&j, "liu2002_ex1", -1.0, methods[i], "1e-2") == 0) {
            ob_mres r;
            ob_err err;
            CHECK(ob_approx_measure(j.v.curve, -1.0, &j.ap, OB_METRIC_PARAM, 256, "t.json", &r, &err) == 0 &&
                      r.applies && r.err > 0.0,
                  "%s, read links: param applies (%g)", methods[i], r.err);
            ob_approx m;
            copy(&j.ap, &m);
            CHECK(unlink_match(j.v.curve, -1.0, &m) == 0 &&
                      ob_approx_measure(j.v.curve, -1.0, &m, OB_METRIC_PARAM, 256, "t.json", &r, &err) == 0 &&
                      !r.applies && strstr(r.why, "parameter"),
                  "%s, matched: param does not apply (%s)", methods[i], r.applies ? "it does" : r.why);
            for (int k = 0; k < OB_METRIC_COUNT; k++) /* the geometric ones still do */
                if (!ob_metric_reads_param((ob_metric)k)) {
                    const int mr = ob_approx_measure(j.v.curve, -1.0, &m, (ob_metric)k, 256, "t.json", &r, &err);
                    CHECK(mr == 0 && r.applies, "%s, matched: %s applies", methods[i], ob_metric_name((ob_metric)k));
                }
            ob_approx_free(&m);
        }
        job_close(&j);
    }
}

int main(int argc, char **argv)
{
    verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
    test_text();
    test_valid();
    test_variants();
    test_foreign();
    test_whole_constructed();
    test_whole();
    test_whole_many();
    test_param();
    return check_done();
}
