/*
 * output.c - results.csv and meta.json writers.  Rows are written in job
 * order, so a results.csv is identical (timing columns aside) for any thread
 * count.
 */
#include "host/io/output.h"
#include "host/io/fsutil.h"

#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <string.h>
#include <time.h>

#include "buildinfo.h"
#include "host/io/columns.h"
#include "host/io/meta_selection.h"
#include "host/io/numfmt.h"
#include "host/io/utf8.h"
#include "host/run/hostinfo.h"
#include "methods/metrics/metric_certified.h"

#include <flint/flint.h>

void ob_csv_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s == '\r' || *s == '\n' ? ' ' : *s, f);
    }
    fputc('"', f);
}

int ob_write_results(FILE *f, const ob_job *jobs, size_t njobs)
{
    fprintf(f, "%s\n", ob_results_header());
    for (size_t i = 0; i < njobs; i++)
        ob_write_result_row(f, &jobs[i]);
    return ferror(f) ? -1 : 0;
}

/* A number of the row in full precision; empty when NaN (none measured). */
static void put_double(FILE *f, double v)
{
    char b[40] = "";
    if (!isnan(v))
        ob_fmt_double(b, sizeof b, v);
    fputs(b, f);
}

/* Column c of job j's row (columns.h). */
static void put_field(FILE *f, const ob_job *j, ob_col c)
{
    const ob_curve *cv = j->curve;
    switch (c) {
    case OB_COL_CURVE: ob_csv_field(f, cv->id); break;
    case OB_COL_D: put_double(f, j->d); break;
    case OB_COL_METHOD: fputs(j->method->name, f); break;
    case OB_COL_METRIC: fputs(ob_metric_name(j->metric), f); break;
    case OB_COL_SPLIT: fputs(ob_split_name(j->split), f); break;
    case OB_COL_TOL: put_double(f, j->tol); break;
    case OB_COL_CTRL_POINTS: fprintf(f, "%ld", j->ctrl_points); break;
    case OB_COL_SEGMENTS: fprintf(f, "%d", j->segments); break;
    case OB_COL_OUT_DEGREE: fprintf(f, "%d", j->out_degree); break;
    case OB_COL_MAX_ERR: put_double(f, j->max_err); break;
    case OB_COL_STATUS: fputs(ob_status_name(j->status), f); break;
    case OB_COL_FIT_NS: fprintf(f, "%.0f", j->fit_ns); break;
    case OB_COL_EVAL_NS: fprintf(f, "%.0f", j->eval_ns); break;
    case OB_COL_MESSAGE: ob_csv_field(f, j->message); break;
    case OB_COL_FAMILY: ob_csv_field(f, cv->family ? cv->family : ""); break;
    case OB_COL_OFFSET_DEGREE:
        if (cv->offset_known)
            fprintf(f, "%d", cv->offset_degree);
        break;
    case OB_COL_OFFSET_RATIONAL:
        if (cv->offset_known)
            fputs(cv->offset_rational ? "yes" : "no", f);
        break;
    /* the joints (methods/driver/joints.h): empty when none was measured */
    case OB_COL_MAX_GAP: put_double(f, j->max_gap); break;
    case OB_COL_MAX_KINK: put_double(f, j->max_kink); break;
    case OB_COL_CONTINUITY: fputs(ob_cont_name(j->continuity), f); break;
    /* the spread of the repetitions (host/run/spread.h): empty without --reps N >= 2 */
    case OB_COL_TIME_IQR_NS:
        if (j->time_reps >= 2)
            fprintf(f, "%.0f", j->time_iqr_ns);  /* whole ns, as fit_ns and eval_ns */
        break;
    case OB_COL_TIME_CV:
        if (j->time_reps >= 2)
            put_double(f, j->time_cv);
        break;
    /* the certificate (host/run/certify.h): empty without --certify or an approximation;
     * one stopped by --job-timeout has its cert_ns only */
    case OB_COL_ERR_UPPER:
        if (j->cert_done == OB_CERT_DONE)
            put_double(f, j->err_upper);
        break;
    case OB_COL_ERR_LOWER:
        if (j->cert_done == OB_CERT_DONE)
            put_double(f, j->err_lower);
        break;
    case OB_COL_CERTIFIED:
        if (j->cert_done == OB_CERT_DONE)
            fputs(ob_job_certified(j) ? "yes" : "no", f);
        break;
    case OB_COL_CERT_NS:
        if (j->cert_done)
            fprintf(f, "%.0f", j->cert_ns);
        break;
    /* the method's own time (host/run/fittime.h): empty without --time-fits or an approximation */
    case OB_COL_FIT_CALLS:
        if (j->fit_calls > 0)
            fprintf(f, "%d", j->fit_calls);
        break;
    case OB_COL_METHOD_NS:
        if (j->fit_calls > 0)
            put_double(f, j->method_ns);
        break;
    case OB_COL_METHOD_IQR_NS:
        if (j->fit_calls > 0)
            put_double(f, j->method_iqr_ns);
        break;
    /* the trimmed offset's distance (host/run/trimmed.h): empty without --trimmed or an approximation */
    case OB_COL_TRIMMED_ERR:
        if (j->trimmed_done)
            put_double(f, j->trimmed_err);
        break;
    case OB_COL_TRIMMED_CUT:
        if (j->trimmed_done)
            fprintf(f, "%d", j->trimmed_cut);
        break;
    case OB_NCOLS: break;
    }
}

