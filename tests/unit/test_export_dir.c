/*
 * test_export_dir.c - what `--export DIR` holds (host/io/export_dir.h):
 * - the export's own names: the four extensions and their .tmp over stems
 *   of the pattern CURVE__dD__METHOD__tolT (every stem ob_export_stem makes,
 *   ids with '/', '.', '_', '-', '__d' inside), index.csv and
 *   index.shardK-of-N.csv; near misses (another extension, d or tol no
 *   number, an empty part, characters ids cannot hold, K >= N) are not;
 * - pruning removes exactly the owned names the rule does not keep, in
 *   scope; other files, directories named like stems, and the targets of
 *   links stay (a link named like a stem goes itself);
 * - an export directory that is $OFFBENCH_DATA's directory (however
 *   spelled: "/.", a trailing slash, a link) or the build's datasets/ is
 *   refused naming --export; a subdirectory and other directories are not.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/diag.h"
#include "host/io/export.h"
#include "host/io/export_dir.h"
#include "tests/check.h"
#include "tests/driver_fixture.h"

static char last_msg[8192];
static void capture(const char *m) { snprintf(last_msg, sizeof last_msg, "%s", m); }

static char dir[256];

static void put(const char *name, const char *text)
{
    char p[600];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static int exists(const char *name)
{
    char p[600];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return lstat(p, &st) == 0;
}

static void expect_kind(const char *name, ob_xname want, const char *want_stem)
{
    char stem[512] = "";
    int k = -1, n = -1;
    const ob_xname got = ob_export_name_kind(name, stem, sizeof stem, &k, &n);
    CHECK(got == want, "'%s': kind %d, want %d", name, (int)got, (int)want);
    if (want_stem)
        CHECK(strcmp(stem, want_stem) == 0, "'%s': stem '%s', want '%s'", name, stem, want_stem);
}

static void test_names(void)
{
    expect_kind("liu2002_ex1__d-1__tiller__tol0.01.json", OB_XNAME_STEM, "liu2002_ex1__d-1__tiller__tol0.01");
    expect_kind("liu2002_ex1__d-1__tiller__tol0.01.curves", OB_XNAME_STEM, "liu2002_ex1__d-1__tiller__tol0.01");
    expect_kind("liu2002_ex1__d1__zhao-rational__tol1e-05.dxf", OB_XNAME_STEM,
                "liu2002_ex1__d1__zhao-rational__tol1e-05");
    expect_kind("rnd5_000003__d0.1234__cubic-opt__tol0.1.svg", OB_XNAME_STEM, "rnd5_000003__d0.1234__cubic-opt__tol0.1");
    expect_kind("a~b.c__d2.5e-07__lee__tol1e-05.json.tmp", OB_XNAME_STEM, "a~b.c__d2.5e-07__lee__tol1e-05");
    expect_kind("x__dd__d0.5__ahn__tol1.json", OB_XNAME_STEM, "x__dd__d0.5__ahn__tol1");  /* "__d" in the id */
    expect_kind("index.csv", OB_XNAME_INDEX, NULL);
    int k = -1, n = -1;
    CHECK(ob_export_name_kind("index.shard3-of-10.csv", NULL, 0, &k, &n) == OB_XNAME_SHARD_INDEX && k == 3 && n == 10,
          "shard index: %d of %d", k, n);
    static const char *const other[] = {
        "liu2002_ex1__d-1__tiller__tol0.01.png",  "liu2002_ex1__d-1__tiller__tol0.01",
        "liu2002_ex1__dx__tiller__tol0.01.json",   "liu2002_ex1__d-1__tiller__tolx.json",
        "liu2002_ex1__d__tiller__tol0.01.json",    "liu2002_ex1__d1____tol0.01.json",
        "__d1__tiller__tol0.01.json",              "a b__d1__tiller__tol0.01.json",
        "a/b__d1__tiller__tol0.01.json",           "c__d1__til ler__tol0.01.json",
        "c__d1__tiller__tol.json",                 "c__d1__tiller__tol0.01.json.bak",
        "index.shard2-of-2.csv",                   "index.shard01-of-2.csv",
        "index.shard0-of-2.csv.tmp",               "index.csv.bak",
        "results.csv",                             "notes.txt",
        ".tmp",                                    "",
    };
    for (size_t i = 0; i < sizeof other / sizeof other[0]; i++)
        expect_kind(other[i], OB_XNAME_OTHER, NULL);

    /* every stem the export makes is one of its names, ids with '/' too */
    static const char *const ids[] = {"liu2002_ex1", "atlas/cardioid", "a.b-c_d", "x__dy", "rnd1_000000"};
    static const double ds[] = {1, -1, 0.5, -2.5e-7, 1e12, 1e-50};
    static const char *const ms[] = {"tiller", "zhao-rational", "bspline-lsq", "exact"};
    static const double tols[] = {0.1, 1e-5, 1e6, 3e-300};
    for (size_t a = 0; a < sizeof ids / sizeof ids[0]; a++)
        for (size_t b = 0; b < sizeof ds / sizeof ds[0]; b++)
            for (size_t m = 0; m < sizeof ms / sizeof ms[0]; m++)
                for (size_t t = 0; t < sizeof tols / sizeof tols[0]; t++) {
                    ob_curve c = fixture_curve(ids[a], 3, fixture_liu_ex1, ds[b]);
                    ob_job j;
                    fixture_job(&j, &c, ob_method_find(ms[m]), OB_METRIC_HAUSDORFF, OB_SPLIT_MID, tols[t]);
                    char stem[400], name[420], back[512];
                    ob_export_stem(stem, sizeof stem, &j);
                    snprintf(name, sizeof name, "%s.curves", stem);
                    CHECK(ob_export_name_kind(name, back, sizeof back, NULL, NULL) == OB_XNAME_STEM &&
                              strcmp(back, stem) == 0,
                          "the export's own stem '%s' is not recognised", stem);
                    ob_curve_free(&c);
                }
    char b[64];
    ob_export_index_name(b, sizeof b, 0, 0);
    CHECK(strcmp(b, "index.csv") == 0, "plain index: %s", b);
    ob_export_index_name(b, sizeof b, 2, 7);
    CHECK(strcmp(b, "index.shard2-of-7.csv") == 0 &&
              ob_export_name_kind(b, NULL, 0, NULL, NULL) == OB_XNAME_SHARD_INDEX,
          "shard index: %s", b);
}

