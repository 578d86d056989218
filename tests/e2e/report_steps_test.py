#!/usr/bin/python3
"""report_steps_test.py - unit checks of scripts/report_steps.py (the step
rule) and of scripts/report_data.py's reading of results.csv by column
name; run by tests/e2e/e2e_report.sh.  Prints "N passed, N failed"."""

import os
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the checkout
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import report_data  # noqa: E402
from report_steps import Point, quality_steps, time_steps  # noqa: E402

passed = failed = 0


def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL: " + what, file=sys.stderr)


def q(ctrls, fails=None, limits=None, jobs=None):
    """Points of a quality series."""
    n = len(ctrls)
    fails, limits, jobs = fails or [0] * n, limits or [0] * n, jobs or ["j"] * n
    return [Point(i, jobs[i], ctrls[i], fails[i], limits[i]) for i in range(n)]


def t(times, machines=None, jobs=None):
    """Points of a time series."""
    n = len(times)
    machines, jobs = machines or ["m"] * n, jobs or ["j"] * n
    return [Point(i, jobs[i], time_ns=times[i], machine=machines[i]) for i in range(n)]


def idx(steps, kind=None):
    return [s[0] for s in steps if kind is None or s[1] == kind]


def quality_checks():
    check(quality_steps(q([10, 10, 10, 10])) == [], "flat ctrl: no step")
    s = quality_steps(q([10, 10, 10, 12, 12]))
    check(idx(s) == [3] and s[0][1] == "quality" and "ctrl 10 -> 12" in s[0][2], "ctrl change: one step at 3: %s" % s)
    check(idx(quality_steps(q([10, 10, 9]))) == [2], "ctrl down is a step too")
    check(idx(quality_steps(q([10, 10, 10], fails=[0, 1, 1]))) == [1], "a new failure is a step")
    check(idx(quality_steps(q([10, 10, 10], limits=[2, 2, 0]))) == [2], "a limit gone is a step")
    s = quality_steps(q([10, 10, 30, 30], jobs=["a", "a", "b", "b"]))
    check(idx(s, "jobs") == [2] and idx(s, "quality") == [], "a job change is marked 'jobs', not a step: %s" % s)
    # runs missing in between (a failed night): compared with the last run present
    pts = [Point(0, "j", 10), Point(3, "j", 10), Point(4, "j", 11)]
    check(idx(quality_steps(pts)) == [4], "gaps: the step at the run index 4")


def time_checks():
    check(time_steps(t([100, 101, 99, 100, 102, 100])) == [], "noise: no time step")
    s = time_steps(t([100, 100, 100, 150, 150, 150]))
    check(idx(s) == [3] and s[0][1] == "time", "time +50 %%: one step at 3, not after: %s" % s)
    check(idx(time_steps(t([100, 100, 100, 60]))) == [3], "time -40 %: a step")
    check(time_steps(t([100, 100, 150])) == [], "2 previous runs: no verdict")
    check(time_steps(t([100, 105, 108, 109])) == [], "+9 % against the median: below 10 %")
    check(time_steps(t([90, 130, 100, 125])) == [], "+25 % but inside the previous range: no step")
    check(time_steps(t([100, 100, 100, 200], machines=["a", "a", "a", "b"])) == [], "another machine: not compared")
    check(time_steps(t([100, 100, 100, 200], jobs=["a", "a", "a", "b"])) == [], "other jobs: not compared")
    # the window: only the last 5 previous runs count
    s = time_steps(t([300, 300, 300, 100, 100, 100, 100, 100, 150]))
    check(idx(s) == [3, 8], "window of 5: the old level forgotten: %s" % s)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def data_checks(tmp):
    """results.csv read by column name: the same figures in any column
    order, quoted messages with commas, FILE:LINE on bad numbers."""
    a = ("curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message\n"
         "c1,1,m,hausdorff,mid,0.1,10,3,3,0.01,ok,100,50,\n"
         "c1,1,m,hausdorff,mid,0.01,20,6,3,0.001,limit,200,50,\"depth, limit\"\n"
         "c1,1,n,hausdorff,mid,0.1,0,0,0,,fail,5,0,\"singular, sorry\"\n")
    b = ("message,status,eval_ns,fit_ns,ctrl_points,tol,split,metric,method,d,curve,extra\n"
         ",ok,50,100,10,0.1,mid,hausdorff,m,1,c1,x\n"
         "\"depth, limit\",limit,50,200,20,0.01,mid,hausdorff,m,1,c1,y\n"
         "\"singular, sorry\",fail,0,5,0,0.1,mid,hausdorff,n,1,c1,z\n")
    write(os.path.join(tmp, "a.csv"), a)
    write(os.path.join(tmp, "b.csv"), b)
    ma = report_data.read_results(os.path.join(tmp, "a.csv"))
    mb = report_data.read_results(os.path.join(tmp, "b.csv"))
    for m in ma.values():
        m["jobs"] = sorted(m["jobs"])
    for m in mb.values():
        m["jobs"] = sorted(m["jobs"])
    check(ma == mb, "column order changes the figures: %s vs %s" % (ma, mb))
    m = ma.get("m", {})
    check(m.get("ctrl") == 30 and m.get("limit") == 1 and m.get("time_ns") == 400, "method m: %s" % m)
    check(ma.get("n", {}).get("fail") == 1, "method n: one failure")
    write(os.path.join(tmp, "c.csv"), a.replace(",ok,100,50,", ",ok,1x0,50,"))
    try:
        report_data.read_results(os.path.join(tmp, "c.csv"))
        check(False, "a bad fit_ns is not an error")
    except ValueError as e:
        check("c.csv:2: fit_ns" in str(e), "the error names FILE:LINE: %s" % e)
    write(os.path.join(tmp, "d.csv"), "curve,d,method\nc,1,m\n")
    try:
        report_data.read_results(os.path.join(tmp, "d.csv"))
        check(False, "missing columns are not an error")
    except ValueError as e:
        check("d.csv:1: no column" in str(e) and "ctrl_points" in str(e), "missing columns named: %s" % e)


quality_checks()
time_checks()
with tempfile.TemporaryDirectory() as d:
    data_checks(d)
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
