#!/usr/bin/python3
"""ci_recipes_check.py ROOT - the lint of the CI recipes in ROOT/scripts/ci/
(docs/nightly.md "Nightly in CI"); run by tests/e2e/e2e_ci_recipes.sh.  Prints each
failure and the line "N passed, N failed[, N skipped]".

For github-nightly.yml (GitHub Actions) and gitlab-nightly.yml (GitLab CI):
- the file parses as YAML (PyYAML, Debian python3-yaml; without it every
  check counts as skipped, with the reason);
- a nightly schedule (a cron of five valid fields; GitLab's schedule lives
  in the project's settings: its jobs must run on schedule pipelines);
- every command of every run:/script: line exists: a script path of the
  repository (also as the argument of sh, bash or python3), a make target of
  the Makefile, a shell builtin, or a tool of the Debian image or installed
  by the recipe's own apt-get line (or by scripts/deps.sh); actions are
  first-party actions/* pinned to a major version; no ${{ }} expression
  inside a run: (they go through env:);
- the nightly is `sh scripts/nightly.sh` (never `make nightly`: make turns
  every failing exit status into 2), under a `timeout` below the job's own
  time limit (a night that runs long is killed by SIGTERM, which nightly.sh
  records as a failed night, and the steps after it still save the store
  and publish the site), and its exit status reaches the job:
  the lines are run, with stand-ins for the repository's scripts, for exit
  statuses 0 to 3, and the job must pass on 0, fail on 1 and 2, and warn on
  3 (docs/nightly.md: not comparable is a warning, the baseline needs accepting);
- the history store is restored before the nightly and saved after it even
  when the night fails (actions/cache restore/save; GitLab cache with
  when: always), and the site, written with --copy-files, is published
  (upload-pages-artifact and deploy-pages; the GitLab job "pages" with
  public/, run even after a failed night);
- every document the recipe cites (in its comments and messages too)
  exists, and so does the section it names: `docs/nightly.md "Nightly in
  CI"` (a heading of that text) or `docs/nightly.md#nightly-in-ci` (a
  heading with that anchor); the README, a front door, is cited only with
  the section meant.  (A reader sent to a section that is not there, as
  `README "Per-machine baselines"` once, finds nothing.)"""

import os
import re
import shlex
import subprocess
import sys
import tempfile

passed = failed = skipped = 0

BUILTINS = {"if", "then", "else", "elif", "fi", "for", "do", "done", "while", "until", "case", "esac", "in",
            "esac", "!", "{", "}", "[", "[[", "test", "echo", "printf", "exit", "cd", "export", "set", "unset", "true",
            "false", ":", "read", "return", "shift", "eval", "exec", "trap", "wait", "local", "."}
# Debian's required packages (in debian:* images) and the runner's own
BASE_TOOLS = {"sh", "bash", "cp", "mv", "rm", "mkdir", "rmdir", "ls", "cat", "tar", "gzip", "find", "xargs",
              "date", "du", "df", "head", "tail", "sed", "grep", "sort", "wc", "tee", "env", "id", "touch",
              "chmod", "ln", "apt-get", "dpkg", "dpkg-query", "uname", "hostname", "mktemp", "dirname",
              "basename", "sleep", "nproc", "cut", "tr", "diff", "cmp", "timeout"}
# tools a recipe may call once it installed their Debian package
PACKAGE_OF = {"git": "git", "gcc": "gcc", "cc": "gcc", "make": "make", "python3": "python3",
              "/usr/bin/python3": "python3", "curl": "curl", "unzip": "unzip", "zstd": "zstd"}
# what scripts/nightly.sh itself needs from the image: the build, the
# commit, the report
NIGHTLY_NEEDS = ("gcc", "make", "git", "python3")
STATUS_WANT = {0: "pass", 1: "fail", 2: "fail", 3: "warn"}


