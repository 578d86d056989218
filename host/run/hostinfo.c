/*
 * hostinfo.c - see hostinfo.h.
 */
#include "host/run/hostinfo.h"

#include "host/diag.h"
#include "host/io/utf8.h"
#include "host/run/shard.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

/* The 1-minute load average, or NAN. */
static double read_loadavg(void)
{
    const char *path = getenv("OFFBENCH_LOADAVG");
    FILE *f = fopen(path && *path ? path : "/proc/loadavg", "r");
    double v = NAN;
    if (!f)
        return NAN;
    if (fscanf(f, "%lf", &v) != 1 || !(v >= 0))
        v = NAN;
    fclose(f);
    return v;
}

void ob_loadavg_sample(ob_loadavg *l)
{
    const double v = read_loadavg();
    if (isnan(v))
        return;
    if (l->samples++ == 0)
        l->start = l->max = v;
    if (v > l->max)
        l->max = v;
    l->end = v;
}

int ob_cores_used(void)
{
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    const int t = omp_get_max_threads();
    return online > 0 && online < t ? (int)online : t;
}

int ob_load_warning(const ob_loadavg *l, int reps, int cores, char *buf, size_t len)
{
    if (reps <= 0 || l->samples == 0 || !(l->max > cores))
        return 0;
    snprintf(buf, len, "load average up to %.2f during the run, above the %d core%s it used: other work "
             "competed for the CPUs, the timings are noisier than they would be on an idle machine",
             l->max, cores, cores == 1 ? "" : "s");
    return 1;
}

/* The value of the first line of path that starts with key, into buf:
 * after key, blanks and one separator (':' or '=') and blanks are skipped,
 * the line end dropped and one pair of matching quotes taken off.  "unknown"
 * when the file or the key is missing.  Serves /etc/os-release (KEY="v")
 * and /proc/cpuinfo (key<TAB>: v). */
static void keyed_value(const char *path, const char *key, char *buf, size_t len)
{
    snprintf(buf, len, "unknown");
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    const size_t klen = strlen(key);
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, key, klen) != 0)
            continue;
        char *v = line + klen;
        v += strspn(v, " \t");
        if (*v != ':' && *v != '=')
            continue;
        v++;
        v += strspn(v, " \t");
        v[strcspn(v, "\r\n")] = '\0';
        size_t n = strlen(v);
        if (n >= 2 && (v[0] == '"' || v[0] == '\'') && v[n - 1] == v[0]) {
            v[n - 1] = '\0';
            v++;
        }
        snprintf(buf, len, "%s", v);
        break;
    }
    fclose(f);
}

void ob_cpu_model(char *buf, size_t len)
{
    keyed_value("/proc/cpuinfo", "model name", buf, len);
}

void ob_host_names(char *host, size_t hlen, char *os, size_t olen, char *kernel, size_t klen)
{
    if (gethostname(host, hlen) != 0 || !*host)
        snprintf(host, hlen, "unknown");
    host[hlen - 1] = '\0';
    keyed_value("/etc/os-release", "PRETTY_NAME", os, olen);
    struct utsname u;
    if (uname(&u) == 0)
        snprintf(kernel, klen, "%s", u.release);
    else
        snprintf(kernel, klen, "unknown");
}

/* The machine-id (machine-id(5)) into buf without its line end, or "" when
 * neither file can be read. */
static void read_machine_id(char *buf, size_t len)
{
    static const char *const paths[] = {"/etc/machine-id", "/var/lib/dbus/machine-id"};
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof paths / sizeof paths[0] && !buf[0]; i++) {
        FILE *f = fopen(paths[i], "r");
        if (!f)
            continue;
        if (!fgets(buf, (int)len, f))
            buf[0] = '\0';
        buf[strcspn(buf, "\r\n")] = '\0';
        fclose(f);
    }
}

/* The id: FNV-1a over a fixed prefix and the parts, each followed by a NUL
 * (so that "ab"+"c" and "a"+"bc" differ), as 16 hex digits. */
static void hash_id(char out[17], const char *a, const char *b)
{
    static const char prefix[] = "offbench machine";
    uint64_t h = ob_fnv1a(OB_FNV_BASIS, prefix, sizeof prefix);
    h = ob_fnv1a(h, a, strlen(a) + 1);
    h = ob_fnv1a(h, b, strlen(b) + 1);
    snprintf(out, 17, "%016llx", (unsigned long long)h);
}

int ob_machine_env_check(void)
{
    const char *env = getenv("OFFBENCH_MACHINE");
    if (!env || !*env)
        return 0;
    const size_t len = strlen(env), most = sizeof ((ob_machine *)0)->name - 1;
    const unsigned char *s = (const unsigned char *)env, *end = s + len;
    const char *why = NULL;
    size_t at = 0;
    while (at < len) {
        const int n = ob_utf8_len(s + at, end);
        if (!n || s[at] < 0x20 || s[at] == 0x7f) {
            why = n ? "is a control character" : "is not UTF-8";
            break;
        }
        at += (size_t)n;
    }
    if (why) {
        ob_error("OFFBENCH_MACHINE: byte %zu (0x%02x) %s: the variable names this machine in meta.json, where "
                 "compare and nightly.sh read it back; set it to UTF-8 text without control characters",
                 at + 1, s[at], why);
        return -1;
    }
    if (len > most) {
        ob_error("OFFBENCH_MACHINE: %zu bytes, more than the %zu a machine name may have (a name cut short would "
                 "give two machines one identity); set it to a shorter name", len, most);
        return -1;
    }
    return 0;
}

void ob_machine_identify(ob_machine *m)
{
    memset(m, 0, sizeof *m);
    char host[256], mid[128];
    if (gethostname(host, sizeof host) != 0 || !*host)
        snprintf(host, sizeof host, "unknown");
    host[sizeof host - 1] = '\0';
    const char *env = getenv("OFFBENCH_MACHINE");
    if (env && *env) {
        snprintf(m->name, sizeof m->name, "%s", env);
        hash_id(m->id, "name", m->name);
        m->id_source = "OFFBENCH_MACHINE";
    } else {
        snprintf(m->name, sizeof m->name, "%.*s", (int)sizeof m->name - 1, host);
        read_machine_id(mid, sizeof mid);
        hash_id(m->id, mid, host);
        m->id_source = mid[0] ? "/etc/machine-id and hostname" : "hostname";
    }
    ob_cpu_model(m->cpu_model, sizeof m->cpu_model);
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    m->logical_cores = cpus > 0 ? (int)cpus : 0;
    char mem[64];
    keyed_value("/proc/meminfo", "MemTotal", mem, sizeof mem);  /* "24683792 kB" */
    const long kb = strtol(mem, NULL, 10);
    m->memory_mib = kb > 0 ? kb / 1024 : 0;
}
