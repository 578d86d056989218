/*
 * cmd_measure.c - `offbench measure --curve ID --d D --approx FILE [--approx FILE]...
 * [--curves FILE] [--metric M|all] [--samples S] [--transform a,b,c,d,e,f]
 * [--translate X,Y] [--scale S|SX,SY] [--flip-y] [--svg-units user|px]
 * [--tol T]`: the error of each
 * approximation someone else made (a .curves file, the JSON of --export, or
 * DXF entities: SPLINE, LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE, POLYLINE;
 * an SVG file's paths) against the exact d-offset of a base curve, under every metric that applies or the one asked, with the run's engine
 * (host/measure/measure.h).  Each file is measured on its own.  Writes a
 * small CSV to standard output, the rows of each file in the order given:
 *   metric,status,max_err,piece,seg,t,message,file,curve,d,pieces,ctrl_points
 * (the last five join with results.csv: curve and d as it writes them,
 * pieces its segments, ctrl_points counted as the driver counts them).
 * status `ok`, or `n/a` with the reason (bound and radial need pieces in
 * the base's parameter: files exported from methods that keep it).  Without
 * --metric the n/a rows are left out and named once per file on stderr;
 * --metric all writes every row.
 * The frame options (measure_more.h) map each file's coordinates to the
 * base's before matching.  A file far from the offset (its cover fails, or
 * its error is over 1e-2 of the curve's size) gets a diagnosis on stderr
 * (host/measure/diagnose.h: the wrong sign of d, a similarity away), which
 * changes no row and no exit status.
 * A file that names the job that exported it (approx.h: have_job) and is
 * measured against another curve or d gets a warning on stderr: its error
 * is then not that job's max_err.
 * --trimmed [--trim-dump FILE]: instead, one row trimmed-hausdorff, the
 * distance between the pieces and the trimmed offset as point sets (no
 * match, no cover: host/measure/trim.h); --metric certified adds a row n/a; --tol decides on
 * trimmed-hausdorff; not with --per-piece or --draw.
 * --per-piece FILE.csv and --draw FILE.svg: where the error is, piece by
 * piece (host/measure/perpiece.h, host/view/draw_approx.h, where_out.h), in
 * the base's coordinates (after the frame options).
 * Exit status: 0 (with --tol: every file within T); 1 with --tol: a
 * file's deciding error (hausdorff-whole, or the row --metric names) over
 * T, after the whole CSV, a line "measure: FILE: within/over tolerance T:
 * METRIC = E" per file on stderr; 1 also when standard output is not
 * writable; 2 bad input (an option, a file, an unknown curve, pieces that
 * do not cover the offset once, a --tol whose deciding row is n/a), with a
 * message naming the option or FILE:LINE; then nothing is written (no
 * partial CSV: the other files' rows are not either).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/cli/cliopts.h"
#include "host/cli/measure_more.h"
#include "host/cli/commands.h"
#include "host/cli/where_out.h"
#include "host/run/plan.h"
#include "host/diag.h"
#include "host/io/approx_read.h"
#include "host/io/numfmt.h"
#include "host/io/output.h"
#include "host/measure/diagnose.h"
#include "host/measure/measure.h"
#include "host/measure/trim.h"
#include "host/run/signals.h"
#include "methods/driver/joints.h"

typedef struct {
    const char **approx;       /* the files, in the order given (owned array) */
    int napprox, capprox;
    int have_d;
    double d;
    int want[OB_METRIC_COUNT]; /* the per-piece metrics asked */
    int whole;                 /* the hausdorff-whole row asked */
    ob_where_out where;        /* --per-piece, --draw (where_out.h) */
    const char *metric_named;  /* --metric's value, NULL: not given (n/a rows left out) */
    ob_measure_more more;      /* frame and verdict options (measure_more.h) */
    int trimmed;               /* --trimmed: the trimmed-hausdorff row (host/measure/trim.h) */
    const char *trim_dump;     /* --trim-dump FILE, or NULL */
} measure_args;

/* The rows --metric V asks for: all (the default: every metric but
 * certified), hausdorff (with its whole row), hausdorff-whole alone, or one
 * metric.  0, or -1 unknown. */
