#!/usr/bin/env python3
"""tiller.py - Tiller & Hanson 1984 as an external method: a line-for-line
port of methods/tiller.c through the protocol of docs/external-methods.md.

    ./offbench run --external tiller_py="python3 examples/external/tiller.py"

Its rows are the built-in tiller's, bit for bit (tests/e2e/e2e_external.sh):
the same operations in the same order on the same doubles, and hypot from
the C library that methods/tiller.c calls (Python's math.hypot is its own
algorithm, which may differ in the last bit).
"""

import ctypes
import ctypes.util
import importlib.util
import os

# offbench/worker.py by its path: the package's __init__ needs numpy and the
# C library, a worker needs neither
_spec = importlib.util.spec_from_file_location(
    "offbench_worker", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python", "offbench",
                                    "worker.py"))
_worker = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_worker)
Fail, serve = _worker.Fail, _worker.serve

_libm = ctypes.CDLL(ctypes.util.find_library("m") or "libm.so.6")
_libm.hypot.restype = ctypes.c_double
_libm.hypot.argtypes = (ctypes.c_double, ctypes.c_double)
hypot = _libm.hypot


def leg_directions(P):
    """Unit leg directions; a collapsed leg borrows its neighbour's."""
    n = len(P) - 1
    u = [None] * n
    have = -1
    for i in range(n):
        dx, dy = P[i + 1][0] - P[i][0], P[i + 1][1] - P[i][1]
        ln = hypot(dx, dy)
        if ln > 0:
            u[i] = (dx / ln, dy / ln)
            if have < 0:
                for k in range(i):
                    u[k] = u[i]
            have = i
        elif have >= 0:
            u[i] = u[have]
    if have < 0:
        raise Fail("control polygon collapses to a point")
    return u


def fit(piece, d, tol, **params):
    P, n = piece.points, piece.degree
    u = leg_directions(P)
    nrm = [(-a[1], a[0]) for a in u]
    Q = [(P[0][0] + d * nrm[0][0], P[0][1] + d * nrm[0][1])]
    for i in range(1, n):
        A = (P[i][0] + d * nrm[i - 1][0], P[i][1] + d * nrm[i - 1][1])
        B = (P[i][0] + d * nrm[i][0], P[i][1] + d * nrm[i][1])
        cr = u[i - 1][0] * u[i][1] - u[i - 1][1] * u[i][0]
        if abs(cr) < 1e-12:
            Q.append(A)  # parallel legs: the shared translated point
        else:
            s = ((B[0] - A[0]) * u[i][1] - (B[1] - A[1]) * u[i][0]) / cr
            Q.append((A[0] + s * u[i - 1][0], A[1] + s * u[i - 1][1]))
    Q.append((P[n][0] + d * nrm[n - 1][0], P[n][1] + d * nrm[n - 1][1]))
    return [{"points": Q, "weights": piece.weights}]


# serve's metadata; also what `offbench/worker.py tiller.py:fit` reads
METHOD = dict(citation="Tiller & Hanson 1984, IEEE CG&A 4(9):36-46 (Python port)", degree="same",
              continuity="G0", caps=["poly_out", "rational_in", "same_param", "interp_ends"])

if __name__ == "__main__":
    serve(fit, **METHOD)