void ob_write_result_field(FILE *f, const ob_job *j, int col)
{
    if (col >= 0 && col < OB_NCOLS)
        put_field(f, j, (ob_col)col);
}

int ob_write_result_row(FILE *f, const ob_job *j)
{
    for (int c = 0; c < OB_NCOLS; c++) {
        if (c)
            fputc(',', f);
        put_field(f, j, (ob_col)c);
    }
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}

const char OB_SAMPLES_HEADER[] = "curve,d,method,metric,split,tol,rep,fit_ns,eval_ns";

int ob_write_samples(FILE *f, const ob_job *jobs, size_t njobs, int reps, const double *fit, const double *eval)
{
    fprintf(f, "%s\n", OB_SAMPLES_HEADER);
    for (size_t i = 0; i < njobs; i++)
        ob_write_job_samples(f, &jobs[i], reps, fit + i, eval + i, njobs);
    return ferror(f) ? -1 : 0;
}

int ob_write_job_samples(FILE *f, const ob_job *j, int reps, const double *fit, const double *eval, size_t stride)
{
    char d[40], tol[40];
    ob_fmt_double(d, sizeof d, j->d);
    ob_fmt_double(tol, sizeof tol, j->tol);
    for (int r = 0; r < reps; r++) {
        ob_csv_field(f, j->curve->id);
        fprintf(f, ",%s,%s,%s,%s,%s,%d,%.0f,%.0f\n", d, j->method->name, ob_metric_name(j->metric),
                ob_split_name(j->split), tol, r + 1, fit[(size_t)r * stride], eval[(size_t)r * stride]);
    }
    return ferror(f) ? -1 : 0;
}

const char OB_FITS_HEADER[] = "curve,d,method,metric,split,tol,round,fit_calls,method_ns";

int ob_write_fits(FILE *f, const ob_job *jobs, size_t njobs, int rounds, const double *round_ns)
{
    fprintf(f, "%s\n", OB_FITS_HEADER);
    for (size_t i = 0; i < njobs; i++) {
        const ob_job *j = &jobs[i];
        if (j->fit_calls < 1)
            continue;
        char d[40], tol[40], ns[40];
        ob_fmt_double(d, sizeof d, j->d);
        ob_fmt_double(tol, sizeof tol, j->tol);
        for (int r = 0; r < rounds; r++) {
            ob_fmt_double(ns, sizeof ns, round_ns[(size_t)r * njobs + i]);
            ob_csv_field(f, j->curve->id);
            fprintf(f, ",%s,%s,%s,%s,%s,%d,%d,%s\n", d, j->method->name, ob_metric_name(j->metric),
                    ob_split_name(j->split), tol, r + 1, j->fit_calls, ns);
        }
    }
    return ferror(f) ? -1 : 0;
}

