/*
 * test_curvefile.c - the `.curves` reader (host/io/curvefile.c).
 *
 * Run from the repository root (paths are relative to it).  Covers the
 * published data set, CRLF / BOM / layout variants, the corpus of malformed
 * files in tests/data/bad_curves/ (each names the line its error must report in a
 * first line "# expect-line: N"), directory loading, file limits, and a small
 * deterministic fuzz run that must never crash or leak into the set.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/check.h"
#include "host/io/curvefile.h"

#define PUBLISHED "datasets/published.curves"
#define BAD_DIR "tests/data/bad_curves"

static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            cap = cap ? 2 * cap : 4096;
            char *nb = realloc(buf, cap);
            if (!nb)
                break;
            buf = nb;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (!got)
            break;
    }
    fclose(f);
    *len = n;
    return buf;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    CHECK(f != NULL, "cannot write %s", path);
}

static int starts_with(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

/* Parses a buffer that is exactly len bytes long (malloc'd copy, so ASan sees
 * any read past the end). */
static int parse_exact(const char *text, size_t len, const char *name, ob_curveset *set,
                       ob_err *err)
{
    char *copy = malloc(len ? len : 1);
    if (len)
        memcpy(copy, text, len);
    int rc = ob_curves_parse(copy, len, name, set, err);
    free(copy);
    return rc;
}

/* The two curves are identical field by field (segments bitwise). */
static int same_curve(const ob_curve *a, const ob_curve *b)
{
    if (strcmp(a->id, b->id) || strcmp(a->source, b->source) || strcmp(a->family, b->family))
        return 0;
    if (a->nseg != b->nseg || a->nd != b->nd || a->line != b->line)
        return 0;
    for (int i = 0; i < a->nseg; i++)
        if (a->seg[i].deg != b->seg[i].deg || a->seg[i].rational != b->seg[i].rational ||
            memcmp(a->seg[i].h, b->seg[i].h, sizeof a->seg[i].h))
            return 0;
    return memcmp(a->d, b->d, (size_t)a->nd * sizeof *a->d) == 0;
}

