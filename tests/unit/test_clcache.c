/*
 * test_clcache.c - the OpenCL program binary cache (host/backend/clcache.h):
 * a stored binary comes back only for its own key and intact; a corrupt,
 * truncated, foreign or other-format file is ignored, never trusted; a link
 * at the file or its temporary is replaced, never written through; names
 * are SHA-256 (FIPS 180-4's vectors); a directory or file that is not the
 * user's own (a link, group- or world-writable, a FIFO: not waited on) is
 * refused (issue 48).  Then,
 * on an OpenCL device (PoCL here): the first open builds and stores, the
 * second reads the cache, a cached program measures as the CPU does, a
 * corrupted cache file is rebuilt, a changed kernel source builds anew,
 * OFFBENCH_CL_CACHE=off turns it off.  The programs are one per metric and
 * layout (issue 40): their build options name both, the key holds the
 * options (a file each), opening builds none, a batch builds only the
 * programs of its records' metrics (the build report, ob_cl_builds, lists
 * what was built).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/backend/clcache.h"
#include "host/backend/clrt.h"
#include "methods/metrics/metric.h"
#include "tests/check.h"

static char dir[256];

static int write_bytes(const char *path, const void *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    const int ok = fwrite(p, 1, n, f) == n;
    return fclose(f) == 0 && ok ? 0 : -1;
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fclose(f);
    return n;
}

/* The binary for key in path on a hit, else NULL (why says why). */
static unsigned char *rd(const char *path, const char *key, size_t *n, char *why, size_t wlen)
{
    unsigned char *bin = NULL;
    ob_clcache_read(path, key, &bin, n, why, wlen);
    return bin;
}

/* Flip one byte of a file at offset off (from the end when negative). */
static void flip(const char *path, long off)
{
    FILE *f = fopen(path, "r+b");
    if (!f)
        return;
    fseek(f, off, off < 0 ? SEEK_END : SEEK_SET);
    const int c = fgetc(f);
    fseek(f, off, off < 0 ? SEEK_END : SEEK_SET);
    fputc(c ^ 0x5a, f);
    fclose(f);
}

