/*
 * certify_export.c - the certified Hausdorff enclosure (methods/metrics/
 * metric_certified.h) of every ok job of a `run --random N:SEED --export DIR`,
 * against the sampled metric: the tightness and cost figures of
 * docs/certified.md (issue 41, item 2).
 *
 * Build: make build/tests/tools/certify_export (the Makefile's rule for
 *        tests/; not part of `make test`).
 * Usage: build/tests/tools/certify_export DIR [--seed S] [--every K] [--budget B]
 *            [--samples S] [--jobs FILE]
 *   DIR      an export directory of a run on random curves (the base curves
 *            are regenerated from their ids: host/io/random.h);
 *   --every K  only every K-th ok job, in file-name order (a deterministic subset);
 *   --per-piece 1  each piece enclosed to rtol of its own distance
 *            (ob_certify_hausdorff_opts) instead of the job's (ob_certify_job);
 *   --roundoff X  err_upper <= X counts as certified at round-off (1e-9);
 *   --match S  only the files whose name holds S (to study a few jobs);
 *   --verbose 1  print each certified job's pieces (the sampled error, the
 *            piece's enclosure, rc, met, leaves, its base's end legs);
 *   --jobs FILE  one line per job: file, method, family, pieces, max_err,
 *            sampled, lower, upper, rc, met, leaves, ns_cert, ns_sampled.
 * Per job (ob_certify_job, cert_job.h, the pieces ordered by their sampled
 * errors): err_upper = max over its pieces of the certificate's upper,
 * err_lower = max of lower; ratio = err_upper / err_lower (1 when both are
 * 0).  Time per job: the sum over its pieces of the certificate, and of
 * ob_measure(OB_METRIC_HAUSDORFF, 256 samples), one thread, CLOCK_MONOTONIC.
 * Columns: jobs; r-o: certified at round-off (--roundoff); +inf: a piece
 * could not be bounded (a cusp of its base); <=1.01%, <=1.1%: jobs with
 * ratio within, round-off ones counted in; med.rat: median ratio; max ratio
 * and inf (ratio +inf) over the others; cert ms, samp ms: median time per
 * job; x med: their ratio; x sum: total certificate time / total sampled.
 * Checks printed: the sampled max equals the file's max_err; sampled <=
 * upper (1 + 1e-9) (sampled is a distance to a found foot).
 */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "host/io/approx.h"
#include "host/io/approx_read.h"
#include "host/io/random.h"
#include "host/io/slurp.h"
#include "methods/metrics/metric.h"
#include "methods/metrics/cert_job.h"
#include "methods/metrics/metric_certified.h"

typedef struct {
    char file[256], method[32], family[32];
    int pieces, rc, met;
    double max_err, sampled, lower, upper, ratio;
    long leaves;
    double ns_cert, ns_samp;
} job_t;

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }
static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    if (n == 0)
        return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_dbl);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* the value after "key": in text (a number), or NAN */
static double json_num(const char *text, const char *key)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = strstr(text, pat);
    return p ? strtod(p + strlen(pat), NULL) : NAN;
}

/* method: the third "__" field of the file name curve__dX__method__tolY.json */
static void method_of(const char *name, char *out, size_t len)
{
    const char *p = strstr(name, "__");
    p = p ? strstr(p + 2, "__") : NULL;
    snprintf(out, len, "?");
    if (!p)
        return;
    p += 2;
    const char *e = strstr(p, "__");
    if (e)
        snprintf(out, len, "%.*s", (int)(e - p), p);
}

/* Returns 0 (certified into *j), 1 (not ok), 2 (ok, not in the subset), -1. */
static int job_level = 1;
/* a job whose err_upper is at most this is certified at round-off: its
 * distance is that of an exact method, err_lower may be 0 and the ratio says
 * nothing (the unit-box curves of --random; 1e-6 of the tolerance 1e-3) */
static double roundoff = 1e-9;
static const char *match = NULL;  /* --match: a substring of the file names */
static int verbose = 0;           /* --verbose: one line per piece */

/* |P1 - P0| and |Pn - Pn-1| of b's control points: a collapsed end leg
 * (a cusp of the base at an end) shows as a tiny number here */
