/*
 * clrt.c - OpenCL runtime.  See clrt.h.
 *
 * Every OpenCL call goes through CL_CHECK, which names the call and its error
 * code; a failed build prints its log.  The entry points are looked up with
 * dlsym from libOpenCL.so.1 (the ICD loader), once.
 */
#define _GNU_SOURCE
#include "host/diag.h"
#include "host/backend/clrt.h"
#include "host/backend/clcache.h"
#include "host/backend/clprobe.h"
#include "host/backend/kernsrc.h"

#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "methods/metrics/metric.h"

#if defined(__has_include)
#if __has_include(<CL/cl.h>)
#define OB_HAVE_CL 1
#endif
#endif

const char *ob_cl_layout_name(ob_cl_layout layout) { return layout == OB_CL_ITEMS ? "items" : "groups"; }
int ob_cl_layout_env(ob_cl_layout *layout, ob_err *err)
{
    const char *v = getenv("OFFBENCH_CL_LAYOUT");
    if (!v || !*v)
        return 0;
    if (strcmp(v, "groups") == 0 || strcmp(v, "items") == 0) {
        *layout = strcmp(v, "items") == 0 ? OB_CL_ITEMS : OB_CL_GROUPS;
        return 1;
    }
    ob_fail(err, "OFFBENCH_CL_LAYOUT='%.100s': expected groups or items", v);
    return -1;
}

/* The language version every program is built for: part of the options. */
static const char CL_STD[] = "-cl-std=CL1.2";

int ob_cl_program_options(ob_metric m, ob_cl_layout l, char *buf, size_t len)
{
    const char *name = m == OB_METRIC_RADIAL      ? "RADIAL"
                       : m == OB_METRIC_NORMAL    ? "NORMAL"
                       : m == OB_METRIC_HAUSDORFF ? "HAUSDORFF"
                       : m == OB_METRIC_PARAM     ? "PARAM"
                                                  : NULL;
    if (!name)
        return -1;
    snprintf(buf, len, "%s -D OBC_ONLY_%s -D OBC_ONLY_%s", CL_STD, name, l == OB_CL_ITEMS ? "ITEMS" : "GROUPS");
    return 0;
}

char *ob_cl_program_key(const char *platform, const char *device, const char *driver, const char *device_version,
                        const char *options, const char *src)
{
    const size_t n = strlen(src);
    char hex[OB_SHA256_HEX];
    const size_t len = strlen(platform) + strlen(device) + strlen(driver) + strlen(device_version) +
                       strlen(options) + 256;
    char *key = malloc(len);
    if (key)
        snprintf(key, len, "offbench OpenCL program\nplatform=%s\ndevice=%s\ndriver=%s\ndevice_version=%s\n"
                 "options=%s\nsource_bytes=%zu\nsource_sha256=%s\n", platform, device, driver, device_version,
                 options, n, (ob_sha256_hex(src, n, hex), hex));
    return key;
}

/* The buffers a record moves (stage() and ob_cl_wait below): to the device
 * six ints (metric, the two degrees and control-point offsets, the scratch
 * offset), two doubles (d, stop) and both pieces' homogeneous control
 * points; back three doubles (error, parameter, work). */
void ob_cl_record_bytes(int nb, int na, size_t *to, size_t *back)
{
    *to = 6 * sizeof(int) + 2 * sizeof(double) + 3 * (size_t)(nb + 1 + na + 1) * sizeof(double);
    *back = 3 * sizeof(double);
}

#ifndef OB_HAVE_CL

int ob_cl_compiled(void) { return 0; }
void ob_cl_set_layout(ob_cl *cl, ob_cl_layout layout) { (void)cl, (void)layout; }
ob_cl_layout ob_cl_get_layout(const ob_cl *cl) { (void)cl; return OB_CL_GROUPS; }
int ob_cl_group_size(const ob_cl *cl) { (void)cl; return 0; }
int ob_cl_loader_status(char *msg, size_t len)
{
    snprintf(msg, len, "not compiled in (the OpenCL headers were missing at build time)");
    return -1;
}
int ob_cl_open(const char *device_substr, int gpu_only, ob_cl **out, ob_err *err)
{
    (void)gpu_only;
    (void)device_substr;
    *out = NULL;
    ob_fail(err, "this build has no OpenCL backend (the OpenCL headers were missing at build time)");
    return -1;
}
void ob_cl_close(ob_cl *cl) { (void)cl; }
const char *ob_cl_platform(const ob_cl *cl) { (void)cl; return ""; }
const char *ob_cl_device(const ob_cl *cl) { (void)cl; return ""; }
const char *ob_cl_driver(const ob_cl *cl) { (void)cl; return ""; }
const char *ob_cl_source(const ob_cl *cl) { (void)cl; return ""; }
uint64_t ob_cl_kernel_hash(const ob_cl *cl) { (void)cl; return 0; }
const char *ob_cl_cache_status(const ob_cl *cl) { (void)cl; return ""; }
int ob_cl_is_gpu(const ob_cl *cl) { (void)cl; return 0; }
double ob_cl_build_seconds(const ob_cl *cl) { (void)cl; return 0.0; }
int ob_cl_list_devices(FILE *f)
{
    fprintf(f, "# no OpenCL backend in this build (OpenCL headers missing at build time)\n");
    return -1;
}
int ob_cl_measure_batch(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out)
{
    (void)ctx, (void)recs, (void)n, (void)samples, (void)out;
    return -1;
}
int ob_cl_submit(ob_cl *c, int slot, const ob_measure_rec *recs, int n, int samples)
{
    (void)c, (void)slot, (void)recs, (void)n, (void)samples;
    return -1;
}
int ob_cl_wait(ob_cl *c, int slot, ob_errval *out, double *device_ns)
{
    (void)c, (void)slot, (void)out;
    *device_ns = 0.0;
    return -1;
}
int ob_cl_batch_submit(void *ctx, int slot, const ob_measure_rec *recs, int n, int samples)
{
    return ob_cl_submit(ctx, slot, recs, n, samples);
}
int ob_cl_batch_wait(void *ctx, int slot, ob_errval *out, double *device_ns)
{
    return ob_cl_wait(ctx, slot, out, device_ns);
}
int ob_cl_prepare(ob_cl *c, ob_metric m, ob_cl_layout l, ob_err *err)
{
    (void)c, (void)m, (void)l;
    ob_fail(err, "this build has no OpenCL backend");
    return -1;
}
int ob_cl_builds(const ob_cl *c, ob_cl_build *out, int max)
{
    (void)c, (void)out, (void)max;
    return 0;
}
int ob_cl_fma_peak(ob_cl *c, double target_s, double *flops, double *seconds, ob_err *err)
{
    (void)c, (void)target_s;
    *flops = *seconds = 0.0;
    ob_fail(err, "this build has no OpenCL backend");
    return -1;
}

#else

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

/* Whether the last failing call said memory: ob_cl_open and ob_cl_prepare
 * then return -2 (the run exits 1, out of memory, not 2, a setup error). */