static int set_metrics(measure_args *a, const char *v)
{
    ob_metric m = OB_METRIC_COUNT;
    const int all = strcmp(v, "all") == 0, whole = strcmp(v, "hausdorff-whole") == 0;
    if (!all && !whole && ob_metric_parse(v, &m))
        return -1;
    for (int k = 0; k < OB_METRIC_COUNT; k++) /* all: every metric but certified (50x the cost: asked by name) */
        a->want[k] = (all && (ob_metric)k != OB_METRIC_CERTIFIED) || (ob_metric)k == m;
    a->whole = all || whole || m == OB_METRIC_HAUSDORFF;
    return 0;
}

enum { MO_APPROX, MO_D, MO_METRIC, MO_PER_PIECE, MO_DRAW, MO_TRIMMED, MO_TRIM_DUMP };

static const ob_flag measure_flags[] = {
    {"approx", "FILE", "the approximation, covering the offset once: a .curves file, --export's JSON, or DXF "
     "(SPLINE, LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE, POLYLINE) or SVG paths; repeat it to measure several, each on its own",
     MO_APPROX, OB_FLAG_REPEAT},
    {"d", "D", "the signed offset distance it approximates", MO_D, OB_FLAG_ONCE},
    {"metric", "M|all", "bound, radial, normal, hausdorff (with hausdorff-whole), param, certified, hausdorff-whole or all "
     "(default: every one but certified)", MO_METRIC, OB_FLAG_ONCE},
    {"per-piece", "FILE.csv", "also write one row per piece of each file: its entity, handle, line, base range, "
     "hausdorff error and worst point (x, y; x_off, y_off on the exact offset)", MO_PER_PIECE, OB_FLAG_ONCE},
    {"draw", "FILE.svg", "also draw the base, the exact offset and the pieces coloured by their error, the worst "
     "point marked (base coordinates)", MO_DRAW, OB_FLAG_ONCE},
    {"trimmed", NULL, "measure against the trimmed offset (its loops and the parts nearer than |d| to the curve cut "
     "away, as CAD kernels ship it): one row, trimmed-hausdorff, the distance between the two as point sets",
     MO_TRIMMED, OB_FLAG_ONCE},
    {"trim-dump", "FILE", "with --trimmed: write the trimmed offset's arcs and split points to FILE as CSV (for checks)",
     MO_TRIM_DUMP, OB_FLAG_ONCE},
};

static int apply_measure_flag(void *ctx, int id, const char *opt, const char *v)
{
    measure_args *a = ctx;
    switch (id) {
    case MO_APPROX:
        if (!*v) {
            ob_error("%s: empty file name", opt);
            return -1;
        }
        if (a->napprox == a->capprox) {
            const int cap = a->capprox ? 2 * a->capprox : 4;
            const char **nv = realloc(a->approx, (size_t)cap * sizeof *nv);
            if (!nv) {
                ob_error("%s: out of memory", opt);
                return -1;
            }
            a->approx = nv;
            a->capprox = cap;
        }
        a->approx[a->napprox++] = v;
        return 0;
    case MO_PER_PIECE:
    case MO_DRAW:
        if (!*v) {
            ob_error("%s: empty file name", opt);
            return -1;
        }
        *(id == MO_DRAW ? &a->where.draw : &a->where.per_piece) = v;
        return 0;
    case MO_D:
        if (ob_parse_double(v, &a->d) || a->d == 0.0) {
            ob_error("%s: '%s' is not an offset distance (a nonzero finite number)", opt, v);
            return -1;
        }
        a->have_d = 1;
        return 0;
    case MO_TRIMMED:
        a->trimmed = 1;
        return 0;
    case MO_TRIM_DUMP:
        if (!*v) {
            ob_error("%s: empty file name", opt);
            return -1;
        }
        a->trim_dump = v;
        return 0;
    default:
        a->metric_named = v;
        if (set_metrics(a, v)) {
            ob_error("%s: unknown metric '%s' (bound, radial, normal, hausdorff, param, certified, hausdorff-whole, all)", opt,
                     v);
            return -1;
        }
        return 0;
    }
}

/* --trim-dump needs --trimmed, and --trimmed takes no --metric but
 * certified (the others need the pieces matched to the untrimmed offset);
 * 0, or 2 after ob_error(). */
