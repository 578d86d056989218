/*
 * fuzz_journal.c - libFuzzer target: what `--resume` reads of a journal or
 * of a finished run (host/run/journal.c, host/io/results_csv.c) on arbitrary bytes.
 * The input's first line is taken as a recorded fingerprint and compared
 * with itself and with a real one both ways (ob_fingerprint_diff must return
 * 0 or 1 with a terminated message, never crash or overrun); the rest as the
 * journal's rows, which start on line 2 (ob_res_parse_at must return 0 or
 * -1 with a NAME:LINE message, never crash, overrun or leak).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "host/run/journal.h"
#include "host/io/results_csv.h"

static const char real_fp[] = /* a finished run's results.fingerprint */
    "samples=256 max_depth=40 max_segments=20000 inflections=1 job_timeout=0 data=datasets "
    "data_hash=733eb5bf6f21874f curves=all "
    "methods=tiller,cobb,coquillart,elber,interp,liu,chebyshev,lstsq,kim2018,ahn,lee,zhao,zhao-"
    "rational,hoschek,exact,sisl tols=0.1,0.01,0.001,0.0001,1e-05 metric=hausdorff split=mid shard=none "
    "git=8d387cd1c26802fb52ec68391ecb4e0204fdc5c0 dirty=0 "
    "cflags=-std=c11%20-g%20-Wall%20-Wextra%20-Wshadow%20-fopenmp%20-D_POSIX_C_SOURCE=200809L%20-O2 "
    "version.tiller=1 version.cobb=1 version.coquillart=1 version.elber=1 version.interp=1 version.liu=1 "
    "version.chebyshev=1 version.lstsq=1 version.kim2018=1 version.ahn=1 version.lee=1 version.zhao=1 "
    "version.zhao-rational=1 version.hoschek=1 version.exact=1 version.sisl=1 coquillart.reading=0 "
    "coquillart.foot=0 elber.iterations=5 elber.update=0 elber.variant=0 elber.rounds=20 liu.nodes=64 "
    "chebyshev.nodes=64 lstsq.samples=32 lstsq.target=0 lee.tol_frac=1 lee.arc=0 lee.arcs_on=0 "
    "lee.start=0 lee.clip=0 zhao.iterations=5 zhao.npfac=8 zhao.weighted=1 zhao.degree=0 zhao.on_pole=1 "
    "zhao-rational.iterations=5 zhao-rational.npfac=8 zhao-rational.weighted=1 zhao-rational.degree=0 "
    "zhao-rational.on_pole=1 hoschek.samples=0 hoschek.iterations=20 hoschek.tangents=0 hoschek.degree=0 "
    "exact.detect_tol=1e-10 sisl.max_step=0 sisl.timeout=20";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *nl = memchr(data, '\n', size);
    const size_t l1 = nl ? (size_t)(nl - (const char *)data) : size;
    char *fp = malloc(l1 + 1);
    if (!fp)
        return 0;
    memcpy(fp, data, l1);
    fp[l1] = '\0';
    char out[512];
    out[sizeof out - 1] = 'x';
    for (int k = 0; k < 3; k++) {
        const char *was = k == 2 ? real_fp : fp, *now = k == 1 ? real_fp : fp;
        const int r = ob_fingerprint_diff(was, now, out, sizeof out);
        if ((r != 0 && r != 1) || !memchr(out, '\0', sizeof out))
            __builtin_trap(); /* 0 or 1, and a terminated message */
    }
    free(fp);
    if (!nl)
        return 0;
    const char *rows = nl + 1;
    const size_t n = size - l1 - 1;
    ob_err err;
    err.msg[0] = '\0';
    ob_res_table t;
    if (ob_res_parse_at(rows, n, "fuzz.journal", 2, &t, &err) != 0 &&
        strncmp(err.msg, "fuzz.journal", 12) != 0)
        __builtin_trap(); /* every error names the input */
    ob_res_free(&t);
    return 0;
}
