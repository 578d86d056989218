#!/usr/bin/python3
"""cert_brute.py - an independent brute-force judge of `offbench run --certify`
(issue 47; docs/certified.md, "An independent check").

    /usr/bin/python3 scripts/cert_brute.py RUN EXP [--out FILE.csv] [--procs N]
        [--samples S] [--family F] [--methods M,...] [--curves ID,...]
        [--limit N] [--verbose]

RUN is a run directory of `offbench run ... --certify --out RUN --export EXP`
(its results.csv: err_lower, err_upper, certified per job), EXP that run's
export directory (index.csv and one STEM.json per job with an approximation).
Every job with a certificate and an exported approximation is measured here
again, sharing no code with offbench: each piece's homogeneous control points
and its base span (seg, [a, b], [t0, t1]) come from the JSON, the base
segment itself from the JSON's `base_homogeneous` (the segment as the run
holds it, binary64), and the exact offset O(u) = C(u) + d N(u),
N = (-y', x') / |C'|, of that segment over the real range
u = a + (b - a)(t0 + (t1 - t0) s), s in [0, 1], whose ends are computed
exactly from the doubles (fractions.Fraction), not the piece offbench cut out
in floating point.

Per piece, both sides of the two-sided Hausdorff distance,
    H = max( sup_s min_u |A(s) - O(u)|,  sup_u min_s |O(u) - A(s)| ),
are sampled (S >= 20000 parameters per side, uniform, plus as many uniform in
arc length), each sample's inner min is found from its nearest samples on
the other curve (a k-d tree, several candidates) and Gauss-Newton projection
to a foot, and the largest values are refined by zooming (repeated dense
resampling of the bracket around each of the top local maxima). The value B
of a job is the max over its pieces. It is a distance attained (up to the
inner min's accuracy), so a correct certificate has B <= err_upper; it may
miss a narrow sup, so B is a lower estimate of H and err_lower <= B is
expected only up to that (a job where err_lower > B is measured again with
10 x the samples before it is flagged).

Evaluation: C, C' (hodograph) and C'' in float64 from the segment's own
Bernstein form; where the Bernstein sum of C' loses more than 6 digits to
cancellation (the sum of its terms' magnitudes over |C'| above 1e6: near a
cusp), or C' is exactly 0 (a collapsed end leg: the limit from inside), or
the piece is shorter than 1e-9 in u, the offset is evaluated in mpmath at 50
digits instead.  A |C'| that is merely small (a leg of 1e-8 without
cancellation) is evaluated to ~1 ulp in float64 (checked against mpmath: the
offsets agree to 2e-16 down to |C'| = 7e-8 at a 1.5e-8 end leg);
--mp-tiny-cprime also sends every sample with |C'| < 1e-6 of the control
polygon's size to mpmath (some 1000 x slower there).

Flags per job: upper_violation (B > err_upper (1 + 1e-9) + 1e-15: the
certificate is wrong), lower_violation (err_lower > B (1 + 1e-6) + 1e-15
after refinement: the certificate's attained distance is not found here;
less sure, since B is a lower estimate), verdict_violation (certified = yes
but B > tol). Output: a CSV
curve,d,method,tol,status,pieces,B,err_lower,err_upper,certified,flags
(plus family and mp_pieces) and a summary line on stdout. Exit status 0
without violations, 1 with any, 2 on bad input.
"""
import argparse
import csv
import json
import math
import multiprocessing
import os
import sys
from fractions import Fraction

import numpy as np
from scipy.spatial import cKDTree
import mpmath

MP_DPS = 50
REL_CPRIME = 1e-6      # |C'| below this x polygon size: mpmath
COND_MAX = 1e6         # cancellation in C' beyond this: mpmath
SHORT_U = 1e-9         # a piece shorter than this in u: mpmath throughout
MP_TINY_CPRIME = False  # --mp-tiny-cprime: also wherever |C'| < REL_CPRIME x size


# ---------------------------------------------------------------- curves

def binom_row(n):
    return np.array([math.comb(n, i) for i in range(n + 1)], float)


def bernstein(n, t):
    """(len(t), n+1) Bernstein basis of degree n at t (float64)."""
    t = np.asarray(t, float)
    m = len(t)
    tp = np.ones((m, n + 1))
    up = np.ones((m, n + 1))
    for i in range(1, n + 1):
        tp[:, i] = tp[:, i - 1] * t
        up[:, n - i] = up[:, n - i + 1] * (1.0 - t)
    return binom_row(n)[None, :] * tp * up