static void test_published(void)
{
    ob_curveset set = {0};
    ob_err err = {""};
    int rc = ob_curves_load_file(PUBLISHED, &set, &err);
    CHECK(rc == 0, "load %s: %s", PUBLISHED, err.msg);
    CHECK(set.n == 5, "%d curves", set.n);
    static const struct {
        const char *id;
        int nseg, deg, nd;
        double d0, d1;
    } want[] = {
        {"liu2002_ex1", 1, 3, 2, 1.0, -1.0},
        {"liu2002_ex2", 4, 3, 1, 0.5, 0},
        {"liu2002_ex2_unclamped", 4, 3, 1, 0.5, 0},
        {"zhao2017_septic", 1, 7, 1, 0.5, 0},
        {"zhao2017_quintic", 1, 5, 1, 0.5, 0},
    };
    for (int k = 0; k < 5; k++) {
        int i = ob_curveset_find(&set, want[k].id);
        CHECK(i == k, "%s at index %d", want[k].id, i);
        if (i < 0)
            continue;
        const ob_curve *c = &set.v[i];
        CHECK(c->nseg == want[k].nseg, "%s: %d segments", c->id, c->nseg);
        for (int s = 0; s < c->nseg; s++)
            CHECK(c->seg[s].deg == want[k].deg && !c->seg[s].rational, "%s seg %d: deg %d rat %d",
                  c->id, s, c->seg[s].deg, c->seg[s].rational);
        CHECK(c->nd == want[k].nd, "%s: %d offsets", c->id, c->nd);
        CHECK(c->nd >= 1 && c->d[0] == want[k].d0, "%s: d0", c->id);
        if (want[k].nd == 2)
            CHECK(c->nd == 2 && c->d[1] == want[k].d1, "%s: d1", c->id);
        CHECK(!strcmp(c->family, "published"), "%s: family '%s'", c->id, c->family);
        CHECK(!strcmp(c->file, PUBLISHED), "%s: file '%s'", c->id, c->file);
        CHECK(c->line > 0, "%s: line %d", c->id, c->line);
        CHECK(strstr(c->source, "seed text") != NULL, "%s: source '%s'", c->id, c->source);
    }
    /* spot checks of the data itself */
    if (set.n == 5) {
        const ob_bez *b = &set.v[0].seg[0];
        CHECK(b->h[0][0] == -0.785938 && b->h[0][1] == 0.891849 && b->h[3][0] == 0.9 &&
                  b->h[3][1] == -0.2 && b->h[2][2] == 1.0,
              "liu2002_ex1 control points");
        b = &set.v[3].seg[0];
        CHECK(b->h[0][0] == -0.8 && b->h[7][1] == 3.9 && b->h[5][0] == -1.2, "septic points");
        b = &set.v[4].seg[0];
        CHECK(b->h[0][0] == 3 && b->h[0][1] == -1 && b->h[5][0] == 7, "quintic points");
        /* ex2, open uniform (clamped): it starts at P0 and ends at P6 */
        b = &set.v[1].seg[0];
        CHECK(b->h[0][0] == -3.01619 && b->h[0][1] == 2.34143, "ex2 (clamped) starts at P0");
        CHECK(set.v[1].seg[3].h[3][0] == 2.8027 && set.v[1].seg[3].h[3][1] == 3.02775, "ex2 (clamped) ends at P6");
        /* ex2 unclamped: the first Bézier point of a uniform cubic is (P0 + 4 P1 + P2) / 6 */
        b = &set.v[2].seg[0];
        CHECK_NEAR(b->h[0][0], (-3.01619 + 4 * -3.97193 + -1.07045) / 6, 1e-14, "ex2 unclamped start x");
        CHECK_NEAR(b->h[0][1], (2.34143 + 4 * -2.20842 + 0.0722807) / 6, 1e-14, "ex2 unclamped start y");
        for (int c = 1; c <= 2; c++)
            for (int s = 0; s + 1 < 4; s++)
                CHECK(fabs(set.v[c].seg[s].h[3][0] - set.v[c].seg[s + 1].h[0][0]) < 1e-14, "%s joint %d",
                      set.v[c].id, s);
    }
    ob_curveset_free(&set);
    CHECK(set.n == 0 && set.v == NULL, "freed set is zeroed");
    ob_curveset_free(&set); /* twice is fine */
}

/* CRLF, a byte order mark and a missing final newline all parse to the same
 * curves as the LF original. */
static void test_crlf_roundtrip(void)
{
    size_t len = 0;
    char *lf = read_all(PUBLISHED, &len);
    CHECK(lf != NULL, "read %s", PUBLISHED);
    if (!lf)
        return;
    char *crlf = malloc(2 * len + 3);
    size_t m = 0;
    for (size_t i = 0; i < len; i++) {
        if (lf[i] == '\n')
            crlf[m++] = '\r';
        crlf[m++] = lf[i];
    }
    ob_curveset a = {0}, b = {0}, c = {0};
    ob_err err = {""};
    CHECK(parse_exact(lf, len, PUBLISHED, &a, &err) == 0, "LF: %s", err.msg);
    CHECK(parse_exact(crlf, m, PUBLISHED, &b, &err) == 0, "CRLF: %s", err.msg);
    /* BOM in front, CRLF, and the final "\r\n" dropped */
    char *bom = malloc(m + 3);
    memcpy(bom, "\xEF\xBB\xBF", 3);
    memcpy(bom + 3, crlf, m);
    CHECK(parse_exact(bom, m + 3 - 2, PUBLISHED, &c, &err) == 0, "BOM: %s", err.msg);
    CHECK(a.n == 5 && b.n == a.n && c.n == a.n, "counts %d %d %d", a.n, b.n, c.n);
    for (int i = 0; i < a.n && i < b.n && i < c.n; i++) {
        CHECK(same_curve(&a.v[i], &b.v[i]), "CRLF curve %d differs", i);
        CHECK(same_curve(&a.v[i], &c.v[i]), "BOM curve %d differs", i);
    }
    ob_curveset_free(&a);
    ob_curveset_free(&b);
    ob_curveset_free(&c);
    free(bom);
    free(crlf);
    free(lf);
}