static void test_files(void)
{
    const char *key = "device=A\nsource=1\n", *other = "device=B\nsource=1\n";
    char path[4200], opath[4200], why[300];
    setenv("OFFBENCH_CL_CACHE", dir, 1);
    CHECK(ob_clcache_path(key, path, sizeof path, why, sizeof why) == 0 && strstr(path, dir) == path,
          "the cache path is under OFFBENCH_CL_CACHE: %s", path);
    ob_clcache_path(other, opath, sizeof opath, why, sizeof why);
    CHECK(strcmp(path, opath) != 0, "two keys, two files");
    unsigned char bin[1000];
    for (int i = 0; i < 1000; i++)
        bin[i] = (unsigned char)(i * 7);
    size_t n = 0;
    CHECK(rd(path, key, &n, why, sizeof why) == NULL && strstr(why, "no cached"), "absent: %s", why);
    CHECK(ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why) == 0, "write: %s", why);
    unsigned char *got = rd(path, key, &n, why, sizeof why);
    CHECK(got && n == sizeof bin && memcmp(got, bin, n) == 0, "read back whole");
    free(got);
    /* a link planted at the file or at its temporary (PATH.PID.tmp) is
     * replaced, never written through: its target keeps its bytes */
    char victim[300], tmp[4300];
    snprintf(victim, sizeof victim, "%s/victim", dir);
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    const char *at[] = {path, tmp};
    for (int i = 0; i < 2; i++) {
        write_bytes(victim, "precious", 8);
        unlink(at[i]);
        CHECK(symlink(victim, at[i]) == 0, "symlink at %s", at[i]);
        CHECK(ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why) == 0 && file_size(victim) == 8,
              "a link at %s: written (%s), its target kept (%ld bytes)", at[i], why, file_size(victim));
        got = rd(path, key, &n, why, sizeof why);
        CHECK(got && n == sizeof bin && access(tmp, F_OK) != 0, "a link at %s: the cache file replaces it", at[i]);
        free(got);
    }
    /* the same file asked for with another key: foreign */
    CHECK(rd(path, other, &n, why, sizeof why) == NULL && strstr(why, "another"), "foreign: %s",
          why);
    /* one byte of the binary changed: the checksum */
    flip(path, -10);
    CHECK(rd(path, key, &n, why, sizeof why) == NULL && strstr(why, "checksum"), "corrupt: %s", why);
    /* truncated, and one byte too many */
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    CHECK(truncate(path, file_size(path) - 1) == 0, "truncate");
    CHECK(rd(path, key, &n, why, sizeof why) == NULL && strstr(why, "truncated"), "truncated: %s",
          why);
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    FILE *f = fopen(path, "ab");
    fputc(0, f);
    fclose(f);
    CHECK(rd(path, key, &n, why, sizeof why) == NULL, "a byte appended: %s", why);
    /* another format; a length field gone wild */
    write_bytes(path, "OBCLBIN0 whatever", 17);
    CHECK(rd(path, key, &n, why, sizeof why) == NULL && strstr(why, "format"), "format: %s", why);
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    flip(path, 8 + 8 + (long)strlen(key) + 7);  /* the binary length's high byte */
    CHECK(rd(path, key, &n, why, sizeof why) == NULL, "a wild length: %s", why);
    setenv("OFFBENCH_CL_CACHE", "off", 1);
    CHECK(ob_clcache_path(key, path, sizeof path, why, sizeof why) == -1 && strstr(why, "off"), "off: %s", why);
    unsetenv("OFFBENCH_CL_CACHE");
    setenv("XDG_CACHE_HOME", dir, 1);
    CHECK(ob_clcache_path(key, path, sizeof path, why, sizeof why) == 0 && strstr(path, "/offbench/cl-"),
          "XDG_CACHE_HOME/offbench: %s", path);
    unsetenv("XDG_CACHE_HOME");
}

