/*
 * test_journal.c - the resume fingerprint (host/run/journal.c) and the owner
 * lock of a run directory (host/io/fsutil.c).
 *
 * The fingerprint changes with each option, the data hash, and each method
 * version that decides a resumed run's results; ob_fingerprint_diff names
 * the first difference as the user knows it, its values as written (no
 * %-escapes), and ob_fp_get reads a value back the same way.  A second lock of a locked
 * directory (from another process: fcntl locks are per process) is refused
 * with the holder's pid, and granted once the holder has died.
 */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "host/io/fsutil.h"
#include "tests/check.h"
#include "host/cli/commands.h"
#include "host/diag.h"
#include "host/run/journal.h"
#include "host/run/options.h"

static char *fp_of(char **args, int n, uint64_t hash)
{
    ob_run_opts o;
    char *fp = NULL;
    if (ob_run_opts_parse(n, args, &o) == 0) {
        const ob_run_record rec = {.data_hash = hash};
        fp = ob_resume_fingerprint(&o, &rec, "random 4:5");
    }
    ob_run_opts_free(&o);
    return fp;
}

static void test_fingerprint(void)
{
    char *base[] = {"run", "--methods", "tiller,cobb", "--samples", "8"};
    char *fp0 = fp_of(base, 5, 1);
    CHECK(fp0 != NULL, "fingerprint");
    if (!fp0)
        return;
    char diff[512];
    CHECK(ob_fingerprint_diff(fp0, fp0, diff, sizeof diff) == 0 && !diff[0], "equal: %s", diff);
    static const struct {
        const char *opt, *val, *named;
    } cases[] = {
        {"--samples", "16", "--samples"},         {"--max-segments", "5", "--max-segments"},
        {"--methods", "tiller", "--methods"},     {"--tols", "1e-3", "--tols"},
        {"--metric", "radial", "--metric"},       {"--split", "maxerr", "--split"},
        {"--curve", "rnd5_000001", "--curve"},    {"--param", "elber.iterations=7", "elber.iterations"},
        {"--job-timeout", "3", "--job-timeout"},  {"--inflections", "no", "--inflections"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        /* each option once (a repeated option is refused): the varied one
         * replaces the base's own value */
        char *a[] = {"run", "--methods", "tiller,cobb", "--samples", "8", (char *)cases[i].opt, (char *)cases[i].val};
        int n = 7;
        if (strcmp(cases[i].opt, "--methods") == 0 || strcmp(cases[i].opt, "--samples") == 0) {
            a[strcmp(cases[i].opt, "--methods") == 0 ? 2 : 4] = (char *)cases[i].val;
            n = 5;
        }
        char *fp = fp_of(a, n, 1);
        CHECK(fp && ob_fingerprint_diff(fp0, fp, diff, sizeof diff) == 1 && strstr(diff, cases[i].named),
              "%s %s: '%s'", cases[i].opt, cases[i].val, diff);
        free(fp);
    }
    char *fp = fp_of(base, 5, 2);
    CHECK(fp && ob_fingerprint_diff(fp0, fp, diff, sizeof diff) == 1 && strstr(diff, "curve data"), "hash: %s", diff);
    free(fp);
    CHECK(strstr(fp0, " git=") && strstr(fp0, " dirty=") && strstr(fp0, " cflags=") && strstr(fp0, " version.tiller="),
          "the build is in it: %s", fp0);
    /* a fingerprint of another method version (another build) */
    char *other = malloc(strlen(fp0) + 8), *v = strstr(fp0, " version.tiller=");
    if (other && v) {
        snprintf(other, strlen(fp0) + 8, "%.*s version.tiller=999%s", (int)(v - fp0), fp0, strchr(v + 1, ' '));
        CHECK(ob_fingerprint_diff(other, fp0, diff, sizeof diff) == 1 && strstr(diff, "tiller") &&
                  strstr(diff, "build"), "version: %s", diff);
    }
    free(other);
    /* a key that only one side has (an older journal) is a difference too */
    CHECK(ob_fingerprint_diff("samples=8", "samples=8 git=abc", diff, sizeof diff) == 1 && strstr(diff, "git"),
          "missing key: %s", diff);
    /* values as the user wrote them, not %-escaped (issue 46: "random%20250:2026") */
    CHECK(ob_fingerprint_diff("data=random%20250:2026 x=1", "data=random%202:2026 x=1", diff, sizeof diff) == 1 &&
              strstr(diff, "the run's random 250:2026, now random 2:2026") && !strchr(diff, '%'),
          "unescaped values: %s", diff);
    char *got = ob_fp_get("a=1 data=my%20file%25.curves b=2", "data"), *none = ob_fp_get("a=1", "data");
    CHECK(got && strcmp(got, "my file%.curves") == 0 && !none, "ob_fp_get: '%s'", got ? got : "(null)");
    free(got);
    free(fp0);
}

static void test_lock(void)
{
    char dir[] = "/tmp/ob_test_lock_XXXXXX";
    if (!mkdtemp(dir)) {
        SKIP("mkdtemp");
        return;
    }
    int p[2];
    if (pipe(p) != 0) {
        SKIP("pipe");
        return;
    }
    const pid_t child = fork();
    if (child == 0) {  /* the holder: lock, tell the parent, wait to be killed */
        ob_err err = {""};
        int fd;
        char c = ob_lock_dir(dir, &fd, &err) == 0 ? 'y' : 'n';
        if (write(p[1], &c, 1) != 1)
            _exit(1);
        pause();
        _exit(0);
    }
    char c = 0;
    CHECK(read(p[0], &c, 1) == 1 && c == 'y', "the child locks %s", dir);
    char pid[32];
    ob_err err = {""};
    int fd = -1;
    snprintf(pid, sizeof pid, "pid %ld", (long)child);
    CHECK(ob_lock_dir(dir, &fd, &err) == -2 && strstr(err.msg, pid) && strstr(err.msg, dir), "held: %s", err.msg);
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    CHECK(ob_lock_dir(dir, &fd, &err) == 0 && fd >= 0, "after the holder died: %s", err.msg);
    if (fd >= 0)
        close(fd);
    CHECK(ob_lock_dir("/proc/no/such/dir", &fd, &err) == -1, "no directory: %s", err.msg);
    close(p[0]);
    close(p[1]);
    char path[64];
    snprintf(path, sizeof path, "%s/.lock", dir);
    remove(path);
    rmdir(dir);
}

static void quiet(const char *m) { (void)m; }

int main(void)
{
    ob_set_error_handler(quiet);
    test_fingerprint();
    test_lock();
    return check_done();
}