static int cl_last_oom;
static int cl_oom(cl_int e)
{
    return e == CL_OUT_OF_HOST_MEMORY || e == CL_OUT_OF_RESOURCES || e == CL_MEM_OBJECT_ALLOCATION_FAILURE;
}

/* ---- the loader ------------------------------------------------------ */

#define CL_FUNCS(X)                                                                            \
    X(clGetPlatformIDs) X(clGetPlatformInfo) X(clGetDeviceIDs) X(clGetDeviceInfo)             \
    X(clCreateContext) X(clCreateCommandQueue) X(clCreateProgramWithSource) X(clBuildProgram) \
    X(clGetProgramBuildInfo) X(clCreateKernel) X(clCreateBuffer) X(clSetKernelArg)            \
    X(clEnqueueWriteBuffer) X(clEnqueueNDRangeKernel) X(clEnqueueReadBuffer) X(clFinish)      \
    X(clReleaseMemObject) X(clReleaseKernel) X(clReleaseProgram) X(clReleaseCommandQueue)     \
    X(clReleaseContext) X(clGetKernelWorkGroupInfo) X(clGetProgramInfo) X(clCreateProgramWithBinary)      \
    X(clFlush) X(clWaitForEvents) X(clGetEventProfilingInfo) X(clReleaseEvent)

static struct {
#define X(f) __typeof__(&f) f;
    CL_FUNCS(X)
#undef X
} cl;
static int cl_loaded = 0;  /* 0 not tried, 1 loaded, -1 failed */