/* SHA-256 as FIPS 180-4 gives it, and the names made of it. */
static void test_sha(void)
{
    char hex[OB_SHA256_HEX], path[4200], why[300];
    ob_sha256_hex("abc", 3, hex);
    CHECK(strcmp(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad") == 0, "SHA-256(abc): %s",
          hex);
    const char *two = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    ob_sha256_hex(two, strlen(two), hex);
    CHECK(strcmp(hex, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1") == 0, "SHA-256(448 bits): %s",
          hex);
    ob_sha256_hex("", 0, hex);
    CHECK(strcmp(hex, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855") == 0, "SHA-256(''): %s", hex);
    setenv("OFFBENCH_CL_CACHE", dir, 1);
    ob_clcache_path("abc", path, sizeof path, why, sizeof why);
    const char *base = strrchr(path, '/');
    CHECK(base && strcmp(base, "/cl-ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad.bin") == 0,
          "the name is the key's SHA-256: %s", path);
    unsetenv("OFFBENCH_CL_CACHE");
}

/* What reading sub/NAME of the test's key says after setup: the status and why. */
static ob_clcache_status trust_case(const char *sub, const char *setup, char *why, size_t wlen)
{
    const char *key = "device=T\n";
    char d[400], path[4200], cmd[9000];
    snprintf(d, sizeof d, "%s/trust/%s", dir, sub);
    setenv("OFFBENCH_CL_CACHE", d, 1);
    ob_clcache_path(key, path, sizeof path, why, wlen);
    unsigned char bin[100] = {1, 2, 3};
    ob_clcache_write(path, key, bin, sizeof bin, why, wlen);
    snprintf(cmd, sizeof cmd, "D=%s F=%s; %s", d, path, setup);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot run: %s\n", cmd);
    unsigned char *got = NULL;
    size_t n = 0;
    alarm(60); /* a FIFO that blocks fails the test instead of hanging it */
    const ob_clcache_status st = ob_clcache_read(path, key, &got, &n, why, wlen);
    alarm(0);
    free(got);
    unsetenv("OFFBENCH_CL_CACHE");
    return st;
}

/* Only the user's own directory and file are read: each refusal says why
 * and names the path; a refused directory is not written either. */
static void test_trust(void)
{
    char why[600];
    struct stat st;
    CHECK(trust_case("own", "true", why, sizeof why) == OB_CLCACHE_HIT, "own: %s", why);
    CHECK(stat(dir, &st) == 0, "stat");
    char own[400];
    snprintf(own, sizeof own, "%s/trust/own", dir);
    CHECK(stat(own, &st) == 0 && (st.st_mode & 0777) == 0700, "the directory made 0700: %o", st.st_mode & 0777);
    static const struct {
        const char *sub, *setup, *want;
        ob_clcache_status st;
    } c[] = {
        {"ww", "chmod 777 $D", "writable by others", OB_CLCACHE_UNSAFE},
        {"gw", "chmod 770 $D", "writable by others", OB_CLCACHE_UNSAFE},
        {"ln", "mv $D $D.real && ln -s $D.real $D", "symbolic link", OB_CLCACHE_UNSAFE},
        {"fw", "chmod 622 $F", "writable by others", OB_CLCACHE_BAD},
        {"fl", "mv $F $F.real && ln -s $F.real $F", "symbolic link", OB_CLCACHE_BAD},
        {"ff", "rm $F && mkfifo $F", "not a regular file", OB_CLCACHE_BAD},
        {"fd", "rm $F && mkdir $F", "not a regular file", OB_CLCACHE_BAD},
        {"od", "chown nobody $D", "another user", OB_CLCACHE_UNSAFE},
        {"of", "chown nobody $F", "another user", OB_CLCACHE_BAD},
    };
    for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
        if (c[i].setup[0] == 'c' && c[i].setup[1] == 'h' && c[i].setup[2] == 'o' && geteuid() != 0) {
            SKIP("another owner: chown to nobody needs root");
            continue;
        }
        const ob_clcache_status got = trust_case(c[i].sub, c[i].setup, why, sizeof why);
        CHECK(got == c[i].st && strstr(why, c[i].want) && strstr(why, c[i].sub), "%s (%s): %d, %s", c[i].sub,
              c[i].setup, (int)got, why);
    }
    /* a refused directory gets no file */
    char ww[400], cmd[600];
    snprintf(ww, sizeof ww, "%s/trust/ww/cl-x.bin", dir);
    const unsigned char bin[4] = {9};
    CHECK(ob_clcache_write(ww, "k", bin, sizeof bin, why, sizeof why) == -1 && strstr(why, "writable") &&
              access(ww, F_OK) != 0,
          "a world-writable directory is not written: %s", why);
    snprintf(cmd, sizeof cmd, "rm -rf %s/trust", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot run: %s\n", cmd);
}

/* The programs' build options and cache keys: each metric and layout its
 * own defines, and the key holds them, so each program has its own file. */
static void test_keys(void)
{
    char oh[256], or_[256], og[256], why[300];
    CHECK(ob_cl_program_options(OB_METRIC_HAUSDORFF, OB_CL_ITEMS, oh, sizeof oh) == 0 &&
              strstr(oh, "-cl-std=CL1.2") && strstr(oh, "-D OBC_ONLY_HAUSDORFF") && strstr(oh, "-D OBC_ONLY_ITEMS") &&
              !strstr(oh, "GROUPS"),
          "hausdorff, items: %s", oh);
    CHECK(ob_cl_program_options(OB_METRIC_RADIAL, OB_CL_ITEMS, or_, sizeof or_) == 0 &&
              strstr(or_, "-D OBC_ONLY_RADIAL") && !strstr(or_, "HAUSDORFF"),
          "radial, items: %s", or_);
    CHECK(ob_cl_program_options(OB_METRIC_HAUSDORFF, OB_CL_GROUPS, og, sizeof og) == 0 &&
              strstr(og, "-D OBC_ONLY_GROUPS") && !strstr(og, "ITEMS"),
          "hausdorff, groups: %s", og);
    char tmp[256];
    CHECK(ob_cl_program_options(OB_METRIC_NORMAL, OB_CL_GROUPS, tmp, sizeof tmp) == 0 && strstr(tmp, "OBC_ONLY_NORMAL"),
          "normal: %s", tmp);
    CHECK(ob_cl_program_options(OB_METRIC_PARAM, OB_CL_GROUPS, tmp, sizeof tmp) == 0 && strstr(tmp, "OBC_ONLY_PARAM"),
          "param: %s", tmp);
    CHECK(ob_cl_program_options(OB_METRIC_BOUND, OB_CL_ITEMS, tmp, sizeof tmp) == -1, "bound: no program");
    char *kh = ob_cl_program_key("P", "D", "1.0", "OpenCL 3.0", oh, "src"),
         *kr = ob_cl_program_key("P", "D", "1.0", "OpenCL 3.0", or_, "src"),
         *kg = ob_cl_program_key("P", "D", "1.0", "OpenCL 3.0", og, "src"),
         *ks = ob_cl_program_key("P", "D", "1.0", "OpenCL 3.0", oh, "src2");
    CHECK(kh && kr && kg && ks, "keys made");
    if (kh && kr && kg && ks) {
        char want[300];
        snprintf(want, sizeof want, "options=%s\n", oh);
        CHECK(strstr(kh, want) != NULL, "the key holds the build options, defines included: %s", kh);
        CHECK(strcmp(kh, kr) != 0 && strcmp(kh, kg) != 0 && strcmp(kh, ks) != 0,
              "another metric, layout or source: another key");
        char ph[4200], pr[4200];
        setenv("OFFBENCH_CL_CACHE", dir, 1);
        CHECK(ob_clcache_path(kh, ph, sizeof ph, why, sizeof why) == 0 &&
                  ob_clcache_path(kr, pr, sizeof pr, why, sizeof why) == 0 && strcmp(ph, pr) != 0,
              "each metric's program its own cache file: %s, %s", ph, pr);
        unsetenv("OFFBENCH_CL_CACHE");
    }
    free(kh);
    free(kr);
    free(kg);
    free(ks);
}

/* One record measured through cl equals the CPU's, bit for bit. */
static int measures_like_cpu(ob_cl *cl)
{
    ob_bez base, approx;
    const double b[4][2] = {{0, 0}, {0.3, 0.5}, {0.7, 0.5}, {1, 0}}, a[4][2] = {{0, 0.1}, {0.3, 0.62}, {0.7, 0.62},
                                                                                  {1, 0.1}};
    ob_bez_from_points(&base, 3, b);
    ob_bez_from_points(&approx, 3, a);
    ob_measure_rec r = {&base, &approx, 0.1, OB_METRIC_HAUSDORFF, 0.0};
    ob_errval g, c;
    if (ob_cl_measure_batch(cl, &r, 1, 64, &g) != 0)
        return 0;
    ob_measure(OB_METRIC_HAUSDORFF, &base, &approx, 0.1, 64, &c);
    return memcmp(&g.err, &c.err, sizeof g.err) == 0;
}

/* Open, build the hausdorff program of the device's layout, say what the
 * cache did, check a measurement, close. */
static int open_status(char *status, size_t len)
{
    ob_cl *cl = NULL;
    ob_err err = {""};
    if (ob_cl_open(NULL, 0, &cl, &err) != 0 ||
        ob_cl_prepare(cl, OB_METRIC_HAUSDORFF, ob_cl_get_layout(cl), &err) != 0) {
        snprintf(status, len, "%s", err.msg);
        ob_cl_close(cl);
        return -1;
    }
    snprintf(status, len, "%s", ob_cl_cache_status(cl));
    const int ok = measures_like_cpu(cl);
    ob_cl_close(cl);
    return ok ? 0 : 1;
}

/* One record of metric m measured through cl, as the CPU does. */
static int measure_one(ob_cl *cl, ob_metric m)
{
    ob_bez base, approx;
    const double b[3][2] = {{0, 0}, {0.5, 0.6}, {1, 0}}, a[3][2] = {{0, 0.1}, {0.5, 0.72}, {1, 0.1}};
    ob_bez_from_points(&base, 2, b);
    ob_bez_from_points(&approx, 2, a);
    ob_measure_rec r = {&base, &approx, 0.1, m, 0.0};
    ob_errval g, c;
    if (ob_cl_measure_batch(cl, &r, 1, 32, &g) != 0)
        return 0;
    ob_measure(m, &base, &approx, 0.1, 32, &c);
    return memcmp(&g.err, &c.err, sizeof g.err) == 0;
}

/* Opening builds nothing; a batch builds the programs of its records'
 * metrics, in the layout in use, and nothing else; the build report lists
 * them in the order built, each with its time and what the cache did. */
static void test_lazy(void)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -f %s/*.bin", dir);
    if (system(cmd) != 0)
        return;
    setenv("OFFBENCH_CL_CACHE", dir, 1);
    ob_cl *cl = NULL;
    ob_err err = {""};
    if (ob_cl_open(NULL, 0, &cl, &err) != 0) {
        SKIP("the programs built on first use: no OpenCL platform");
        unsetenv("OFFBENCH_CL_CACHE");
        return;
    }
    ob_cl_build rep[16];
    CHECK(ob_cl_builds(cl, rep, 16) == 0 && ob_cl_build_seconds(cl) == 0.0, "opening builds no program");
    ob_cl_set_layout(cl, OB_CL_ITEMS);
    CHECK(measure_one(cl, OB_METRIC_RADIAL), "radial measured as on the CPU");
    int n = ob_cl_builds(cl, rep, 16);
    CHECK(n == 1 && rep[0].metric == OB_METRIC_RADIAL && rep[0].layout == OB_CL_ITEMS && rep[0].seconds > 0.0 &&
              strncmp(rep[0].cache, "miss", 4) == 0,
          "a radial batch builds the radial program of the items layout alone: %d programs, %s",
          n, n > 0 ? rep[0].cache : "");
    CHECK(measure_one(cl, OB_METRIC_RADIAL) && ob_cl_builds(cl, rep, 16) == 1, "built once");
    CHECK(measure_one(cl, OB_METRIC_HAUSDORFF), "hausdorff measured as on the CPU");
    ob_cl_set_layout(cl, OB_CL_GROUPS);
    CHECK(measure_one(cl, OB_METRIC_HAUSDORFF), "hausdorff, groups, measured as on the CPU");
    n = ob_cl_builds(cl, rep, 16);
    CHECK(n == 3 && rep[1].metric == OB_METRIC_HAUSDORFF && rep[1].layout == OB_CL_ITEMS &&
              rep[2].metric == OB_METRIC_HAUSDORFF && rep[2].layout == OB_CL_GROUPS,
          "then hausdorff's, in each layout used: %d programs", n);
    CHECK(ob_cl_group_size(cl) >= 1, "the group layout's work-items per record: %d", ob_cl_group_size(cl));
    CHECK(strstr(ob_cl_cache_status(cl), "radial") && strstr(ob_cl_cache_status(cl), "hausdorff"),
          "the cache status names each program: %s", ob_cl_cache_status(cl));
    ob_cl_close(cl);
    snprintf(cmd, sizeof cmd, "test $(ls %s/*.bin | wc -l) -eq 3", dir);
    CHECK(system(cmd) == 0, "three programs, three cache files");
    /* opened again: each from the cache */
    if (ob_cl_open(NULL, 0, &cl, &err) == 0) {
        CHECK(ob_cl_prepare(cl, OB_METRIC_RADIAL, OB_CL_ITEMS, &err) == 0 &&
                  ob_cl_prepare(cl, OB_METRIC_HAUSDORFF, OB_CL_GROUPS, &err) == 0,
              "prepared: %s", err.msg);
        n = ob_cl_builds(cl, rep, 16);
        CHECK(n == 2 && strncmp(rep[0].cache, "hit", 3) == 0 && strncmp(rep[1].cache, "hit", 3) == 0,
              "opened again, each program from its cache file: %s / %s", n > 0 ? rep[0].cache : "",
              n > 1 ? rep[1].cache : "");
        CHECK(ob_cl_prepare(cl, OB_METRIC_BOUND, OB_CL_ITEMS, &err) == -1, "bound: no program to build");
        ob_cl_close(cl);
    }
    unsetenv("OFFBENCH_CL_CACHE");
}

/* The cache file of the one .bin in dir (the test's only key). */
static int only_file(char *path, size_t len, int *count)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "ls %s/*.bin 2>/dev/null", dir);
    FILE *p = popen(cmd, "r");
    *count = 0;
    char line[4200];
    while (p && fgets(line, sizeof line, p)) {
        line[strcspn(line, "\n")] = '\0';
        snprintf(path, len, "%s", line);
        ++*count;
    }
    if (p)
        pclose(p);
    return *count == 1 ? 0 : -1;
}

static void copy_file(const char *from, const char *to, const char *append)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "cp %s %s && printf '%s' >> %s", from, to, append, to);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot run: %s\n", cmd);
}

