"""report_steps.py - the step rule of scripts/report.py (docs/nightly.md "Nightly
history and report"), apart from the HTML so that a test can check it.

A step is a run where a method's figures for one run set (published,
random) change from the runs before it:

- quality: the summed control points (ctrl_points over the method's rows),
  the failures (status fail or timeout) or the limits (status limit) differ
  from the previous run that has the same jobs.  Any change is a step: the
  figures are exact, the same code gives the same numbers.
- time: the method's total time T (fit_ns + eval_ns summed over its rows;
  with --reps each row holds the median of its repetitions) is compared
  with the previous K = 5 runs on the same machine (host, CPU model, thread
  count, backend) with the same jobs, once there are at least 3 of them: a step when
  |T - median| > 10 % of their median AND T lies outside their range
  (min..max), so that one noisy run in the window does not mark the next.
- the jobs themselves (curves, offsets, tolerances, metric, split of the
  method's rows) changing is not a step but a "jobs" mark: the figures are
  not comparable across it.
"""

import statistics

TIME_WINDOW = 5        # K: previous runs the time is compared with
TIME_MIN_PREVIOUS = 3  # fewer previous comparable runs: no time verdict
TIME_THRESHOLD = 0.10  # relative change of the total against their median


class Point:
    """One run's figures for one (set, method); absent runs are not points."""

    def __init__(self, index, jobs, ctrl=0, fail=0, limit=0, time_ns=0, machine=""):
        self.index = index      # position of the run in run order
        self.jobs = jobs        # signature of the method's job keys
        self.ctrl = ctrl
        self.fail = fail        # status fail or timeout
        self.limit = limit
        self.time_ns = time_ns
        self.machine = machine  # runs with other machines' timings differ


def quality_steps(points):
    """Returns [(index, kind, text)] for the points (in run order): kind
    "quality" where ctrl, fail or limit changed from the previous point with
    the same jobs, "jobs" where the job set changed."""
    out = []
    prev = None
    for p in points:
        if prev is not None and p.jobs != prev.jobs:
            out.append((p.index, "jobs", "the jobs changed: not compared"))
        elif prev is not None:
            parts = []
            for name in ("ctrl", "fail", "limit"):
                a, b = getattr(prev, name), getattr(p, name)
                if a != b:
                    parts.append("%s %d -> %d" % (name, a, b))
            if parts:
                out.append((p.index, "quality", ", ".join(parts)))
        prev = p
    return out


def time_steps(points, window=TIME_WINDOW, min_previous=TIME_MIN_PREVIOUS,
               threshold=TIME_THRESHOLD):
    """Returns [(index, "time", text)] for the points whose total time
    leaves the previous comparable runs (see the module's header)."""
    out = []
    for i, p in enumerate(points):
        prev = [q.time_ns for q in points[:i]
                if q.machine == p.machine and q.jobs == p.jobs and q.time_ns > 0]
        prev = prev[-window:]
        if len(prev) < min_previous or p.time_ns <= 0:
            continue
        med = statistics.median(prev)
        rel = (p.time_ns - med) / med
        outside = p.time_ns > max(prev) or p.time_ns < min(prev)
        if abs(rel) > threshold and outside:
            out.append((p.index, "time", "%+.0f %% against the median of the %d runs before (%s .. %s ms)"
                        % (100 * rel, len(prev), fmt_ms(min(prev)), fmt_ms(max(prev)))))
    return out


def fmt_ms(ns):
    """ns as milliseconds: 3 significant digits, whole ones from 100 ms."""
    ms = ns / 1e6
    return "%.0f" % ms if abs(ms) >= 100 else "%.3g" % ms


def rule_text():
    """The rule as one paragraph, for the page itself."""
    return ("Quality: a step is any change of a method's summed control points (ctrl_points), "
            "failures (status fail or timeout) or limits (status limit) from the previous run "
            "with the same jobs. Time: the method total (fit_ns + eval_ns over its rows; with "
            "--reps the rows hold the median of the repetitions) is a step when it differs by "
            "more than %d %% from the median of the previous %d runs on the same machine "
            "(host, CPU, threads, backend) with the same jobs, needs at least %d of them, and lies "
            "outside their range. A change of the jobs themselves is marked 'jobs' and not "
            "compared across." % (round(100 * TIME_THRESHOLD), TIME_WINDOW, TIME_MIN_PREVIOUS))
