"""report_commits.py - where scripts/report.py links a run's commit (docs/nightly.md
"Nightly history and report").

The link is a template with {sha} for the full commit id:
- NIGHTLY_COMMIT_URL (or report.py --commit-url), e.g.
  https://git.example.org/offbench/commit/{sha}; 'none' for no links;
- else from the checkout's `git remote get-url origin` when it names a
  GitHub or GitLab host (a host named github.com or gitlab.com, or one whose
  name holds "github" or "gitlab"), in its https, ssh:// or scp-like
  (git@host:path) form: https://HOST/PATH/commit/{sha} on GitHub,
  https://HOST/PATH/-/commit/{sha} on GitLab.  User names, passwords and
  tokens in the remote (GitLab CI's clone URL holds the job's token) are
  dropped, and an ssh port is not an https port: it is dropped too;
- else no links: the commit is plain text.
Only commit ids (7 to 64 hexadecimal digits) are linked."""

import os
import re
import subprocess
import urllib.parse

SHA = re.compile(r"^[0-9a-fA-F]{7,64}$")
ENV = "NIGHTLY_COMMIT_URL"


def template_from_remote(url):
    """The commit link template of a GitHub or GitLab remote URL, or None."""
    url = (url or "").strip()
    if not url:
        return None
    m = re.match(r"^(?:[^@/:]+@)?([A-Za-z0-9.-]+):(?!//)(.*)$", url)  # scp-like: [user@]host:path
    if m and "://" not in url:
        host, path = m.group(1), m.group(2)
    else:
        try:
            u = urllib.parse.urlsplit(url)
            host = u.hostname or ""
        except ValueError:
            return None
        if u.scheme not in ("https", "http", "ssh", "git", "git+ssh", "ssh+git"):
            return None
        path = u.path
    host = host.lower()
    path = path.strip("/")
    if path.endswith(".git"):
        path = path[:-4]
    path = path.strip("/")
    if not host or not path or not re.match(r"^[A-Za-z0-9._~/-]+$", path) or "/" not in path:
        return None
    if host == "github.com" or "github" in host:
        return "https://%s/%s/commit/{sha}" % (host, path)
    if host == "gitlab.com" or "gitlab" in host:
        return "https://%s/%s/-/commit/{sha}" % (host, path)
    return None


def git_remote(root):
    """`git remote get-url origin` in ROOT, or None (no git, no remote)."""
    try:
        p = subprocess.run(["git", "-C", root, "remote", "get-url", "origin"], capture_output=True, text=True,
                           timeout=10, env=dict(os.environ, GIT_TERMINAL_PROMPT="0"))
    except (OSError, subprocess.SubprocessError):
        return None
    return p.stdout.strip() if p.returncode == 0 else None


def check_template(t):
    """None when T is a usable template, else why not."""
    if "{sha}" not in t:
        return "%s=%r has no {sha}: no commit links" % (ENV, t)
    if not re.match(r"^https?://[^\s\"<>]+$", t):
        return "%s=%r is not an http(s) URL: no commit links" % (ENV, t)
    return None


def commit_template(env, remote):
    """(template or None, problem or None): from ENV[NIGHTLY_COMMIT_URL]
    when set ('none': none), else from remote() (the origin's URL or None)."""
    t = env.get(ENV, "")
    if t:
        if t == "none":
            return None, None
        problem = check_template(t)
        return (None, problem) if problem else (t, None)
    return template_from_remote(remote()), None


def commit_url(template, sha):
    """The link of commit SHA, or None (no template, not a commit id)."""
    if not template or not isinstance(sha, str) or not SHA.match(sha):
        return None
    return template.replace("{sha}", sha)
