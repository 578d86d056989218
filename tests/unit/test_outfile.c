/*
 * test_outfile.c - files written never through a link (host/io/outfile.h,
 * and its users in host/io/fsutil.h): a symbolic link (dangling or not) or
 * a hard link at a file's name or its temporary is replaced, and the file it
 * pointed to keeps its bytes; a file updated in place (.lock) that is a link
 * is refused with -2 naming it; a FIFO is refused without waiting; a name
 * that is, or leads to, a directory, a FIFO or a device is refused.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/diag.h"
#include "host/io/fsutil.h"
#include "host/io/outfile.h"
#include "tests/check.h"

static char dir[256], victim[300];
static const char precious[] = "precious bytes\n";

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* The victim outside the names under test, fresh */
static void new_victim(void) { put(victim, precious); }

static int victim_intact(void)
{
    char buf[64] = "";
    FILE *f = fopen(victim, "r");
    if (!f)
        return 0;
    const size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    return n == strlen(precious) && memcmp(buf, precious, n) == 0;
}

/* path is a regular file of one name holding text */
static int holds(const char *path, const char *text)
{
    struct stat st;
    char buf[256] = "";
    if (lstat(path, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1)
        return 0;
    FILE *f = fopen(path, "r");
    const size_t n = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
    if (f)
        fclose(f);
    return n == strlen(text) && memcmp(buf, text, n) == 0;
}

/* kind 's': symbolic link, 'd': dangling symbolic link, 'h': hard link */
static void plant(char kind, const char *at)
{
    unlink(at);
    new_victim();
    if (kind == 'h' && link(victim, at) != 0)
        perror("link");
    if (kind == 's' && symlink(victim, at) != 0)
        perror("symlink");
    if (kind == 'd') {
        unlink(victim);
        if (symlink(victim, at) != 0)
            perror("symlink");
    }
}

static int write_hello(FILE *f, void *ctx)
{
    (void)ctx;
    return fputs("hello\n", f) < 0 ? -1 : 0;
}

static void test_outfile(void)
{
    char path[400], tmp[420], pid_tmp[440];
    snprintf(path, sizeof path, "%s/out.csv", dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    snprintf(pid_tmp, sizeof pid_tmp, "%s.%ld.tmp", path, (long)getpid());
    const char kinds[] = "shd";
    for (int k = 0; kinds[k]; k++) {
        const char *names[] = {path, tmp, pid_tmp};
        for (int w = 0; w < 3; w++) {
            plant(kinds[k], names[w]);
            ob_outfile o;
            ob_err err;
            const int per_process = w == 2;
            int rc = ob_outfile_open(&o, path, per_process, &err);
            if (rc == 0) {
                fputs("new\n", o.f);
                rc = ob_outfile_commit(&o, w == 1, &err);
            }
            const int dangling_kept = kinds[k] != 'd' || access(victim, F_OK) != 0;
            CHECK(rc == 0 && holds(path, "new\n"), "%c-link at %s: written: %s", kinds[k], names[w], err.msg);
            CHECK(kinds[k] == 'd' ? dangling_kept : victim_intact(), "%c-link at %s: its target changed",
                  kinds[k], names[w]);
            CHECK(access(tmp, F_OK) != 0 && access(pid_tmp, F_OK) != 0, "no temporary left (%c, %s)", kinds[k],
                  names[w]);
            unlink(path);
            unlink(names[w]);
        }
    }
    /* discard leaves the old file as it was */
    put(path, "old\n");
    ob_outfile o;
    ob_err err;
    CHECK(ob_outfile_open(&o, path, 0, &err) == 0, "open: %s", err.msg);
    fputs("half", o.f);
    ob_outfile_discard(&o);
    CHECK(holds(path, "old\n") && access(tmp, F_OK) != 0, "discard: the old file kept, no temporary");
    /* a directory at the temporary's name: an error naming it, nothing written */
    CHECK(mkdir(tmp, 0777) == 0, "mkdir %s", tmp);
    CHECK(ob_outfile_open(&o, path, 0, &err) == -1 && strstr(err.msg, ".tmp: cannot write"),
          "a directory at the temporary: %s", err.msg);
    rmdir(tmp);
    unlink(path);
    /* a name that is, or leads to, no regular file: refused, left as it is
     * (the rename would replace a directory, a FIFO, /dev/null) */
    char fifo[420];
    snprintf(fifo, sizeof fifo, "%s/fifo", dir);
    CHECK(mkfifo(fifo, 0666) == 0, "mkfifo");
    const char *nodes[] = {dir, fifo, "/dev/null"};
    for (int i = 0; i < 3; i++) {
        unlink(path);
        CHECK(ob_outfile_open(&o, nodes[i], 0, &err) == -1 && strstr(err.msg, nodes[i]) &&
              (strstr(err.msg, "is a directory") || strstr(err.msg, "not a regular file")),
              "%s: refused: %s", nodes[i], err.msg);
        CHECK(symlink(nodes[i], path) == 0, "symlink");
        struct stat st;
        CHECK(ob_outfile_open(&o, path, 0, &err) == -1 && lstat(path, &st) == 0 && S_ISLNK(st.st_mode),
              "a link to %s: refused, the link kept: %s", nodes[i], err.msg);
    }
    unlink(path);
    unlink(fifo);
}

static void test_write_atomically(void)
{
    char path[400], tmp[420];
    snprintf(path, sizeof path, "%s/r.csv", dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    const char *names[] = {path, tmp};
    for (int w = 0; w < 2; w++) {
        plant('s', names[w]);
        CHECK(ob_write_atomically(dir, "r.csv", write_hello, NULL) == 0 && holds(path, "hello\n") &&
              victim_intact(), "ob_write_atomically with a link at %s", names[w]);
        plant('h', names[w]);
        const ob_out_file set[] = {{"m.json", write_hello, NULL}, {"r.csv", write_hello, NULL}};
        CHECK(ob_write_set_atomically(dir, set, 2) == 0 && holds(path, "hello\n") && victim_intact(),
              "ob_write_set_atomically with a hard link at %s", names[w]);
        unlink(names[w]);
    }
}

static void test_in_place(void)
{
    char ldir[400], lock[420];
    snprintf(ldir, sizeof ldir, "%s/run", dir);
    snprintf(lock, sizeof lock, "%s/.lock", ldir);
    mkdir(ldir, 0777);
    const char kinds[] = "shd";
    for (int k = 0; kinds[k]; k++) {
        plant(kinds[k], lock);
        int fd = -1;
        ob_err err;
        const int rc = ob_lock_dir(ldir, &fd, &err);
        CHECK(rc == -2 && fd < 0 && strstr(err.msg, lock) && strstr(err.msg, "link"), "%c-link at .lock: %d %s",
              kinds[k], rc, err.msg);
        CHECK(kinds[k] == 'd' ? access(victim, F_OK) != 0 : victim_intact(), "%c-link at .lock: target changed",
              kinds[k]);
        if (fd >= 0)
            close(fd);
        unlink(lock);
    }
    ob_err err;
    char fifo[420];
    snprintf(fifo, sizeof fifo, "%s/fifo", dir);
    CHECK(mkfifo(fifo, 0666) == 0, "mkfifo");
    CHECK(ob_open_in_place(fifo, O_WRONLY | O_APPEND, &err) == -1, "a FIFO for writing: refused without waiting");
    CHECK(ob_open_in_place(fifo, O_RDWR, &err) == -1 && strstr(err.msg, "not a regular file"),
          "a FIFO: not a regular file: %s", err.msg);
    unlink(fifo);
    int fd = ob_open_in_place(lock, O_RDWR | O_CREAT, &err);
    CHECK(fd >= 0, "a new .lock: %s", fd < 0 ? err.msg : "");
    if (fd >= 0)
        close(fd);
    unlink(lock);
    rmdir(ldir);
}

static void quiet(const char *msg) { (void)msg; }

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/ob_outfile_XXXXXX");
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp");
        return check_done();
    }
    snprintf(victim, sizeof victim, "%s.victim", dir);  /* outside dir */
    ob_set_error_handler(quiet);
    test_outfile();
    test_write_atomically();
    test_in_place();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s %s", dir, victim);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
    return check_done();
}
