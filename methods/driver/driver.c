/*
 * driver.c - the driver's API: split and status names, default options, and
 * ob_driver_run, which hands the jobs to an engine.  See driver.h; the
 * files of the driver are listed in driver_int.h.
 */
#include "methods/driver/driver_int.h"

#include <string.h>

static const char *const split_names[OB_SPLIT_COUNT] = {"mid", "maxerr", "greedy", "optimal"};

const char *ob_split_name(ob_split s) { return (s >= 0 && s < OB_SPLIT_COUNT) ? split_names[s] : "?"; }

const char *ob_status_name(ob_status s)
{
    switch (s) {
    case OB_OK: return "ok";
    case OB_LIMIT: return "limit";
    case OB_FAIL: return "fail";
    case OB_SKIP: return "skip";
    case OB_TIMEOUT: return "timeout";
    }
    return "?";
}

int ob_split_parse(const char *name, ob_split *s)
{
    for (int i = 0; i < OB_SPLIT_COUNT; i++)
        if (strcmp(name, split_names[i]) == 0) {
            *s = (ob_split)i;
            return 0;
        }
    return -1;
}

void ob_driver_defaults(ob_driver_opts *o)
{
    memset(o, 0, sizeof *o);  /* no batch backend: the CPU measures */
    o->samples = OB_DEFAULT_SAMPLES;
    o->max_depth = 40;
    o->max_segments = 20000;
    o->inflections = 1;
    o->chunk = 0;  /* auto: the batch backend's size, else OB_CPU_CHUNK */
}

static const char *const engine_names[OB_ENGINE_COUNT] = {"auto", "level", "group", "device"};

const char *ob_engine_name(ob_engine e) { return (e >= 0 && e < OB_ENGINE_COUNT) ? engine_names[e] : "?"; }

int ob_engine_parse(const char *name, ob_engine *e)
{
    for (int i = 0; i < OB_ENGINE_COUNT; i++)
        if (strcmp(name, engine_names[i]) == 0) {
            *e = (ob_engine)i;
            return 0;
        }
    return -1;
}

/* auto: the group engine on the CPU; with a batch backend, chunks of
 * records from all groups at once, overlapped with the fits where the
 * backend runs beside the threads.  The device engine needs an
 * asynchronous backend: without one it is the level engine. */
static ob_engine engine_for(const drv_run *R)
{
    const int async = R->h.batch_submit && R->h.batch_wait;
    switch (R->o.engine) {
    case OB_ENGINE_LEVEL:
    case OB_ENGINE_GROUP: return R->o.engine;
    case OB_ENGINE_DEVICE: return async ? OB_ENGINE_DEVICE : OB_ENGINE_LEVEL;
    default: break;
    }
    if (!R->h.batch)
        return OB_ENGINE_GROUP;
    return async && R->h.batch_overlap ? OB_ENGINE_DEVICE : OB_ENGINE_LEVEL;
}

int ob_driver_run(ob_job *jobs, size_t njobs, const ob_driver_opts *opts, const ob_driver_hooks *hooks)
{
    drv_run R;
    int rc = drv_run_start(&R, jobs, njobs, opts, hooks);
    R.st.engine = engine_for(&R);
    if (rc == 0)
        rc = R.st.engine == OB_ENGINE_GROUP    ? drv_run_group(&R)
             : R.st.engine == OB_ENGINE_DEVICE ? drv_run_device(&R)
                                               : drv_run_level(&R);
    drv_run_end(&R, rc);
    return rc;
}
