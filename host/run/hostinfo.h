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

/* The machine a run ran on, for meta.json's "machine" object: compare
 * judges timings only between runs of one machine (README "Nightly
 * regression runs").  Two virtual machines can share a CPU model string
 * (a masked "AMD EPYC"), so the identity is a name and an id:
 *   name       $OFFBENCH_MACHINE when set (the user names the machine, as
 *              `asv machine` does), else the host name;
 *   id         16 hex digits, FNV-1a of the name when $OFFBENCH_MACHINE
 *              names it, else of /etc/machine-id (or
 *              /var/lib/dbus/machine-id) and the host name: stable across
 *              reboots, different on another installation; the machine-id
 *              itself is never written (it is meant to stay private:
 *              machine-id(5)), and 64 bits of hash leave 2^64 candidates for
 *              its 128 bits;
 *   id_source  "OFFBENCH_MACHINE", "/etc/machine-id and hostname" or
 *              "hostname" (no machine-id file);
 * and what makes timings of one id comparable or not: the CPU model, the
 * online logical CPUs and the physical memory (MiB).  Clones of one disk
 * image share /etc/machine-id, and often the host name: such machines need
 * OFFBENCH_MACHINE set to tell them apart (README). */
typedef struct {
    char name[128];
    char id[17];
    const char *id_source;
    char cpu_model[256];
    int logical_cores;  /* sysconf(_SC_NPROCESSORS_ONLN), 0 unknown */
    long memory_mib;    /* MemTotal of /proc/meminfo in MiB, 0 unknown */
} ob_machine;

/* Purpose: refuse a $OFFBENCH_MACHINE that cannot be the machine's name:
 *          bytes that are no UTF-8, a control character, or more than
 *          sizeof m->name - 1 bytes (cut short, two names could become one
 *          identity).  The user gave it: it is refused, not mended.  Called
 *          before a run starts, not when its meta.json is written.
 * Errors:  0, or -1 after ob_error() naming the variable (exit 2). */
int ob_machine_env_check(void);

/* Purpose: fill m with this machine's identity (above).  $OFFBENCH_MACHINE
 *          longer than m->name is cut (ob_machine_env_check refuses it
 *          first); unreadable files fall back as said.
 * Errors:  none (what cannot be read is "unknown" or 0). */
void ob_machine_identify(ob_machine *m);

#endif
