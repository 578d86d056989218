/*
 * test_side_order.c - a Hausdorff side's result does not depend on the
 * order its samples are computed in (kernels/metric_core.h, "one side's
 * scan, data-parallel").
 *
 * Why: the serial scan (obc_sample_refine) chains its queries (each starts
 * where the last one's foot lay, and is asked only above the running
 * maximum); the GPU's group kernel computes every sample at once and must
 * still give the serial bits.  That holds when (1) a query's exact distance
 * and foot are the same whatever hint it starts from, (2) a query asked
 * above a cut returns its exact distance where that is above the cut and
 * something at or below the cut elsewhere, and (3) the two-phase procedure
 * built on them (exact coarse samples, the rest above the coarse maximum,
 * the serial bookkeeping replayed) ends where the serial scan ends, under
 * every stop.  Checked here on the CPU on random pairs (polynomial and
 * rational, degrees 1..7, offsets inside and past the radius of curvature),
 * on a point-like target (every sample at the same distance: the nearest
 * sample is a tie, once settled by the hint) and on curves far apart;
 * tests/unit/test_opencl.c checks the kernel itself against the CPU.
 */
#include <stdint.h>
#include <string.h>

#include "kernels/metric_core.h"
#include "tests/check.h"

enum { MAXS = 257 };

static double tab_o[OBC_TABLE_SIZE(MAXS)], tab_a[OBC_TABLE_SIZE(MAXS)], errs[MAXS];

static uint64_t rng_state = 0x2545f4914f6cdd1du;
static double urand(double lo, double hi)
{
    rng_state = rng_state * 6364136223846793005u + 1442695040888963407u;
    return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1p-53;
}

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* A pair: base C (degree n, gently turning, rational when asked) and an
 * approximation A of its d-offset of degree na: C's polygon shifted by d
 * along the polygon's normals, with noise of relative size `noise`. */
static void make_pair(double *hb, int n, double *ha, int na, int rational, double d, double noise)
{
    double ang = urand(0.0, 6.28), x = 0.0, y = 0.0;
    double px[OBC_MAX_DEG + 1], py[OBC_MAX_DEG + 1];
    for (int i = 0; i <= n; i++) {
        px[i] = x, py[i] = y;
        const double w = rational ? urand(0.5, 2.0) : 1.0;
        hb[3 * i] = w * x, hb[3 * i + 1] = w * y, hb[3 * i + 2] = w;
        ang += urand(-0.8, 0.8);
        x += cos(ang), y += sin(ang);
    }
    for (int i = 0; i <= na; i++) { /* A's points along C's polygon, shifted */
        const double s = (double)i * n / na;
        const int j = s >= n ? n - 1 : (int)s;
        const double f = s - j, tx = px[j + 1] - px[j], ty = py[j + 1] - py[j], l = sqrt(tx * tx + ty * ty);
        ha[3 * i] = px[j] + f * tx - d * ty / l + noise * urand(-1.0, 1.0);
        ha[3 * i + 1] = py[j] + f * ty + d * tx / l + noise * urand(-1.0, 1.0);
        ha[3 * i + 2] = 1.0;
    }
}

/* (1) and (2) for every sample of one side: exact bits whatever the hint,
 * and the cut's contract.  Returns the failures. */
static int side_queries(int kind, const double *hb, int nb, const double *ha, int na, double d, int S)
{
    const double *tgt = kind == OBC_K_H_APPROX ? tab_o : tab_a, *qry = kind == OBC_K_H_APPROX ? tab_a : tab_o;
    long ops = 0;
    int bad = 0, chain = OBC_NO_HINT;
    for (int k = 0; k < S; k++) {
        int none = OBC_NO_HINT, h2 = (int)urand(-S, S);
        double t0, t1, t2;
        const double t = obc_sample_t(k, S);
        const double e0 = obc_side_dist(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, t, k, -1.0, &none, &t0);
        const double e1 = obc_side_dist(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, t, k, -1.0, &chain, &t1);
        const double e2 = obc_side_dist(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, t, k, -1.0, &h2, &t2);
        bad += !(same(e0, e1) && same(e0, e2) && same(t0, t1) && same(t0, t2));
        const double cut = e0 * urand(0.5, 1.5);
        int h3 = chain;
        const double ec = obc_side_dist(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, t, k, cut, &h3, &t2);
        bad += e0 > cut ? !same(ec, e0) : !(ec <= cut);
        if (bad == 1 && k >= 0)
            fprintf(stderr, "  sample %d: exact %a at %a, chained %a at %a, hint %a at %a, cut %a -> %a\n", k, e0,
                    t0, e1, t1, e2, t2, cut, ec);
    }
    return bad;
}

