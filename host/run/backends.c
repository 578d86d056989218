/*
 * backends.c - the backends that computed a run's rows (see backends.h).
 */
#include "host/run/backends.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "host/io/outfile.h"
#include "host/io/output.h"

static const char FILE_NAME[] = "results.backends";

static int file_path(const char *dir, char *path, size_t len)
{
    const int n = snprintf(path, len, "%s/%s", dir, FILE_NAME);
    return n < 0 || (size_t)n >= len ? -1 : 0;
}

/* src into dst with tabs and line ends as spaces: one field of a line. */
static void field(char *dst, size_t len, const char *src)
{
    snprintf(dst, len, "%s", src);
    for (char *p = dst; *p; p++)
        if (*p == '\t' || *p == '\n' || *p == '\r')
            *p = ' ';
}

/* b as a line of the file. */
static void line_of(const ob_backend_info *b, char *line, size_t len)
{
    char p[sizeof b->platform], d[sizeof b->device], v[sizeof b->driver];
    if (!b->opencl) {
        snprintf(line, len, "cpu");
        return;
    }
    field(p, sizeof p, b->platform);
    field(d, sizeof d, b->device);
    field(v, sizeof v, b->driver);
    snprintf(line, len, "opencl\t%s\t%s\t%s", p, d, v);
}

int ob_backends_load(const char *dir, int resume, ob_backend_list *l, char *why, size_t wlen)
{
    char path[4200], buf[sizeof l->line[0]];
    l->n = 0;
    if (file_path(dir, path, sizeof path) != 0)
        return snprintf(why, wlen, "%s/%s: the path is too long", dir, FILE_NAME), -1;
    if (!resume) {
        unlink(path);  /* a fresh run: another run's list is not this one's */
        return 0;
    }
    FILE *f = fopen(path, "r");
    if (!f)
        return errno == ENOENT ? 0 : (snprintf(why, wlen, "%s: %s", path, strerror(errno)), -1);
    while (fgets(buf, sizeof buf, f) && l->n < OB_MAX_BACKENDS) {
        buf[strcspn(buf, "\n")] = '\0';
        if (buf[0])
            snprintf(l->line[l->n++], sizeof l->line[0], "%s", buf);
    }
    fclose(f);
    return 0;
}

static int write_list(FILE *f, void *ctx)
{
    const ob_backend_list *l = ctx;
    for (int i = 0; i < l->n; i++)
        fprintf(f, "%s\n", l->line[i]);
    return ferror(f) ? -1 : 0;
}

int ob_backends_note(const char *dir, const ob_backend_info *b, ob_backend_list *l, char *why, size_t wlen)
{
    char line[sizeof l->line[0]], path[4200];
    line_of(b, line, sizeof line);
    for (int i = 0; i < l->n; i++)
        if (strcmp(l->line[i], line) == 0)
            return 0;
    if (l->n == OB_MAX_BACKENDS)
        return 0;  /* as many as any run has; the last one keeps "backend" */
    snprintf(l->line[l->n++], sizeof l->line[0], "%s", line);
    ob_outfile o;
    ob_err err;
    if (file_path(dir, path, sizeof path) != 0 || ob_outfile_open(&o, path, 1, &err) != 0 ||
        (write_list(o.f, l) != 0 ? (ob_outfile_discard(&o), 1) : ob_outfile_commit(&o, 1, &err) != 0)) {
        snprintf(why, wlen, "%s/%s: cannot write", dir, FILE_NAME);
        return -1;
    }
    return 0;
}

/* One entry: {"backend": KIND[, "platform": .., "device": .., "driver": ..]}. */
static void entry_json(FILE *f, const char *line)
{
    static const char *const keys[] = {"kind", "platform", "device", "driver"};
    char rest[700];
    snprintf(rest, sizeof rest, "%s", line);
    char *at = rest;
    const int opencl = strncmp(rest, "opencl\t", 7) == 0;
    fprintf(f, "{\"backend\": ");
    for (int k = 0; k < (opencl ? 4 : 1); k++) {
        char *tab = at ? strchr(at, '\t') : NULL;
        if (tab)
            *tab = '\0';
        if (k)
            fprintf(f, ", \"%s\": ", keys[k]);
        ob_json_string(f, at ? at : "");
        at = tab ? tab + 1 : NULL;
    }
    fputc('}', f);
}

void ob_backends_json(FILE *f, const ob_backend_list *l, const ob_backend_info *cur)
{
    fputc('[', f);
    if (l && l->n > 0) {
        for (int i = 0; i < l->n; i++) {
            fputs(i ? ", " : "", f);
            entry_json(f, l->line[i]);
        }
    } else {
        char line[700];
        line_of(cur, line, sizeof line);
        entry_json(f, line);
    }
    fputc(']', f);
}
