#!/usr/bin/python3
"""Put the tables written by `./offbench tables` into the README.

Usage: scripts/readme_tables.py TABLES_MD README_MD

Replaces everything between the marker lines
    <!-- tables:begin -->
    <!-- tables:end -->
in README_MD (the markers stay) with TABLES_MD, minus its first line if that
is a level-1 heading ("# ..."), and with every heading demoted one level
("## X" becomes "### X") so the tables sit under the README's own
"## Reproduced tables".  Headings inside ``` or ~~~ fences are left alone.
The README is written atomically (temporary file + rename) and only when it
changes; running it twice gives the same README.  Exits 2 with a message if a
file is unreadable or the markers are missing, duplicated or out of order.
"""
import os
import re
import sys
import tempfile

BEGIN = "<!-- tables:begin -->"
END = "<!-- tables:end -->"


def die(msg):
    print(f"readme_tables: {msg}", file=sys.stderr)
    sys.exit(2)


def read(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as e:
        die(f"cannot read {path}: {getattr(e, 'strerror', None) or e}")


def demoted(text, path):
    """The body of tables.md: leading '# title' dropped, headings demoted."""
    lines = text.replace("\r\n", "\n").split("\n")
    while lines and not lines[0].strip():
        lines.pop(0)
    if lines and re.match(r"# ", lines[0]):
        lines.pop(0)
    out, fence = [], None
    for line in lines:
        if line.strip() in (BEGIN, END):
            die(f"{path} contains the marker line {line.strip()}")
        m = re.match(r" {0,3}(```|~~~)", line)
        if m and (fence is None or m.group(1) == fence):
            fence = None if fence else m.group(1)
        elif fence is None and re.match(r"#{1,5}( |$)", line):
            line = "#" + line
        out.append(line)
    return "\n".join(out).strip("\n")


def markers(lines, path):
    """The indices of the begin and end marker lines, checked."""
    begins = [i for i, l in enumerate(lines) if l.strip() == BEGIN]
    ends = [i for i, l in enumerate(lines) if l.strip() == END]
    for name, found in ((BEGIN, begins), (END, ends)):
        if not found:
            die(f"{path}: marker line {name} is missing")
        if len(found) > 1:
            where = ", ".join(str(i + 1) for i in found)
            die(f"{path}: marker line {name} appears {len(found)} times (lines {where})")
    if ends[0] < begins[0]:
        die(f"{path}:{ends[0] + 1}: {END} comes before {BEGIN} (line {begins[0] + 1})")
    return begins[0], ends[0]


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().split("\n\n")[1], file=sys.stderr)
        sys.exit(2)
    tables_md, readme = argv[1], argv[2]
    body = demoted(read(tables_md), tables_md)
    old = read(readme)
    lines = old.split("\n")
    b, e = markers(lines, readme)
    new_lines = lines[:b + 1] + [""] + ([body, ""] if body else []) + lines[e:]
    new = "\n".join(new_lines)
    if new == old:
        print(f"{readme}: unchanged")
        return
    directory = os.path.dirname(os.path.abspath(readme))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".readme_tables.", dir=directory)
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
            f.write(new)
        os.chmod(tmp, os.stat(readme).st_mode & 0o7777)
        os.replace(tmp, readme)
    except OSError as err:
        if "tmp" in locals() and os.path.exists(tmp):
            os.unlink(tmp)
        die(f"cannot write {readme}: {err}")
    print(f"{readme}: tables updated from {tables_md}")


if __name__ == "__main__":
    main(sys.argv)