static void test_device(void)
{
    char st[700], path[4200];
    int count = 0;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -f %s/*", dir);
    if (system(cmd) != 0)
        return;
    setenv("OFFBENCH_CL_CACHE", dir, 1);
    const int rc = open_status(st, sizeof st);
    if (rc < 0) {
        if (strstr(st, "no OpenCL"))
            SKIP("the binary cache on a device: no OpenCL platform");
        else
            CHECK(0, "the backend does not open: %s", st);
        return;
    }
    CHECK(rc == 0 && strncmp(st, "miss", 4) == 0 && strstr(st, "built and stored"), "first open: %s", st);
    CHECK(only_file(path, sizeof path, &count) == 0, "one cache file (%d)", count);
    CHECK(open_status(st, sizeof st) == 0 && strncmp(st, "hit", 3) == 0, "second open reads the cache: %s", st);
    flip(path, -100);
    CHECK(open_status(st, sizeof st) == 0 && strstr(st, "checksum") && strstr(st, "built and stored"),
          "a corrupted cache file is ignored and rebuilt: %s", st);
    CHECK(open_status(st, sizeof st) == 0 && strncmp(st, "hit", 3) == 0, "and read after: %s", st);
    /* a changed kernel source: another key, built anew */
    char kd[300], from[400], to[400];
    snprintf(kd, sizeof kd, "%s/kernels", dir);
    snprintf(cmd, sizeof cmd, "mkdir -p %s", kd);
    if (system(cmd) == 0) {
        snprintf(from, sizeof from, "kernels/metric_core.h");
        snprintf(to, sizeof to, "%s/metric_core.h", kd);
        copy_file(from, to, "");
        snprintf(from, sizeof from, "kernels/measure.cl");
        snprintf(to, sizeof to, "%s/measure.cl", kd);
        copy_file(from, to, "\\n/* changed */\\n");
        setenv("OFFBENCH_KERNELS", kd, 1);
        CHECK(open_status(st, sizeof st) == 0 && strncmp(st, "miss", 4) == 0, "a changed source builds: %s", st);
        only_file(path, sizeof path, &count);
        CHECK(count == 2, "its own cache file: %d files", count);
        unsetenv("OFFBENCH_KERNELS");
    }
    setenv("OFFBENCH_CL_CACHE", "off", 1);
    CHECK(open_status(st, sizeof st) == 0 && strncmp(st, "off", 3) == 0, "OFFBENCH_CL_CACHE=off: %s", st);
    unsetenv("OFFBENCH_CL_CACHE");
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/ob_clcache_XXXXXX");
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return check_done();
    }
    test_files();
    test_sha();
    test_trust();
    test_keys();
    test_device();
    test_lazy();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_done();
}