static int check_trimmed(measure_args *a)
{
    if (a->trim_dump && !a->trimmed) {
        ob_error("--trim-dump: needs --trimmed (it writes the trimmed offset)");
        return 2;
    }
    if (a->trimmed && (a->where.per_piece || a->where.draw)) {
        ob_error("%s: not with --trimmed (it locates the error piece by piece against the untrimmed offset, "
                 "matched; --trimmed measures two point sets, with no match)", a->where.per_piece ? "--per-piece" : "--draw");
        return 2;
    }
    int other = 0;
    for (int m = 0; m < OB_METRIC_COUNT; m++)
        other |= a->want[m] && (ob_metric)m != OB_METRIC_CERTIFIED;
    if (a->trimmed && (a->metric_named != NULL) && (other || a->whole)) {
        ob_error("--metric: with --trimmed only certified (a row saying it does not apply): the other metrics "
                 "measure against the untrimmed offset, matched piece by piece; --trimmed writes trimmed-hausdorff");
        return 2;
    }
    if (!a->trimmed)
        return 0;
    for (int m = 0; m < OB_METRIC_COUNT; m++) /* its row alone, or with certified's */
        a->want[m] = (a->metric_named != NULL) && (ob_metric)m == OB_METRIC_CERTIFIED;
    a->whole = 0;
    return 0;
}

/* Parses into a and o; 0, 2 after ob_error(), or -1 after --help. */
static int parse(int argc, char **argv, measure_args *a, ob_run_opts *o)
{
    memset(a, 0, sizeof *a);
    set_metrics(a, "all");
    a->where.draw_opt = "--draw";
    if (ob_run_opts_init(o, argc, argv)) {
        ob_error("measure: out of memory");
        return 2;
    }
    const ob_flagset sets[3] = {
        {measure_flags, (int)(sizeof measure_flags / sizeof measure_flags[0]), NULL, NULL, "options",
         apply_measure_flag, a},
        {ob_run_flags, ob_run_nflags, "curves curve random samples ", NULL, "run options (as for run)",
         ob_run_flag_apply, o},
        ob_measure_more_flags(&a->more),
    };
    const int rc = ob_cli_parse("--curve ID --d D --approx FILE [--approx FILE]... [--curves FILE] [--metric M|all] "
                                "[--samples S] [--per-piece FILE.csv] [--draw FILE.svg] [--transform a,b,c,d,e,f] "
                                "[--translate X,Y] [--scale S] [--flip-y] [--svg-units user|px] [--tol T] "
                                "[--trimmed [--trim-dump FILE]]",
                                sets, 3, argc, argv, 0, NULL, NULL);
    if (rc == OB_CLI_HELP)
        return -1;
    if (rc != OB_CLI_OK)
        return 2;
    const char *miss = o->ncurve_ids == 0 ? "--curve ID" : !a->have_d ? "--d D" : !a->napprox ? "--approx FILE" : NULL;
    if (miss) {
        ob_error("measure: %s missing (measure --curve ID --d D --approx FILE)", miss);
        return 2;
    }
    if (o->ncurve_ids != 1) {
        ob_error("--curve: measure takes exactly one curve id");
        return 2;
    }
    return check_trimmed(a);
}

static void put_num(FILE *f, double x)
{
    char b[40];
    ob_fmt_double(b, sizeof b, x);
    fputs(b, f);
}

/* One file's measurement, kept until every file is measured. */
typedef struct {
    ob_measure_out m;   /* its rows (ob_measure_approx) */
    int pieces, ctrl_points;
    ob_approx ap;       /* with --per-piece or --draw: its pieces, */
    ob_perpiece pp;     /* and where each is off (perpiece.h) */
    ob_mres trimmed;    /* --trimmed: its row, its message in trim_msg */
    char trim_msg[200];
} file_rows;

/* The columns after the message: file,curve,d,pieces,ctrl_points. */
static void join_cols(FILE *f, const char *file, const ob_curve *c, double d, const file_rows *fr)
{
    fputc(',', f);
    ob_csv_field(f, file);
    fputc(',', f);
    ob_csv_field(f, c->id);
    fputc(',', f);
    put_num(f, d);
    fprintf(f, ",%d,%d\n", fr->pieces, fr->ctrl_points);
}