#define A "c__d1__tiller__tol0.1"
#define B "c__d-1__tiller__tol0.1"
#define C "c__d1__cobb__tol0.1"

/* A directory with the three stems' files, an index, shard indexes,
 * someone else's files and a link named like a stem to a file outside. */
static void populate(const char *outside)
{
    static const char *const ext[] = {"json", "curves", "dxf", "svg", "json.tmp"};
    char name[128], lp[600];
    for (size_t e = 0; e < sizeof ext / sizeof ext[0]; e++) {
        snprintf(name, sizeof name, A ".%s", ext[e]);
        put(name, "a");
        snprintf(name, sizeof name, B ".%s", ext[e]);
        put(name, "b");
        snprintf(name, sizeof name, C ".%s", ext[e]);
        put(name, "c");
    }
    put("index.csv", "i");
    put("index.shard0-of-2.csv", "s");
    put("index.shard1-of-3.csv", "s");
    put("notes.txt", "mine");
    put("c__d1__tiller__tol0.1.png", "mine");
    snprintf(lp, sizeof lp, "%s/old__d1__tiller__tol1.svg", dir);
    unlink(lp);
    CHECK(symlink(outside, lp) == 0, "symlink: %s", strerror(errno));
    snprintf(lp, sizeof lp, "%s/z__d1__tiller__tol1.json", dir);
    mkdir(lp, 0777);
}

static void test_prune(void)
{
    char outside[300];
    snprintf(outside, sizeof outside, "%s.outside", dir);
    FILE *f = fopen(outside, "w");
    if (f) {
        fputs("precious", f);
        fclose(f);
    }
    ob_strmap keep = {0}, scope = {0};
    ob_strmap_put(&keep, A, 0);
    ob_err err;
    long removed = -1;

    /* a plain export keeping A: B, C, the link, the shard indexes and index.csv go */
    populate(outside);
    const ob_prune_rule plain = {&keep, NULL, 0, 1};
    CHECK(ob_export_prune(dir, &plain, &removed, &err) == 0, "prune: %s", err.msg);
    CHECK(removed == 10 + 1 + 1 + 2 + 1, "plain: removed %ld", removed);
    CHECK(exists(A ".json") && exists(A ".svg") && exists(A ".json.tmp") == 0, "A's files stay, its .tmp goes");
    CHECK(!exists(B ".json") && !exists(C ".dxf") && !exists(B ".json.tmp"), "B and C go");
    CHECK(!exists("index.csv") && !exists("index.shard0-of-2.csv") && !exists("index.shard1-of-3.csv"),
          "indexes go");
    CHECK(exists("notes.txt") && exists("c__d1__tiller__tol0.1.png") && exists("z__d1__tiller__tol1.json"),
          "other files and a directory named like a stem stay");
    CHECK(!exists("old__d1__tiller__tol1.svg") && access(outside, F_OK) == 0, "the link goes, not its target");
    f = fopen(outside, "r");
    char buf[32] = "";
    if (f) {
        CHECK(fgets(buf, sizeof buf, f) && strcmp(buf, "precious") == 0, "the link's target keeps its bytes");
        fclose(f);
    }

    /* a shard (scope: its own jobs A and B; B has no approximation now):
     * only B goes; C (another shard's), index.csv and shard indexes stay */
    populate(outside);
    ob_strmap_put(&scope, A, 0);
    ob_strmap_put(&scope, B, 0);
    const ob_prune_rule shard = {&keep, &scope, -1, 0};
    CHECK(ob_export_prune(dir, &shard, &removed, &err) == 0 && removed == 5 + 1, "shard: removed %ld", removed);
    CHECK(exists(A ".dxf") && !exists(B ".dxf") && exists(C ".dxf") && exists(C ".json.tmp"),
          "shard: only its own job without an approximation goes");
    CHECK(exists("index.csv") && exists("index.shard0-of-2.csv") && exists("index.shard1-of-3.csv") &&
              exists("old__d1__tiller__tol1.svg"),
          "shard: indexes and names out of scope stay");

    /* merge of 2 shards: its shard indexes stay, another N's go */
    populate(outside);
    const ob_prune_rule merge = {&keep, NULL, 2, 0};
    CHECK(ob_export_prune(dir, &merge, &removed, &err) == 0, "merge prune: %s", err.msg);
    CHECK(exists("index.shard0-of-2.csv") && !exists("index.shard1-of-3.csv") && exists("index.csv"),
          "merge: shard indexes of its N stay, index.csv stays");

    /* nothing to keep: every stem goes; a missing directory is nothing to do */
    populate(outside);
    const ob_prune_rule none = {NULL, NULL, -1, 0};
    CHECK(ob_export_prune(dir, &none, &removed, &err) == 0 && !exists(A ".json") && exists("notes.txt"),
          "keep nothing");
    char gone[300];
    snprintf(gone, sizeof gone, "%s/no/such/dir", dir);
    CHECK(ob_export_prune(gone, &none, &removed, &err) == 0 && removed == 0, "missing directory: %s", err.msg);
    ob_strmap_free(&keep);
    ob_strmap_free(&scope);
    unlink(outside);
}

