/*
 * merge_export.c - the export index of a merged run (merge.h): the shards
 * that ran with --export into one directory each wrote
 * index.shardK-of-N.csv there (export_dir.h); their rows, checked against
 * the shards' results.csv, become that directory's index.csv in job order,
 * and the export's names it does not list are removed.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "host/cli/merge.h"
#include "host/diag.h"
#include "host/io/export.h"
#include "host/io/export_dir.h"
#include "host/io/fsutil.h"
#include "host/io/slurp.h"

/* The first n comma-separated fields of line into f[] (pointers into buf,
 * a copy); the fields offbench writes before a message never hold commas.
 * 0, or -1 when the line has fewer. */
static int fields(const char *line, char *buf, size_t cap, const char **f, int n)
{
    if (snprintf(buf, cap, "%s", line) >= (int)cap)
        return -1;
    char *p = buf;
    for (int i = 0; i < n; i++) {
        f[i] = p;
        char *c = strchr(p, ',');
        if (!c)
            return i == n - 1 ? 0 : -1;
        *c = '\0';
        p = c + 1;
    }
    return 0;
}

/* The index row irow is the results row rrow's job with its status:
 * index curve,d,method,tol,status vs results fields 0, 1, 2, 5, 10. */
static int same_job(const char *irow, const char *rrow)
{
    char ib[4096], rb[4096];
    const char *fi[5], *fr[11];
    if (fields(irow, ib, sizeof ib, fi, 5) != 0 || fields(rrow, rb, sizeof rb, fr, 11) != 0)
        return 0;
    static const int at[5] = {0, 1, 2, 5, 10};
    for (int k = 0; k < 5; k++)
        if (strcmp(fi[k], fr[at[k]]) != 0)
            return 0;
    return 1;
}

/* The export directory of every shard, if they share one: 1 with x->dir set,
 * 0 after a warning (or silently when no shard exported). */
static int shared_dir(const ob_shard_in *sh, int nsh, ob_merge_export *x)
{
    int exported = 0;
    struct stat first = {0};
    for (int i = 0; i < nsh; i++) {
        const ob_json_entry *e = ob_json_get(&sh[i].meta, "export_dir");
        exported += e && e->type == OB_JSON_STRING;
    }
    if (exported == 0)
        return 0;
    if (exported < nsh) {
        ob_warn("merge: only %d of the %d shards ran with --export: no combined index.csv (each exporting shard's "
                "directory keeps its index.shardK-of-N.csv)", exported, nsh);
        return 0;
    }
    for (int i = 0; i < nsh; i++) {
        const char *d = ob_json_get(&sh[i].meta, "export_dir")->value;
        struct stat st;
        if (stat(d, &st) != 0 || !S_ISDIR(st.st_mode)) {
            ob_warn("merge: %s/meta.json: the export directory %s is not there: no combined index.csv", sh[i].dir,
                    d);
            return 0;
        }
        if (i == 0) {
            first = st;
            snprintf(x->dir, sizeof x->dir, "%s", d);
        } else if (st.st_dev != first.st_dev || st.st_ino != first.st_ino) {
            ob_warn("merge: the shards exported into different directories (%s, %s): no combined index.csv (each "
                    "keeps its index.shardK-of-N.csv)", x->dir, d);
            return 0;
        }
    }
    return 1;
}

