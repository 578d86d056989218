/*
 * cmd_run.c - `./offbench run`: parse the options, plan the jobs (plan.h),
 * take the output directory, run them in the mode the options ask for
 * (modes.h: plain, journaled, repeated; sharded or under MPI), write the
 * run's files (files.h).
 *
 * Every step returns GO_ON or the command's exit status (commands.h: 0, 1
 * a run-time failure, 2 bad input, 128 + signal when interrupted).
 */
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "host/backend/select.h"
#include "host/cli/commands.h"
#include "host/diag.h"
#include "host/io/export.h"
#include "host/io/fsutil.h"
#include "host/io/numfmt.h"
#include "host/run/certify.h"
#include "host/run/trimmed.h"
#include "host/run/files.h"
#include "host/run/fittime.h"
#include "host/run/journal.h"
#include "host/run/modes.h"
#include "host/run/mpirun.h"
#include "host/run/plan.h"
#include "host/run/resume_opts.h"
#include "host/run/shard.h"
#include "host/run/signals.h"

enum { GO_ON = -1 };

/* One `run` command: its configuration, record and what it holds. */
typedef struct {
    ob_run_opts o;
    ob_run_record rec;
    int ranks;                   /* MPI ranks (1 without mpirun) */
    ob_curveset set;
    char where[4096];            /* the curves' source */
    ob_job *jobs;                /* this process's jobs */
    size_t njobs;
    size_t *shard_idx;           /* with a shard: their indices in the whole run */
    ob_cl *cl;
    ob_journal journal;
    int lock_fd;
    ob_span_log *spans;          /* --export, --certify: the accepted pieces of each job (host/io/export.h) */
    int cert_failed;             /* --certify: a job could not be certified (exit 1; its columns empty) */
    double wall;
    double *rep_fit, *rep_eval;  /* --reps: reps x njobs timings */
    double *fit_round;           /* --time-fits: rounds x njobs method times */
} run_cmd;

/* Under mpirun the ranks split the run among themselves as shards. */
static int setup_ranks(run_cmd *r)
{
    r->ranks = ob_mpi_size();
    r->rec.shard_k = r->o.shard_k;
    r->rec.shard_n = r->o.shard_n;
    if (r->ranks <= 1)
        return GO_ON;
    if (r->o.shard_n > 0 || r->o.resume_dir) {  /* every rank sees the same arguments: they all stop here alike */
        ob_error("under mpirun the ranks split the run: --shard and --resume do not apply");
        return 2;
    }
    if (r->o.time_fits) {  /* the gather carries rows and samples, not fits.csv */
        ob_error("under mpirun: --time-fits does not apply (time the fits in a run of one process, or per --shard)");
        return 2;
    }
    r->rec.shard_k = ob_mpi_rank();
    r->rec.shard_n = r->ranks;
    r->rec.mpi_ranks = r->ranks;
    return GO_ON;
}

/* The curves, their offset degrees, the jobs and the hashes that identify
 * them; then this process's shard. */
/* The test hook OFFBENCH_TEST_SLOW=METHOD:FACTOR (driver.h): read once,
 * before any work.  0, or -1 after ob_error() when it is malformed. */
static int test_slow_hook(ob_driver_opts *d)
{
    const char *v = getenv("OFFBENCH_TEST_SLOW");
    if (!v || !*v)
        return 0;
    const char *colon = strrchr(v, ':');
    char name[64];
    double k = 0;
    if (colon && colon - v < (long)sizeof name)
        snprintf(name, sizeof name, "%.*s", (int)(colon - v), v);
    else
        name[0] = '\0';
    d->test_slow_method = name[0] ? ob_method_find(name) : NULL;
    if (!d->test_slow_method || ob_parse_double(colon + 1, &k) || !(k >= 1 && k <= 1000)) {
        ob_error("OFFBENCH_TEST_SLOW: expected METHOD:FACTOR (a method and a number from 1 to 1000), got '%s'", v);
        return -1;
    }
    d->test_slow_factor = k;
    ob_warn("test hook OFFBENCH_TEST_SLOW: every fit of %s is done %g times (on average over its pieces)", name, k);
    return 0;
}