/* Layout freedom the format allows. */
static void test_valid_variants(void)
{
    const char *text =
        "\t# leading comment\n"
        "curve r/1.a-b_c   # trailing comment\n"
        "\tfamily random-convex\n"
        "  bspline 2\n"
        "  knots 0 0 0\n"
        "  knots   1   # split over lines\n"
        "  knots 2 2 2\n"
        "  point 0 0\n"
        "  point 1 2 0.5\n"
        "  point 3 -1 2\n"
        "  point 4 1\n"
        "  offset 0.25 -0.25\n"
        "  offset 1e-3\n"
        "end\n"
        "\n"
        "curve s\n"
        "  bezier 1\n"
        "  point 0 0\n"
        "  point 1 0\n"
        "  offset 2\n"
        "end"; /* no final newline */
    ob_curveset set = {0};
    ob_err err = {""};
    int rc = parse_exact(text, strlen(text), "mem", &set, &err);
    CHECK(rc == 0, "variants: %s", err.msg);
    if (rc == 0 && set.n == 2) {
        const ob_curve *c = &set.v[0];
        CHECK(!strcmp(c->id, "r/1.a-b_c"), "id '%s'", c->id);
        CHECK(!strcmp(c->family, "random-convex"), "family '%s'", c->family);
        CHECK(!strcmp(c->source, ""), "source '%s'", c->source);
        CHECK(c->line == 2 && set.v[1].line == 16, "lines %d %d", c->line, set.v[1].line);
        CHECK(c->nseg == 2 && c->seg[0].deg == 2, "bspline: %d segments", c->nseg);
        CHECK(c->seg[0].rational && c->seg[1].rational, "rational flags");
        CHECK(c->nd == 3 && c->d[0] == 0.25 && c->d[1] == -0.25 && c->d[2] == 1e-3, "offsets");
        /* clamped quadratic: first point (0,0), last (4,1), weight 1 */
        double p[2];
        ob_bez_point(&c->seg[0], 0.0, p);
        CHECK(p[0] == 0 && p[1] == 0, "start point");
        ob_bez_point(&c->seg[1], 1.0, p);
        CHECK_NEAR(p[0], 4, 1e-15, "end x");
        CHECK_NEAR(p[1], 1, 1e-15, "end y");
        CHECK(!strcmp(set.v[1].file, "mem") && set.v[1].nseg == 1, "second curve");
    } else {
        CHECK(0, "expected 2 curves, got %d", set.n);
    }
    ob_curveset_free(&set);

    /* a line of exactly 4096 bytes is accepted, 4097 is not */
    char *big = malloc(5000);
    for (int extra = 0; extra <= 1; extra++) {
        size_t n = 0;
        n += (size_t)sprintf(big, "curve long\n  bezier 1\n  point 0 0\n  point 1 0\n  offset 1\nend\n");
        size_t start = n;
        big[n++] = '#';
        while (n - start < 4096 + (size_t)extra)
            big[n++] = 'z';
        big[n++] = '\r'; /* CRLF does not count */
        big[n++] = '\n';
        rc = parse_exact(big, n, "big", &set, &err);
        CHECK(rc == (extra ? -1 : 0), "line of %d bytes: rc %d (%s)", 4096 + extra, rc, err.msg);
        if (extra)
            CHECK(starts_with(err.msg, "big:7:"), "long line message '%s'", err.msg);
        ob_curveset_free(&set);
    }
    free(big);

    /* empty input and comment-only input give no curves and no error */
    CHECK(ob_curves_parse(NULL, 0, "empty", &set, &err) == 0 && set.n == 0, "empty");
    CHECK(parse_exact("# nothing\n\n", 11, "c", &set, &err) == 0 && set.n == 0,
          "comments only");
}