def check(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL: " + what, file=sys.stderr)


def commands(text):
    """The simple commands of shell TEXT as token lists (operators, keywords,
    assignments and redirections taken off); rough, but enough for the
    recipes' lines."""
    text = re.sub(r"\\\n", " ", text)
    out = []
    in_case = False  # between `case ... in` and `esac`: a word list before ) is a pattern
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        lx = shlex.shlex(line, posix=True, punctuation_chars=";&|()<>")
        lx.whitespace_split = True
        lx.commenters = "#"
        try:
            toks = list(lx)
        except ValueError:
            out.append(["<unparsable: %s>" % line])
            continue
        cur, skip_next = [], False
        for t in toks + [";"]:
            if skip_next:
                skip_next = False
                continue
            if t and set(t) <= set(";&|()"):
                if cur and not (in_case and t == ")"):
                    out.append(cur)
                    if cur[0] == "case":
                        in_case = True
                    elif cur[0] == "esac":
                        in_case = False
                cur = []
                continue
            if t and set(t) <= set("<>&") or re.match(r"^\d*[<>]+&?\d*$", t):
                skip_next = not re.search(r"&\d+$", t)
                continue
            if not cur and (t in ("if", "then", "else", "elif", "do", "while", "until", "!", "{")):
                continue
            if not cur and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", t):
                continue
            cur.append(t)
        if cur:
            out.append(cur)
    return out


def apt_packages(texts):
    """The packages of every `apt-get install` in TEXTS."""
    pk = set()
    for t in texts:
        for c in commands(t):
            if c and c[0] == "apt-get" and "install" in c:
                pk |= {w for w in c[c.index("install") + 1:] if not w.startswith("-")}
    return pk


def make_targets(root):
    with open(os.path.join(root, "Makefile"), encoding="utf-8") as f:
        return set(re.findall(r"^([A-Za-z0-9_.-]+)\s*:(?!=)", f.read(), re.M))


def deps_packages(root):
    with open(os.path.join(root, "scripts", "deps.sh"), encoding="utf-8") as f:
        return set(re.findall(r"\b(python3-[a-z0-9-]+|lib[a-z0-9-]+-dev|[a-z0-9-]+-opencl-icd|opencl-headers)\b",
                              f.read()))


def duration(text):
    """seconds of a time limit: timeout's 280m, 90s, 60; GitLab's 5h or 3h 30m"""
    parts = re.findall(r"(\d+(?:\.\d+)?)\s*([smhd]?)", str(text))
    if not parts or re.sub(r"[\d.\s]|[smhd]", "", str(text)):
        return None
    return sum(float(n) * {"": 1, "s": 1, "m": 60, "h": 3600, "d": 86400}[u] for n, u in parts)


def under_timeout(cmd):
    """(its limit in seconds, the command) of `timeout [OPTION]... DURATION
    COMMAND...`; (None, CMD) for any other command"""
    if cmd[:1] != ["timeout"]:
        return None, cmd
    i = 1
    while i < len(cmd) and cmd[i].startswith("-"):
        i += 2 if cmd[i] in ("-s", "--signal", "-k", "--kill-after") else 1
    return (duration(cmd[i]), cmd[i + 1:]) if i < len(cmd) else (None, [])


def command_problems(cmd, root, packages, targets):
    """Why the command CMD cannot run, or None."""
    w = cmd[0]
    if w.startswith("<unparsable"):
        return w
    if w == "timeout":
        limit, inner = under_timeout(cmd)
        return ("timeout: no limit or no command: %s" % " ".join(cmd) if limit is None or not inner
                else command_problems(inner, root, packages, targets))
    if w in BUILTINS:
        return None
    if w in ("sh", "bash", "python3", "/usr/bin/python3"):
        args = [a for a in cmd[1:] if not a.startswith("-")]
        if w in PACKAGE_OF and PACKAGE_OF[w] not in packages:
            return "%s: its package %s is not installed by the recipe" % (w, PACKAGE_OF[w])
        if args and ("/" in args[0] or re.search(r"\.(sh|py)$", args[0])):
            if not os.path.isfile(os.path.join(root, args[0])):
                return "%s %s: no such script in the repository" % (w, args[0])
        return None
    if w == "make":
        if "make" not in packages:
            return "make: not installed by the recipe"
        bad = [a for a in cmd[1:] if not a.startswith("-") and "=" not in a and a not in targets]
        if bad:
            return "make %s: no such target in the Makefile" % " ".join(bad)
        if any(a in ("nightly", "accept-baseline") for a in cmd[1:]):
            return "make %s: make turns every failing exit status into 2; call sh scripts/nightly.sh" % cmd[1]
        return None
    if "/" in w and not w.startswith("/"):
        return None if os.path.isfile(os.path.join(root, w)) else "%s: no such file in the repository" % w
    if w in PACKAGE_OF:
        return None if PACKAGE_OF[w] in packages else "%s: its package %s is not installed" % (w, PACKAGE_OF[w])
    if w in BASE_TOOLS:
        return None
    return "%s: not a known tool" % w


def lint_commands(name, texts, root, packages, job_limit):
    """the commands of TEXTS; job_limit: the nightly job's time limit, seconds"""
    targets = make_targets(root)
    n = 0
    for t in texts:
        for c in commands(t):
            p = command_problems(c, root, packages, targets)
            check(p is None, "%s: %s (in: %s)" % (name, p, " ".join(c)))
            n += 1
    check(n > 0, "%s: commands found" % name)
    for pk in NIGHTLY_NEEDS:
        check(pk in packages, "%s: installs %s (scripts/nightly.sh needs it)" % (name, pk))
    nightly = [under_timeout(c) for t in texts for c in commands(t) if "scripts/nightly.sh" in c]
    check(len(nightly) == 1 and nightly[0][1][:1] == ["sh"], "%s: one `sh scripts/nightly.sh`: %s" % (name, nightly))
    limit = nightly[0][0] if len(nightly) == 1 else None
    check(limit is not None and job_limit is not None and limit < job_limit,
          "%s: the nightly runs under `timeout` below the job's time limit (%s s), so that a night that runs "
          "long is recorded and the store still saved: its limit %s s" % (name, job_limit, limit))


def cron_ok(c):
    f = str(c).split()
    return len(f) == 5 and all(re.match(r"^(\*|\d+(-\d+)?)(/\d+)?(,(\*|\d+(-\d+)?)(/\d+)?)*$", x) for x in f)


def stub_tree(texts, root, tmp):
    """A scratch directory with stand-ins for every repository script the
    texts name: scripts/nightly.sh exits $FAKE_STATUS, the others 0."""
    for t in texts:
        for c in commands(t):
            for a in c:
                if "/" in a and not a.startswith("/") and os.path.isfile(os.path.join(root, a)):
                    p = os.path.join(tmp, a)
                    os.makedirs(os.path.dirname(p), exist_ok=True)
                    with open(p, "w") as f:
                        if a.endswith(".py"):  # leaves a mark: the report ran
                            f.write("import os\nopen(os.path.join(os.getcwd(), '.ran-' + os.path.basename(__file__)),"
                                    " 'w').close()\n")
                        elif a == "scripts/nightly.sh":
                            f.write('mkdir -p out/nightly history\necho "stand-in nightly: exit $FAKE_STATUS" >&2\n'
                                    'exit "$FAKE_STATUS"\n')
                        else:
                            f.write("exit 0\n")


def run_shell(text, cwd, env, shell):
    p = subprocess.run(shell + ["-c", text], cwd=cwd, env=env, capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout + p.stderr


def base_env(tmp):
    return {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "HOME": tmp, "LC_ALL": "C"}


def github(root, y):
    name = "github-nightly.yml"
    on = y.get("on", y.get(True))  # YAML 1.1 reads a bare `on` as true
    check(isinstance(on, dict), "%s: an `on:` mapping" % name)
    on = on if isinstance(on, dict) else {}
    crons = [s.get("cron") for s in on.get("schedule") or [] if isinstance(s, dict)]
    check(crons and all(cron_ok(c) for c in crons), "%s: a nightly schedule: %s" % (name, crons))
    perms = y.get("permissions") or {}
    check(perms.get("pages") == "write" and perms.get("id-token") == "write",
          "%s: permissions pages and id-token: write (deploy-pages): %s" % (name, perms))
    jobs = y.get("jobs") or {}
    check(isinstance(jobs, dict) and jobs, "%s: jobs" % name)
    steps = [s for j in jobs.values() if isinstance(j, dict) for s in j.get("steps") or []]
    runs = [s["run"] for s in steps if isinstance(s, dict) and "run" in s]
    for s in steps:
        u = s.get("uses")
        if u:
            check(re.match(r"^actions/[a-z-]+(/[a-z-]+)?@v\d+$", u) is not None,
                  "%s: %s: a first-party action pinned to a major version" % (name, u))
    for r in runs:
        check("${{" not in r, "%s: no ${{ }} inside a run: (use env:): %s" % (name, r.splitlines()[0]))
    limits = [60 * float(j.get("timeout-minutes", 360)) for j in jobs.values()
              if isinstance(j, dict) and "scripts/nightly.sh" in str(j.get("steps"))]
    lint_commands(name, runs, root, apt_packages(runs), limits[0] if limits else None)
    env = dict(y.get("env") or {})
    hist = str(env.get("NIGHTLY_HISTORY", "out/history"))
    k_n = next((k for k, s in enumerate(steps) if "scripts/nightly.sh" in str(s.get("run", ""))), None)
    check(k_n is not None and steps[k_n].get("id"), "%s: the nightly step has an id" % name)
    if k_n is None:
        return
    nid = steps[k_n]["id"]
    restore = [k for k, s in enumerate(steps) if str(s.get("uses", "")).startswith(("actions/cache/restore@",
                                                                                      "actions/cache@"))
               and str((s.get("with") or {}).get("path", "")).strip().rstrip("/") == hist.rstrip("/")]
    save = [k for k, s in enumerate(steps) if str(s.get("uses", "")).startswith("actions/cache/save@")
            and str((s.get("with") or {}).get("path", "")).strip().rstrip("/") == hist.rstrip("/")]
    check(restore and restore[0] < k_n, "%s: the history store (%s) restored before the nightly" % (name, hist))
    check(save and save[0] > k_n and re.search(r"always\(\)|!\s*cancelled\(\)", str(steps[save[0]].get("if", ""))),
          "%s: the history store saved after the nightly, also after a failed night" % name)
    if restore and save:
        rk, sk = (steps[restore[0]].get("with") or {}).get("key", ""), (steps[save[0]].get("with") or {}).get("key", "")
        prefix = (steps[restore[0]].get("with") or {}).get("restore-keys", "")
        check(rk == sk and prefix and str(sk).startswith(str(prefix).strip()) and "github.run_id" in str(sk),
              "%s: a new cache key per run, restored by its prefix (cache keys are immutable)" % name)
    rep = [k for k, s in enumerate(steps) if "scripts/report.py" in str(s.get("run", ""))]
    site = None
    if rep:
        c = next(c for c in commands(steps[rep[0]]["run"]) if "scripts/report.py" in c)
        site = c[c.index("--out") + 1] if "--out" in c else None
        check("--copy-files" in c and c[c.index("scripts/report.py") + 1] == hist,
              "%s: the site made from the store with --copy-files: %s" % (name, c))
    check(rep and rep[0] > k_n, "%s: the site written after the nightly" % name)
    up = [k for k, s in enumerate(steps) if str(s.get("uses", "")).startswith("actions/upload-pages-artifact@")]
    dep = [k for k, s in enumerate(steps) if str(s.get("uses", "")).startswith("actions/deploy-pages@")]
    check(up and dep and rep and rep[0] < up[0] < dep[0]
          and str((steps[up[0]].get("with") or {}).get("path", "")).rstrip("/") == str(site).rstrip("/"),
          "%s: the site uploaded and deployed to Pages" % name)
    for k in up + dep + rep:
        check(re.search(r"always\(\)|!\s*cancelled\(\)", str(steps[k].get("if", ""))),
              "%s: step %d (%s) runs after a failed night too" % (name, k, steps[k].get("uses") or "report"))
    # the exit status: the nightly step itself must pass (so that the
    # steps after it run) and hand the status to a later step that fails
    # the job on 1 and 2
    ref = re.compile(r"\$\{\{\s*steps\.%s\.outputs\.([A-Za-z_]+)\s*\}\}" % re.escape(nid))
    later = [k for k, s in enumerate(steps) if k > k_n
             and any(ref.search(str(v)) for v in list((s.get("env") or {}).values()) + [s.get("run", "")])]
    check(len(later) >= 1 and "run" in steps[later[-1]], "%s: a later step reads steps.%s.outputs" % (name, nid))
    if not later:
        return
    vk = later[-1]
    check(re.search(r"always\(\)|!\s*cancelled\(\)", str(steps[vk].get("if", ""))),
          "%s: the verdict step runs after a failed night too" % name)
    shell = ["bash", "--noprofile", "--norc", "-eo", "pipefail"]
    for st, want in STATUS_WANT.items():
        with tempfile.TemporaryDirectory() as tmp:
            stub_tree([steps[k_n]["run"]], root, tmp)
            e = dict(base_env(tmp), FAKE_STATUS=str(st), GITHUB_OUTPUT=os.path.join(tmp, "gh-output"))
            e.update({k: str(v) for k, v in env.items() if "${{" not in str(v)})
            e.update({k: str(v) for k, v in (steps[k_n].get("env") or {}).items() if "${{" not in str(v)})
            rc, log = run_shell(steps[k_n]["run"], tmp, e, shell)
            outs = {}
            if os.path.exists(e["GITHUB_OUTPUT"]):
                with open(e["GITHUB_OUTPUT"]) as f:
                    for line in f:
                        if "=" in line:
                            a, b = line.rstrip("\n").split("=", 1)
                            outs[a] = b
            check(rc == 0, "%s: the nightly step passes whatever nightly's exit (%d): rc %d %s" % (name, st, rc, log))
            ve = dict(base_env(tmp))
            for k, v in (steps[vk].get("env") or {}).items():
                ve[k] = ref.sub(lambda m: outs.get(m.group(1), ""), str(v))
            rc2, log2 = run_shell(ref.sub(lambda m: outs.get(m.group(1), ""), steps[vk]["run"]), tmp, ve, shell)
            got = "pass" if rc2 == 0 and "::warning" not in log2 else "warn" if rc2 == 0 else "fail"
            check(got == want, "%s: nightly exit %d: the job should %s, it would %s (%s)" % (name, st, want, got,
                                                                                          log2.strip()))


GITLAB_RESERVED = {"stages", "variables", "default", "workflow", "include", "image", "services", "cache",
                   "before_script", "after_script"}


def gitlab(root, y):
    name = "gitlab-nightly.yml"
    jobs = {k: v for k, v in y.items() if k not in GITLAB_RESERVED and not str(k).startswith(".")
            and isinstance(v, dict)}
    check(jobs, "%s: jobs" % name)
    texts = []
    for jn, j in jobs.items():
        for key in ("before_script", "script", "after_script"):
            v = j.get(key) or []
            v = [v] if isinstance(v, str) else v
            for x in v:
                # a plain `- echo "a: b"` is a mapping in YAML, not a line
                check(isinstance(x, str), "%s: %s: %s: a line of text, not %r (quote it)" % (name, jn, key, x))
            texts += [x for x in v if isinstance(x, str)]
    limits = [duration(j.get("timeout", "1h")) for j in jobs.values() if "scripts/nightly.sh" in str(j.get("script"))]
    lint_commands(name, texts, root, apt_packages(texts), limits[0] if limits else None)
    var = {k: str(v) for k, v in (y.get("variables") or {}).items()}
    hist = var.get("NIGHTLY_HISTORY", "out/history")
    nj = next((k for k, j in jobs.items() if any("scripts/nightly.sh" in str(x) for x in j.get("script") or [])),
              None)
    check(nj is not None, "%s: a job runs the nightly in its script" % name)
    if nj is None:
        return
    j = jobs[nj]
    rules = j.get("rules") or []
    check(any("$CI_PIPELINE_SOURCE" in str(r.get("if", "")) and "schedule" in str(r.get("if", "")) for r in rules),
          "%s: %s runs on schedule pipelines" % (name, nj))
    check(str(j.get("image", y.get("image", ""))).startswith("debian:"), "%s: a Debian image (scripts/deps.sh)" % name)
    cache = j.get("cache") or {}
    cache = cache[0] if isinstance(cache, list) and cache else cache
    paths = [str(p).rstrip("/") for p in (cache.get("paths") or [])] if isinstance(cache, dict) else []
    check(hist.rstrip("/") in paths and cache.get("when") == "always",
          "%s: the history store (%s) cached, also after a failed night: %s" % (name, hist, cache))
    af = j.get("allow_failure")
    codes = af.get("exit_codes") if isinstance(af, dict) else None
    codes = [codes] if isinstance(codes, int) else codes or []
    arts = j.get("artifacts") or {}
    check(arts.get("when") == "always" and "public" in [str(p).rstrip("/") for p in arts.get("paths") or []],
          "%s: the site (public/) kept as an artifact, also after a failed night" % name)
    rep = [c for t in j.get("script") or [] for c in commands(str(t)) if "scripts/report.py" in c]
    check(rep and "--copy-files" in rep[0] and rep[0][rep[0].index("--out") + 1].rstrip("/") == "public"
          and rep[0][rep[0].index("scripts/report.py") + 1].strip('"') in (hist, "$NIGHTLY_HISTORY"),
          "%s: the site written into public/ from the store with --copy-files: %s" % (name, rep))
    pages = jobs.get("pages")
    check(isinstance(pages, dict) and "public" in [str(p).rstrip("/") for p in
                                                   (pages.get("artifacts") or {}).get("paths") or []],
          "%s: a job named pages publishing public/" % name)
    if isinstance(pages, dict):
        needs = pages.get("needs") or []
        check(any((n == nj) or (isinstance(n, dict) and n.get("job") == nj and n.get("artifacts", True))
                  for n in needs), "%s: pages takes %s's artifacts" % (name, nj))
        whens = [r.get("when") for r in pages.get("rules") or []] + [pages.get("when")]
        check("always" in whens, "%s: pages runs after a failed night too" % name)
    # the exit status through the script's lines, as the runner runs them
    # (one shell, set -eo pipefail), with stand-ins for the scripts
    script = "\n".join(str(x) for x in j.get("script") or [])
    for st, want in STATUS_WANT.items():
        with tempfile.TemporaryDirectory() as tmp:
            stub_tree([script], root, tmp)
            e = dict(base_env(tmp), FAKE_STATUS=str(st))
            e.update({k: v for k, v in var.items() if "$" not in v})
            rc, log = run_shell(script, tmp, e, ["bash", "-eo", "pipefail"])
            got = "pass" if rc == 0 else "warn" if rc in codes else "fail"
            check(got == want, "%s: nightly exit %d: the job should %s, it would %s (exit %d; %s)"
                  % (name, st, want, got, rc, log.strip()))
            check(os.path.exists(os.path.join(tmp, ".ran-report.py")),
                  "%s: nightly exit %d: the site is written all the same" % (name, st))


CITE = re.compile(r'\b(README(?:\.md)?|docs/[\w./-]+\.md)(?:#([\w-]+)|\s+"([^"]+)")?')


def headings(path):
    """the headings of a markdown file (outside code fences): their text"""
    out, fence = [], False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if re.match(r" {0,3}(```|~~~)", line):
                fence = not fence
            elif not fence and re.match(r"#{1,6} ", line):
                out.append(line.lstrip("#").strip())
    return out


def anchor(text):
    """GitHub's anchor of a heading (as scripts/docs.py makes them)"""
    s = re.sub(r"[^\w\- ]", "", text.replace("`", "").replace("*", "").lower())
    return s.replace(" ", "-")


def lint_citations(root, name, text):
    """every document, section and anchor the recipe's text cites exists"""
    n = 0
    for m in CITE.finditer(text):
        doc, frag, section = m.group(1), m.group(2), m.group(3)
        if section:  # a title that goes on on the next comment line
            section = re.sub(r"\s*\n\s*#?\s*", " ", section)
        rel = "README.md" if doc.startswith("README") else doc
        path = os.path.join(root, rel)
        n += 1
        if not os.path.isfile(path):
            check(False, "%s: cites %s, which does not exist" % (name, doc))
            continue
        heads = headings(path)
        if frag:
            check(frag in [anchor(h) for h in heads], "%s: cites %s#%s: no heading of %s has that anchor"
                  % (name, doc, frag, rel))
        elif section:
            check(section.lower() in [h.lower() for h in heads], '%s: cites %s "%s": %s has no such section'
                  % (name, doc, section, rel))
        else:
            check(rel != "README.md", "%s: cites the README without the section meant (%s)"
                  % (name, text[max(0, m.start() - 40):m.end() + 10].replace("\n", " ")))
    check(n > 0, "%s: cites its documentation" % name)


def main(root):
    global skipped
    try:
        import yaml
    except ImportError:
        print("ci_recipes_check: no PyYAML (Debian python3-yaml): the recipes' checks skipped")
        skipped += 2
        return
    for fname, fn in (("github-nightly.yml", github), ("gitlab-nightly.yml", gitlab)):
        path = os.path.join(root, "scripts", "ci", fname)
        try:
            with open(path, encoding="utf-8") as f:
                y = yaml.safe_load(f)
        except (OSError, yaml.YAMLError) as e:
            check(False, "%s: %s" % (fname, e))
            continue
        check(isinstance(y, dict), "%s parses as a YAML mapping" % fname)
        if isinstance(y, dict):
            fn(root, y)
        with open(path, encoding="utf-8") as f:
            lint_citations(root, fname, f.read())


main(os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else ".")
print("%d passed, %d failed, %d skipped" % (passed, failed, skipped) if skipped else
      "%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