/* One CSV row, without its line end. */
static void row(FILE *f, const char *metric, const ob_mres *r)
{
    fprintf(f, "%s,%s,", metric, ob_mres_status(r));
    if (r->applies) {
        put_num(f, r->err);
        fprintf(f, ",%d,%d,", r->piece, r->seg);
        put_num(f, r->t);
        if (!r->ok)
            fprintf(f, ",\"%s\"", r->why);
        else
            fprintf(f, r->note[0] ? ",\"%s\"" : ",", r->note);
    } else {
        fprintf(f, ",,,,\"%s\"", r->why);
    }
}

/* The entities the reader skipped, in one warning. */
static void warn_skipped(const char *name, const ob_approx *ap)
{
    char buf[1024] = "";
    size_t n = 0;
    int listed = 0;
    for (int i = 0; i < ap->nskipped_types && n < sizeof buf; i++) {
        const ob_askip *k = &ap->skipped[i];
        n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%d %s (%s line %d)", i ? ", " : "", k->count, k->type,
                              k->count > 1 ? "the first at" : "at", k->line);
        listed += k->count;
    }
    if (ap->nskipped > listed && n < sizeof buf)
        snprintf(buf + n, sizeof buf - n, ", and %d of other types", ap->nskipped - listed);
    ob_warn("measure: %s: skipped %d entit%s that are no pieces measure reads: %s", name, ap->nskipped,
            ap->nskipped == 1 ? "y" : "ies", buf);
}

/* The problems kept in list (n of them, of total), one line each through
 * report, then how many more. */
static void say_issues(void (*report)(const char *, ...), const ob_cover_issue *list, int n, int total,
                       const ob_approx *ap, const char *name)
{
    char buf[1024];
    for (int i = 0; i < n; i++) {
        ob_cover_text(&list[i], ap, name, buf, sizeof buf);
        report("%s", buf);
    }
    if (total > n)
        report("%s: and %d more like these", name, total - n);
}

/* Says what ob_measure_approx found noteworthy or wrong in the cover
 * (its summary, when it fails, is the error that follows). */
static void say_cover(const ob_approx *ap, const ob_cover *cv, const char *name)
{
    const int *k = cv->count;
    const int notes = k[OB_COVER_ORDER] + k[OB_COVER_NEAR_GAP] + k[OB_COVER_NEAR_OVERLAP];
    say_issues(ob_warn, cv->note, cv->nnote, notes, ap, name);
    if (k[OB_COVER_ORDER])
        ob_warn("measure: %s: %d of its %d pieces come after a piece that lies after them on the base: measured in "
                "the base's order (piece numbers are the file's)", name, k[OB_COVER_ORDER], ap->n);
    say_issues(ob_error, cv->fail, cv->nfail, ob_cover_fails(cv), ap, name);
}

/* The control points of ap as results.csv counts them (docs/output.md,
 * methods/driver/jobs.c): 1 + the sum of the pieces' degrees, and one more
 * for each open joint (joints.h: the ends of two pieces consecutive on the
 * base farther apart than the gap threshold of c at d).  Pieces in the
 * base's order (cv->order) and direction (ob_approx_match). */
static int count_ctrl_points(const ob_curve *c, double d, const ob_approx *ap, const ob_cover *cv)
{
    const double gap_tol = ob_joint_gap_tol(c, d);
    int n = 1;
    for (int i = 0; i < ap->n; i++) {
        const ob_bez *b = &ap->v[cv->order[i]].approx;
        if (ap->v[cv->order[i]].part > 0)
            continue;  /* a further part of a piece cut at a base joint: its points are the piece's */
        n += b->deg;
        if (i > 0) {
            ob_end left, right;
            ob_bez_end(&ap->v[cv->order[i - 1]].approx, 1, &left);
            ob_bez_end(b, 0, &right);
            const double gap = hypot(right.p[0] - left.p[0], right.p[1] - left.p[1]);
            n += !(gap <= gap_tol);  /* as ob_joint_measure: NaN is open */
        }
    }
    return n;
}

/* Pieces matched by projection on an offset with loops can land on the
 * wrong branch (measure.h), and then each is measured against offset it
 * does not approximate.  hausdorff-whole is at most the per-piece
 * hausdorff when the match is right (measure.h); the two apart by more
 * than a factor 2, either way, show a wrong match (seen: 0.0295 per piece
 * against 0.0068 whole and the run's 0.0090, liu2002_ex2 at d = 0.5;
 * 0.0025 against 0.036 and the run's 0.00097, at d = 1: whole's tiles
 * come from the match too). */
