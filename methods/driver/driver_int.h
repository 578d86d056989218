/*
 * driver_int.h - the driver's internal vocabulary, shared by its files (not
 * part of the API: driver.h is).
 *   jobs.c          a job's bookkeeping, its first pieces, its outputs; share groups
 *   rules.c         the split rules: what becomes of one measured piece
 *   steps.c         fit and measure pieces, their joints, the chunk helpers
 *   run.c           what every engine shares: the run's state, a chunk's
 *                   work and decisions, a job's end
 *   engine_level.c  the level engine
 *   engine_group.c  the group engine
 *   engine_device.c the device engine
 *   trace.c         task traces and the schedule model
 */
#ifndef OB_DRIVER_INT_H
#define OB_DRIVER_INT_H

#include "methods/driver/driver.h"
#include "methods/core/grow.h"

/* greedy bisection stops when the bracket on the end parameter is this
 * fraction of the stretch still to cover */
static const double GREEDY_EPS = 1e-4;
/* optimal: the bisection on the common error level stops when its bracket
 * is within this ratio, or after OPT_ROUNDS passes */
static const double OPT_RATIO = 1.02;
enum { OPT_ROUNDS = 12 };
/* maxerr split keeps this fraction of the piece on either side */
static const double MAXERR_MARGIN = 0.05;
/* A piece whose error has not dropped below STALL_RATIO of its parent's over
 * STALL_LEVELS successive splits cannot reach the tolerance by subdivision
 * (an error floor of the method, e.g. Lee's circle approximation under the
 * Hausdorff metric); it is accepted and the job ends with status limit.
 * Convergent methods gain a factor 4 to 16 per split, so this never fires for
 * them; slowly converging pieces (a factor 2) are not taken for stalled. */
static const double STALL_RATIO = 0.9;
enum { STALL_LEVELS = 4 };
/* A method asks for a smaller piece when its output would not fit (too many
 * arcs, spans or a pole); a few halvings cure that.  A piece still asking
 * after this many halvings below its initial size never will: the job fails
 * (instead of halving down to the segment limit). */
enum { RETRY_LEVELS = 12 };

/* What the joints need of one fit (joints.h): the start of its first piece,
 * the end of its last, and the joints between its own pieces. */
typedef struct {
    ob_end first, last;
    ob_joint_stats in;
    int count_open;     /* open inner joints counted in ctrl_points (none for a
                           method's own representation: it has its own count) */
} fitjoints;

/* One pending piece of one job. */
typedef struct {
    int job, seg, depth;
    int grp;            /* the job's share group (drv_share_groups) */
    double a, b;        /* the piece fitted now: base parameters of segment seg */
    double end;         /* greedy: end of the stretch being covered */
    double lo, hi;      /* greedy: longest passing / shortest failing end so far */
    double pass_err;    /* greedy: results of the candidate [a, lo] */
    int pass_ctrl_add, pass_maxdeg, pass_n;
    fitjoints pass_fj;  /* greedy: the joints of the candidate [a, lo] */
    int final;          /* greedy: accept this fit whatever its error */
    double parent_err;  /* mid/maxerr: the error of the piece this one was split from */
    int stall;          /* successive splits without a real drop of the error */
    int chain_to;       /* > 0: the leftmost piece of a chain of requests for a
                           smaller piece, already fitted down to this depth
                           (drv_probe_retry_chain): not fitted again above it */
    /* optimal (decide_optimal): greedy passes over the stretch [start, end]
     * at an error level; phase 0 counts the pieces at tol, 1 bisects the
     * level, 2 is the final pass (the greedy code, at the level) */
    int phase, pieces, target, rounds;
    double start, level, elo, ehi, pass_max;
} item;

typedef struct {
    item *v;
    size_t n, cap;
} itemvec;