static void test_bad_corpus(void)
{
    DIR *d = opendir(BAD_DIR);
    CHECK(d != NULL, "cannot open %s", BAD_DIR);
    if (!d)
        return;
    char *names[512];
    int n = 0;
    struct dirent *de;
    while ((de = readdir(d)) && n < 512) {
        size_t k = strlen(de->d_name);
        if (k > 7 && !strcmp(de->d_name + k - 7, ".curves"))
            names[n++] = strdup(de->d_name);
    }
    closedir(d);
    CHECK(n >= 25, "only %d malformed files", n);

    /* the published curves are loaded first, so that a file may also test
     * duplicate ids across files */
    ob_curveset set = {0};
    ob_err err = {""};
    CHECK(ob_curves_load_file(PUBLISHED, &set, &err) == 0, "%s", err.msg);
    const int n0 = set.n;
    for (int i = 0; i < n; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", BAD_DIR, names[i]);
        size_t len = 0;
        char *text = read_all(path, &len);
        int expect = -1;
        if (text && len > 16 && !strncmp(text, "# expect-line: ", 15))
            expect = atoi(text + 15);
        free(text);
        CHECK(expect > 0, "%s: no '# expect-line: N' first line", path);

        strcpy(err.msg, "untouched");
        int rc = ob_curves_load_file(path, &set, &err);
        char prefix[600];
        snprintf(prefix, sizeof prefix, "%s:%d: ", path, expect);
        CHECK(rc == -1, "%s: parsed although malformed", path);
        CHECK(starts_with(err.msg, prefix), "%s: message '%s', expected it to start with '%s'", path,
              err.msg, prefix);
        CHECK(strchr(err.msg, '\n') == NULL && strlen(err.msg) > strlen(prefix), "%s: message '%s'",
              path, err.msg);
        CHECK(set.n == n0, "%s: set grew to %d", path, set.n);
        free(names[i]);
    }
    for (int i = 0; i < n0 && i < set.n; i++)
        CHECK(set.v[i].nseg >= 1 && set.v[i].d != NULL, "set damaged at %d", i);
    ob_curveset_free(&set);
}