static void end_legs(const ob_bez *b, double leg[2])
{
    double p[4][2];
    ob_bez_ctrl(b, 0, p[0]), ob_bez_ctrl(b, 1, p[1]);
    ob_bez_ctrl(b, b->deg - 1, p[2]), ob_bez_ctrl(b, b->deg, p[3]);
    leg[0] = hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]);
    leg[1] = hypot(p[3][0] - p[2][0], p[3][1] - p[2][1]);
}

/* --verbose: each piece's enclosure, to see which piece makes a job loose */
static void print_pieces(const char *name, int n, const ob_bez *base, const ob_bez *apx, const double *hint,
                         const ob_certified *r)
{
    for (int k = 0; k < n; k++) {
        double leg[2];
        end_legs(&base[k], leg);
        printf("%s piece %d: deg %d%s base deg %d%s, sampled %.9g, [%.9g, %.9g] met %d leaves %ld, base legs %.3g %.3g\n",
               name, k, apx[k].deg, apx[k].rational ? "r" : "", base[k].deg, base[k].rational ? "r" : "", hint[k],
               r[k].lower, r[k].upper, r[k].met, r[k].leaves, leg[0], leg[1]);
    }
}

static int certify_job(const char *dir, const char *name, uint64_t seed_default, const ob_cert_opts *o, int S,
                       int *nok, int every, job_t *j)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *text = NULL;
    size_t len = 0;
    ob_err err = {0};
    if (ob_slurp(path, &text, &len, &err) != 0)
        return fprintf(stderr, "%s: %s\n", path, err.msg), -1;
    if (!strstr(text, "\"status\": \"ok\"")) {
        free(text);
        return 1;
    }
    if ((*nok)++ % every || (match && !strstr(name, match))) {
        free(text);
        return 2;
    }
    ob_approx a = {0};
    if (ob_approx_read_json(text, len, name, &a, &err) != 0 || !a.have_job) {
        fprintf(stderr, "%s: %s\n", path, err.msg);
        free(text);
        return -1;
    }
    memset(j, 0, sizeof *j);
    snprintf(j->file, sizeof j->file, "%s", name);
    method_of(name, j->method, sizeof j->method);
    j->max_err = json_num(text, "max_err");
    free(text);
    unsigned long long seed = seed_default;
    long index = -1;
    if (sscanf(a.job_curve, "rnd%llu_%ld", &seed, &index) != 2) {
        fprintf(stderr, "%s: curve '%s' is not a random curve\n", path, a.job_curve);
        ob_approx_free(&a);
        return -1;
    }
    ob_curve c = {0};
    if (ob_random_curve(seed, index, &c) != 0) {
        ob_approx_free(&a);
        return -1;
    }
    snprintf(j->family, sizeof j->family, "%s", c.family);
    j->pieces = a.n;
    ob_bez *base = malloc((size_t)(a.n + 1) * sizeof *base), *apx = malloc((size_t)(a.n + 1) * sizeof *apx);
    double *hint = malloc((size_t)(a.n + 1) * sizeof *hint);
    ob_cert_src *src = malloc((size_t)(a.n + 1) * sizeof *src);
    for (int k = 0; k < a.n; k++) {
        const ob_apiece *p = &a.v[k];
        if (ob_apiece_base(&c, p, &base[k]) != 0) {
            fprintf(stderr, "%s: piece %d has no base\n", path, k);
            free(base), free(apx), free(hint), free(src), ob_curve_free(&c), ob_approx_free(&a);
            return -1;
        }
        src[k] = (ob_cert_src){&c.seg[p->seg], p->a, p->b, p->t0, p->t1};  /* enclosed as stored */
        apx[k] = p->approx;
    }
    /* the sampled metric, as the run measures each piece: its time, and the
     * order the certificate takes the pieces in */
    double t0 = now_ns();
    for (int k = 0; k < a.n; k++) {
        ob_errval e;
        ob_measure(OB_METRIC_HAUSDORFF, &base[k], &apx[k], a.job_d, S, &e);
        hint[k] = e.err;
    }
    double t1 = now_ns();
    ob_cert_job cj;
    ob_certified *piece = calloc((size_t)(a.n + 1), sizeof *piece);
    if (job_level)
        j->rc = ob_certify_job_src(a.n, base, src, apx, a.job_d, S, o, hint, &cj, piece);
    else {  /* every piece to rtol of its own distance */
        cj = (ob_cert_job){0.0, 0.0, 1, 0, -1, 0, 0, 0};
        for (int k = 0; k < a.n; k++) {
            ob_certified r;
            j->rc |= ob_certify_piece(&base[k], &src[k], &apx[k], a.job_d, S, o, 0.0, &r);
            piece[k] = r;
            cj.lower = fmax(cj.lower, r.lower), cj.upper = fmax(cj.upper, r.upper);
            cj.met &= r.met, cj.leaves += r.leaves;
        }
    }
    double t2 = now_ns();
    if (verbose)
        print_pieces(name, a.n, base, apx, hint, piece);
    free(piece);
    free(src);
    j->ns_samp = t1 - t0, j->ns_cert = t2 - t1;
    j->sampled = 0.0;
    for (int k = 0; k < a.n; k++)
        if (!(hint[k] <= j->sampled) || k == 0)
            j->sampled = k == 0 ? hint[k] : fmax(j->sampled, hint[k]);
    j->lower = cj.lower, j->upper = cj.upper, j->met = cj.met, j->leaves = cj.leaves;
    free(base), free(apx), free(hint);
    j->ratio = j->upper == 0 && j->lower == 0 ? 1.0 : j->upper / j->lower;
    ob_curve_free(&c);
    ob_approx_free(&a);
    return 0;
}