/* Per-job bookkeeping the caller does not see. */
typedef struct {
    long ctrl_add;  /* sum over accepted fits of the control points each adds
                       beyond the shared start point */
    long pending;   /* items of this job still queued */
    int dead;       /* failed or skipped: drop its remaining items */
    int finished;   /* counted as done for progress */
    int told;       /* its end was passed to the engine (drv_chunk_decide) */
    int floored;    /* a piece hit an error floor: keep the rest as they are */
    ob_span_log *spans; /* NULL, or where accepted pieces go */
    /* joints: the ends of every accepted fit until the job is finalized */
    double gap_tol;     /* a joint is open past this (joints.h) */
    struct fitends *ends;
    int nends, capends;
    int ends_oom;       /* an end could not be stored */
    ob_joint_stats st;  /* inner joints of the accepted fits, then (finalized) all */
    long open_count;    /* joints counted twice in ctrl_points */
    int joined;         /* the joints between fits are measured, ends freed */
} jstate;

/* The ends of one accepted fit over [a, ...] of base segment seg. */
typedef struct fitends {
    int seg;
    double a;
    ob_end first, last;
} fitends;

/* Results of fitting and measuring one item. */
typedef struct {
    ob_fit_status st;       /* the method's, or OB_FIT_FAIL where its output
                               is not usable (piece count, not measurable) */
    int ctrl_add, maxdeg, n;
    double err, t;          /* t: base parameter of the largest error */
    int chain_to;           /* > 0: asks for a smaller piece, and so do its
                               leftmost descendants down to this depth, the
                               retry or depth limit (drv_probe_retry_chain) */
    char msg[160];
} itemres;

/* The measurements of one batch: every piece of every fitted item. */
typedef struct {
    ob_bez *base;          /* base sub-piece of each record */
    ob_measure_rec *rec;
    ob_errval *out;
    double *ns;
    int *first;            /* first record of each item (nitems + 1 entries) */
    int *sampled;          /* indices of the records a batch backend takes */
    ob_measure_rec *srec;
    ob_errval *sout;
    int nsampled;          /* records for the batch backend (srec, sampled) */
    int backend_n;         /* records the batch backend measured (0: none) */
    double backend_wall;   /* its wall time, ns */
} batch;

/* How a chunk's loops run: a team of all threads (the level engine, outside
 * any parallel region), as tasks other threads may take (inside one), or on
 * the calling thread alone. */
typedef enum { DRV_SERIAL = 0, DRV_TEAM, DRV_TASKS } drv_how;

/* The buffers of one chunk of items: one set for the level engine, one per
 * thread for the group engine. */
typedef struct {
    int chunk;          /* entries of each buffer */
    ob_fit *fits;
    itemres *res;
    double *fit_ns, *eval_ns;
    double *stop;       /* each measuring item's stop (drv_chunk_stops) */
    fitjoints *fj;
    int *rep;
    batch B;
} drv_scratch;

/* One driver run, whatever the engine: its jobs, settings, hooks, each
 * job's bookkeeping and share group, the methods' work areas. */
typedef struct {
    ob_job *jobs;
    size_t njobs;
    ob_driver_opts o;
    ob_driver_hooks h;
    jstate *js;
    int *grp;           /* njobs: each job's share group */
    int ngroups;
    size_t wsize;       /* the largest work area a method asks for */
    char *work;         /* wsize bytes per thread */
    size_t done;        /* jobs finished */
    ob_engine_stats st; /* what the engine did (hooks.stats gets a copy) */
    /* each share group's work, for hooks.progress (ob_progress_info); the
     * engines' threads update them with OpenMP atomics, the callback reads
     * them so (drv_progress) */
    double *gcost;      /* predicted: its costliest job's ob_job_cost */
    size_t *gorder;     /* the schedule: groups by decreasing gcost */
    double *gspent;     /* thread time of its fits and measurements so far */
    int *gleft;         /* its jobs not ended yet */
    int *gkind;         /* its method's ob_method_index */
    double *gstart, *gend; /* the group engine: wall ns it was taken and
                              ended (0: not yet) */
    int whole_groups;   /* the engine runs a group on one thread to its end */
    double last_tick;   /* wall ns of the last progress call (drv_progress_tick) */
} drv_run;

