/*
 * hostinfo.h - the machine a run ran on, for meta.json's "host" object, and
 * the load average during the run (a timed run on a busy machine measures
 * the other work too: run --reps warns when the load exceeded the cores the
 * run used).
 *
 * Load average: the 1-minute average, the first field of /proc/loadavg
 * (the file named by $OFFBENCH_LOADAVG instead when set: a test hook).  The
 * run samples it before its first job, after each timed repetition and at
 * the end; loadavg_max is the largest sample.  cores_used: the OpenMP thread
 * count, at most the online CPUs.  The run's own threads count in the load,
 * so a load above cores_used means more runnable work than the run's
 * cores: other programs competed for them.
 */
#ifndef OB_HOSTINFO_H
#define OB_HOSTINFO_H

#include <stddef.h>

typedef struct {
    double start, end, max;  /* NAN when never read */
    int samples;             /* readings taken */
} ob_loadavg;

/* Takes one reading into l (the first is the start); an unreadable file
 * leaves l as it was. */
void ob_loadavg_sample(ob_loadavg *l);

/* Threads the run uses: omp_get_max_threads(), at most the online CPUs. */
int ob_cores_used(void);

/* Purpose: the load warning of a run with --reps, or none.
 * Outputs: 1 with the text in buf ("load average up to 3.1 during the
 *          run, above the 2 cores it used: ..."), or 0 (no repetitions, the
 *          load within the cores, or never read). */
int ob_load_warning(const ob_loadavg *l, int reps, int cores, char *buf, size_t len);

/* The host's name, OS (PRETTY_NAME of /etc/os-release) and kernel release
 * (uname -r); "unknown" for what cannot be read. */
void ob_host_names(char *host, size_t hlen, char *os, size_t olen, char *kernel, size_t klen);

/* The CPU model (the first "model name" of /proc/cpuinfo), or "unknown":
 * timings of runs on different CPUs are not compared. */
void ob_cpu_model(char *buf, size_t len);

#endif