static int plan_run(run_cmd *r)
{
    const ob_run_opts *o = &r->o;
    if (ob_load_run_curves(o, &r->set, r->where, sizeof r->where) != 0)
        return 2;
    r->rec.curves = &r->set;
    if (o->threads > 0)
        omp_set_num_threads(o->threads);
    ob_offset_degrees(o, &r->set);
    r->jobs = ob_plan_jobs(o, &r->set, &r->njobs);
    if (!r->jobs) {
        ob_error("out of memory planning the jobs");
        return 1;
    }
    if (r->njobs == 0) {
        ob_error("no jobs: the selected curves have no offsets");
        return 2;
    }
    for (size_t i = 0; o->driver.test_slow_method && i < r->njobs; i++)
        if (r->jobs[i].method == o->driver.test_slow_method)
            r->jobs[i].test_fit_repeat = o->driver.test_slow_factor;
    r->rec.data_hash = ob_curves_hash(o, &r->set);
    char *fp = ob_run_fingerprint(o, r->where, r->rec.data_hash);
    if (!fp) {
        ob_error("out of memory");
        return 1;
    }
    r->rec.jobs_total = r->njobs;
    r->rec.plan_hash = ob_plan_hash(r->jobs, r->njobs, fp);
    r->rec.plan_seed = ob_plan_seed(fp);
    free(fp);
    if (r->ranks > 1 && !ob_mpi_all_equal(r->rec.plan_hash)) {
        ob_error("rank %d: the ranks were started with other arguments or data (plan hash differs)", ob_mpi_rank());
        return 2;
    }
    if (r->rec.shard_n > 0) {
        if (ob_select_shard(r->rec.shard_k, r->rec.shard_n, &r->jobs, &r->njobs, &r->shard_idx) != 0)
            return 1;
        ob_info("%s %d/%d: %zu of %zu jobs", r->ranks > 1 ? "rank" : "shard", r->rec.shard_k, r->rec.shard_n,
                r->njobs, r->rec.jobs_total);
    }
    return GO_ON;
}

/* A fresh run owns its directory: the files of an earlier run there go
 * (only with --force: without it a finished or interrupted run there was
 * refused before). */
static void remove_stale(const char *dir)
{
    static const char *const names[] = {"results.csv", "meta.json", "samples.csv", "fits.csv", "shard.csv",
                                        "results.fingerprint", "results.journal.csv",
                                        "certify.journal.csv", "results.backends"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char p[4200];
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        remove(p);
    }
}

/* The directory checks of one process: 0, or the exit status. */
static int claim_dir(run_cmd *r)
{
    const ob_run_opts *o = &r->o;
    struct stat st;
    const char *const inputs[] = {o->curves_file};
    if (ob_check_out_not_input("run", o->out_dir, 1, inputs, 1) != 0)
        return 2;  /* the curve file would sit among (or be) the run's outputs */
    if (o->resume_dir && stat(o->out_dir, &st) != 0) {
        ob_error("--resume: %s does not exist: nothing to resume", o->out_dir);
        return 2;
    }
    const int trc = ob_take_run_dir("run", o->out_dir, !o->resume_dir, &r->lock_fd);
    if (trc != 0)
        return trc;
    if (o->resume_dir)
        return 0;
    char jp[4200];
    snprintf(jp, sizeof jp, "%s/results.journal.csv", o->out_dir);
    if (!o->force && stat(jp, &st) == 0) {
        ob_error("%s holds an interrupted run (%s): finish it with --resume %s, choose another --out, "
                 "or add --force to discard it and start afresh", o->out_dir, jp, o->out_dir);
        return 2;
    }
    snprintf(jp, sizeof jp, "%s/results.csv", o->out_dir);
    if (!o->force && stat(jp, &st) == 0) {
        ob_error("%s holds a finished run (%s): choose another --out, or add --force to replace it", o->out_dir,
                 jp);
        return 2;
    }
    remove_stale(o->out_dir);
    return 0;
}

/* Only when the run can start is the directory created and taken: under MPI
 * only rank 0 writes; the ranks learn together that it can. */
static int take_out_dir(run_cmd *r)
{
    const int fail = ob_mpi_rank() == 0 ? claim_dir(r) : 0;
    const long worst = ob_mpi_max(fail);
    return worst > 0 ? (worst == 2 ? 2 : 1) : GO_ON;
}

