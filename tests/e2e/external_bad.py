#!/usr/bin/env python3
"""external_bad.py MODE - an external method (docs/external-methods.md) that
is examples/external/tiller.py except for d = -1, where it misbehaves in one
way, MODE (tests/e2e/e2e_external.sh): crash, hang, spin, mem, garbage,
nan, inf, wrongid, huge, baddeg, badweight, error, params, skip."""
import importlib.util
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("tiller_port", os.path.join(HERE, "..", "..", "examples", "external",
                                                                          "tiller.py"))
tiller = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tiller)
worker = tiller._worker
MODE = sys.argv[1]


def bad(req):
    """The line sent for a d = -1 request, or None to answer as tiller."""
    i, n = req["id"], req["degree"]
    pts = [[0.0, 0.0]] * (n + 1)
    if MODE == "crash":
        sys.exit(1)
    if MODE == "hang":
        time.sleep(600)
    if MODE == "spin":
        while True:
            pass
    if MODE == "mem":
        return json.dumps({"id": i, "pieces": [{"degree": n, "points": pts, "junk": [0.0] * (400 << 20)}]})
    if MODE == "garbage":
        return "hello, this is not JSON"
    if MODE == "nan":
        return '{"id": %d, "pieces": [{"degree": %d, "points": %s}]}' % (i, n, json.dumps([[float("nan"), 0.0]] * (n + 1)))
    if MODE == "inf":
        return '{"id": %d, "pieces": [{"degree": %d, "points": [[1e999, 0]%s]}]}' % (i, n, ",[0,0]" * n)
    if MODE == "wrongid":
        return json.dumps({"id": i + 7, "pieces": [{"degree": n, "points": pts}]})
    if MODE == "huge":
        return json.dumps({"id": i, "pieces": [{"degree": n, "points": pts}] * 100})
    if MODE == "baddeg":
        return json.dumps({"id": i, "pieces": [{"degree": n + 1, "points": pts + [[0.0, 0.0]]}]})
    if MODE == "badweight":
        return json.dumps({"id": i, "pieces": [{"degree": n, "points": pts, "weights": [-1.0] * (n + 1)}]})
    if MODE == "error":
        return json.dumps({"id": i, "error": "no offset for d = -1 here"})
    if MODE == "params":
        return json.dumps({"id": i, "error": "params %s" % json.dumps(req["params"], sort_keys=True)})
    if MODE == "skip":
        return json.dumps({"id": i, "error": "d = -1 does not apply", "status": "skip"})
    raise SystemExit("external_bad.py: unknown mode " + MODE)


def main():
    print(json.dumps({"protocol": 1, "citation": "a broken worker (" + MODE + ")", "degree": "same",
                      "continuity": "G0", "caps": ["poly_out", "rational_in"],
                      "params": [{"name": "scale", "default": 1, "min": 0, "max": 10, "doc": "unused"}]}), flush=True)
    for line in sys.stdin:
        req = json.loads(line)
        out = bad(req) if req["d"] == -1 else None
        print(out if out is not None else worker._answer(lambda b, d, tol, scale: tiller.fit(b, d, tol), req), flush=True)


main()