void ob_json_string(FILE *f, const char *s)
{
    /* the strings come from the environment, the host and argv too (a host
     * name, a path with a Latin-1 byte): what is no UTF-8 becomes U+FFFD,
     * so that offbench's own reader (metajson.c, the same check) and every
     * other JSON reader take the file */
    const unsigned char *p = (const unsigned char *)s, *end = p + strlen(s);
    fputc('"', f);
    while (p < end) {
        const int n = ob_utf8_len(p, end);
        if (n == 0)
            fputs("\\ufffd", f);
        else if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p < 0x20 || *p == 0x7f)
            fprintf(f, "\\u%04x", *p);
        else
            fwrite(p, 1, (size_t)n, f);
        p += n ? n : 1;
    }
    fputc('"', f);
}

/* meta.json: the machine (hostinfo.h), on one line: compare judges timings
 * only between runs of one machine id with the same CPU, cores, memory and
 * device; scripts/nightly.sh reads the name and id from this line. */
static void meta_machine(FILE *f, const ob_backend_info *b)
{
    ob_machine m;
    ob_machine_identify(&m);
    fprintf(f, "  \"machine\": {\"name\": ");
    ob_json_string(f, m.name);
    fprintf(f, ", \"id\": \"%s\", \"id_source\": ", m.id);
    ob_json_string(f, m.id_source);
    fprintf(f, ", \"cpu_model\": ");
    ob_json_string(f, m.cpu_model);
    fprintf(f, ", \"logical_cores\": %d, \"memory_mib\": %ld, \"device\": ", m.logical_cores, m.memory_mib);
    ob_json_string(f, b->opencl ? b->device : "cpu");
    fprintf(f, ", \"doc\": \"name: $OFFBENCH_MACHINE, else the host name; id: a hash of that name when "
               "OFFBENCH_MACHINE is set, else of /etc/machine-id and the host name (the machine-id itself is not "
               "written); logical_cores: online CPUs; memory_mib: MemTotal; device: the backend's device. compare "
               "judges timings only between runs with the same id, CPU model, cores, memory and device\"},\n");
}

/* meta.json: the build and what measured (l: every backend that computed
 * rows, across --resume; "backend" and "opencl" say the last). */
static void meta_build(FILE *f, const ob_backend_info *b, const ob_backend_list *l)
{
    fprintf(f, "{\n  \"program\": \"offbench\",\n  \"git_commit\": ");
    ob_json_string(f, OB_GIT_COMMIT);
    fprintf(f, ",\n  \"git_dirty\": %s,\n  \"compiler\": ", OB_GIT_DIRTY ? "true" : "false");
    ob_json_string(f, "gcc " __VERSION__);
    fprintf(f, ",\n  \"cflags\": ");
    ob_json_string(f, OB_CFLAGS);
    fprintf(f, ",\n  \"backends\": ");
    ob_backends_json(f, l, b);
    fprintf(f, ",\n  \"backend\": \"%s\",\n  \"opencl\": ", b->opencl ? "opencl" : "cpu");
    if (b->opencl) {
        fprintf(f, "{\"platform\": ");
        ob_json_string(f, b->platform);
        fprintf(f, ", \"device\": ");
        ob_json_string(f, b->device);
        fprintf(f, ", \"driver\": ");
        ob_json_string(f, b->driver);
        fprintf(f, ", \"kernels\": ");
        ob_json_string(f, b->kernels);
        fprintf(f, ", \"layout\": \"%s\", \"work_items_per_record\": %d", b->layout, b->group_size);
        fprintf(f, ", \"build_seconds\": %.3f, \"binary_cache\": ", b->build_seconds);
        ob_json_string(f, b->cache);
        fprintf(f, ", \"programs\": [");  /* one per metric and layout built (clrt.h) */
        for (int i = 0; i < b->nbuilds; i++) {
            fprintf(f, "%s{\"metric\": \"%s\", \"layout\": \"%s\", \"build_seconds\": %.3f, \"binary_cache\": ",
                    i ? ", " : "", ob_metric_name(b->builds[i].metric), ob_cl_layout_name(b->builds[i].layout),
                    b->builds[i].seconds);
            ob_json_string(f, b->builds[i].cache);
            fprintf(f, "}");
        }
        fprintf(f, "]");
        fprintf(f, ", \"cpu_fallback_batches\": %ld},\n", b->fallbacks);
    } else {
        fprintf(f, "null,\n  \"cpu_because\": ");
        ob_json_string(f, b->why_cpu);
        fprintf(f, ",\n");
    }
    char cpu[256];
    ob_cpu_model(cpu, sizeof cpu);
    fprintf(f, "  \"cpu_model\": ");
    ob_json_string(f, cpu);
    fprintf(f, ",\n  \"omp_threads\": %d,\n", omp_get_max_threads());
    meta_machine(f, b);
}