static void expect_refused(const char *what, const char *d, const char *curves, const char *want)
{
    last_msg[0] = '\0';
    CHECK(ob_export_check_dir("run", d, curves) == -1 && strstr(last_msg, "--export") && strstr(last_msg, want),
          "%s (%s): '%s'", what, d, last_msg);
}

static void test_curve_dirs(void)
{
    char data[300], sub[320], alias[320], spelled[330], other[320], curves[330];
    snprintf(data, sizeof data, "%s/data", dir);
    snprintf(sub, sizeof sub, "%s/sub", data);
    snprintf(alias, sizeof alias, "%s/alias", dir);
    snprintf(other, sizeof other, "%s/other", dir);
    snprintf(curves, sizeof curves, "%s/my.curves", other);
    mkdir(data, 0777);
    mkdir(sub, 0777);
    mkdir(other, 0777);
    unlink(alias);
    CHECK(symlink(data, alias) == 0, "symlink: %s", strerror(errno));
    setenv("OFFBENCH_DATA", data, 1);
    expect_refused("$OFFBENCH_DATA itself", data, NULL, "OFFBENCH_DATA");
    snprintf(spelled, sizeof spelled, "%s/.", data);
    expect_refused("$OFFBENCH_DATA/.", spelled, NULL, "OFFBENCH_DATA");
    snprintf(spelled, sizeof spelled, "%s/", data);
    expect_refused("$OFFBENCH_DATA/", spelled, NULL, "OFFBENCH_DATA");
    expect_refused("a link to $OFFBENCH_DATA", alias, NULL, "OFFBENCH_DATA");
    snprintf(spelled, sizeof spelled, "%s/sub/..", data);
    expect_refused("$OFFBENCH_DATA/sub/..", spelled, NULL, "OFFBENCH_DATA");
    CHECK(ob_export_check_dir("run", sub, NULL) == 0, "a subdirectory of $OFFBENCH_DATA is fine: %s", last_msg);
    CHECK(ob_export_check_dir("run", other, NULL) == 0, "another directory is fine: %s", last_msg);
    snprintf(spelled, sizeof spelled, "%s/new", dir);
    CHECK(ob_export_check_dir("draw", spelled, NULL) == 0, "a directory not there yet is fine: %s", last_msg);
    unsetenv("OFFBENCH_DATA");
    CHECK(ob_export_check_dir("run", data, NULL) == 0, "without $OFFBENCH_DATA the directory is not special");
    setenv("OFFBENCH_DATA", "", 1);
    CHECK(ob_export_check_dir("run", data, NULL) == 0, "an empty $OFFBENCH_DATA is unset");
    unsetenv("OFFBENCH_DATA");

    /* the datasets/ directory the program was built from */
    const char *bd = ob_export_build_datasets();
    CHECK(bd && bd[0] == '/' && strstr(bd, "/datasets"), "build datasets: '%s'", bd ? bd : "(null)");
    struct stat st;
    if (bd && stat(bd, &st) == 0) {
        expect_refused("the build's datasets/", bd, NULL, "built from");
        snprintf(spelled, sizeof spelled, "%s/", bd);
        expect_refused("the build's datasets/ with a slash", spelled, NULL, "built from");
    } else {
        SKIP("the build's datasets/ is not there");
    }

    /* the --curves file inside */
    put("other/my.curves", "curve x\n");
    expect_refused("holds the --curves file", other, curves, "holds the input");
    CHECK(ob_export_check_dir("run", sub, curves) == 0, "--curves elsewhere is fine: %s", last_msg);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/ob_test_export_dir.%ld", (long)getpid());
    mkdir(dir, 0777);
    ob_set_error_handler(capture);
    test_names();
    test_prune();
    test_curve_dirs();
    ob_set_error_handler(NULL);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return check_done();
}