static void warn_branches(const char *name, const ob_approx *ap, const file_rows *fr)
{
    const ob_mres *h = &fr->m.res[OB_METRIC_HAUSDORFF], *w = &fr->m.whole;
    int matched = 0;
    for (int i = 0; i < ap->n; i++)
        matched |= ap->v[i].matched;
    if (!matched || !h->applies || !w->applies || !h->ok || !w->ok || fmax(h->err, w->err) <= 1e-12)
        return;
    if (h->err > 2.0 * w->err || w->err > 2.0 * h->err)
        ob_warn("measure: %s: hausdorff %.3g and hausdorff-whole %.3g differ by a factor %.3g: some pieces matched "
                "by projection may lie near another branch of the offset (its loops or cusps) than the one they "
                "approximate, and either value may be off (a file with base links, as --export writes, is matched "
                "exactly)", name, h->err, w->err, fmax(h->err, w->err) / fmin(h->err, w->err));
}

/* Writes the CSV of every file (rows[k] that of a->approx[k]); the exit
 * status. */
static int write_csv(const measure_args *a, const ob_curve *c, const file_rows *rows)
{
    fputs("metric,status,max_err,piece,seg,t,message,file,curve,d,pieces,ctrl_points\n", stdout);
    for (int k = 0; k < a->napprox; k++) {
        for (int m = 0; m < OB_METRIC_COUNT; m++)
            if (a->want[m] && (a->metric_named || rows[k].m.res[m].applies)) { /* default: the rows that apply */
                row(stdout, ob_metric_name((ob_metric)m), &rows[k].m.res[m]);
                join_cols(stdout, a->approx[k], c, a->d, &rows[k]);
            }
        if (a->whole) {
            row(stdout, "hausdorff-whole", &rows[k].m.whole);
            join_cols(stdout, a->approx[k], c, a->d, &rows[k]);
        }
        if (a->trimmed) {
            row(stdout, "trimmed-hausdorff", &rows[k].trimmed);
            join_cols(stdout, a->approx[k], c, a->d, &rows[k]);
        }
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ob_error("measure: writing standard output failed");
        return 1;
    }
    return 0;
}

/* With --per-piece or --draw: each piece's own error into fr->pp, and the
 * pieces moved into fr->ap; 0, or 2 after ob_error(). */
static int keep_where(const ob_curve *c, double d, const char *name, int samples, ob_approx *ap, file_rows *fr)
{
    ob_err err;
    if (ob_approx_per_piece(c, d, ap, samples, name, &fr->pp, &err) != 0) {
        if (!ob_stop_signal()) /* stopped: measure() says so */
            ob_error("%s", err.msg);
        return 2;
    }
    fr->ap = *ap;
    memset(ap, 0, sizeof *ap);
    return 0;
}

/* The largest error measured of a file (hausdorff-whole when asked), for
 * the diagnosis's rule (diagnose.h); NAN when none applies. */
static double largest_err(const measure_args *a, const file_rows *fr)
{
    double e = a->whole ? fr->m.whole.err : NAN;
    for (int m = 0; m < OB_METRIC_COUNT && !a->whole; m++)
        if (a->want[m] && fr->m.res[m].applies && !(fr->m.res[m].err <= e))
            e = fr->m.res[m].err;
    return e;
}

/* What a file far from the offset looks like instead (diagnose.h), on
 * stderr; failed: its measurement failed with msg (the hint about cusps
 * cut from it when the diagnosis explains the file), which this prints. */
static void diagnose(const measure_args *a, const ob_curve *c, const ob_approx *ap, const char *name, char *msg)
{
    char line[1024];
    const ob_frame f = ob_measure_more_frame(&a->more);
    const int found = ob_diagnose(c, a->d, ap, &f, name, line, sizeof line);
    char *hint = msg && found == 1 ? strstr(msg, OB_MEASURE_CUSP_HINT) : NULL;
    if (hint)
        *hint = '\0';
    if (msg)
        ob_error("%s", msg);
    if (found == 1)
        ob_warn("measure: %s", line);
}

/* --trimmed: file name (read into ap) against the trimmed offset
 * (host/measure/trim.h): no match, no cover; its pieces and control points
 * in the file's order.  0, or 2 after ob_error(). */