void ob_write_meta_certify(FILE *f, int mode, double wall_seconds)
{
    if (mode) {
        ob_cert_opts co;
        ob_cert_defaults(&co);
        fprintf(f, "  \"certify\": {\"mode\": \"%s\", \"rtol\": %.17g, \"floor_rel\": %.17g, \"budget\": %ld, "
                   "\"doc\": \"every job "
                   "with an approximation (ok, limit): err_lower <= H <= err_upper, H the two-sided Hausdorff distance "
                   "of its pieces to the exact offsets of their base pieces (untrimmed; each enclosed from the segment "
                   "as stored, over its exact parameter range), whatever the run's metric; "
                   "err_upper by interval enclosures of a parameter correspondence, err_lower a distance attained; "
                   "mode verdict: refined only until err_upper <= tol or err_lower > tol (neither end need be tight; "
                   "err_upper inf where err_lower > tol was shown first: not sought); "
                   "mode tight: until err_upper <= err_lower (1 + rtol), and on while tol lies between them; at most budget "
                   "enclosures per side and piece; inf: a piece unbounded (C' may vanish on it: a cusp, a collapsed leg); "
                   "certified: yes when err_upper <= tol; cert_ns: thread CPU "
                   "time of the certificate (docs/certified.md); wall_seconds: the certificate pass, after the jobs ran "
                   "(not in meta's wall_seconds)\", \"wall_seconds\": %.3f},\n",
                mode == OB_CERTIFY_TIGHT ? "tight" : "verdict", co.rtol, co.floor_rel, co.budget, wall_seconds);
    } else {
        fprintf(f, "  \"certify\": null,\n");
    }
}

/* meta.json: the settings that decide results (seed, samples, limits,
 * method parameters and versions). */