/* The driver's status of a run that did not finish, as the exit status. */
static int unfinished(run_cmd *r, int drc)
{
    const ob_run_opts *o = &r->o;
    ob_journal_close(&r->journal, 0);  /* the journal keeps the finished jobs' rows */
    if (drc == 1) {
        if (o->reps > 0)
            return ob_stop_exit("nothing written (a run with --reps cannot be resumed)");
        return ob_stop_exit("the finished jobs' rows are in %s; run --resume %s finishes the run (its options "
                            "are taken from the journal)", r->journal.path, o->out_dir);
    }
    /* jobs that never ran are no results: nothing is written */
    if (o->reps > 0)
        ob_error("ran out of memory: nothing written");
    else
        ob_error("ran out of memory before every job had run: nothing written; the finished jobs' rows are in "
                 "%s; --resume %s runs the others", r->journal.path, o->out_dir);
    return 1;
}

/* --time-fits: the pass that times every method's fits on the pieces its
 * jobs accepted.  Returns the driver's codes: 0, 1 stopped, -1 failed. */
static int time_fits(run_cmd *r)
{
    const ob_fittime_opts fo = {r->o.fit_rounds, r->o.fit_min_ns};
    r->fit_round = malloc((size_t)fo.rounds * (r->njobs ? r->njobs : 1) * sizeof *r->fit_round);
    if (!r->fit_round) {
        ob_error("--time-fits: out of memory");
        return -1;
    }
    return ob_fittime_run(&fo, r->jobs, r->njobs, r->spans, r->fit_round, &r->rec.fit_seconds);
}

/* The jobs, in the mode the options ask for: journaled (resumable), or a
 * warm-up and timed repetitions; under MPI, plain. */
static int run_jobs(run_cmd *r)
{
    const ob_run_opts *o = &r->o;
    ob_run_ctx c = {o, &r->rec, {.stop = ob_stop_flag()}};
    ob_backend_hooks(r->cl, &r->rec.binfo, &c.hooks);
    c.hooks.spans = r->spans;
    size_t restored = 0;
    ob_loadavg_sample(&r->rec.load);  /* before the first job (hostinfo.h) */
    const int journaled = !(o->reps > 0 || r->ranks > 1 || o->time_fits || o->trimmed);
    int drc = !journaled ? ob_run_plain(&c, r->jobs, r->njobs, o->reps > 0 ? "warm-up run" : NULL, &r->wall)
                         : ob_run_journaled(&c, r->jobs, r->njobs, r->where, &r->journal, &r->wall, &restored);
    c.hooks.spans = NULL;  /* the first run's pieces: --reps repeats it for the timings only */
    if (drc == 0 && o->certify) {  /* outside every timing; a stop here is a stop of the run */
        const int crc = ob_certify_run(o->driver.samples, o->certify, o->driver.job_timeout_ns, r->jobs, r->njobs,
                                       r->spans,
                                       journaled ? &r->journal : NULL, &r->rec.cert_seconds);
        r->cert_failed = crc < 0;
        drc = crc > 0 ? 1 : 0;
    }
    if (drc == 0 && o->trimmed) {  /* the trimmed offset (trimmed.h), outside every timing */
        const int trc = ob_trimmed_run(o->driver.samples, r->jobs, r->njobs, r->spans, &r->rec.trim_seconds);
        if (trc < 0)
            return 1;  /* said: nothing is written (no journal with --trimmed) */
        drc = trc;
    }
    if (drc == 0 && o->time_fits) {  /* the method's own time (fittime.h), outside every other timing */
        drc = time_fits(r);
        if (drc < 0)
            return 1;  /* said: nothing is written (no journal with --time-fits) */
    }
    if (r->ranks > 1 && ob_mpi_max(drc == 1) > 0 && drc != 1) {
        drc = 1;  /* another rank was stopped: none writes */
        ob_note_stop(SIGTERM);
    }
    if (drc == 2)
        return 2;
    if (drc == 0 && o->reps > 0) {
        r->rep_fit = malloc((size_t)o->reps * r->njobs * sizeof *r->rep_fit);
        r->rep_eval = malloc((size_t)o->reps * r->njobs * sizeof *r->rep_eval);
        drc = !r->rep_fit || !r->rep_eval ? -1 : ob_run_reps(&c, r->jobs, r->njobs, r->rep_fit, r->rep_eval, &r->wall);
    }
    ob_loadavg_sample(&r->rec.load);
    char warn[512];
    if (drc == 0 && ob_mpi_rank() == 0 && ob_load_warning(&r->rec.load, o->reps, ob_cores_used(), warn, sizeof warn))
        ob_warn("%s", warn);  /* meta.json's "warnings" has it too */
    if (r->ranks > 1) {
        ob_info("rank %d: %zu jobs in %.2f s", ob_mpi_rank(), r->njobs, r->wall);
        const ob_run_files w = {o, &r->rec, r->jobs, r->njobs, r->shard_idx, r->where, ob_mpi_max(r->wall),
                                r->rep_fit, r->rep_eval, NULL};
        return drc == 1 ? unfinished(r, drc) : ob_mpi_write_run_files(&w, drc);
    }
    return drc != 0 ? unfinished(r, drc) : GO_ON;
}