class Bez:
    """A rational Bézier segment from homogeneous points (w x, w y, w),
    evaluated in float64: point, first and second derivative."""

    def __init__(self, hpts):
        self.H = np.array(hpts, float)
        self.n = len(self.H) - 1
        n = self.n
        self.D1 = n * (self.H[1:] - self.H[:-1]) if n >= 1 else np.zeros((1, 3))
        self.D2 = (n - 1) * (self.D1[1:] - self.D1[:-1]) if n >= 2 else np.zeros((1, 3))
        self.size = float(np.max(np.ptp(self.H[:, :2] / self.H[:, 2:], axis=0))) if n >= 1 else 0.0

    def jets(self, t):
        """point P, derivative P1, second derivative P2 (each (m, 2)) and the
        condition of P1 (abs-sum bound / |P1|) at parameters t."""
        n = self.n
        h = bernstein(n, t) @ self.H
        if n >= 1:
            B1 = bernstein(n - 1, t)
            h1 = B1 @ self.D1
            a1 = B1 @ np.abs(self.D1)
        else:
            h1 = np.zeros_like(h)
            a1 = np.zeros_like(h)
        h2 = bernstein(n - 2, t) @ self.D2 if n >= 2 else np.zeros_like(h)
        w, w1, w2 = h[:, 2:], h1[:, 2:], h2[:, 2:]
        P = h[:, :2] / w
        P1 = (h1[:, :2] - P * w1) / w
        P2 = (h2[:, :2] - 2.0 * P1 * w1 - P * w2) / w
        num = np.hypot(P1[:, 0], P1[:, 1]) * np.abs(w[:, 0])
        absb = np.hypot(a1[:, 0], a1[:, 1]) + np.hypot(P[:, 0], P[:, 1]) * a1[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            cond = np.where(num > 0, absb / num, np.inf)
        return P, P1, P2, cond


def mp_jets(H, u):
    """C, C', C'' of homogeneous Bézier H at mpf u, by de Casteljau in mpf."""
    n = len(H) - 1
    pts = [[mpmath.mpf(c) for c in p] for p in H]

    def casteljau(q, t):
        q = [list(p) for p in q]
        for r in range(1, len(q)):
            for i in range(len(q) - r):
                q[i] = [(1 - t) * q[i][c] + t * q[i + 1][c] for c in range(3)]
        return q[0]

    h = casteljau(pts, u)
    if n >= 1:
        d1 = [[n * (pts[i + 1][c] - pts[i][c]) for c in range(3)] for i in range(n)]
        h1 = casteljau(d1, u)
    else:
        d1, h1 = [], [mpmath.mpf(0)] * 3
    if n >= 2:
        d2 = [[(n - 1) * (d1[i + 1][c] - d1[i][c]) for c in range(3)] for i in range(n - 1)]
        h2 = casteljau(d2, u)
    else:
        h2 = [mpmath.mpf(0)] * 3
    w, w1, w2 = h[2], h1[2], h2[2]
    P = [h[0] / w, h[1] / w]
    P1 = [(h1[c] - P[c] * w1) / w for c in range(2)]
    P2 = [(h2[c] - 2 * P1[c] * w1 - P[c] * w2) / w for c in range(2)]
    return P, P1, P2


class Offset:
    """O(u) = C(u) + d N(u) of base segment H over u in [ua, ub] (exact ends,
    as Fractions), parameterized by s in [0, 1]: u = ua + (ub - ua) s."""

    def __init__(self, H, d, ua, ub):
        self.bez = Bez(H)
        self.H = [[float(c) for c in p] for p in H]
        self.d = float(d)
        self.ua, self.ub = ua, ub
        self.uaf, self.ubf = float(ua), float(ub)
        self.all_mp = (ub - ua) < SHORT_U
        self.mp_count = 0
        with mpmath.workdps(MP_DPS):
            self.mua = mpmath.mpf(ua.numerator) / ua.denominator
            self.mub = mpmath.mpf(ub.numerator) / ub.denominator

    def _mp_point(self, s):
        """O, O' (d/ds), O'' (d/ds^2) at s in mpmath; an exact zero of C'
        (a collapsed end leg) is replaced by the limit from inside."""
        with mpmath.workdps(MP_DPS):
            s = mpmath.mpf(float(s))
            L = self.mub - self.mua
            u = self.mua + L * s
            P, P1, P2 = mp_jets(self.H, u)
            sp = mpmath.sqrt(P1[0] ** 2 + P1[1] ** 2)
            if sp == 0:
                eps = mpmath.mpf(10) ** (-(MP_DPS - 10))
                u2 = u + eps if s < 0.5 else u - eps
                _, Q1, _ = mp_jets(self.H, u2)
                P1d = Q1
                sp = mpmath.sqrt(Q1[0] ** 2 + Q1[1] ** 2)
                N = [-P1d[1] / sp, P1d[0] / sp]
                O = [P[0] + self.d * N[0], P[1] + self.d * N[1]]
                # a cusp of O's parameterization: its derivative is ~0 there
                return [float(x) for x in O], [0.0, 0.0], [0.0, 0.0]
            N = [-P1[1] / sp, P1[0] / sp]
            kap = (P1[0] * P2[1] - P1[1] * P2[0]) / sp ** 3
            O = [P[0] + self.d * N[0], P[1] + self.d * N[1]]
            f = 1 - self.d * kap
            O1 = [P1[0] * f * L, P1[1] * f * L]
            return [float(x) for x in O], [float(x) for x in O1], [0.0, 0.0]

    def jets(self, s):
        """O(s) and O'(s) (float64, (m, 2) each) at s in [0, 1]."""
        s = np.clip(np.asarray(s, float), 0.0, 1.0)
        L = self.ubf - self.uaf
        u = np.clip(self.uaf + (self.ubf - self.uaf) * s, min(self.uaf, self.ubf), max(self.uaf, self.ubf))
        P, P1, P2, cond = self.bez.jets(u)
        sp = np.hypot(P1[:, 0], P1[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            N = np.stack([-P1[:, 1], P1[:, 0]], 1) / sp[:, None]
            kap = (P1[:, 0] * P2[:, 1] - P1[:, 1] * P2[:, 0]) / sp ** 3
        O = P + self.d * N
        O1 = P1 * ((1.0 - self.d * kap) * L)[:, None]
        if self.all_mp:
            need = np.ones(len(s), bool)
        else:
            need = ~(cond < COND_MAX) | ~np.isfinite(O).all(1)
            # the ends from the exact ua, ub: where the normal turns fast
            # (|dO/du| ~ |d| / leg), rounding u to a double moves O(u) along
            # the curve by |dO/du| ulp(u), which at an end changes the extent
            need |= (s == 0.0) | (s == 1.0)
            if MP_TINY_CPRIME:
                need |= sp < REL_CPRIME * self.bez.size
        if need.any():
            for i in np.nonzero(need)[0]:
                o, o1, _ = self._mp_point(s[i])
                O[i], O1[i] = o, o1
                self.mp_count += 1
        O1[~np.isfinite(O1).all(1)] = 0.0
        return O, O1


class Approx:
    """An approximation piece A(s), s in [0, 1] (float64)."""

    def __init__(self, H):
        self.bez = Bez(H)
        self.mp_count = 0

    def jets(self, s):
        P, P1, _, _ = self.bez.jets(np.clip(np.asarray(s, float), 0.0, 1.0))
        P1 = np.where(np.isfinite(P1), P1, 0.0)
        return P, P1


# ---------------------------------------------------------------- distances

class Sampled:
    """A curve (Offset or Approx) sampled densely: parameters, points,
    derivatives, and a k-d tree of the points."""

    def __init__(self, curve, n):
        # n samples: half uniform in the parameter, half uniform in arc
        # length (measured on the first half's polygon), so that a part of
        # the curve swept fast (the offset around a tiny leg of its base)
        # is covered as densely as the rest
        h = max(n // 2, 2)
        s = np.linspace(0.0, 1.0, h)
        P, _ = curve.jets(s)
        seg = np.hypot(*np.diff(P, axis=0).T)
        seg[~np.isfinite(seg)] = 0.0
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        if cum[-1] > 0:
            s2 = np.interp(np.linspace(0.0, cum[-1], n - h + 2)[1:-1], cum, s)
            s = np.unique(np.concatenate([s, s2]))
        P, P1 = curve.jets(s)
        ok = np.isfinite(P).all(1)
        self.curve, self.s, self.P, self.P1 = curve, s[ok], P[ok], P1[ok]
        self.tree = cKDTree(self.P)
        self.h = np.diff(self.s).max() if len(self.s) > 1 else 1.0

    def min_dist(self, X, k=4, iters=8, nearest=None):
        """min_s |X_i - curve(s)| for points X (m, 2): from the nearest of
        the k nearest samples, and from each other one that lies apart from
        those before it (another stretch of the curve: a fold), a projection
        to the foot by damped Gauss-Newton (steps of at most 16 sample
        spacings, kept only where they bring the point nearer); the least."""
        X = np.asarray(X, float)
        k = min(k, len(self.s))
        if nearest is not None:
            dd, ii = nearest
        else:
            dd, ii = self.tree.query(X, k=k)
        if k == 1:
            dd, ii = dd[:, None], ii[:, None]
        best = dd[:, 0].copy()
        bs = self.s[ii[:, 0]].copy()
        for c in range(k):
            if c == 0:
                rows = np.arange(len(X))
            else:
                apart = np.ones(len(X), bool)
                for e in range(c):
                    apart &= np.abs(ii[:, c] - ii[:, e]) > 2
                rows = np.nonzero(apart)[0]
                if not len(rows):
                    continue
            x = X[rows]
            s = self.s[ii[rows, c]].copy()
            P, P1 = self.P[ii[rows, c]], self.P1[ii[rows, c]]
            dist = dd[rows, c].copy()
            lam = np.ones(len(rows))
            act = np.arange(len(rows))
            for _ in range(iters):
                if not len(act):
                    break
                r = x[act] - P[act]
                g = (P1[act] ** 2).sum(1)
                with np.errstate(divide="ignore", invalid="ignore"):
                    step = np.where(g > 0, (r * P1[act]).sum(1) / g, 0.0)
                step = np.clip(np.nan_to_num(step), -16 * self.h, 16 * self.h) * lam[act]
                s2 = np.clip(s[act] + step, 0.0, 1.0)
                moved = s2 != s[act]
                act, s2 = act[moved], s2[moved]
                if not len(act):
                    break
                Q, Q1 = self.curve.jets(s2)
                d2 = np.hypot(*(x[act] - Q).T)
                better = d2 < dist[act]
                ab = act[better]
                s[ab], P[ab], P1[ab], dist[ab] = s2[better], Q[better], Q1[better], d2[better]
                lam[ab] = 1.0
                lam[act[~better]] *= 0.25
                # converged rows: a step that changes the distance by nothing
                act = act[better | (lam[act] > 1e-3)]
            upd = dist < best[rows]
            best[rows[upd]] = dist[upd]
            bs[rows[upd]] = s[upd]
        return best, bs

    def min_dist_careful(self, x):
        """min over the curve of |x - curve(s)| for one point: every local
        minimum of the sampled distance that could hold the least (its
        distance minus the arc to the next samples below the best so far)
        is projected; returns the least distance and its s."""
        x = np.asarray(x, float)
        dist = np.hypot(*(self.P - x).T)
        chord = np.hypot(*np.diff(self.P, axis=0).T)
        lb = np.minimum(dist[:-1], dist[1:]) - 0.5 * chord * 1.01
        best, bs = self.min_dist(x[None, :], k=8, iters=8)
        best, bs = float(best[0]), float(bs[0])
        cand = np.nonzero(lb < best)[0]
        if len(cand) > 400:
            cand = cand[np.argsort(lb[cand])[:400]]
        for j in cand:
            lo, hi = self.s[max(j - 1, 0)], self.s[min(j + 2, len(self.s) - 1)]
            for _ in range(3):
                ss = np.linspace(lo, hi, 33)
                Q, _ = self.curve.jets(ss)
                dq = np.hypot(*(Q - x).T)
                m = int(dq.argmin())
                if dq[m] < best:
                    best, bs = float(dq[m]), float(ss[m])
                lo, hi = ss[max(m - 1, 0)], ss[min(m + 1, 32)]
            # polish by Gauss-Newton from the bracket's best
            s = bs if lo <= bs <= hi else 0.5 * (lo + hi)
            for _ in range(6):
                Q, Q1 = self.curve.jets(np.array([s]))
                g = float((Q1[0] ** 2).sum())
                if not g > 0:
                    break
                s2 = min(max(s + float(((x - Q[0]) * Q1[0]).sum()) / g, 0.0), 1.0)
                Q2, _ = self.curve.jets(np.array([s2]))
                d2 = float(np.hypot(*(x - Q2[0])))
                if d2 < best:
                    best, bs = d2, s2
                if s2 == s:
                    break
                s = s2
        return best, bs


def side_coarse(src, dst, top=4):
    """sup over src of min over dst (both Sampled), on src's samples:
    (value, [the (lo, hi) brackets of the top local maxima])."""
    s, X = src.s, src.P
    # branch and bound on the samples: a sampled distance (nearest sample)
    # bounds the projected one from above, so refine in decreasing order
    # until the refined max is above every sample not yet refined
    k = min(4, len(dst.s))
    D4, I4 = dst.tree.query(X, k=k)
    if k == 1:
        D4, I4 = D4[:, None], I4[:, None]
    dd = D4[:, 0]
    order = np.argsort(-dd)
    val = np.full(len(s), -np.inf)
    i, chunk = 0, 2048
    while i < len(order):
        idx = order[i:i + chunk]
        v, _ = dst.min_dist(X[idx], k=k, nearest=(D4[idx], I4[idx]))
        val[idx] = v
        i += chunk
        if i < len(order) and np.nanmax(val) >= dd[order[i]]:
            break
    fin = np.isfinite(val)
    cand = []
    for j in np.argsort(-np.where(fin, val, -np.inf)):
        if not fin[j]:
            break
        if all(abs(j - c) > 2 for c in cand):
            cand.append(j)
        if len(cand) >= top:
            break
    if not cand:
        return -np.inf, []
    last = len(s) - 1
    return float(val[cand[0]]), [(float(s[max(j - 1, 0)]), float(s[min(j + 1, last)])) for j in cand]


def side_refine(src, dst, cand, rounds=4, m=49):
    """the sup in each candidate bracket, by zooming: m points over the
    bracket, the best, a bracket 4 spacings wide around it, repeated; then
    the best point's inner min again, carefully (min_dist_careful)."""
    lo = np.array([c[0] for c in cand])
    hi = np.array([c[1] for c in cand])
    cb = np.full(len(cand), -np.inf)
    cbs = 0.5 * (lo + hi)
    for _ in range(rounds):
        ss = np.linspace(lo, hi, m).T  # (ncand, m)
        Y, _ = src.jets(ss.ravel())
        v, _ = dst.min_dist(Y, k=4, iters=6)
        v = np.where(np.isfinite(v), v, -np.inf).reshape(len(cand), m)
        j = v.argmax(1)
        vb = v[np.arange(len(cand)), j]
        up = vb > cb
        cb = np.where(up, vb, cb)
        cbs = np.where(up, ss[np.arange(len(cand)), j], cbs)
        w = (hi - lo) / (m - 1)
        lo, hi = np.maximum(cbs - 2 * w, 0.0), np.minimum(cbs + 2 * w, 1.0)
    # each candidate's best point again, its inner min carefully: the side's
    # value is the largest of those (an inner min that the fast projection
    # got wrong cannot make it)
    best, bs = -np.inf, 0.0
    Y, _ = src.jets(cbs)
    for k in np.argsort(-cb):
        if not np.isfinite(cb[k]) or cb[k] <= best:
            break
        v, _ = dst.min_dist_careful(Y[k])
        v = min(v, float(cb[k]))
        if v > best:
            best, bs = v, float(cbs[k])
    return best, bs


class PieceCheck:
    """One piece: the approximation A and the exact offset O of its base
    span, sampled; coarse() both sides, refine() around the top maxima."""

    def __init__(self, approx_h, base_h, d, a, b, t0, t1, n):
        Fa, Fb, F0, F1 = (Fraction(float(x)) for x in (a, b, t0, t1))
        ua = Fa + (Fb - Fa) * F0
        ub = Fa + (Fb - Fa) * F1
        self.n = n
        self.A = Approx(approx_h)
        self.O = Offset(base_h, d, ua, ub)
        self.SA = Sampled(self.A, n)
        self.SO = Sampled(self.O, n)

    def coarse(self):
        self.v1, self.c1 = side_coarse(self.SA, self.SO)
        self.v2, self.c2 = side_coarse(self.SO, self.SA)
        return max(self.v1, self.v2)

    def refine(self):
        r1 = side_refine(self.A, self.SO, self.c1)[0] if self.c1 else -np.inf
        r2 = side_refine(self.O, self.SA, self.c2)[0] if self.c2 else -np.inf
        return max(r1, r2)


# ---------------------------------------------------------------- jobs

def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def measure_job(task, near=0.9):
    """B of a job: every piece coarse, then the pieces whose coarse value is
    within `near` of the job's largest refined."""
    path, d, n = task["json"], task["d"], task["samples"]
    with open(path) as f:
        J = json.load(f)
    checks, coarse = [], []
    for p in J["pieces"]:
        if "base_homogeneous" not in p:
            raise ValueError("%s: a piece without base_homogeneous (an export of an older offbench)" % path)
        pc = PieceCheck(p["homogeneous"], p["base_homogeneous"], d, p["span"][0], p["span"][1],
                        p["t"][0], p["t"][1], n)
        coarse.append(pc.coarse())
        checks.append(pc)
    top = max(coarse) if coarse else -np.inf
    B = -np.inf
    for k in np.argsort(-np.array(coarse)):
        if coarse[k] < near * top:
            break
        B = max(B, checks[k].refine())
    mp_pieces = sum(1 for c in checks if c.O.all_mp or c.O.mp_count)
    return float(B), len(checks), mp_pieces, sum(c.O.mp_count for c in checks)


def judge(task):
    try:
        B, pieces, mpp, mpc = measure_job(task)
    except Exception as e:  # noqa: BLE001 - reported per job
        return dict(task, B=float("nan"), pieces=0, mp=0, flags="error:" + str(e).replace(",", ";"), sure="")
    lo, up, tol = task["err_lower"], task["err_upper"], task["tol"]
    flags, sure = [], ""
    if math.isfinite(up) and B > up * (1 + 1e-9) + 1e-15:
        flags.append("upper_violation")
    if math.isfinite(lo) and lo > B * (1 + 1e-6) + 1e-15:
        # B is a lower estimate: measure again with 10 x the samples
        B2, pieces, mpp, mpc = measure_job(dict(task, samples=10 * task["samples"]))
        sure = "refined %s -> %s" % (repr(B), repr(B2))
        B = max(B, B2)
        if lo > B * (1 + 1e-6) + 1e-15:
            flags.append("lower_violation")
        if math.isfinite(up) and B > up * (1 + 1e-9) + 1e-15 and "upper_violation" not in flags:
            flags.append("upper_violation")
    if task["certified"] == "yes" and B > tol:
        flags.append("verdict_violation")
    return dict(task, B=B, pieces=pieces, mp=mpp, flags=";".join(flags), sure=sure)


def load_tasks(run, exp, args):
    with open(os.path.join(exp, "index.csv")) as f:
        stems = {}
        for r in csv.DictReader(f):
            stems[(r["curve"], r["d"], r["method"], r["tol"])] = r["stem"]
    tasks = []
    with open(os.path.join(run, "results.csv")) as f:
        for r in csv.DictReader(f):
            if "err_upper" not in r:
                raise SystemExit("cert_brute: %s/results.csv has no err_upper: not a --certify run" % run)
            if r.get("err_upper", "") == "" and r.get("err_lower", "") == "":
                continue
            stem = stems.get((r["curve"], r["d"], r["method"], r["tol"]), "")
            if not stem:
                continue
            if args.family and r.get("family", "") not in args.family:
                continue
            if args.methods and r["method"] not in args.methods:
                continue
            if args.curves and r["curve"] not in args.curves:
                continue
            tasks.append(dict(curve=r["curve"], d=float(r["d"]), d_text=r["d"], method=r["method"],
                              tol=float(r["tol"]), tol_text=r["tol"], status=r["status"],
                              family=r.get("family", ""), err_lower=num(r["err_lower"]),
                              err_upper=num(r["err_upper"]), certified=r.get("certified", ""),
                              json=os.path.join(exp, stem + ".json"), samples=args.samples))
    if args.limit:
        tasks = tasks[:args.limit]
    return tasks


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="run directory of `offbench run --certify` (results.csv)")
    ap.add_argument("export", help="that run's --export directory (index.csv, STEM.json)")
    ap.add_argument("--out", help="CSV to write (default: RUN/cert_brute.csv)")
    ap.add_argument("--procs", type=int, default=os.cpu_count() or 1, help="worker processes (default: all cores)")
    ap.add_argument("--samples", type=int, default=20000, help="samples per piece per side (>= 20000 unless testing)")
    ap.add_argument("--family", type=lambda s: s.split(","), help="only these families (results.csv's family)")
    ap.add_argument("--methods", type=lambda s: s.split(","), help="only these methods")
    ap.add_argument("--curves", type=lambda s: s.split(","), help="only these curve ids")
    ap.add_argument("--limit", type=int, default=0, help="only the first N jobs")
    ap.add_argument("--verbose", action="store_true", help="print every flagged job")
    ap.add_argument("--progress", type=int, default=0, metavar="N", help="a line on stderr every N jobs")
    ap.add_argument("--mp-tiny-cprime", action="store_true",
                    help="also evaluate in mpmath wherever |C'| < 1e-6 of the control polygon's size")
    args = ap.parse_args(argv)
    global MP_TINY_CPRIME
    MP_TINY_CPRIME = args.mp_tiny_cprime
    if args.samples < 2:
        ap.error("--samples must be at least 2")
    try:
        tasks = load_tasks(args.run, args.export, args)
    except (OSError, KeyError) as e:
        print("cert_brute: %s" % e, file=sys.stderr)
        return 2
    # the most pieces first, so that the pool ends evenly
    sizes = {}
    for t in tasks:
        try:
            sizes[t["json"]] = os.path.getsize(t["json"])
        except OSError:
            sizes[t["json"]] = 0
    order = sorted(range(len(tasks)), key=lambda i: -sizes[tasks[i]["json"]])
    results = [None] * len(tasks)
    def progress(done):
        if args.progress and (done % args.progress == 0 or done == len(tasks)):
            print("cert_brute: %d/%d jobs" % (done, len(tasks)), file=sys.stderr, flush=True)

    if args.procs > 1 and len(tasks) > 1:
        with multiprocessing.Pool(args.procs) as pool:
            for done, (i, res) in enumerate(zip(order, pool.imap(judge, [tasks[i] for i in order], chunksize=1))):
                results[i] = res
                progress(done + 1)
    else:
        for done, i in enumerate(order):
            results[i] = judge(tasks[i])
            progress(done + 1)
    out = args.out or os.path.join(args.run, "cert_brute.csv")
    kinds = ["upper_violation", "lower_violation", "verdict_violation"]
    count = {k: 0 for k in kinds}
    errors = 0
    worst_up, worst_lo = (0.0, None), (0.0, None)
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["curve", "d", "method", "tol", "status", "pieces", "B", "err_lower", "err_upper",
                    "certified", "flags", "family", "mp_pieces", "note"])
        for r in results:
            w.writerow([r["curve"], r["d_text"], r["method"], r["tol_text"], r["status"], r["pieces"],
                        repr(r["B"]), repr(r["err_lower"]), repr(r["err_upper"]), r["certified"], r["flags"],
                        r["family"], r["mp"], r["sure"]])
            if r["flags"].startswith("error:"):
                errors += 1
                print("cert_brute: %s d=%s %s tol=%s: %s" % (r["curve"], r["d_text"], r["method"], r["tol_text"],
                                                             r["flags"]), file=sys.stderr)
                continue
            for k in kinds:
                if k in r["flags"].split(";"):
                    count[k] += 1
            B, lo, up = r["B"], r["err_lower"], r["err_upper"]
            if math.isfinite(up) and up > 0 and B / up > worst_up[0]:
                worst_up = (B / up, r)
            if B > 0 and math.isfinite(lo) and lo / B > worst_lo[0]:
                worst_lo = (lo / B, r)
            if args.verbose and r["flags"]:
                print("  %s d=%s %s tol=%s: B %.9g err_lower %.9g err_upper %.9g certified %s: %s %s" % (
                    r["curve"], r["d_text"], r["method"], r["tol_text"], B, lo, up, r["certified"], r["flags"],
                    r["sure"]))

    def who(x):
        r = x[1]
        return "" if r is None else " (%s d=%s %s tol=%s)" % (r["curve"], r["d_text"], r["method"], r["tol_text"])

    print("cert_brute: %d jobs checked%s; upper_violation %d, lower_violation %d, verdict_violation %d; "
          "worst B/err_upper %.9g%s, worst err_lower/B %.9g%s; wrote %s" % (
              len(results) - errors, (", %d errors" % errors) if errors else "", count["upper_violation"],
              count["lower_violation"], count["verdict_violation"], worst_up[0], who(worst_up), worst_lo[0],
              who(worst_lo), out))
    if errors:
        return 2
    return 1 if any(count.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