/* Shard s's index: read, and each row checked against its results.csv row. */
static int load_one(const ob_shard_in *s, ob_merge_export *x, char **text, char ***rows)
{
    char name[64], path[4300], *hdr = NULL;
    size_t len, n = 0;
    ob_err err;
    ob_export_index_name(name, sizeof name, s->k, s->n);
    snprintf(path, sizeof path, "%s/%s", x->dir, name);
    *rows = NULL;
    if (ob_slurp(path, text, &len, &err) != 0) {
        ob_error("merge: %s (shard %d/%d of %s ran with --export %s: run it again to export its jobs)", err.msg,
                 s->k, s->n, s->dir, x->dir);
        return -1;
    }
    if (ob_merge_split_lines(*text, len, &hdr, rows, &n) != 0) {
        ob_error("merge: out of memory");
        return -1;
    }
    if (!hdr || strcmp(hdr, OB_EXPORT_INDEX_HEADER) != 0 || n != s->nlines) {
        ob_error("merge: %s: expected the header '%s' and one row per row of %s/results.csv (%zu)", path,
                 OB_EXPORT_INDEX_HEADER, s->dir, s->nlines);
        return -1;
    }
    for (size_t r = 0; r < n; r++)
        if (!same_job((*rows)[r], s->lines[r])) {
            ob_error("merge: %s:%zu: not the job and status of %s/results.csv:%zu: an index of another run or "
                     "an earlier export (run shard %d/%d again)",
                     path, r + 2, s->dir, r + 2, s->k, s->n);
            return -1;
        }
    return 0;
}

int ob_merge_export_load(const ob_shard_in *sh, int nsh, const int *who, const size_t *row, size_t total,
                         ob_merge_export *x)
{
    memset(x, 0, sizeof *x);
    if (!shared_dir(sh, nsh, x))
        return 0;
    char ***rows = calloc((size_t)nsh, sizeof *rows);
    x->texts = calloc((size_t)nsh, sizeof *x->texts);
    x->rows = malloc((total ? total : 1) * sizeof *x->rows);
    int rc = !rows || !x->texts || !x->rows ? -1 : 0;
    if (rc != 0)
        ob_error("merge: out of memory");
    x->ntexts = nsh;
    for (int i = 0; rc == 0 && i < nsh; i++)
        rc = load_one(&sh[i], x, &x->texts[i], &rows[i]);
    for (size_t j = 0; rc == 0 && j < total; j++)
        x->rows[j] = rows[who[j]][row[j]];
    x->nrows = total;
    x->nshards = sh[0].n;
    for (int i = 0; rows && i < nsh; i++)
        free(rows[i]);
    free(rows);
    x->active = rc == 0;
    return rc;
}

static int write_index_cb(FILE *f, void *ctx)
{
    const ob_merge_export *x = ctx;
    fprintf(f, "%s\n", OB_EXPORT_INDEX_HEADER);
    for (size_t j = 0; j < x->nrows; j++)
        fprintf(f, "%s\n", x->rows[j]);
    return ferror(f) ? -1 : 0;
}

/* The stems index.csv lists (its last column, when not empty). */
static int listed_stems(const ob_merge_export *x, ob_strmap *keep)
{
    for (size_t j = 0; j < x->nrows; j++) {
        const char *c = strrchr(x->rows[j], ',');
        if (c && c[1] && ob_strmap_put(keep, c + 1, 0) == -2)
            return -1;
    }
    return 0;
}

int ob_merge_export_write(const ob_merge_export *x)
{
    if (!x->active)
        return 0;
    if (ob_write_atomically(x->dir, "index.csv", write_index_cb, (void *)x) != 0)
        return -1;
    ob_strmap keep = {0};
    ob_err err;
    long removed = 0;
    const ob_prune_rule rule = {&keep, NULL, x->nshards, 0};
    int rc = listed_stems(x, &keep);
    if (rc != 0)
        ob_error("merge: out of memory");
    else if ((rc = ob_export_prune(x->dir, &rule, &removed, &err)) != 0)
        ob_error("merge: %s", err.msg);
    ob_strmap_free(&keep);
    if (rc == 0)
        ob_info("merge: wrote %s/index.csv (%zu jobs)%s", x->dir, x->nrows,
                removed > 0 ? "; removed the files of jobs it does not list" : "");
    return rc;
}

void ob_merge_export_free(ob_merge_export *x)
{
    for (int i = 0; x->texts && i < x->ntexts; i++)
        free(x->texts[i]);
    free(x->texts);
    free(x->rows);
    memset(x, 0, sizeof *x);
}