static int load_cl(ob_err *err)
{
    if (cl_loaded)
        return cl_loaded > 0 ? 0 : (ob_fail(err, "no OpenCL loader (libOpenCL.so.1)"), -1);
    void *lib = dlopen("libOpenCL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib)
        lib = dlopen("libOpenCL.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char *e = dlerror();
        char lim[100];
        ob_as_limit(lim, sizeof lim);
        if (ob_dl_oom(e)) { /* not remembered: with memory freed it may load */
            cl_last_oom = 1;
            return ob_fail(err, "out of memory loading the OpenCL loader libOpenCL.so.1: %.300s%s", e, lim);
        }
        cl_loaded = -1;
        ob_fail(err, "no OpenCL loader (libOpenCL.so.1): install ocl-icd-libopencl1 and an ICD such as pocl-opencl-icd");
        return -1;
    }
#define X(f)                                                              \
    if (!(*(void **)&cl.f = dlsym(lib, #f))) {                            \
        cl_loaded = -1;                                                   \
        ob_fail(err, "libOpenCL lacks %s", #f);                  \
        return -1;                                                        \
    }
    CL_FUNCS(X)
#undef X
    cl_loaded = 1;
    return 0;
}

static const char *cl_errname(cl_int e)
{
    switch (e) {
#define E(x) case x: return #x;
    E(CL_DEVICE_NOT_FOUND) E(CL_DEVICE_NOT_AVAILABLE) E(CL_COMPILER_NOT_AVAILABLE)
    E(CL_MEM_OBJECT_ALLOCATION_FAILURE) E(CL_OUT_OF_RESOURCES) E(CL_OUT_OF_HOST_MEMORY)
    E(CL_BUILD_PROGRAM_FAILURE) E(CL_INVALID_VALUE) E(CL_INVALID_PLATFORM) E(CL_INVALID_DEVICE)
    E(CL_INVALID_CONTEXT) E(CL_INVALID_COMMAND_QUEUE) E(CL_INVALID_MEM_OBJECT) E(CL_INVALID_PROGRAM)
    E(CL_INVALID_KERNEL_NAME) E(CL_INVALID_KERNEL) E(CL_INVALID_ARG_INDEX) E(CL_INVALID_ARG_VALUE)
    E(CL_INVALID_ARG_SIZE) E(CL_INVALID_KERNEL_ARGS) E(CL_INVALID_WORK_DIMENSION)
    E(CL_INVALID_WORK_GROUP_SIZE) E(CL_INVALID_GLOBAL_WORK_SIZE) E(CL_INVALID_BUFFER_SIZE)
#undef E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR"; /* the ICD loader's: no platform it could start */
    default: return "unknown error";
    }
}

/* Names the failing call and its error; jumps to `fail`. */
#define CL_CHECK(call)                                                                      \
    do {                                                                                    \
        cl_int cl_e_ = (call);                                                              \
        if (cl_e_ != CL_SUCCESS) {                                                          \
            cl_last_oom = cl_oom(cl_e_);                                                    \
            ob_fail(err, "%s failed: %s (%d)", #call, cl_errname(cl_e_), (int)cl_e_); \
            goto fail;                                                                      \
        }                                                                                   \
    } while (0)

/* ---- the runtime ------------------------------------------------------ */

/* Metrics with a program (OB_METRIC_RADIAL .. OB_METRIC_PARAM), and the
 * kernels a batch launches at most (one per metric). */
enum { NPROG_METRIC = 4, MAX_LAUNCH = NPROG_METRIC };

/* The buffers of one batch in flight: device buffers grown on demand, the
 * host staging they are written from and read into, and the events of its
 * kernels and of its last read (ob_cl_submit, ob_cl_wait).  The records are
 * staged by metric (one launch each): staged record j is recs[perm[j]]. */
typedef struct {
    size_t cap_rec, cap_ctrl, cap_scr;
    cl_mem metric, d, stop, bdeg, boff, adeg, aoff, ctrl, soff, scratch, err, tpar, work;
    int *h_metric, *h_bdeg, *h_boff, *h_adeg, *h_aoff, *h_soff, *perm;
    double *h_d, *h_stop, *h_ctrl, *h_err, *h_tpar, *h_work;
    cl_event kernel[MAX_LAUNCH], done;  /* done NULL: nothing in flight */
    int nk;                 /* kernels launched */
    int n;                  /* records in flight */
    int nother;             /* of them, the last nother no sampled metric: no launch, +inf */
} clslot;

/* One program: a metric's kernel in one layout (ob_cl_prepare). */
typedef struct {
    cl_program prog;
    cl_kernel k;
    int state;           /* 0 not built; 1 built; -1 its build failed (fail says why) */
    int order;           /* its place in the order built (ob_cl_builds) */
    size_t group;        /* the group layout: work-items per record */
    double seconds;
    char cache[600];     /* what the binary cache did (clcache.h) */
    char *fail;
} clprog;

struct ob_cl {
    cl_context ctx;
    cl_command_queue q;
    cl_device_id dev;
    char *src;           /* the kernel text, built on first use (kernsrc.h) */
    ob_cl_layout layout;
    clprog prog[NPROG_METRIC][2];  /* [metric - OB_METRIC_RADIAL][layout] */
    int nbuilt;
    char platform[256], device[256], driver[128], source[512], version[256];
    uint64_t kernel_hash; /* of the text built (kernsrc.h) */
    char cache[2048];    /* what the binary cache did, every program (ob_cl_cache_status) */
    char warned[4400];   /* the last cache warning: the programs sharing a refused
                            directory say it once */
    int gpu;             /* CL_DEVICE_TYPE_GPU or _ACCELERATOR */
    cl_program peak;     /* ob_cl_fma_peak's program, when asked for */
    clslot slot[OB_CL_SLOTS];
};

int ob_cl_compiled(void) { return 1; }
int ob_cl_loader_status(char *msg, size_t len)
{
    ob_err why;
    if (load_cl(&why) != 0) {
        snprintf(msg, len, "%s", why.msg);
        return -1;
    }
    snprintf(msg, len, "compiled in; loader libOpenCL found");
    return 0;
}
const char *ob_cl_platform(const ob_cl *c) { return c ? c->platform : ""; }
const char *ob_cl_device(const ob_cl *c) { return c ? c->device : ""; }
const char *ob_cl_driver(const ob_cl *c) { return c ? c->driver : ""; }
const char *ob_cl_source(const ob_cl *c) { return c ? c->source : ""; }
uint64_t ob_cl_kernel_hash(const ob_cl *c) { return c ? c->kernel_hash : 0; }
const char *ob_cl_cache_status(const ob_cl *c) { return c ? c->cache : ""; }
int ob_cl_is_gpu(const ob_cl *c) { return c ? c->gpu : 0; }
double ob_cl_build_seconds(const ob_cl *c)
{
    double s = 0.0;
    for (int m = 0; c && m < NPROG_METRIC; m++)
        for (int l = 0; l < 2; l++)
            if (c->prog[m][l].state == 1)
                s += c->prog[m][l].seconds;
    return s;
}
void ob_cl_set_layout(ob_cl *c, ob_cl_layout layout)
{
    if (c)
        c->layout = layout;
}
ob_cl_layout ob_cl_get_layout(const ob_cl *c) { return c ? c->layout : OB_CL_GROUPS; }
int ob_cl_group_size(const ob_cl *c)
{
    size_t g = 0;
    for (int m = 0; c && m < NPROG_METRIC; m++) {
        const clprog *p = &c->prog[m][OB_CL_GROUPS];
        if (p->state == 1 && (g == 0 || p->group < g))
            g = p->group;
    }
    return (int)g;
}

int ob_cl_builds(const ob_cl *c, ob_cl_build *out, int max)
{
    const int n = c ? c->nbuilt : 0;
    for (int m = 0; c && m < NPROG_METRIC; m++)
        for (int l = 0; l < 2; l++) {
            const clprog *p = &c->prog[m][l];
            if (p->state != 1 || p->order >= max)
                continue;
            ob_cl_build *b = &out[p->order];
            b->metric = (ob_metric)(OB_METRIC_RADIAL + m);
            b->layout = (ob_cl_layout)l;
            b->seconds = p->seconds;
            snprintf(b->cache, sizeof b->cache, "%s", p->cache);
        }
    return n;
}

static int has_fp64(cl_device_id dev)
{
    cl_device_fp_config fp = 0;
    if (cl.clGetDeviceInfo(dev, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof fp, &fp, NULL) != CL_SUCCESS)
        return 0;
    return fp != 0;
}

/* A warning about the binary cache (why, then what the run does instead),
 * unless it is the one this backend gave last. */
static void cache_warn(ob_cl *c, const char *why, const char *then)
{
    char msg[sizeof c->warned];
    snprintf(msg, sizeof msg, "OpenCL binary cache: %.3400s: %s", why, then);
    if (strcmp(msg, c->warned) == 0)
        return;
    snprintf(c->warned, sizeof c->warned, "%s", msg);
    ob_warn("%s", msg);
}

/* The program from a cached binary, when the cache holds one for key that
 * the driver takes and builds: 1.  Else 0 (build it and store it), or -1
 * (build it, store nothing: the directory is not the user's own); cache
 * says why, and a file or directory refused is warned about. */
static int program_from_cache(ob_cl *c, const char *key, const char *path, const char *options, cl_program *prog,
                              char *cache, size_t clen)
{
    size_t n = 0;
    unsigned char *bin = NULL;
    char why[3300];
    const ob_clcache_status st = ob_clcache_read(path, key, &bin, &n, why, sizeof why);
    if (st == OB_CLCACHE_UNSAFE) {
        cache_warn(c, why, "not used, the programs are built from source (the cache is off; make the directory "
                           "the user's own, chmod go-w, or set OFFBENCH_CL_CACHE)");
        snprintf(cache, clen, "off (%.580s)", why);
        return -1;
    }
    if (st != OB_CLCACHE_HIT) {
        if (st == OB_CLCACHE_BAD)
            cache_warn(c, why, "not loaded, the program is built from source and the file replaced");
        snprintf(cache, clen, "miss: %.580s", why);
        return 0;
    }
    cl_int e, st_bin = CL_SUCCESS;
    const unsigned char *bins[1] = {bin};
    *prog = cl.clCreateProgramWithBinary(c->ctx, 1, &c->dev, &n, bins, &st_bin, &e);
    free(bin);
    if (e == CL_SUCCESS && st_bin == CL_SUCCESS &&
        cl.clBuildProgram(*prog, 1, &c->dev, options, NULL, NULL) == CL_SUCCESS) {
        snprintf(cache, clen, "hit: %.580s", path);
        return 1;
    }
    if (*prog)
        cl.clReleaseProgram(*prog);
    *prog = NULL;
    snprintf(cache, clen, "miss: the driver refused the cached binary (%s)",
             cl_errname(e != CL_SUCCESS ? e : st_bin));
    return 0;
}

/* A built program's binary into the cache (cache: what became of it,
 * appended). */
static void program_to_cache(cl_program prog, const char *key, const char *path, char *cache, size_t clen)
{
    size_t n = 0;
    unsigned char *bin = NULL;
    char why[300] = "";
    if (cl.clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof n, &n, NULL) != CL_SUCCESS || n == 0 ||
        !(bin = malloc(n))) {
        snprintf(why, sizeof why, "the driver gave no binary");
    } else {
        unsigned char *bins[1] = {bin};
        if (cl.clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof bins, bins, NULL) != CL_SUCCESS)
            snprintf(why, sizeof why, "the driver gave no binary");
        else
            ob_clcache_write(path, key, bin, n, why, sizeof why);
    }
    free(bin);
    const size_t had = strlen(cache);
    snprintf(cache + had, clen - had, "; %s", why[0] ? why : "built and stored");
}

/* Purpose: *prog built from src with options for the device: from the
 *          binary cache when it holds this source for this device, driver
 *          and options, else from the source (and then stored in the
 *          cache); cache says which.
 * Returns: 0; -1 with the build log in err (a failed source build). */
static int build_program(ob_cl *c, const char *src, const char *options, cl_program *prog, char *cache,
                         size_t clen, ob_err *err)
{
    char path[4200], why[300];
    char *key = ob_cl_program_key(c->platform, c->device, c->driver, c->version, options, src);
    int cached = key && ob_clcache_path(key, path, sizeof path, why, sizeof why) == 0;
    *prog = NULL;
    if (!key)
        snprintf(cache, clen, "off (out of memory)");
    else if (!cached)
        snprintf(cache, clen, "%s", why);
    const int from = cached ? program_from_cache(c, key, path, options, prog, cache, clen) : 0;
    if (from == 1) {
        free(key);
        return 0;
    }
    cached = cached && from == 0;
    cl_int e;
    const char *srcs[1] = {src};
    *prog = cl.clCreateProgramWithSource(c->ctx, 1, srcs, NULL, &e);
    if (e != CL_SUCCESS) {
        cl_last_oom = cl_oom(e);
        ob_fail(err, "clCreateProgramWithSource failed: %s (%d)", cl_errname(e), (int)e);
        free(key);
        return -1;
    }
    e = cl.clBuildProgram(*prog, 1, &c->dev, options, NULL, NULL);
    if (e != CL_SUCCESS) {
        char log[8192] = "";
        cl_last_oom = cl_oom(e);
        cl.clGetProgramBuildInfo(*prog, c->dev, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log, NULL);
        ob_fail(err, "clBuildProgram failed: %s (%d); build log of %s (%s):\n%s", cl_errname(e), (int)e, c->source,
                options, log);
        free(key);
        return -1;
    }
    if (cached)
        program_to_cache(*prog, key, path, cache, clen);
    free(key);
    return 0;
}

/* c->cache from the programs' statuses, in the order built: one program's
 * status alone, as before the programs were split; several named. */
static void cache_summary(ob_cl *c)
{
    c->cache[0] = '\0';
    for (int k = 0; k < c->nbuilt; k++)
        for (int m = 0; m < NPROG_METRIC; m++)
            for (int l = 0; l < 2; l++) {
                const clprog *p = &c->prog[m][l];
                if (p->state != 1 || p->order != k)
                    continue;
                const size_t had = strlen(c->cache);
                if (c->nbuilt == 1)
                    snprintf(c->cache, sizeof c->cache, "%s", p->cache);
                else
                    snprintf(c->cache + had, sizeof c->cache - had, "%s%s/%s: %s", k ? "; " : "",
                             ob_metric_name((ob_metric)(OB_METRIC_RADIAL + m)), ob_cl_layout_name((ob_cl_layout)l),
                             p->cache);
            }
}

/* One launch of the new program in the shape runs make of it (item
 * layout: radial and param records in groups of 32, the others one per
 * group; group layout: one), so that a driver that compiles a kernel at
 * its first launch (PoCL does, per group size) does it here, outside the
 * time charged to the first jobs.  Its results are not used. */
static void warm_up(ob_cl *c, ob_metric m, ob_cl_layout l)
{
    ob_bez base, approx;
    const double line[2][2] = {{0.0, 0.0}, {1.0, 0.0}}, shifted[2][2] = {{0.0, 0.1}, {1.0, 0.1}};
    ob_bez_from_points(&base, 1, line);
    ob_bez_from_points(&approx, 1, shifted);
    ob_measure_rec r = {&base, &approx, 0.1, m, 0.0, {NULL, 0, 0, 0, 0}};
    ob_errval out;
    const ob_cl_layout keep = c->layout;
    c->layout = l;
    ob_cl_measure_batch(c, &r, 1, OB_MIN_SAMPLES, &out);
    c->layout = keep;
}

int ob_cl_prepare(ob_cl *c, ob_metric m, ob_cl_layout l, ob_err *err)
{
    char options[256];
    if (!c || ob_cl_program_options(m, l, options, sizeof options) != 0) {
        ob_fail(err, "no OpenCL program for the %s metric", ob_metric_name(m));
        return -1;
    }
    clprog *p = &c->prog[m - OB_METRIC_RADIAL][l];
    if (p->state == 1)
        return 0;
    if (p->state < 0) {  /* failed once: not again */
        ob_fail(err, "%s", p->fail ? p->fail : "the program did not build");
        return -1;
    }
    cl_last_oom = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    cl_int e;
    if (build_program(c, c->src, options, &p->prog, p->cache, sizeof p->cache, err) != 0)
        goto fail;
    p->k = cl.clCreateKernel(p->prog, l == OB_CL_ITEMS ? "ob_measure_batch" : "ob_measure_groups", &e);
    CL_CHECK(e);
    if (l == OB_CL_GROUPS) {
        /* the group's work-items share out a record's tables and samples: 64
         * covers the 2 x 64 lane groups of the default 256 samples in one or
         * two rounds; the kernel's own limit on this device may be lower
         * (OBG_MAX in kernels/measure.cl is 256) */
        size_t wg = 0;
        CL_CHECK(cl.clGetKernelWorkGroupInfo(p->k, c->dev, CL_KERNEL_WORK_GROUP_SIZE, sizeof wg, &wg, NULL));
        p->group = wg < 64 ? (wg > 0 ? wg : 1) : 64;
    }
    p->state = 1;
    p->order = c->nbuilt++;
    warm_up(c, m, l);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    p->seconds = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
    cache_summary(c);
    return 0;
fail:
    if (p->k)
        cl.clReleaseKernel(p->k);
    if (p->prog)
        cl.clReleaseProgram(p->prog);
    p->k = NULL;
    p->prog = NULL;
    p->state = -1;
    free(p->fail);
    p->fail = strdup(err->msg);
    return cl_last_oom ? -2 : -1;
}

/* Why the ICD loader gave no platform (e its error), into err; sets
 * cl_last_oom when it is memory (clprobe.h tells that from a missing ICD). */
static void no_platform(cl_int e, ob_err *err)
{
    char why[1800], lim[100];
    if (cl_oom(e)) {
        ob_as_limit(lim, sizeof lim);
        cl_last_oom = 1;
        ob_fail(err, "out of memory starting the OpenCL platform (clGetPlatformIDs: %s)%s", cl_errname(e), lim);
        return;
    }
    cl_last_oom = ob_cl_no_platform_why(why, sizeof why);
    ob_fail(err, "%s (clGetPlatformIDs: %s)", why, cl_errname(e));
}

/* The first device (see ob_cl_open) with its names in c, or NULL after
 * err; a device query that fails for memory is said as such. */
static cl_device_id pick_device(ob_cl *c, const char *device_substr, int gpu_only, ob_err *err)
{
    cl_uint np = 0;
    cl_platform_id plats[16];
    const cl_int e = cl.clGetPlatformIDs(16, plats, &np);
    if (e != CL_SUCCESS || np == 0) {
        no_platform(e, err);
        return NULL;
    }
    int saw_match = 0;
    cl_int oom = CL_SUCCESS;
    for (cl_uint p = 0; p < np; p++) {
        cl_uint nd = 0;
        cl_device_id devs[16];
        const cl_int de = cl.clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &nd);
        if (de != CL_SUCCESS) {
            oom = cl_oom(de) ? de : oom;
            continue;
        }
        for (cl_uint k = 0; k < nd; k++) {
            char pn[256] = "", dn[256] = "", full[520];
            cl.clGetPlatformInfo(plats[p], CL_PLATFORM_NAME, sizeof pn, pn, NULL);
            cl.clGetDeviceInfo(devs[k], CL_DEVICE_NAME, sizeof dn, dn, NULL);
            snprintf(full, sizeof full, "%s %s", pn, dn);
            if (device_substr && *device_substr && !strstr(full, device_substr))
                continue;
            saw_match = 1;
            cl_device_type ty = 0;
            cl.clGetDeviceInfo(devs[k], CL_DEVICE_TYPE, sizeof ty, &ty, NULL);
            if (!has_fp64(devs[k]) || (gpu_only && !(ty & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR))))
                continue;
            snprintf(c->platform, sizeof c->platform, "%s", pn);
            snprintf(c->device, sizeof c->device, "%s", dn);
            cl.clGetDeviceInfo(devs[k], CL_DRIVER_VERSION, sizeof c->driver, c->driver, NULL);
            return devs[k];
        }
    }
    char lim[100];
    ob_as_limit(lim, sizeof lim);
    cl_last_oom = oom != CL_SUCCESS;
    if (cl_last_oom)
        ob_fail(err, "out of memory starting the OpenCL platform (clGetDeviceIDs: %s)%s", cl_errname(oom), lim);
    else if (device_substr && *device_substr && !saw_match)
        ob_fail(err, "--device: no OpenCL device matches '%s' (see './offbench list devices')", device_substr);
    else if (gpu_only)
        ob_fail(err, "no OpenCL GPU or accelerator with double precision (cl_khr_fp64)");
    else
        ob_fail(err, "no OpenCL device with double precision (cl_khr_fp64)");
    return NULL;
}

/* The device's context, queue, layout and kernel text in c: 0, or -1 after err. */
static int open_device(ob_cl *c, cl_device_id dev, int layout_set, ob_cl_layout layout, ob_err *err)
{
    cl_int e;
    c->dev = dev;
    cl.clGetDeviceInfo(dev, CL_DEVICE_VERSION, sizeof c->version - 1, c->version, NULL);
    /* the layout by the device unless the environment names one: a CPU
     * device runs a work-group's items in a loop on one core, where the
     * group layout only adds its barriers (0.8-0.9x the item layout on
     * PoCL: README "Backends and performance"); a GPU wants them */
    cl_device_type dtype = 0;
    cl.clGetDeviceInfo(dev, CL_DEVICE_TYPE, sizeof dtype, &dtype, NULL);
    c->layout = layout_set ? layout : (dtype & CL_DEVICE_TYPE_CPU) ? OB_CL_ITEMS : OB_CL_GROUPS;
    c->gpu = (dtype & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) != 0;
    c->ctx = cl.clCreateContext(NULL, 1, &dev, NULL, NULL, &e);
    CL_CHECK(e);
    /* profiling: the kernel's own time (ob_cl_wait), not the host's wait */
    c->q = cl.clCreateCommandQueue(c->ctx, dev, CL_QUEUE_PROFILING_ENABLE, &e);
    CL_CHECK(e);
    c->src = ob_kernel_source(c->source, sizeof c->source);
    if (!c->src) {
        ob_fail(err, "cannot read the kernel sources metric_core.h and measure.cl in $OFFBENCH_KERNELS (%.300s)",
                c->source);
        goto fail;
    }
    c->kernel_hash = ob_kernel_hash(c->src);
    return 0;
fail:
    return -1;
}

int ob_cl_open(const char *device_substr, int gpu_only, ob_cl **out, ob_err *err)
{
    *out = NULL;
    cl_last_oom = 0;
    if (load_cl(err))
        return cl_last_oom ? -2 : -1;
    ob_cl_layout layout = OB_CL_GROUPS;
    const int layout_set = ob_cl_layout_env(&layout, err);
    if (layout_set < 0)
        return -1;
    ob_cl *c = calloc(1, sizeof *c);
    if (!c) {
        ob_fail(err, "out of memory");
        return -2;
    }
    cl_device_id dev = pick_device(c, device_substr, gpu_only, err);
    if (!dev || open_device(c, dev, layout_set, layout, err) != 0) {
        ob_cl_close(c);
        return cl_last_oom ? -2 : -1;
    }
    *out = c;
    return 0;
}

static void release_buffers(clslot *sl)
{
    cl_mem *bufs[] = {&sl->metric, &sl->d, &sl->stop, &sl->bdeg, &sl->boff, &sl->adeg, &sl->aoff,
                      &sl->ctrl, &sl->soff, &sl->scratch, &sl->err, &sl->tpar, &sl->work};
    for (size_t i = 0; i < sizeof bufs / sizeof *bufs; i++)
        if (*bufs[i]) {
            cl.clReleaseMemObject(*bufs[i]);
            *bufs[i] = NULL;
        }
}

/* The slot's events released (what was in flight is forgotten). */
static void release_events(clslot *sl)
{
    for (int k = 0; k < sl->nk; k++)
        if (sl->kernel[k])
            cl.clReleaseEvent(sl->kernel[k]);
    if (sl->done)
        cl.clReleaseEvent(sl->done);
    sl->nk = 0;
    sl->done = NULL;
}

static void slot_free(clslot *sl)
{
    release_events(sl);
    release_buffers(sl);
    free(sl->h_metric);
    free(sl->h_bdeg);
    free(sl->h_boff);
    free(sl->h_adeg);
    free(sl->h_aoff);
    free(sl->h_soff);
    free(sl->perm);
    free(sl->h_d);
    free(sl->h_stop);
    free(sl->h_ctrl);
    free(sl->h_err);
    free(sl->h_tpar);
    free(sl->h_work);
}

void ob_cl_close(ob_cl *c)
{
    if (!c)
        return;
    if (c->q)
        cl.clFinish(c->q);  /* nothing left in flight that writes the staging */
    for (int k = 0; k < OB_CL_SLOTS; k++)
        slot_free(&c->slot[k]);
    for (int m = 0; m < NPROG_METRIC; m++)
        for (int l = 0; l < 2; l++) {
            clprog *p = &c->prog[m][l];
            if (p->k)
                cl.clReleaseKernel(p->k);
            if (p->prog)
                cl.clReleaseProgram(p->prog);
            free(p->fail);
        }
    if (c->peak)
        cl.clReleaseProgram(c->peak);
    if (c->q)
        cl.clReleaseCommandQueue(c->q);
    if (c->ctx)
        cl.clReleaseContext(c->ctx);
    free(c->src);
    free(c);
}

/* Grows a device buffer and its host staging array to hold n elements. */
#define GROW(buf, host, type, n, flags)                                                 \
    do {                                                                                \
        void *nh_ = realloc(sl->host, (n) * sizeof(type));                              \
        if (!nh_) {                                                                     \
            ob_fail(err, "out of memory");                                     \
            goto fail;                                                                  \
        }                                                                               \
        sl->host = nh_;                                                                 \
        if (sl->buf)                                                                    \
            cl.clReleaseMemObject(sl->buf);                                             \
        sl->buf = cl.clCreateBuffer(c->ctx, flags, (n) * sizeof(type), NULL, &e);        \
        CL_CHECK(e);                                                                    \
    } while (0)

static int ensure_capacity(ob_cl *c, clslot *sl, size_t nrec, size_t nctrl, size_t nscr, ob_err *err)
{
    cl_int e;
    if (nrec > sl->cap_rec) {
        size_t n = nrec + nrec / 2;
        void *np = realloc(sl->perm, n * sizeof(int));
        if (!np) {
            ob_fail(err, "out of memory");
            goto fail;
        }
        sl->perm = np;
        GROW(metric, h_metric, int, n, CL_MEM_READ_ONLY);
        GROW(bdeg, h_bdeg, int, n, CL_MEM_READ_ONLY);
        GROW(boff, h_boff, int, n, CL_MEM_READ_ONLY);
        GROW(adeg, h_adeg, int, n, CL_MEM_READ_ONLY);
        GROW(aoff, h_aoff, int, n, CL_MEM_READ_ONLY);
        GROW(soff, h_soff, int, n, CL_MEM_READ_ONLY);
        GROW(d, h_d, double, n, CL_MEM_READ_ONLY);
        GROW(stop, h_stop, double, n, CL_MEM_READ_ONLY);
        GROW(err, h_err, double, n, CL_MEM_WRITE_ONLY);
        GROW(tpar, h_tpar, double, n, CL_MEM_WRITE_ONLY);
        GROW(work, h_work, double, n, CL_MEM_WRITE_ONLY);
        sl->cap_rec = n;
    }
    if (nctrl > sl->cap_ctrl) {
        size_t n = nctrl + nctrl / 2;
        GROW(ctrl, h_ctrl, double, n, CL_MEM_READ_ONLY);
        sl->cap_ctrl = n;
    }
    if (nscr > sl->cap_scr || !sl->scratch) {
        size_t n = nscr > 0 ? nscr + nscr / 2 : 1;
        if (sl->scratch)
            cl.clReleaseMemObject(sl->scratch);
        sl->scratch = cl.clCreateBuffer(c->ctx, CL_MEM_READ_WRITE, n * sizeof(double), NULL, &e);
        CL_CHECK(e);
        sl->cap_scr = n;
    }
    return 0;
fail:
    sl->cap_rec = sl->cap_ctrl = sl->cap_scr = 0;
    release_buffers(sl);
    return -1;
}

/* Scratch doubles of one record: hausdorff's two sample tables (in the
 * group layout with both sides' sample errors after them); in the group
 * layout, the other metrics' errors and work per sample. */
static size_t rec_scratch(const ob_cl *c, ob_metric m, int S)
{
    if (m == OB_METRIC_HAUSDORFF)
        return ob_metric_scratch(S) + (c->layout == OB_CL_GROUPS ? 2 * (size_t)S : 0);
    return c->layout == OB_CL_GROUPS ? 2 * (size_t)S : 0;
}

/* The program slot of metric m (0 .. NPROG_METRIC - 1), or -1: no sampled
 * metric (measured as +inf, as the kernel did before the programs split). */
static int prog_index(ob_metric m)
{
    return m >= OB_METRIC_RADIAL && m <= OB_METRIC_PARAM ? (int)m - OB_METRIC_RADIAL : -1;
}

/* Enqueues the program of metric m in the layout over staged records
 * [lo, hi). */
static int launch(ob_cl *c, clslot *sl, ob_metric m, int lo, int hi, int S, ob_err *err)
{
    clprog *p = &c->prog[prog_index(m)][c->layout];
    cl_mem args[] = {sl->metric, sl->d,    sl->stop,    sl->bdeg, sl->boff, sl->adeg, sl->aoff,
                     sl->ctrl,   sl->soff, sl->scratch, sl->err,  sl->tpar, sl->work};
    CL_CHECK(cl.clSetKernelArg(p->k, 0, sizeof(int), &lo));
    CL_CHECK(cl.clSetKernelArg(p->k, 1, sizeof(int), &hi));
    CL_CHECK(cl.clSetKernelArg(p->k, 2, sizeof(int), &S));
    for (cl_uint a = 0; a < sizeof args / sizeof *args; a++)
        CL_CHECK(cl.clSetKernelArg(p->k, 3 + a, sizeof(cl_mem), &args[a]));
    const size_t n = (size_t)(hi - lo);
    cl_event *ev = &sl->kernel[sl->nk];
    if (c->layout == OB_CL_GROUPS) {
        const size_t local = p->group, global = n * local;
        CL_CHECK(cl.clEnqueueNDRangeKernel(c->q, p->k, 1, NULL, &global, &local, 0, NULL, ev));
    } else {
        /* A hausdorff or normal record is heavy (thousands of evaluations):
         * one per work-group, so the device spreads them over all its
         * compute units (a NULL local size let PoCL put a whole batch in one
         * group, on one thread).  A radial or param record is light: groups
         * of 32 amortize the group overhead. */
        const int light = m == OB_METRIC_RADIAL || m == OB_METRIC_PARAM;
        const size_t local = light ? 32 : 1, global = (n + local - 1) / local * local;
        CL_CHECK(cl.clEnqueueNDRangeKernel(c->q, p->k, 1, NULL, &global, &local, 0, NULL, ev));
    }
    sl->nk++;
    return 0;
fail:
    return -1;
}

/* The slot's staging filled from recs, metric by metric (radial, normal,
 * hausdorff, param, then any other: sl->perm; lo[k] .. lo[k + 1] the
 * records of program k); 0, or -1 (too large, memory). */
static int stage(ob_cl *c, clslot *sl, const ob_measure_rec *recs, int n, int S, int lo[NPROG_METRIC + 2],
                 size_t *pc_out, ob_err *err)
{
    size_t nctrl = 0, nscr = 0;
    int count[NPROG_METRIC + 1] = {0};
    for (int i = 0; i < n; i++) {
        nctrl += 3 * (size_t)(recs[i].base->deg + 1) + 3 * (size_t)(recs[i].approx->deg + 1);
        nscr += rec_scratch(c, recs[i].metric, S);
        const int k = prog_index(recs[i].metric);
        count[k < 0 ? NPROG_METRIC : k]++;
    }
    if (nctrl > (size_t)INT32_MAX || nscr > (size_t)INT32_MAX / 2) {
        ob_fail(err, "a batch too large for 32-bit offsets");
        return -1;
    }
    if (ensure_capacity(c, sl, (size_t)n, nctrl, nscr, err))
        return -1;
    lo[0] = 0;
    for (int k = 0; k <= NPROG_METRIC; k++)
        lo[k + 1] = lo[k] + count[k];
    int at[NPROG_METRIC + 1];
    for (int k = 0; k <= NPROG_METRIC; k++)
        at[k] = lo[k];
    for (int i = 0; i < n; i++) { /* in order within each metric */
        const int k = prog_index(recs[i].metric);
        sl->perm[at[k < 0 ? NPROG_METRIC : k]++] = i;
    }
    size_t pc = 0, ps = 0;
    for (int j = 0; j < n; j++) {
        const ob_measure_rec *r = &recs[sl->perm[j]];
        const ob_bez *b = r->base, *a = r->approx;
        sl->h_metric[j] = (int)r->metric;
        sl->h_d[j] = r->d;
        sl->h_stop[j] = r->stop;
        sl->h_bdeg[j] = b->deg;
        sl->h_boff[j] = (int)pc;
        memcpy(sl->h_ctrl + pc, &b->h[0][0], 3 * (size_t)(b->deg + 1) * sizeof(double));
        pc += 3 * (size_t)(b->deg + 1);
        sl->h_adeg[j] = a->deg;
        sl->h_aoff[j] = (int)pc;
        memcpy(sl->h_ctrl + pc, &a->h[0][0], 3 * (size_t)(a->deg + 1) * sizeof(double));
        pc += 3 * (size_t)(a->deg + 1);
        sl->h_soff[j] = (int)ps;
        ps += rec_scratch(c, r->metric, S);
    }
    *pc_out = pc;
    return 0;
}

int ob_cl_submit(ob_cl *c, int slot, const ob_measure_rec *recs, int n, int samples)
{
    ob_err why, *err = &why; /* the name CL_CHECK writes to */
    if (!c || n <= 0 || slot < 0 || slot >= OB_CL_SLOTS)
        return -1;
    clslot *sl = &c->slot[slot];
    if (sl->done)  /* a batch still in flight in this slot: its staging is in use */
        return -1;
    /* the programs of the batch's metrics, built when first used */
    for (int i = 0; i < n; i++)
        if (prog_index(recs[i].metric) >= 0 && ob_cl_prepare(c, recs[i].metric, c->layout, err) != 0)
            goto fail;
    const int S = ob_clamp_samples(samples);
    size_t pc = 0;
    int lo[NPROG_METRIC + 2];
    if (stage(c, sl, recs, n, S, lo, &pc, err))
        goto fail;
    const size_t ni = (size_t)n * sizeof(int), nd = (size_t)n * sizeof(double);
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->metric, CL_FALSE, 0, ni, sl->h_metric, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->d, CL_FALSE, 0, nd, sl->h_d, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->stop, CL_FALSE, 0, nd, sl->h_stop, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->bdeg, CL_FALSE, 0, ni, sl->h_bdeg, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->boff, CL_FALSE, 0, ni, sl->h_boff, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->adeg, CL_FALSE, 0, ni, sl->h_adeg, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->aoff, CL_FALSE, 0, ni, sl->h_aoff, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->soff, CL_FALSE, 0, ni, sl->h_soff, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueWriteBuffer(c->q, sl->ctrl, CL_FALSE, 0, pc * sizeof(double), sl->h_ctrl, 0, NULL, NULL));
    for (int k = 0; k < NPROG_METRIC; k++)
        if (lo[k + 1] > lo[k] && launch(c, sl, (ob_metric)(OB_METRIC_RADIAL + k), lo[k], lo[k + 1], S, err))
            goto fail;
    CL_CHECK(cl.clEnqueueReadBuffer(c->q, sl->err, CL_FALSE, 0, nd, sl->h_err, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueReadBuffer(c->q, sl->tpar, CL_FALSE, 0, nd, sl->h_tpar, 0, NULL, NULL));
    CL_CHECK(cl.clEnqueueReadBuffer(c->q, sl->work, CL_FALSE, 0, nd, sl->h_work, 0, NULL, &sl->done));
    CL_CHECK(cl.clFlush(c->q));
    sl->n = n;
    sl->nother = lo[NPROG_METRIC + 1] - lo[NPROG_METRIC];
    return 0;
fail:
    /* what was enqueued finishes before the staging is used again */
    cl.clFinish(c->q);
    release_events(sl);
    ob_info("OpenCL batch of %d records: %s; measuring it on the CPU", n, why.msg);
    return -1;
}

int ob_cl_wait(ob_cl *c, int slot, ob_errval *out, double *device_ns)
{
    ob_err why, *err = &why; /* the name CL_CHECK writes to */
    *device_ns = 0.0;
    if (!c || slot < 0 || slot >= OB_CL_SLOTS || !c->slot[slot].done)
        return -1;
    clslot *sl = &c->slot[slot];
    CL_CHECK(cl.clWaitForEvents(1, &sl->done));
    for (int k = 0; k < sl->nk; k++) {
        cl_ulong t0 = 0, t1 = 0;
        if (sl->kernel[k] &&
            cl.clGetEventProfilingInfo(sl->kernel[k], CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL) == CL_SUCCESS &&
            cl.clGetEventProfilingInfo(sl->kernel[k], CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL) == CL_SUCCESS &&
            t1 > t0)
            *device_ns += (double)(t1 - t0);
    }
    release_events(sl);
    for (int j = 0; j < sl->n; j++) {
        ob_errval *o = &out[sl->perm[j]];
        if (j >= sl->n - sl->nother) { /* no sampled metric: no program measured it */
            o->err = INFINITY;
            o->t = o->work = 0.0;
            continue;
        }
        o->err = sl->h_err[j];
        o->t = sl->h_tpar[j];
        o->work = sl->h_work[j];
    }
    return 0;
fail:
    cl.clFinish(c->q);
    release_events(sl);
    ob_info("OpenCL batch of %d records: %s; measuring it on the CPU", sl->n, why.msg);
    return -1;
}

/* ---- the device's fp64 peak ------------------------------------------- */

/* Independent chains of mad (a multiply and an add: 2 flops, fused or not,
 * as the device does it) per work-item: bound by the multiply-add units,
 * not by latency.  Two kernels, the faster counts: 8 chains of doubles (a
 * GPU runs each work-item on one lane, its many work-items fill it) and 8
 * chains of double8 (a CPU device's vector units: PoCL reached 9 GFLOP/s
 * with the scalar chains on 2 cores, 45-60 with these).  The sums are
 * written so that no chain is dead code. */
static const char PEAK_SRC[] =
    "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
    "#define PEAK(name, T, SUM)                                                      \\\n"
    "__kernel void name(const int iters, const double a, const double b, __global double *out) \\\n"
    "{                                                                               \\\n"
    "    const int g = get_global_id(0);                                             \\\n"
    "    const T x = (T)(1.0 + 1e-3 * (g % 97));                                     \\\n"
    "    T x0 = x, x1 = x + 0.01, x2 = x + 0.02, x3 = x + 0.03;                      \\\n"
    "    T x4 = x + 0.04, x5 = x + 0.05, x6 = x + 0.06, x7 = x + 0.07;               \\\n"
    "    for (int i = 0; i < iters; i++) {                                           \\\n"
    "        x0 = mad(a, x0, b); x1 = mad(a, x1, b); x2 = mad(a, x2, b);             \\\n"
    "        x3 = mad(a, x3, b); x4 = mad(a, x4, b); x5 = mad(a, x5, b);             \\\n"
    "        x6 = mad(a, x6, b); x7 = mad(a, x7, b);                                 \\\n"
    "    }                                                                           \\\n"
    "    const T s = x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7;                          \\\n"
    "    out[g] = SUM;                                                               \\\n"
    "}\n"
    "PEAK(ob_fma_peak1, double, s)\n"
    "PEAK(ob_fma_peak8, double8, s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7)\n";
enum { PEAK_CHAINS = 8 };

/* One launch of a peak kernel: its own time, seconds (profiling), or -1
 * after err. */
static double peak_launch(ob_cl *c, cl_kernel k, cl_mem buf, size_t global, size_t local, int iters, ob_err *err)
{
    const double a = 0.999999, b = 1e-7;
    cl_event ev = NULL;
    cl_ulong t0 = 0, t1 = 0;
    CL_CHECK(cl.clSetKernelArg(k, 0, sizeof(int), &iters));
    CL_CHECK(cl.clSetKernelArg(k, 1, sizeof(double), &a));
    CL_CHECK(cl.clSetKernelArg(k, 2, sizeof(double), &b));
    CL_CHECK(cl.clSetKernelArg(k, 3, sizeof(cl_mem), &buf));
    CL_CHECK(cl.clEnqueueNDRangeKernel(c->q, k, 1, NULL, &global, &local, 0, NULL, &ev));
    CL_CHECK(cl.clWaitForEvents(1, &ev));
    CL_CHECK(cl.clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL));
    CL_CHECK(cl.clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL));
    cl.clReleaseEvent(ev);
    return t1 > t0 ? 1e-9 * (double)(t1 - t0) : 1e-9;