static void meta_settings(FILE *f, const ob_run_opts *o, const ob_run_record *rec)
{
    if (o->random_n > 0)
        fprintf(f, "  \"seed\": %" PRIu64 ",\n  \"random_curves\": %ld,\n", o->random_seed, o->random_n);
    else
        fprintf(f, "  \"seed\": null,\n");
    fprintf(f, "  \"samples_per_segment\": %d,\n", o->driver.samples);
    if (o->driver.job_timeout_ns > 0)
        fprintf(f, "  \"job_timeout_seconds\": %.6g,\n", o->driver.job_timeout_ns * 1e-9);
    else
        fprintf(f, "  \"job_timeout_seconds\": null,\n");
    fprintf(f, "  \"max_depth\": %d,\n  \"max_segments\": %d,\n  \"inflection_split\": %s,\n",
            o->driver.max_depth, o->driver.max_segments, o->driver.inflections ? "true" : "false");
    fprintf(f, "  \"method_params\": {");
    int first = 1;
    for (int m = 0; ob_methods[m]; m++)
        for (int k = 0; k < ob_methods[m]->nparams; k++) {
            char key[128], num[40];
            snprintf(key, sizeof key, "%s.%s", ob_methods[m]->name, ob_methods[m]->params[k].name);
            ob_fmt_double(num, sizeof num, o->params[m * OB_MAX_PARAMS + k]);
            fprintf(f, "%s", first ? "" : ", ");
            ob_json_string(f, key);
            fprintf(f, ": %s", num);
            first = 0;
        }
    fprintf(f, "},\n  \"method_versions\": {");
    for (int m = 0; ob_methods[m]; m++) {
        fprintf(f, "%s", m ? ", " : "");
        ob_json_string(f, ob_methods[m]->name);
        fprintf(f, ": %d", ob_methods[m]->version);
    }
    fprintf(f, "},\n");
    /* --certify (host/run/certify.h): what the certificate's columns mean */
    ob_write_meta_certify(f, o->certify, rec->cert_seconds);
    /* --time-fits (host/run/fittime.h): how the method's own time was measured */
    if (o->time_fits)
        fprintf(f, "  \"fit_timing\": {\"rounds\": %d, \"min_time_ms\": %g, \"wall_seconds\": %.3f, \"doc\": "
                   "\"every job with an approximation (ok, limit): its accepted pieces fitted again, outside every other "
                   "timing; a warm-up calibrates the iterations so that one measurement lasts min_time_ms of thread "
                   "CPU time; rounds sweeps over the jobs each measure every job once; method_ns: the median over the "
                   "rounds of the thread CPU ns of one fit of each accepted piece (fit_calls fits), method_iqr_ns "
                   "their interquartile range; fits.csv: every round (docs/output.md)\"},\n",
                o->fit_rounds, o->fit_min_ns * 1e-6, rec->fit_seconds);
    else
        fprintf(f, "  \"fit_timing\": null,\n");
    /* --trimmed (host/run/trimmed.h): what trimmed_err and trimmed_cut are */
    if (o->trimmed)
        fprintf(f, "  \"trimmed\": {\"wall_seconds\": %.3f, \"margin\": \"2 max(tol, max_err)\", \"doc\": "
                   "\"every job with an approximation (ok, limit): its pieces cut at their crossings with each other, "
                   "with the exact C - dN and with the end circles, the arcs between cuts nearer than |d| - margin to "
                   "the curve removed (trimmed_cut of them), the rest measured against the exact trimmed offset (the "
                   "points at distance |d| from the curve): trimmed_err, the two-sided distance of the two sets "
                   "(docs/export-measure.md)\"},\n",
                rec->trim_seconds);
    else
        fprintf(f, "  \"trimmed\": null,\n");
    /* the test hook OFFBENCH_TEST_SLOW (driver.h): a run with it is slower on purpose */
    if (o->driver.test_slow_method)
        fprintf(f, "  \"test_slow\": \"%s:%g\",\n", o->driver.test_slow_method->name, o->driver.test_slow_factor);
    else
        fprintf(f, "  \"test_slow\": null,\n");
}

/* meta.json: what the timing columns, offset degrees and joints mean. */
static void meta_definitions(FILE *f, const ob_run_opts *o, const ob_run_record *rec)
{
    /* timings are medians over reps timed runs after a warm-up (1: one run) */
    fprintf(f, "  \"timing\": {\"fit_ns\": \"CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID) in the "
               "method's fit calls of the job, summed\", \"eval_ns\": \"measuring the job's pieces: on the CPU the "
               "thread CPU time of each measurement, summed; with the OpenCL backend each launch's wall time shared "
               "among its records by the floating-point operations each took (counted by the kernel), summed\", "
               "\"with_reps\": \"the median over the timed repetitions; samples.csv has each\"},\n");
    fprintf(f, "  \"reps\": %d,\n  \"warmup\": %s,\n  \"rep_mismatches\": %ld,\n", o->reps > 0 ? o->reps : 1,
            o->reps > 0 ? "true" : "false", rec->rep_mismatches);
    fprintf(f, "  \"offset_degree\": \"exact (FLINT %s): 2n + 2tau - mu of each Bezier segment, the largest per curve, "
               "on the control points as stored (each double is exactly the rational m 2^e)\",\n", FLINT_VERSION);
    /* the thresholds of the joint columns (methods/driver/joints.h) */
    fprintf(f, "  \"joints\": {\"open_gap_rel\": %.17g, \"size\": \"the diagonal of the base curve's control-point "
               "bounding box grown by |d| on every side\", \"g1_kink_rad\": %.17g, \"doc\": \"max_gap: the largest "
               "distance between the end of a piece and the start of the next; a joint farther apart than "
               "open_gap_rel * size is open and counts two control points; max_kink: the largest angle between "
               "their end tangents; continuity: open (a joint open), G0 (closed, a kink over g1_kink_rad), G1, or "
               "empty (no joint); joints at a corner or gap of the base curve are not measured\"},\n",
            OB_JOINT_GAP_REL, OB_JOINT_KINK_RAD);
    /* the error metrics a run may use (--metric; each row's metric column) */
    fprintf(f, "  \"metrics\": {");
    for (int m = 0; m < OB_METRIC_COUNT; m++) {
        fprintf(f, "%s", m ? ", " : "");
        ob_json_string(f, ob_metric_name((ob_metric)m));
        fprintf(f, ": ");
        ob_json_string(f, ob_metric_doc((ob_metric)m));
    }
    fprintf(f, "},\n");
}

