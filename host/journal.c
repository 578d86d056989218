/*
 * journal.c - rows saved as jobs finish, and resuming an interrupted run
 * (see journal.h).
 */
#include "journal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "numfmt.h"
#include "output.h"
#include "slurp.h"

static const char MAGIC[] = "#offbench-journal 1 ";

static double mono_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

char *ob_run_fingerprint(const ob_run_opts *o, const char *where)
{
    size_t cap = 4096, n = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    n += (size_t)snprintf(s, cap, "samples=%d max_depth=%d max_segments=%d inflections=%d job_timeout=%.17g data=%s",
                          o->driver.samples, o->driver.max_depth, o->driver.max_segments, o->driver.inflections,
                          o->driver.job_timeout_ns, where);
    for (int m = 0; ob_methods[m]; m++)
        for (int k = 0; k < ob_methods[m]->nparams; k++) {
            char num[40];
            ob_fmt_double(num, sizeof num, o->params[m * OB_MAX_PARAMS + k]);
            const size_t need = strlen(ob_methods[m]->name) + strlen(ob_methods[m]->params[k].name) + strlen(num) + 4;
            if (n + need >= cap) {
                char *ns = realloc(s, cap *= 2);
                if (!ns) {
                    free(s);
                    return NULL;
                }
                s = ns;
            }
            n += (size_t)snprintf(s + n, cap - n, " %s.%s=%s", ob_methods[m]->name, ob_methods[m]->params[k].name,
                                  num);
        }
    for (char *p = s; *p; p++)  /* one line, whatever the data path holds */
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    return s;
}

/* Creates the journal afresh: first line and header. */
static int create(ob_journal *j, const char *fp, char *err, size_t errlen)
{
    j->f = fopen(j->path, "w");
    if (!j->f) {
        snprintf(err, errlen, "%s: cannot write: %s", j->path, strerror(errno));
        return -1;
    }
    fprintf(j->f, "%s%s\n%s\n", MAGIC, fp, OB_RESULTS_HEADER);
    if (fflush(j->f) != 0) {
        snprintf(err, errlen, "%s: write failed", j->path);
        return -1;
    }
    return 0;
}

/* Reads an existing journal into *restored; cuts a partial last line. */
static int reopen(ob_journal *j, const char *fp, ob_res_table *restored, char *err, size_t errlen)
{
    char *text;
    size_t len;
    if (ob_slurp(j->path, &text, &len, err, errlen) != 0)
        return -1;
    const char *nl = memchr(text, '\n', len);
    if (!nl) {  /* killed while the first line was written: nothing saved */
        free(text);
        return create(j, fp, err, errlen);
    }
    const size_t first = (size_t)(nl - text);
    if (first < sizeof MAGIC - 1 || memcmp(text, MAGIC, sizeof MAGIC - 1) != 0) {
        snprintf(err, errlen, "%s:1: not an offbench journal", j->path);
        free(text);
        return -1;
    }
    const size_t fplen = first - (sizeof MAGIC - 1);
    if (fplen != strlen(fp) || memcmp(text + sizeof MAGIC - 1, fp, fplen) != 0) {
        snprintf(err, errlen, "%s:1: the interrupted run had other options (samples, limits, job timeout, method "
                 "parameters or data): resume it with the same options", j->path);
        free(text);
        return -1;
    }
    size_t keep = len;
    while (keep > first + 1 && text[keep - 1] != '\n')
        keep--;
    if (keep < len && truncate(j->path, (off_t)keep) != 0) {
        snprintf(err, errlen, "%s: cannot cut the partial last line: %s", j->path, strerror(errno));
        free(text);
        return -1;
    }
    const char *body = text + first + 1;
    const size_t blen = keep - (first + 1);
    const char *hend = memchr(body, '\n', blen);
    if (hend && ((size_t)(hend - body) != strlen(OB_RESULTS_HEADER) ||
                 memcmp(body, OB_RESULTS_HEADER, strlen(OB_RESULTS_HEADER)) != 0)) {
        /* rows of another build's columns cannot be continued or restored */
        snprintf(err, errlen, "%s:2: written by another version of offbench (its columns differ): run again "
                 "without --resume", j->path);
        free(text);
        return -1;
    }
    int rc = 0;
    if (blen > 0 && memchr(body, '\n', blen)) {  /* a header line at least */
        rc = ob_res_parse(body, blen, j->path, restored, err, errlen);
        if (rc == 0) {
            j->f = fopen(j->path, "a");
            if (!j->f) {
                snprintf(err, errlen, "%s: cannot append: %s", j->path, strerror(errno));
                rc = -1;
            }
        }
    } else {
        rc = create(j, fp, err, errlen);
    }
    free(text);
    return rc;
}

int ob_journal_open(ob_journal *j, const char *dir, const char *fp, int resume, ob_res_table *restored, char *err,
                    size_t errlen)
{
    memset(j, 0, sizeof *j);
    memset(restored, 0, sizeof *restored);
    snprintf(j->path, sizeof j->path, "%s/results.journal.csv", dir);
    j->last_sync = mono_s();
    if (!resume)
        return create(j, fp, err, errlen);
    struct stat st;
    if (stat(j->path, &st) == 0)
        return reopen(j, fp, restored, err, errlen);
    char res[4200];
    snprintf(res, sizeof res, "%s/results.csv", dir);
    if (stat(res, &st) != 0) {
        snprintf(err, errlen, "--resume: %s has neither results.journal.csv nor results.csv: nothing to resume",
                 dir);
        return -1;
    }
    /* the run had finished: its rows are taken as they are */
    if (ob_res_load(res, restored, err, errlen) != 0)
        return -1;
    if (!restored->has_joints) {
        snprintf(err, errlen, "--resume: %s was written by an older offbench (no max_gap column): run again without "
                 "--resume", res);
        ob_res_free(restored);
        return -1;
    }
    j->from_results = 1;
    return create(j, fp, err, errlen);
}

int ob_journal_add(ob_journal *j, const ob_job *job)
{
    if (!j->f)
        return -1;
    if (ob_write_result_row(j->f, job) != 0 || fflush(j->f) != 0)
        return -1;
    const double now = mono_s();
    if (now - j->last_sync >= 1.0) {
        fsync(fileno(j->f));
        j->last_sync = now;
    }
    return 0;
}

void ob_journal_close(ob_journal *j, int remove_it)
{
    if (!j)
        return;
    if (j->f) {
        fflush(j->f);
        fsync(fileno(j->f));
        fclose(j->f);
        j->f = NULL;
    }
    if (remove_it && j->path[0])
        remove(j->path);
}

int ob_job_from_row(ob_job *job, const ob_res_row *row)
{
    static const ob_status st[] = {OB_OK, OB_LIMIT, OB_FAIL, OB_SKIP, OB_TIMEOUT};
    int k = -1;
    for (int i = 0; i < (int)(sizeof st / sizeof st[0]); i++)
        if (strcmp(row->status, ob_status_name(st[i])) == 0)
            k = i;
    if (k < 0)
        return -1;
    job->status = st[k];
    job->ctrl_points = row->ctrl_points;
    job->segments = (int)row->segments;
    job->out_degree = (int)row->out_degree;
    job->max_err = row->max_err;
    job->fit_ns = row->fit_ns;
    job->eval_ns = row->eval_ns;
    snprintf(job->message, sizeof job->message, "%s", row->message);
    job->max_gap = row->max_gap;
    job->max_kink = row->max_kink;
    if (ob_cont_parse(row->continuity ? row->continuity : "", &job->continuity) != 0)
        job->continuity = OB_CONT_NONE;
    return 0;
}