static int measure_trimmed(const measure_args *a, const char *name, const ob_curve *c, int samples, ob_approx *ap,
                           file_rows *fr)
{
    static const ob_mres cert_na = {0, "certified does not apply with --trimmed: its interval certificate bounds each "
                                       "piece against the base piece a parameter match gives, and the distance between "
                                       "two point sets has none (trimmed-hausdorff is sampled and refined)",
                                    NAN, -1, -1, NAN, 0, ""};
    ob_err err;
    if (ob_measure_trimmed(c, a->d, ap, samples, a->trim_dump, &fr->trimmed, fr->trim_msg, sizeof fr->trim_msg,
                           &err) != 0) {
        if (!ob_stop_signal())
            ob_error("measure: %s: %s", name, err.msg);
        return 2;
    }
    fr->m.res[OB_METRIC_CERTIFIED] = cert_na;
    int *order = malloc((size_t)(ap->n > 0 ? ap->n : 1) * sizeof *order);
    if (!order) {
        ob_error("measure: out of memory");
        return 2;
    }
    for (int i = 0; i < ap->n; i++)
        order[i] = i;
    ob_cover cv = {0};
    cv.order = order;
    fr->pieces = ob_approx_file_pieces(ap);
    fr->ctrl_points = count_ctrl_points(c, a->d, ap, &cv);
    free(order);
    return 0;
}

/* Reads file name, matches and checks its cover, and measures it into *fr;
 * 0, or 2 after ob_error(). */
static int measure_file(const measure_args *a, const char *name, const ob_curve *c, int samples, file_rows *fr)
{
    ob_approx ap = {0};
    ob_cover cv = {0};
    ob_err err;
    int status = 2;
    ap.svg_units_px = a->more.svg_px;
    if (ob_approx_read(name, &ap, &err) != 0) {
        ob_error("%s", err.msg);
        goto out;
    }
    if (ap.nskipped)
        warn_skipped(name, &ap);
    if (ap.have_job && (strcmp(ap.job_curve, c->id) != 0 || ap.job_d != a->d))
        ob_warn("measure: %s was exported by a job on curve %s at d = %.17g, and is measured against curve %s at "
                "d = %.17g: its error is not that job's max_err", name, ap.job_curve, ap.job_d, c->id, a->d);
    if (a->more.have_frame) {
        const ob_frame f = ob_measure_more_frame(&a->more);
        ob_frame_apply(&f, &ap);  /* file -> base coordinates, before matching */
    }
    if (a->trimmed) {
        status = measure_trimmed(a, name, c, samples, &ap, fr);
        goto out;
    }
    ob_measure_ask ask = {{0}, a->whole, samples};
    memcpy(ask.want, a->want, sizeof ask.want);
    const int rc = ob_measure_approx(c, a->d, &ap, &ask, name, &cv, &fr->m, &err);
    say_cover(&ap, &cv, name);
    if (rc != 0) {
        if (!ob_stop_signal()) /* stopped: measure() says so */
            diagnose(a, c, &ap, name, err.msg);
        goto out;
    }
    fr->pieces = ob_approx_file_pieces(&ap);
    fr->ctrl_points = count_ctrl_points(c, a->d, &ap, &cv);
    warn_branches(name, &ap, fr);
    if (ob_diag_far(c, a->d, largest_err(a, fr)))
        diagnose(a, c, &ap, name, NULL);
    status = a->where.per_piece || a->where.draw ? keep_where(c, a->d, name, samples, &ap, fr) : 0;
out:
    ob_cover_free(&cv);
    ob_approx_free(&ap);
    return status;
}

/* --per-piece and --draw: neither an input, nor one file; 0, or 2 after
 * ob_error(). */
static int where_check(const measure_args *a, const ob_run_opts *o)
{
    const char **in = malloc((size_t)(a->napprox + 1) * sizeof *in);
    if (!in) {
        ob_error("measure: out of memory");
        return 2;
    }
    memcpy(in, a->approx, (size_t)a->napprox * sizeof *in);
    in[a->napprox] = o->curves_file;
    const int rc = ob_where_check("measure", &a->where, in, a->napprox + 1);
    free(in);
    return rc;
}

