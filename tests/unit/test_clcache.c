/*
 * test_clcache.c - the OpenCL program binary cache (host/backend/clcache.h):
 * a stored binary comes back only for its own key and intact; a corrupt,
 * truncated, foreign or other-format file is ignored, never trusted; a link
 * at the file or its temporary is replaced, never written through.  Then,
 * on an OpenCL device (PoCL here): the first open builds and stores, the
 * second reads the cache, a cached program measures as the CPU does, a
 * corrupted cache file is rebuilt, a changed kernel source builds anew,
 * OFFBENCH_CL_CACHE=off turns it off.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL && strstr(why, "no cached"), "absent: %s", why);
    CHECK(ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why) == 0, "write: %s", why);
    unsigned char *got = ob_clcache_read(path, key, &n, why, sizeof why);
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
        got = ob_clcache_read(path, key, &n, why, sizeof why);
        CHECK(got && n == sizeof bin && access(tmp, F_OK) != 0, "a link at %s: the cache file replaces it", at[i]);
        free(got);
    }
    /* the same file asked for with another key: foreign */
    CHECK(ob_clcache_read(path, other, &n, why, sizeof why) == NULL && strstr(why, "another"), "foreign: %s",
          why);
    /* one byte of the binary changed: the checksum */
    flip(path, -10);
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL && strstr(why, "checksum"), "corrupt: %s", why);
    /* truncated, and one byte too many */
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    CHECK(truncate(path, file_size(path) - 1) == 0, "truncate");
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL && strstr(why, "truncated"), "truncated: %s",
          why);
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    FILE *f = fopen(path, "ab");
    fputc(0, f);
    fclose(f);
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL, "a byte appended: %s", why);
    /* another format; a length field gone wild */
    write_bytes(path, "OBCLBIN0 whatever", 17);
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL && strstr(why, "format"), "format: %s", why);
    ob_clcache_write(path, key, bin, sizeof bin, why, sizeof why);
    flip(path, 8 + 8 + (long)strlen(key) + 7);  /* the binary length's high byte */
    CHECK(ob_clcache_read(path, key, &n, why, sizeof why) == NULL, "a wild length: %s", why);
    setenv("OFFBENCH_CL_CACHE", "off", 1);
    CHECK(ob_clcache_path(key, path, sizeof path, why, sizeof why) == -1 && strstr(why, "off"), "off: %s", why);
    unsetenv("OFFBENCH_CL_CACHE");
    setenv("XDG_CACHE_HOME", dir, 1);
    CHECK(ob_clcache_path(key, path, sizeof path, why, sizeof why) == 0 && strstr(path, "/offbench/cl-"),
          "XDG_CACHE_HOME/offbench: %s", path);
    unsetenv("XDG_CACHE_HOME");
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

/* Open, say what the cache did, check a measurement, close. */
static int open_status(char *status, size_t len)
{
    ob_cl *cl = NULL;
    ob_err err = {""};
    if (ob_cl_open(NULL, 0, &cl, &err) != 0) {
        snprintf(status, len, "%s", err.msg);
        return -1;
    }
    snprintf(status, len, "%s", ob_cl_cache_status(cl));
    const int ok = measures_like_cpu(cl);
    ob_cl_close(cl);
    return ok ? 0 : 1;
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
    test_device();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_done();
}