/* A number, or null when NaN (never read). */
static void json_num(FILE *f, double v)
{
    if (isnan(v))
        fputs("null", f);
    else
        fprintf(f, "%.2f", v);
}

/* A build-time package version (Makefile: dpkg-query), or null when the
 * build had none (no dpkg, package not installed). */
static void json_pkg(FILE *f, const char *v)
{
    if (*v)
        ob_json_string(f, v);
    else
        fputs("null", f);
}

/* meta.json: the machine, the load during the run, the library versions and
 * the run's warnings (README "Noise"). */
static void meta_host(FILE *f, const ob_run_opts *o, const ob_run_record *rec)
{
    char host[256], os[256], kernel[256], warn[512];
    ob_host_names(host, sizeof host, os, sizeof os, kernel, sizeof kernel);
    const int cores = ob_cores_used();
    fprintf(f, "  \"host\": {\"hostname\": ");
    ob_json_string(f, host);
    fprintf(f, ", \"os\": ");
    ob_json_string(f, os);
    fprintf(f, ", \"kernel\": ");
    ob_json_string(f, kernel);
    fprintf(f, ", \"cores_used\": %d, \"loadavg_start\": ", cores);
    json_num(f, rec->load.samples ? rec->load.start : NAN);
    fprintf(f, ", \"loadavg_end\": ");
    json_num(f, rec->load.samples ? rec->load.end : NAN);
    fprintf(f, ", \"loadavg_max\": ");
    json_num(f, rec->load.samples ? rec->load.max : NAN);
    fprintf(f, ", \"loadavg_samples\": %d, \"loadavg_doc\": \"1-minute load average (/proc/loadavg) before the "
               "first job, after each timed repetition and at the end; the run's own threads count in it\"},\n",
            rec->load.samples);
    /* SISL has no version macro or call: the Debian package versions come
     * from dpkg-query when the binary was built (Makefile, buildinfo.h) */
    fprintf(f, "  \"versions\": {\"sisl\": ");
    json_pkg(f, OB_PKG_SISL);
    fprintf(f, ", \"flint\": ");
    ob_json_string(f, flint_version);
    fprintf(f, ", \"flint_header\": \"%s\", \"flint_package\": ", FLINT_VERSION);
    json_pkg(f, OB_PKG_FLINT);
    fprintf(f, ", \"opencl_loader\": ");
    json_pkg(f, OB_PKG_OCL_ICD);
    fprintf(f, ", \"doc\": \"flint: the library's flint_version at run time, flint_header: FLINT_VERSION at build "
               "time; sisl, flint_package and opencl_loader (ocl-icd-libopencl1): Debian package versions by "
               "dpkg-query at build time, null without\"},\n");
    fprintf(f, "  \"warnings\": [");
    if (ob_load_warning(&rec->load, o->reps, cores, warn, sizeof warn))
        ob_json_string(f, warn);
    fprintf(f, "],\n");
}

/* meta.json: the engine that scheduled the work and what it did (none of
 * it changes a row: README "Engines"). */