/* jobs.c */
int drv_push(itemvec *q, const item *it);
void drv_job_end(ob_job *j, jstate *s, ob_status st, const char *msg);
int drv_check_applicable(ob_job *j, jstate *s);
int drv_plan_job(const ob_job *j, int jobidx, int grp, const ob_driver_opts *o, itemvec *out);
int drv_span_cmp(const void *x, const void *y);
void drv_accept(ob_job *j, jstate *s, int seg, double a, double b, int npieces, int ctrl_add, int maxdeg, double err,
                const fitjoints *fj);
void drv_accept_item(ob_job *j, jstate *s, const item *it, const itemres *r, const fitjoints *fj);
void drv_finalize(ob_job *j, jstate *s);
int *drv_share_groups(const ob_job *jobs, size_t njobs);

/* rules.c */
int drv_decide(ob_job *jobs, jstate *js, const item *it, const itemres *r, const fitjoints *fj,
               const ob_driver_opts *o, itemvec *next);
double drv_item_stop(const ob_job *j, const item *it, int full_probes);

/* steps.c */
double drv_wall_ns(void);
double drv_thread_ns(void);
double drv_fit_item(const ob_job *jobs, const item *it, double budget_ns, void *work, ob_fit *fit, itemres *r);
double drv_probe_retry_chain(const ob_job *jobs, const item *it, int max_depth, double budget_ns, void *work,
                             ob_fit *fit, itemres *r);
int drv_batch_alloc(batch *b, int chunk);
void drv_batch_free(batch *b);
void drv_for(drv_how how, long n, long min_par, int grain, void (*fn)(const void *ctx, long i), const void *ctx);
int drv_measure_prepare(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                        const itemres *res, int samples, const ob_driver_hooks *h, batch *B, drv_how how);
void drv_measure_backend_done(batch *B, double ns);
void drv_measure_finish(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                        itemres *res, double *eval_ns, int samples, batch *B, int backend_ok, drv_how how);
void drv_measure_chunk(const ob_job *jobs, const item *its, long cnt, const ob_fit *fits, const double *stop,
                       itemres *res, double *eval_ns, int samples, const ob_driver_hooks *h, batch *B, drv_how how);
void drv_joints_chunk(const jstate *js, const item *its, long cnt, const ob_fit *fits, const itemres *res,
                      fitjoints *fj, drv_how how);
int drv_same_piece(const item *x, const item *y);
int drv_item_share_cmp(const void *x, const void *y);
long drv_chunk_count(const itemvec *cur, size_t start, int chunk);
void drv_chunk_reps(const item *its, long cnt, const jstate *js, int *rep);
void drv_chunk_stops(const ob_job *jobs, const item *its, long cnt, const int *rep, int full_probes, double *stop);
void drv_copy_shared(long cnt, const int *rep, itemres *res, fitjoints *fj, double *fit_ns, double *eval_ns);

/* run.c */
int drv_run_start(drv_run *R, ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks);
int drv_plan_all(drv_run *R, itemvec *plans);
int drv_job_finished(drv_run *R, size_t i);
void drv_run_end(drv_run *R, int rc);
void drv_progress(drv_run *R);
void drv_progress_tick(drv_run *R);
int drv_scratch_alloc(drv_scratch *S, int chunk);
void drv_scratch_free(drv_scratch *S);
double drv_chunk_work(drv_run *R, drv_scratch *S, const item *its, long cnt, drv_how how);
void drv_chunk_fit(drv_run *R, drv_scratch *S, const item *its, long cnt, drv_how how);
double drv_chunk_account(drv_run *R, drv_scratch *S, long cnt);
int drv_chunk_decide(drv_run *R, drv_scratch *S, const item *its, long cnt, itemvec *next,
                     int (*finished)(void *ctx, size_t job), void *ctx);

/* trace.c */
int drv_trace_task(ob_trace *t, double ns);
int drv_trace_phase(ob_trace *t, size_t first, int grain, double serial_ns);
int drv_trace_append(ob_trace *t, const ob_trace *part);

/* the engines */
int drv_run_level(drv_run *R);
int drv_run_group(drv_run *R);
int drv_run_device(drv_run *R);

#endif