/* one line of the table over the jobs for which key(j) equals want (NULL: all) */
static void row(const job_t *J, int n, int by_family, const char *want)
{
    double *tc = malloc((size_t)(n + 1) * sizeof *tc), *ts = malloc((size_t)(n + 1) * sizeof *ts);
    double *rt = malloc((size_t)(n + 1) * sizeof *rt);
    int m = 0, le101 = 0, le11 = 0, inf = 0, ro = 0, failed = 0;
    double worst = 1.0, sum_c = 0, sum_s = 0;
    for (int i = 0; i < n; i++) {
        const char *key = by_family ? J[i].family : J[i].method;
        if (want && strcmp(key, want))
            continue;
        tc[m] = J[i].ns_cert, ts[m] = J[i].ns_samp, rt[m] = J[i].ratio;
        sum_c += J[i].ns_cert, sum_s += J[i].ns_samp;
        m++;
        const int at_ro = J[i].upper <= roundoff;
        ro += at_ro;
        failed += J[i].rc != 0;
        le101 += J[i].ratio <= 1.01 || at_ro;
        le11 += J[i].ratio <= 1.1 || at_ro;
        inf += !(J[i].ratio < INFINITY) && !at_ro;
        if (!at_ro)
            worst = fmax(worst, J[i].ratio);
    }
    if (m == 0)
        goto out;
    const double mc = median(tc, m), ms = median(ts, m), mr = median(rt, m);
    printf("| %-13s | %5d | %4d | %4d | %7.2f | %7.2f | %8.5f | %10.4g | %3d | %9.3f | %9.3f | %6.1f | %6.1f |\n",
           want ? want : "all", m, ro, failed, 100.0 * le101 / m, 100.0 * le11 / m, mr, worst, inf, mc * 1e-6,
           ms * 1e-6, mc / ms, sum_c / sum_s);
out:
    free(tc), free(ts), free(rt);
}