static void meta_engine(FILE *f, const ob_run_opts *o, const ob_run_record *rec)
{
    const ob_engine_stats *e = &rec->engine;
    const double eff = e->threads > 0 && e->wall_ns > 0 ? e->work_ns / (e->threads * e->wall_ns) : 0.0;
    fprintf(f, "  \"engine\": {\"name\": \"%s\", \"asked\": \"%s\", \"chunk\": %d, \"threads\": %d, "
               "\"groups\": %ld, \"wall_seconds\": %.6f, \"work_seconds\": %.6f, \"efficiency\": %.4f, "
               "\"helped_seconds\": %.6f, \"backend_launches\": %ld, \"backend_records\": %ld, "
               "\"device_seconds\": %.6f, \"blocked_seconds\": %.6f, "
               "\"doc\": \"work: thread time of the fits and measurements run, a piece shared by several jobs "
               "once; efficiency: work / (threads x wall) of the driver; backend_records / backend_launches: the "
               "batch size a batch backend got; device engine: device_seconds the kernels' own time, "
               "blocked_seconds the time the threads waited for them (the rest was hidden behind fits)\"},\n",
            ob_engine_name(e->engine), ob_engine_name(o->driver.engine), e->chunk, e->threads, e->groups,
            e->wall_ns * 1e-9, e->work_ns * 1e-9, eff, e->helped_ns * 1e-9, e->launches, e->records,
            e->device_ns * 1e-9, e->blocked_ns * 1e-9);
}

int ob_write_meta(FILE *f, const ob_run_opts *o, const ob_run_record *rec, const char *data_source, size_t njobs,
                  double wall_seconds)
{
    char ts[64];
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(ts, sizeof ts, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    meta_build(f, &rec->binfo, &rec->backends);
    meta_settings(f, o, rec);
    meta_definitions(f, o, rec);
    meta_host(f, o, rec);
    meta_engine(f, o, rec);
    fprintf(f, "  \"data\": ");
    ob_json_string(f, data_source);
    fprintf(f, ",\n");
    ob_meta_write_selection(f, o, rec->curves);
    fprintf(f, "  \"jobs\": %zu,\n", njobs);
    /* the shard lines are rewritten by merge (cmd_merge.c): keep them one
     * key per line */
    if (rec->mpi_ranks > 1)
        fprintf(f, "  \"shard\": null,\n  \"mpi_ranks\": %d,\n", rec->mpi_ranks);
    else if (o->shard_n > 0)
        fprintf(f, "  \"shard\": \"%d/%d\",\n", o->shard_k, o->shard_n);
    else
        fprintf(f, "  \"shard\": null,\n");
    /* where --export writes (absolute, for merge to find the shards'
     * indexes: export_dir.h), or null */
    fprintf(f, "  \"export_dir\": ");
    if (o->export_dir) {
        char abs[4200];
        ob_abs_path(o->export_dir, abs, sizeof abs);
        ob_json_string(f, abs);
    } else {
        fputs("null", f);
    }
    fputs(",\n", f);
    /* the identity of what decides the numbers (README "What a run
     * directory guarantees"): the curves' content and the kernel text */
    fprintf(f, "  \"data_hash\": \"%016" PRIx64 "\",\n  \"kernel_fnv1a\": \"%016" PRIx64 "\",\n", rec->data_hash,
            rec->binfo.kernel_hash);
    fprintf(f, "  \"jobs_total\": %zu,\n  \"plan_hash\": \"%016" PRIx64 "\",\n  \"plan_seed\": \"%016" PRIx64 "\",\n",
            rec->jobs_total, rec->plan_hash, rec->plan_seed);
    fprintf(f, "  \"wall_seconds\": %.3f,\n  \"argv\": [", wall_seconds);
    for (int i = 0; i < o->argc; i++) {
        if (i)
            fputs(", ", f);
        ob_json_string(f, o->argv[i]);
    }
    fprintf(f, "],\n  \"timestamp\": \"%s\"\n}\n", ts);
    return ferror(f) ? -1 : 0;
}