/* The --per-piece and --draw files, before the CSV: 0, or 1 after ob_error(). */
static int write_where(const measure_args *a, const ob_curve *c, const file_rows *rows)
{
    if (!a->where.per_piece && !a->where.draw)
        return 0;
    ob_pp_file *files = malloc((size_t)a->napprox * sizeof *files);
    if (!files) {
        ob_error("measure: out of memory");
        return 1;
    }
    for (int k = 0; k < a->napprox; k++)
        files[k] = (ob_pp_file){a->approx[k], &rows[k].ap, &rows[k].pp};
    const int rc = ob_where_write(&a->where, c, a->d, files, a->napprox);
    free(files);
    return rc;
}

/* After the CSV: the rows left out (default) and --tol's verdict, on
 * stderr; 1 when a file is over the tolerance, else 0. */
static int after_csv(const measure_args *a, const file_rows *rows, int dm)
{
    int over = 0;
    for (int k = 0; k < a->napprox; k++) {
        if (!a->metric_named && !a->trimmed)
            ob_measure_say_hidden(a->want, &rows[k].m, a->approx[k]);
        if (a->more.have_tol && a->trimmed) /* its one row decides */
            over |= ob_measure_verdict_row(&a->more, &rows[k].trimmed, "trimmed-hausdorff", a->approx[k]);
        else if (a->more.have_tol)
            over |= ob_measure_verdict(&a->more, dm, &rows[k].m, a->approx[k]);
    }
    return over;
}

/* Loads the curve, measures every file (stopping at the first that fails)
 * and writes the CSV when all were measured; returns the exit status. */
static int measure(const measure_args *a, ob_run_opts *o)
{
    ob_curveset set = {0};
    char where[4096];
    int status = 2;
    file_rows *rows = calloc((size_t)a->napprox, sizeof *rows);
    if (!rows) {
        ob_error("measure: out of memory");
        return 2;
    }
    if (ob_load_run_curves(o, &set, where, sizeof where) != 0)
        goto out;
    const ob_curve *c = &set.v[ob_curveset_find(&set, o->curve_ids[0])];
    if (ob_check_option_d("measure", c, a->d) != 0 || where_check(a, o) != 0)
        goto out;  /* status 2: a d the curve's file would refuse (curvefile.h), outputs that collide */
    const int samples = ob_clamp_samples(o->driver.samples);
    for (int k = 0; k < a->napprox; k++) {
        if (ob_stop_signal() || measure_file(a, a->approx[k], c, samples, &rows[k]) != 0) {
            if (ob_stop_signal()) { /* the loop polls the stop (signals.h); the CSV is written whole or not */
                status = ob_stop_exit("measure: %d of %d file%s measured, no CSV written (it is written once every "
                                      "file is measured): rerun the command", k, a->napprox,
                                      a->napprox == 1 ? "" : "s");
                goto out;
            }
            if (a->napprox > 1)
                ob_error("measure: %s failed: none of the %d files is measured (no CSV written)", a->approx[k],
                         a->napprox);
            goto out;
        }
        char ds[40];
        ob_fmt_double(ds, sizeof ds, a->d);
        ob_info("measure: %d piece%s of %s against %s (%s), d = %s, %d samples", rows[k].pieces,
                rows[k].pieces == 1 ? "" : "s", a->approx[k], c->id, where, ds, samples);
    }
    const int dm = ob_measure_decider(a->metric_named);
    for (int k = 0; k < a->napprox && !a->trimmed; k++)
        if (ob_measure_verdict_check(&a->more, dm, &rows[k].m, a->approx[k]))
            goto out;  /* status 2: a verdict from an n/a row */
    status = write_where(a, c, rows);
    if (status == 0)
        status = write_csv(a, c, rows);
    if (status == 0) { /* a signal from now on finds the work done (signals.h) */
        ob_stop_done("measure: the CSV on standard output is complete: every file was measured before the signal "
                     "was seen");
        status = after_csv(a, rows, dm);
    }
out:
    for (int k = 0; k < a->napprox; k++) {
        ob_approx_free(&rows[k].ap);
        ob_perpiece_free(&rows[k].pp);
    }
    free(rows);
    ob_curveset_free(&set);
    return status;
}

int ob_cmd_measure(int argc, char **argv)
{
    measure_args a;
    ob_run_opts o;
    int status = parse(argc, argv, &a, &o);
    if (status == 0)
        status = measure(&a, &o);
    free(a.approx);
    ob_run_opts_free(&o);
    return status < 0 ? 0 : status;
}