fail:
    if (ev)
        cl.clReleaseEvent(ev);
    return -1.0;
}

/* One peak kernel (W doubles a chain) timed: the flops and seconds of a
 * launch of about target_s seconds, after an untimed first launch (a
 * driver may compile there) and probes that size it.  0, or -1 after err. */
static int peak_kernel(ob_cl *c, const char *name, int W, double target_s, double *flops, double *seconds,
                       ob_err *err)
{
    cl_kernel k = NULL;
    cl_mem buf = NULL;
    cl_int e;
    k = cl.clCreateKernel(c->peak, name, &e);
    CL_CHECK(e);
    /* enough work-items to fill every compute unit many times over */
    cl_uint cu = 1;
    cl.clGetDeviceInfo(c->dev, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
    size_t wg = 0;
    CL_CHECK(cl.clGetKernelWorkGroupInfo(k, c->dev, CL_KERNEL_WORK_GROUP_SIZE, sizeof wg, &wg, NULL));
    const size_t local = wg >= 128 ? 128 : wg > 0 ? wg : 1;
    const size_t global = local * (size_t)(cu > 0 ? cu : 1) * (c->gpu ? 64 : 4);
    buf = cl.clCreateBuffer(c->ctx, CL_MEM_WRITE_ONLY, global * sizeof(double), NULL, &e);
    CL_CHECK(e);
    int iters = 64;
    if (peak_launch(c, k, buf, global, local, iters, err) < 0)
        goto fail;
    double t = peak_launch(c, k, buf, global, local, iters, err);
    while (t >= 0 && t < 0.05 * target_s && iters < (1 << 26)) {
        iters *= 8;
        t = peak_launch(c, k, buf, global, local, iters, err);
    }
    if (t < 0)
        goto fail;
    const double want = iters * fmin(64.0, fmax(1.0, target_s / t));
    iters = want > (double)(1 << 30) ? (1 << 30) : (int)want;
    t = peak_launch(c, k, buf, global, local, iters, err);
    if (t < 0)
        goto fail;
    *flops = 2.0 * PEAK_CHAINS * W * (double)iters * (double)global;
    *seconds = t;
    cl.clReleaseMemObject(buf);
    cl.clReleaseKernel(k);
    return 0;
fail:
    if (buf)
        cl.clReleaseMemObject(buf);
    if (k)
        cl.clReleaseKernel(k);
    return -1;
}

int ob_cl_fma_peak(ob_cl *c, double target_s, double *flops, double *seconds, ob_err *err)
{
    *flops = *seconds = 0.0;
    if (!c) {
        ob_fail(err, "no OpenCL device");
        return -1;
    }
    char cache[600];
    if (!c->peak && build_program(c, PEAK_SRC, CL_STD, &c->peak, cache, sizeof cache, err) != 0)
        return -1;
    double f[2], s[2];
    if (peak_kernel(c, "ob_fma_peak1", 1, target_s, &f[0], &s[0], err) != 0 ||
        peak_kernel(c, "ob_fma_peak8", 8, target_s, &f[1], &s[1], err) != 0)
        return -1;
    const int best = f[1] / s[1] > f[0] / s[0];
    *flops = f[best];
    *seconds = s[best];
    return 0;
}

int ob_cl_measure_batch(void *ctx, const ob_measure_rec *recs, int n, int samples, ob_errval *out)
{
    double device_ns;
    if (ob_cl_submit(ctx, 0, recs, n, samples) != 0)
        return -1;
    return ob_cl_wait(ctx, 0, out, &device_ns);
}

int ob_cl_batch_submit(void *ctx, int slot, const ob_measure_rec *recs, int n, int samples)
{
    return ob_cl_submit(ctx, slot, recs, n, samples);
}

int ob_cl_batch_wait(void *ctx, int slot, ob_errval *out, double *device_ns)
{
    return ob_cl_wait(ctx, slot, out, device_ns);
}

int ob_cl_list_devices(FILE *f)
{
    ob_err err;
    if (load_cl(&err)) {
        fprintf(f, "# %s\n", err.msg);
        return -1;
    }
    cl_uint np = 0;
    cl_platform_id plats[16];
    if (cl.clGetPlatformIDs(16, plats, &np) != CL_SUCCESS || np == 0) {
        fprintf(f, "# no OpenCL platform\n");
        return 0;
    }
    int count = 0;
    fprintf(f, "%-28s %-44s %-6s %-4s %-5s %s\n", "platform", "device", "type", "CUs", "fp64", "driver");
    for (cl_uint p = 0; p < np; p++) {
        char pn[256] = "";
        cl.clGetPlatformInfo(plats[p], CL_PLATFORM_NAME, sizeof pn, pn, NULL);
        cl_uint nd = 0;
        cl_device_id devs[16];
        if (cl.clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &nd) != CL_SUCCESS)
            continue;
        for (cl_uint k = 0; k < nd; k++) {
            char dn[256] = "", dv[128] = "";
            cl_device_type ty = 0;
            cl_uint cu = 0;
            cl.clGetDeviceInfo(devs[k], CL_DEVICE_NAME, sizeof dn, dn, NULL);
            cl.clGetDeviceInfo(devs[k], CL_DRIVER_VERSION, sizeof dv, dv, NULL);
            cl.clGetDeviceInfo(devs[k], CL_DEVICE_TYPE, sizeof ty, &ty, NULL);
            cl.clGetDeviceInfo(devs[k], CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
            fprintf(f, "%-28s %-44s %-6s %-4u %-5s %s\n", pn, dn,
                    (ty & CL_DEVICE_TYPE_GPU) ? "gpu" : (ty & CL_DEVICE_TYPE_CPU) ? "cpu" : "other", cu,
                    has_fp64(devs[k]) ? "yes" : "no", dv);
            count++;
        }
    }
    return count;
}

#endif