static void test_dir_and_files(void)
{
    ob_curveset set = {0};
    ob_err err = {""};

    CHECK(ob_curves_load_dir("datasets", &set, &err) == 0, "datasets: %s", err.msg);
    CHECK(set.n >= 4 && ob_curveset_find(&set, "liu2002_ex2") >= 0 &&
              ob_curveset_find(&set, "zhao2017_quintic") >= 0,
          "datasets: %d curves", set.n);
    CHECK(ob_curveset_find(&set, "no-such-id") == -1, "find missing id");
    ob_curveset_free(&set);

    char dir[] = "/tmp/ob_curvefile_XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    char p[4][300];
    const char *files[4] = {"b.curves", "a.curves", "notes.txt", ".hidden.curves"};
    const char *texts[4] = {
        "curve b1\n bezier 1\n point 0 0\n point 1 1\n offset 1\nend\n",
        ("curve a1\n bezier 1\n point 0 0\n point 1 1\n offset 1\nend\n"
         "curve a2\n bezier 1\n point 0 0\n point 1 1\n offset 1\nend\n"),
        "not a curve file\n",
        "garbage\n",
    };
    for (int i = 0; i < 4; i++) {
        snprintf(p[i], sizeof p[i], "%s/%s", dir, files[i]);
        write_file(p[i], texts[i]);
    }
    CHECK(ob_curves_load_dir(dir, &set, &err) == 0, "tmp dir: %s", err.msg);
    CHECK(set.n == 3, "tmp dir: %d curves", set.n);
    if (set.n == 3) {
        CHECK(!strcmp(set.v[0].id, "a1") && !strcmp(set.v[1].id, "a2") &&
                  !strcmp(set.v[2].id, "b1"),
              "name order: %s %s %s", set.v[0].id, set.v[1].id, set.v[2].id);
        CHECK(!strcmp(set.v[0].file, p[1]) && set.v[1].line == 7, "file '%s' line %d",
              set.v[0].file, set.v[1].line);
    }
    /* loading the same directory again: duplicate ids, nothing appended */
    CHECK(ob_curves_load_dir(dir, &set, &err) == -1 && set.n == 3, "reload");
    char want[400];
    snprintf(want, sizeof want, "%s:1: duplicate id 'a1'", p[1]);
    CHECK(starts_with(err.msg, want), "reload message '%s'", err.msg);
    ob_curveset_free(&set);

    /* a bad file after good ones: all or nothing, message names DIR/FILE */
    char pc[300];
    snprintf(pc, sizeof pc, "%s/c.curves", dir);
    write_file(pc, "curve c1\n bezier 1\n point 0 0\n point 1 x\n offset 1\nend\n");
    CHECK(ob_curves_load_dir(dir, &set, &err) == -1 && set.n == 0,
          "bad file: rc, %d curves", set.n);
    snprintf(want, sizeof want, "%s:4: ", pc);
    CHECK(starts_with(err.msg, want), "bad file message '%s'", err.msg);
    /* the same through a trailing slash */
    char dirslash[320];
    snprintf(dirslash, sizeof dirslash, "%s/", dir);
    CHECK(ob_curves_load_dir(dirslash, &set, &err) == -1 && starts_with(err.msg, want),
          "trailing slash message '%s'", err.msg);
    ob_curveset_free(&set);

    /* a file too large (sparse, so this is cheap) */
    char pbig[300];
    snprintf(pbig, sizeof pbig, "%s/big.data", dir);
    write_file(pbig, "");
    CHECK(truncate(pbig, ((off_t)64 << 20) + 1) == 0, "truncate");
    CHECK(ob_curves_load_file(pbig, &set, &err) == -1 && set.n == 0, "big file");
    CHECK(starts_with(err.msg, pbig) && strstr(err.msg, "too large"), "big file message '%s'", err.msg);

    /* missing file, directory as a file, missing directory */
    char pmiss[300];
    snprintf(pmiss, sizeof pmiss, "%s/missing.curves", dir);
    CHECK(ob_curves_load_file(pmiss, &set, &err) == -1 && starts_with(err.msg, pmiss),
          "missing file: '%s'", err.msg);
    CHECK(ob_curves_load_file(dir, &set, &err) == -1 && starts_with(err.msg, dir),
          "directory as file: '%s'", err.msg);
    CHECK(ob_curves_load_dir(pmiss, &set, &err) == -1 && starts_with(err.msg, pmiss),
          "missing dir: '%s'", err.msg);
    CHECK(set.n == 0, "nothing appended");

    for (int i = 0; i < 4; i++)
        unlink(p[i]);
    unlink(pc);
    unlink(pbig);
    CHECK(rmdir(dir) == 0, "rmdir %s", dir);
    ob_curveset_free(&set);
}

/* A message longer than the carrier is cut inside it (NUL-terminated, the
 * "NAME:LINE: " prefix kept); a missing carrier is allowed. */
static void test_error_buffer(void)
{
    ob_curveset set = {0};
    const char *bad = "curve x\n bezier 99\n";
    static ob_err e;
    static char name[sizeof e.msg + 100];
    memset(name, 'n', sizeof name - 1);
    memset(e.msg, 'Q', sizeof e.msg);
    CHECK(ob_curves_parse(bad, strlen(bad), name, &set, &e) == -1, "long name");
    CHECK(memchr(e.msg, '\0', sizeof e.msg) != NULL && strlen(e.msg) == sizeof e.msg - 1 &&
              starts_with(e.msg, "nnnn"),
          "long message cut at %zu bytes, got %zu", sizeof e.msg - 1, strnlen(e.msg, sizeof e.msg));
    CHECK(ob_curves_parse(bad, strlen(bad), "name", &set, &e) == -1 && starts_with(e.msg, "name:2: "),
          "message '%s'", e.msg);
    CHECK(ob_curves_parse(bad, strlen(bad), "name", &set, NULL) == -1, "NULL err");
    CHECK(ob_curves_parse(bad, strlen(bad), "name", NULL, &e) == -1, "NULL set");
    CHECK(set.n == 0, "nothing appended");
}

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static unsigned rnd(unsigned n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (unsigned)(rng >> 33) % n;
}

/* Every outcome must be a clean success or a clean "fuzz:LINE: ..." failure
 * that leaves the set alone; ASan/UBSan catch the rest. */