static void table(const job_t *J, int n, int by_family)
{
    printf("\n| %-13s | %5s | %4s | %4s | %7s | %7s | %8s | %10s | %3s | %9s | %9s | %6s | %6s |\n",
           by_family ? "family" : "method", "jobs", "r-o", "+inf", "<=1.01%", "<=1.1%", "med.rat", "max ratio", "inf",
           "cert ms", "samp ms", "x med", "x sum");
    printf("|---------------|-------|------|------|---------|---------|----------|------------|-----|-----------|-----------"
           "|--------|--------|\n");
    char seen[64][32];
    int nseen = 0;
    for (int i = 0; i < n; i++) {
        const char *key = by_family ? J[i].family : J[i].method;
        int k = 0;
        while (k < nseen && strcmp(seen[k], key))
            k++;
        if (k == nseen && nseen < 64)
            snprintf(seen[nseen++], sizeof seen[0], "%s", key);
    }
    qsort(seen, (size_t)nseen, sizeof seen[0], (int (*)(const void *, const void *))strcmp);
    for (int k = 0; k < nseen; k++)
        row(J, n, by_family, seen[k]);
    row(J, n, by_family, NULL);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s DIR [--seed S] [--every K] [--budget B] [--samples S] [--jobs FILE] [--match S] [--verbose 1]\n", argv[0]);
        return 2;
    }
    const char *dir = argv[1], *jobs_file = NULL;
    uint64_t seed = 7;
    int every = 1, S = OB_DEFAULT_SAMPLES;
    ob_cert_opts o;
    ob_cert_defaults(&o);
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--seed"))
            seed = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--every"))
            every = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--budget"))
            o.budget = atol(argv[i + 1]);
        else if (!strcmp(argv[i], "--samples"))
            S = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--per-piece"))  /* each piece to rtol of its own distance */
            job_level = atoi(argv[i + 1]) == 0;
        else if (!strcmp(argv[i], "--roundoff"))
            roundoff = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--match"))
            match = argv[i + 1];
        else if (!strcmp(argv[i], "--verbose"))
            verbose = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--jobs"))
            jobs_file = argv[i + 1];
        else
            return fprintf(stderr, "unknown option %s\n", argv[i]), 2;
    }
    DIR *dp = opendir(dir);
    if (!dp)
        return perror(dir), 1;
    char **names = NULL;
    int nn = 0, cap = 0;
    for (struct dirent *e; (e = readdir(dp));) {
        const size_t l = strlen(e->d_name);
        if (l < 5 || strcmp(e->d_name + l - 5, ".json"))
            continue;
        if (nn == cap)
            names = realloc(names, (size_t)(cap = cap ? 2 * cap : 1024) * sizeof *names);
        names[nn++] = strdup(e->d_name);
    }
    closedir(dp);
    qsort(names, (size_t)nn, sizeof *names, cmp_str);
    job_t *J = calloc((size_t)nn + 1, sizeof *J);
    int n = 0, nok = 0, bad_max = 0, bad_samp = 0, bad_order = 0, nrc = 0, nmet = 0;
    FILE *jf = jobs_file ? fopen(jobs_file, "w") : NULL;
    if (jf)
        fprintf(jf, "file,method,family,pieces,max_err,sampled,lower,upper,rc,met,leaves,ns_cert,ns_sampled\n");
    for (int i = 0; i < nn; i++) {
        job_t j;
        if (certify_job(dir, names[i], seed, &o, S, &nok, every, &j) != 0)
            continue;
        J[n++] = j;
        bad_max += !(j.sampled == j.max_err);
        bad_samp += !(j.sampled <= j.upper * (1 + 1e-9) + 1e-15);
        bad_order += !(j.lower <= j.upper);
        nrc += j.rc != 0;
        nmet += j.met;
        if (jf)
            fprintf(jf, "%s,%s,%s,%d,%.17g,%.17g,%.17g,%.17g,%d,%d,%ld,%.0f,%.0f\n", j.file, j.method, j.family,
                    j.pieces, j.max_err, j.sampled, j.lower, j.upper, j.rc, j.met, j.leaves, j.ns_cert, j.ns_samp);
    }
    if (jf)
        fclose(jf);
    printf("%s: %d ok jobs, %d certified (every %d), budget %ld, rtol %g, %d samples\n", dir, nok, n, every,
           o.budget, o.rtol, S);
    printf("checks: sampled != file max_err: %d; sampled > upper: %d; lower > upper: %d; rc != 0: %d; met: %d/%d\n",
           bad_max, bad_samp, bad_order, nrc, nmet, n);
    table(J, n, 0);
    table(J, n, 1);
    for (int i = 0; i < nn; i++)
        free(names[i]);
    free(names);
    free(J);
    return 0;
}
