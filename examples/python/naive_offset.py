"""A method of one's own (docs/python.md "Your method in Python"): move
each control point d along the normal of the control polygon there."""
import math

# what `offbench list methods` says of it (offbench/worker.py's serve)
METHOD = dict(citation="My naive offset (2026)", degree="same", continuity="G0")


def naive(piece, d, tol, **params):
    P = piece.points
    legs = [(b[0] - a[0], b[1] - a[1]) for a, b in zip(P, P[1:])]
    normals = [(-y / math.hypot(x, y), x / math.hypot(x, y)) for x, y in legs]
    # at an inner point, the mean of its two legs' normals
    at = [normals[0]] + [((m[0] + n[0]) / 2, (m[1] + n[1]) / 2) for m, n in zip(normals, normals[1:])]
    Q = [(p[0] + d * n[0], p[1] + d * n[1]) for p, n in zip(P, at + [normals[-1]])]
    return [{"points": Q, "weights": piece.weights}]