static void fuzz_one(const char *buf, size_t len, ob_curveset *set, int *ok, int *bad)
{
    ob_err err = {""};
    int n0 = set->n;
    int rc = parse_exact(buf, len, "fuzz", set, &err);
    if (rc == 0) {
        (*ok)++;
        for (int i = n0; i < set->n; i++) {
            const ob_curve *c = &set->v[i];
            int good = c->nseg >= 1 && c->nd >= 1 && c->source && c->family;
            for (int j = 0; j < c->nd && good; j++)
                good = isfinite(c->d[j]) && c->d[j] != 0;
            for (int s = 0; s < c->nseg && good; s++)
                for (int k = 0; k <= c->seg[s].deg && good; k++)
                    good = isfinite(c->seg[s].h[k][0]) && isfinite(c->seg[s].h[k][1]) &&
                           c->seg[s].h[k][2] > 0;
            if (!good)
                CHECK(0, "fuzz: accepted a bad curve '%s'", c->id);
        }
        for (int i = n0; i < set->n; i++)
            ob_curve_free(&set->v[i]);
        set->n = n0;
    } else {
        (*bad)++;
        if (rc != -1 || !starts_with(err.msg, "fuzz:") || strchr(err.msg, '\n') || set->n != n0)
            CHECK(0, "fuzz: rc %d, message '%s', n %d", rc, err.msg, set->n);
    }
}

static void test_fuzz(void)
{
    size_t len = 0;
    char *orig = read_all(PUBLISHED, &len);
    CHECK(orig != NULL, "read %s", PUBLISHED);
    if (!orig)
        return;
    ob_curveset set = {0};
    int ok = 0, bad = 0;
    char *buf = malloc(len + 64);
    /* every prefix */
    for (size_t k = 0; k <= len; k++)
        fuzz_one(orig, k, &set, &ok, &bad);
    /* random byte edits */
    static const char alphabet[] = "0123456789.-+eE \t\n\r#xyznai\0\x01\x80\xff";
    for (int it = 0; it < 4000; it++) {
        memcpy(buf, orig, len);
        size_t n = len;
        int edits = 1 + (int)rnd(4);
        for (int e = 0; e < edits; e++) {
            size_t at = rnd((unsigned)n);
            switch (rnd(3)) {
            case 0: /* replace */
                buf[at] = rnd(2) ? alphabet[rnd(sizeof alphabet - 1)] : (char)rnd(256);
                break;
            case 1: /* delete */
                memmove(buf + at, buf + at + 1, n - at - 1);
                n--;
                break;
            default: /* duplicate a byte */
                if (n < len + 63) {
                    memmove(buf + at + 1, buf + at, n - at);
                    n++;
                }
            }
        }
        fuzz_one(buf, n, &set, &ok, &bad);
    }
    /* pure noise */
    for (int it = 0; it < 500; it++) {
        size_t n = rnd(64);
        for (size_t i = 0; i < n; i++)
            buf[i] = (char)rnd(256);
        fuzz_one(buf, n, &set, &ok, &bad);
    }
    CHECK(ok > 0 && bad > 0, "fuzz outcomes: %d ok, %d rejected", ok, bad);
    CHECK(set.n == 0, "fuzz left %d curves", set.n);
    ob_curveset_free(&set);
    free(buf);
    free(orig);
}

/* The one offset check (ob_offset_check): the file's `offset` line and
 * --d of draw, trace and measure refuse the same values. */
static void expect_d(double d, double m, int ok, const char *want)
{
    char why[200] = "";
    const int rc = ob_offset_check(d, m, why, sizeof why);
    CHECK((rc == 0) == ok && (ok || strstr(why, want)), "d = %g, coord_max %g: rc %d '%s' (want %s '%s')", d, m, rc,
          why, ok ? "ok" : "refused", want ? want : "");
}

/* A one-curve file of coordinate scale m with offset d: parsed or refused. */
static int file_takes(double m, double d, ob_err *err)
{
    char text[400];
    snprintf(text, sizeof text, "curve c\n  bezier 2\n  point 0 0\n  point %.17g %.17g\n  point %.17g 0\n"
             "  offset %.17g\nend\n", m / 2, m / 2, m, d);
    ob_curveset set = {0};
    const int rc = ob_curves_parse(text, strlen(text), "d.curves", &set, err);
    ob_curveset_free(&set);
    return rc == 0;
}