/* (3): one side as the group kernel computes it, in order-free phases. */
static void side_phases(int kind, const double *hb, int nb, const double *ha, int na, double d, int S,
                        double stop, double *err, double *t)
{
    const double *tgt = kind == OBC_K_H_APPROX ? tab_o : tab_a, *qry = kind == OBC_K_H_APPROX ? tab_a : tab_o;
    long ops = 0;
    const int NC = obc_scan_ncoarse(S);
    for (int i = NC - 1; i >= 0; i--) /* any order: backwards */
        errs[obc_scan_at(i, S)] = obc_side_query(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, obc_scan_at(i, S), -1.0);
    double best = -1.0;
    int kb = 0;
    if (!obc_scan_replay(errs, S, 0, NC, stop, &best, &kb)) {
        for (int i = S - 1; i >= NC; i--)
            errs[obc_scan_at(i, S)] =
                obc_side_query(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, obc_scan_at(i, S), best);
        obc_scan_replay(errs, S, NC, S, stop, &best, &kb);
    }
    obc_scan_finish(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, stop, best, kb, err, t);
    if (kind == OBC_K_H_APPROX && !(isnan(*err) || isinf(*err)))
        *t = obc_h_foot(hb, nb, ha, na, d, S, tgt, qry, &ops, *t);
}

/* Both sides of one pair at S samples: (1), (2), and (3) under stops from
 * none to a third of the side's error.  Returns the failures. */
static int check_pair(const double *hb, int nb, const double *ha, int na, double d, int S, const char *what)
{
    long ops = 0;
    obc_fill_table(hb, nb, d, S, tab_o, &ops);
    obc_fill_table(ha, na, 0.0, S, tab_a, &ops);
    int bad = 0;
    for (int side = 0; side < 2; side++) {
        const int kind = side ? OBC_K_H_OFFSET : OBC_K_H_APPROX;
        const int q = side_queries(kind, hb, nb, ha, na, d, S);
        if (q)
            fprintf(stderr, "%s S=%d side %d: %d queries depend on their history\n", what, S, side, q);
        bad += q;
        const double *tgt = side ? tab_a : tab_o, *qry = side ? tab_o : tab_a;
        double full, tf;
        obc_sample_refine(kind, hb, nb, ha, na, d, S, tgt, qry, &ops, OBC_INF, &full, &tf);
        const double stops[4] = {OBC_INF, 2.0 * full, full, full / 3.0};
        for (int si = 0; si < 4; si++) {
            double e1, t1, e2, t2;
            if (side)
                obc_h_side_offset(hb, nb, ha, na, d, S, tab_a, tab_o, &ops, stops[si], &e1, &t1);
            else
                obc_h_side_approx(hb, nb, ha, na, d, S, tab_o, tab_a, &ops, stops[si], &e1, &t1);
            side_phases(kind, hb, nb, ha, na, d, S, stops[si], &e2, &t2);
            if (!(same(e1, e2) && same(t1, t2))) {
                fprintf(stderr, "%s S=%d side %d stop %a: serial %a at %a, phases %a at %a\n", what, S, side,
                        stops[si], e1, t1, e2, t2);
                bad++;
            }
        }
    }
    return bad;
}

/* The work model of the group kernel (printed, for docs/performance.md):
 * per record at S = 256, the counted flops of the tables, of the serial
 * scan and of its refinement, and of the two phases; over 400 random pairs
 * of degrees 2..7 close to each other (a fitted piece's distance). */