/* Every file of the finished run, then its closing line. */
static int write_files(run_cmd *r)
{
    const ob_run_files w = {&r->o, &r->rec, r->jobs, r->njobs, r->shard_idx, r->where, r->wall,
                            r->rep_fit, r->rep_eval, r->fit_round};
    const int written = ob_write_run_files(&w) == 0;
    ob_journal_close(&r->journal, written);  /* results.csv has every row now */
    ob_run_summary(&w, written);
    const int st = ob_export_finish(&r->o, r->spans, r->jobs, written ? 0 : 1);  /* --export, outside every timing */
    return st == 0 && r->cert_failed ? 1 : st;
}

static void run_cmd_free(run_cmd *r)
{
    ob_journal_close(&r->journal, 0);
    if (r->lock_fd >= 0)
        close(r->lock_fd);  /* the lock goes with it */
    ob_cl_close(r->cl);
    free(r->rep_fit);
    free(r->rep_eval);
    free(r->fit_round);
    free(r->shard_idx);
    ob_export_free(r->spans);
    free(r->jobs);
    ob_curveset_free(&r->set);
    ob_run_opts_free(&r->o);
}

int ob_cmd_run(int argc, char **argv, int full_argc, char **full_argv)
{
    run_cmd r;
    memset(&r, 0, sizeof r);
    r.lock_fd = -1;
    const int prc = ob_run_opts_parse(argc, argv, &r.o);
    int st = prc == OB_CLI_OK ? GO_ON : prc == OB_CLI_HELP ? 0 : 2;
    if (st == GO_ON) {
        r.o.argc = full_argc;
        r.o.argv = full_argv;
        const char *oom = getenv("OFFBENCH_TEST_OOM_AFTER");  /* test hook (driver.h) */
        if (oom && *oom)
            r.o.driver.test_oom_after = strtol(oom, NULL, 10);
        /* --resume DIR: the run's own options, for those not given (resume_opts.h) */
        st = r.o.resume_dir && ob_resume_take_options(&r.o) ? 2 : test_slow_hook(&r.o.driver) ? 2
             : ob_machine_env_check() ? 2 : setup_ranks(&r);  /* meta.json's machine name (hostinfo.h) */
    }
    if (st == GO_ON)
        st = plan_run(&r);
    if (st == GO_ON && (st = ob_export_prepare(&r.o, r.rec.mpi_ranks, r.njobs, &r.spans)) == 0)
        st = GO_ON;  /* --export: a span log per job */
    if (st == GO_ON && (r.o.certify || r.o.time_fits || r.o.trimmed) && !r.spans && !(r.spans = ob_span_logs_new(r.njobs))) {
        ob_error("out of memory");  /* --certify, --time-fits: the same logs */
        st = 1;
    }
    int brc = 0;  /* out of memory starting OpenCL: exit 1, not 2 */
    if (st == GO_ON && (brc = ob_open_backend(r.o.backend, r.o.device, 1u << r.o.metric, &r.rec.binfo, &r.cl)) != 0)
        st = ob_backend_exit(brc);
    if (st == GO_ON)
        st = take_out_dir(&r);
    if (st == GO_ON)
        st = run_jobs(&r);
    if (st == GO_ON)
        st = write_files(&r);
    run_cmd_free(&r);
    return st;
}