static void test_offset_check(void)
{
    expect_d(0.0, 0, 0, "offset distance 0");
    expect_d(-0.0, 1, 0, "offset distance 0");
    expect_d(INFINITY, 0, 0, "not a finite");
    expect_d(-INFINITY, 1, 0, "not a finite");
    expect_d(NAN, 1, 0, "not a finite");
    expect_d(1e-51, 0, 0, "too small");
    expect_d(-1e-60, 0, 0, "too small");
    expect_d(1e-50, 0, 1, NULL);
    expect_d(-1e-50, 0, 1, NULL);
    expect_d(1e12, 0, 1, NULL);
    expect_d(-1.0000001e12, 0, 0, "too large");
    expect_d(1e13, 1, 0, "too large");
    expect_d(1e-7, 2e6, 0, "below 1e-12 times");
    expect_d(-1.9e-6, 2e6, 0, "below 1e-12 times");
    expect_d(2e-6, 2e6, 1, NULL);
    expect_d(-2e-6, 2e6, 1, NULL);
    expect_d(1e-40, 0, 1, NULL);  /* no scale known: only the absolute limits */
    expect_d(0.5, 1, 1, NULL);

    /* the file takes exactly what the check takes, at any scale */
    static const double scales[] = {1e-40, 1e-6, 1, 2e6, 1e11};
    static const double rel[] = {1e-13, 0.99e-12, 1e-12, 1.01e-12, 1e-3, 1};
    for (size_t a = 0; a < sizeof scales / sizeof scales[0]; a++)
        for (size_t b = 0; b < sizeof rel / sizeof rel[0]; b++)
            for (int sign = -1; sign <= 1; sign += 2) {
                const double m = scales[a], d = sign * rel[b] * m;
                ob_err err = {""};
                char why[200];
                const int file = file_takes(m, d, &err), check = ob_offset_check(d, m, why, sizeof why) == 0;
                CHECK(file == check, "scale %g, d %g: the file %s ('%s'), the check %s", m, d,
                      file ? "takes it" : "refuses it", err.msg, check ? "takes it" : "refuses it");
            }

    /* coord_max: the largest |coordinate| as defined, a B-spline's before its
     * conversion, an hpoint's Euclidean x, y */
    const char *full = "curve b\n  bspline 3\n  knots 0 0 0 0 1 2 2 2 2\n  point 0 0\n  point 1 0\n"
                       "  point 2 -9\n  point 3 0\n  point 4 0\n  offset 1\nend\n"
                       "curve h\n  bezier 1\n  hpoint 8 2 2\n  hpoint -10 1 1\n  offset 1\nend\n";
    ob_curveset set = {0};
    ob_err err = {""};
    CHECK(ob_curves_parse(full, strlen(full), "m.curves", &set, &err) == 0 && set.n == 2, "coord_max file: %s",
          err.msg);
    if (set.n == 2) {
        double seg_max = 0;  /* its Bezier segments reach only half of the B-spline's 9 */
        for (int k = 0; k < set.v[0].nseg; k++)
            for (int i = 0; i <= set.v[0].seg[k].deg; i++)
                seg_max = fmax(seg_max, fabs(set.v[0].seg[k].h[i][1] / set.v[0].seg[k].h[i][2]));
        CHECK(set.v[0].coord_max == 9 && seg_max < 9, "B-spline: coord_max %g (segments %g), want 9",
              set.v[0].coord_max, seg_max);
        CHECK(set.v[1].coord_max == 10, "hpoints: coord_max %g, want 10", set.v[1].coord_max);
    }
    ob_curveset_free(&set);
}

int main(void)
{
    test_offset_check();
    test_published();
    test_crlf_roundtrip();
    test_valid_variants();
    test_bad_corpus();
    test_dir_and_files();
    test_error_buffer();
    test_fuzz();
    return check_done();
}