static void work_model(void)
{
    static double hb[3 * (OBC_MAX_DEG + 1)], ha[3 * (OBC_MAX_DEG + 1)];
    const int S = 256, N = 400, NC = obc_scan_ncoarse(S);
    double tabs = 0, scan = 0, ref = 0, ph = 0;
    for (int r = 0; r < N; r++) {
        const int n = 2 + r % 6, na = n + r % 3;
        const double d = (r % 2 ? 1.0 : -1.0) * urand(0.05, 0.6);
        make_pair(hb, n, ha, na, r % 3 == 1, d, 1e-3 * urand(0.1, 10.0));
        long o = 0;
        obc_fill_table(hb, n, d, S, tab_o, &o);
        obc_fill_table(ha, na, 0.0, S, tab_a, &o);
        tabs += o;
        for (int side = 0; side < 2; side++) {
            const int kind = side ? OBC_K_H_OFFSET : OBC_K_H_APPROX;
            const double *tgt = side ? tab_a : tab_o, *qry = side ? tab_o : tab_a;
            long os = 0, orf = 0, op = 0;
            double best = -1.0, e, t;
            int kb = 0, hint = OBC_NO_HINT;
            for (int i = 0; i < S; i++) { /* the serial scan, in its order */
                const int k = obc_scan_at(i, S);
                obc_scan_take(obc_err_at(kind, hb, n, ha, na, d, S, tgt, qry, &os, obc_sample_t(k, S), k, best, &hint),
                              k, &best, &kb);
            }
            obc_scan_refine(kind, hb, n, ha, na, d, S, tgt, qry, &orf, best, kb, &hint, &e, &t);
            double b2 = -1.0;
            int k2 = 0;
            for (int i = 0; i < S; i++) {
                if (i == NC)
                    obc_scan_replay(errs, S, 0, NC, OBC_INF, &b2, &k2);
                const int k = obc_scan_at(i, S);
                errs[k] = obc_side_query(kind, hb, n, ha, na, d, S, tgt, qry, &op, k, i < NC ? -1.0 : b2);
            }
            scan += os, ref += orf, ph += op;
        }
    }
    fprintf(stderr,
            "work model, S = 256, flops per record: tables %.0f, serial scan %.0f, refinement %.0f (%.0f%% of the "
            "serial total, in 2 x 42 queries); the phases %.0f instead of the scan (x%.2f the serial total)\n",
            tabs / N, scan / N, ref / N, 100.0 * ref / (tabs + scan + ref), ph / N,
            (tabs + ph + ref) / (tabs + scan + ref));
}

int main(void)
{
    work_model();
    static double hb[3 * (OBC_MAX_DEG + 1)], ha[3 * (OBC_MAX_DEG + 1)];
    const int Ss[4] = {8, 11, 128, 257};
    int pairs = 0, bad = 0;
    for (int r = 0; r < 48; r++) {
        const int n = 1 + r % 7, na = n + (r % 3), rational = r % 3 == 1;
        const double d = (r % 2 ? 1.0 : -1.0) * (r % 5 == 4 ? 2.5 : urand(0.05, 0.6));
        make_pair(hb, n, ha, na, rational, d, r % 4 == 3 ? 0.3 : 1e-3);
        for (int si = 0; si < 4; si++, pairs++)
            bad += check_pair(hb, n, ha, na, d, Ss[si], "random pair") != 0;
    }
    CHECK(bad == 0, "%d of %d random pairs and sample counts: a side depends on the order of its queries", bad,
          pairs);

    /* a point-like approximation: every sample of A is the same point, so
     * every O query's nearest sample is a tie (the hint once chose it) */
    make_pair(hb, 3, ha, 3, 0, 0.4, 0.0);
    for (int i = 1; i <= 3; i++)
        ha[3 * i] = ha[0], ha[3 * i + 1] = ha[1];
    int pt = 0;
    for (int si = 0; si < 4; si++)
        pt += check_pair(hb, 3, ha, 3, 0.4, Ss[si], "point-like approximation") != 0;
    CHECK(pt == 0, "point-like approximation: %d of 4 sample counts depend on the order", pt);

    /* far apart: A nowhere near the offset (every foot at an end, folds) */
    make_pair(hb, 4, ha, 5, 0, 0.3, 0.0);
    for (int i = 0; i <= 5; i++)
        ha[3 * i] += 7.0, ha[3 * i + 1] -= 3.0;
    int far = 0;
    for (int si = 0; si < 4; si++)
        far += check_pair(hb, 4, ha, 5, 0.3, Ss[si], "far apart") != 0;
    CHECK(far == 0, "far apart: %d of 4 sample counts depend on the order", far);

    /* the scan order: every sample once, the coarse ones first */
    int seen[MAXS] = {0}, order = 1;
    for (int i = 0; i < 257; i++) {
        const int k = obc_scan_at(i, 257);
        order &= k >= 0 && k < 257 && !seen[k]++ && ((i < obc_scan_ncoarse(257)) == (k % OBC_COARSE == 0));
    }
    CHECK(order, "obc_scan_at: a permutation of the samples, coarse first");
    return check_done();
}
