/*
 * mpirun.c - ranks, and the gathering of their rows at rank 0 (mpirun.h).
 * Built against MPI when OB_MPI is defined (make MPI=1), else one process.
 */
#include "host/run/mpirun.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#ifdef OB_MPI
#include <mpi.h>

static int started;

int ob_mpi_init(int *argc, char ***argv)
{
    int provided = 0;
    /* OpenMP threads run inside a rank; only the main thread calls MPI */
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        return -1;
    started = 1;
    return 0;
}

void ob_mpi_finalize(void)
{
    if (started)
        MPI_Finalize();
    started = 0;
}

int ob_mpi_rank(void)
{
    int r = 0;
    if (started)
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int ob_mpi_size(void)
{
    int s = 1;
    if (started)
        MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}

int ob_mpi_all_equal(uint64_t v)
{
    if (!started)
        return 1;
    unsigned long long lo = v, hi = v, a, b;
    MPI_Allreduce(&lo, &a, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&hi, &b, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
    return a == b;
}

double ob_mpi_max(double v)
{
    double m = v;
    if (started)
        MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return m;
}

/* Rank 0: put the gathered texts in job order.  0, or -1. */
static int assemble(int size, const int *cnt, const int *displ, const unsigned long long *idx,
                    const unsigned long long *lens, const char *blob, const long long *bdispl, size_t total,
                    char **res, char **smp)
{
    const char **rp = calloc(total ? total : 1, sizeof *rp), **sp = calloc(total ? total : 1, sizeof *sp);
    size_t *rl = calloc(total ? total : 1, sizeof *rl), *sl = calloc(total ? total : 1, sizeof *sl);
    int rc = -1;
    if (!rp || !sp || !rl || !sl)
        goto out;
    size_t rsum = 0, ssum = 0;
    for (int r = 0; r < size; r++) {
        const char *p = blob + bdispl[r];
        for (int i = 0; i < cnt[r]; i++) {
            const int k = displ[r] + i;
            const unsigned long long j = idx[k];
            if (j >= total || rp[j])
                goto out;  /* out of range, or twice */
            rp[j] = p;
            rl[j] = (size_t)lens[2 * k];
            sp[j] = p + rl[j];
            sl[j] = (size_t)lens[2 * k + 1];
            p += rl[j] + sl[j];
            rsum += rl[j];
            ssum += sl[j];
        }
    }
    for (size_t j = 0; j < total; j++)
        if (!rp[j])
            goto out;  /* a gap */
    *res = malloc(rsum + 1);
    *smp = malloc(ssum + 1);
    if (!*res || !*smp)
        goto out;
    char *q = *res, *t = *smp;
    for (size_t j = 0; j < total; j++) {
        memcpy(q, rp[j], rl[j]);
        q += rl[j];
        memcpy(t, sp[j], sl[j]);
        t += sl[j];
    }
    *q = *t = '\0';
    rc = 0;
out:
    if (rc) {
        free(*res);
        free(*smp);
        *res = *smp = NULL;
    }
    free(rp);
    free(sp);
    free(rl);
    free(sl);
    return rc;
}

int ob_mpi_gather(char *const *rows, char *const *samples, const size_t *idx, size_t n, size_t total, char **res,
                  char **smp)
{
    *res = *smp = NULL;
    const int rank = ob_mpi_rank(), size = ob_mpi_size();
    unsigned long long *myidx = malloc((n ? n : 1) * sizeof *myidx), *mylens = malloc((n ? n : 1) * 2 * sizeof *mylens);
    size_t bytes = 0;
    for (size_t i = 0; i < n; i++)
        bytes += strlen(rows[i]) + strlen(samples[i]);
    char *myblob = malloc(bytes ? bytes : 1);
    int ok = myidx && mylens && myblob && n <= INT_MAX / 2 && bytes <= INT_MAX;
    if (ok) {
        char *p = myblob;
        for (size_t i = 0; i < n; i++) {
            const size_t a = strlen(rows[i]), b = strlen(samples[i]);
            myidx[i] = idx[i];
            mylens[2 * i] = a;
            mylens[2 * i + 1] = b;
            memcpy(p, rows[i], a);
            memcpy(p + a, samples[i], b);
            p += a + b;
        }
    }
    int all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    int rc = -1;
    int *cnt = NULL, *displ = NULL, *cnt2 = NULL, *displ2 = NULL, *bcnt = NULL, *bdisp = NULL;
    long long *bdispl = NULL;
    unsigned long long *idx0 = NULL, *lens0 = NULL;
    char *blob0 = NULL;
    if (!all_ok)
        goto out;
    const int mine = (int)n, mybytes = (int)bytes;
    if (rank == 0) {
        cnt = calloc((size_t)size, sizeof *cnt);
        displ = calloc((size_t)size, sizeof *displ);
        cnt2 = calloc((size_t)size, sizeof *cnt2);
        displ2 = calloc((size_t)size, sizeof *displ2);
        bcnt = calloc((size_t)size, sizeof *bcnt);
        bdisp = calloc((size_t)size, sizeof *bdisp);
        bdispl = calloc((size_t)size, sizeof *bdispl);
    }
    MPI_Gather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Gather(&mybytes, 1, MPI_INT, bcnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
    long long nsum = 0, bsum = 0;
    if (rank == 0) {
        for (int r = 0; r < size; r++) {
            displ[r] = (int)nsum;
            cnt2[r] = 2 * cnt[r];
            displ2[r] = (int)(2 * nsum);
            bdisp[r] = (int)bsum;
            bdispl[r] = bsum;
            nsum += cnt[r];
            bsum += bcnt[r];
        }
        if (nsum > INT_MAX / 2 || bsum > INT_MAX)
            nsum = bsum = -1;  /* past what one gather can carry: refused below */
        else {
            idx0 = malloc((size_t)(nsum ? nsum : 1) * sizeof *idx0);
            lens0 = malloc((size_t)(nsum ? nsum : 1) * 2 * sizeof *lens0);
            blob0 = malloc((size_t)(bsum ? bsum : 1));
        }
    }
    int ready = rank != 0 || (nsum >= 0 && idx0 && lens0 && blob0);
    int all_ready = 0;
    MPI_Allreduce(&ready, &all_ready, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all_ready)
        goto out;
    MPI_Gatherv(myidx, mine, MPI_UNSIGNED_LONG_LONG, idx0, cnt, displ, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    MPI_Gatherv(mylens, 2 * mine, MPI_UNSIGNED_LONG_LONG, lens0, cnt2, displ2, MPI_UNSIGNED_LONG_LONG, 0,
                MPI_COMM_WORLD);
    MPI_Gatherv(myblob, mybytes, MPI_CHAR, blob0, bcnt, bdisp, MPI_CHAR, 0, MPI_COMM_WORLD);
    int done = 1;
    if (rank == 0)
        done = (size_t)nsum == total && assemble(size, cnt, displ, idx0, lens0, blob0, bdispl, total, res, smp) == 0;
    MPI_Bcast(&done, 1, MPI_INT, 0, MPI_COMM_WORLD);
    rc = done ? 0 : -1;
out:
    free(myidx);
    free(mylens);
    free(myblob);
    free(cnt);
    free(displ);
    free(cnt2);
    free(displ2);
    free(bcnt);
    free(bdisp);
    free(bdispl);
    free(idx0);
    free(lens0);
    free(blob0);
    if (rc) {
        free(*res);
        free(*smp);
        *res = *smp = NULL;
    }
    return rc;
}

#else /* one process */

int ob_mpi_init(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    return 0;
}
void ob_mpi_finalize(void) {}
int ob_mpi_rank(void) { return 0; }
int ob_mpi_size(void) { return 1; }
int ob_mpi_all_equal(uint64_t v)
{
    (void)v;
    return 1;
}
double ob_mpi_max(double v) { return v; }
int ob_mpi_gather(char *const *rows, char *const *samples, const size_t *idx, size_t n, size_t total, char **res,
                  char **smp)
{
    (void)rows, (void)samples, (void)idx, (void)n, (void)total;
    *res = *smp = NULL;
    return -1;  /* only called with more than one rank */
}

#endif
