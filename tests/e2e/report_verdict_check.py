#!/usr/bin/python3
"""report_verdict_check.py PAGE.html RUN.json [--methods M,M] [--regressed M]
- checks the nightly report's first section against the run's exit status
(tests/e2e/e2e_report.sh; the written page or Chromium's rendered DOM):

- the first <h2> of the page is inside <section id="latest">, before the
  steps and the history;
- its verdict (id="verdict") is the one of run.json's "status", the exit
  code of the nightly: data-status, the class verdict-WORD and the shown
  word (.verdict-word) follow 0 no regression, 1 regression, 2 error,
  3 not comparable, and the text says "exit status N";
- with --methods: the per-method comparison is an HTML <table
  class="compare-methods"> per run set with a row per method named (the
  first cell), none of it preformatted (no <pre> holding a markdown table
  in the section); with --regressed M: M's row says "regression".
Prints "ok" or every problem; exit 0 when all hold, 1 otherwise.  The
mapping is written out here, apart from scripts/report*.py, on purpose."""

import json
import sys
from html.parser import HTMLParser

WORDS = {0: ("ok", "no regression"), 1: ("regression", "regression"), 2: ("error", "error"),
         3: ("not-comparable", "not comparable")}
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


class Node:
    def __init__(self, tag, attrs, parent):
        self.tag, self.attrs, self.parent = tag, dict(attrs), parent
        self.children = []  # Node or str

    def text(self):
        return "".join(c if isinstance(c, str) else c.text() for c in self.children)

    def walk(self):
        yield self
        for c in self.children:
            if isinstance(c, Node):
                yield from c.walk()

    def classes(self):
        return (self.attrs.get("class") or "").split()


class Tree(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.root = Node("#root", [], None)
        self.cur = self.root

    def handle_starttag(self, tag, attrs):
        n = Node(tag, attrs, self.cur)
        self.cur.children.append(n)
        if tag not in VOID:
            self.cur = n

    def handle_startendtag(self, tag, attrs):
        self.cur.children.append(Node(tag, attrs, self.cur))

    def handle_endtag(self, tag):
        n = self.cur
        while n is not None and n.tag != tag:
            n = n.parent
        if n is not None and n.parent is not None:
            self.cur = n.parent

    def handle_data(self, data):
        self.cur.children.append(data)


def inside(node, ancestor):
    while node is not None:
        if node is ancestor:
            return True
        node = node.parent
    return False


def main(argv):
    page, runjson = argv[0], argv[1]
    methods, regressed = [], None
    i = 2
    while i < len(argv):
        if argv[i] == "--methods":
            methods = argv[i + 1].split(",")
        elif argv[i] == "--regressed":
            regressed = argv[i + 1]
        i += 2
    with open(runjson, encoding="utf-8") as f:
        status = json.load(f)["status"]
    t = Tree()
    with open(page, encoding="utf-8") as f:
        t.feed(f.read())
    nodes = list(t.root.walk())
    problems = []
    latest = next((n for n in nodes if n.attrs.get("id") == "latest"), None)
    h2 = [n for n in nodes if n.tag == "h2"]
    if latest is None or latest.tag != "section":
        problems.append("no <section id=\"latest\">")
    elif not h2 or not inside(h2[0], latest):
        problems.append("the first <h2> (%r) is not in the latest section" % (h2[0].text() if h2 else None))
    v = next((n for n in nodes if n.attrs.get("id") == "verdict"), None)
    cls, word = WORDS.get(status, ("unknown", "exit %s" % status))
    if v is None:
        problems.append("no element id=\"verdict\"")
    else:
        if latest is not None and not inside(v, latest):
            problems.append("the verdict is not in the latest section")
        if v.attrs.get("data-status") != str(status):
            problems.append("verdict data-status %r, run.json's status %r" % (v.attrs.get("data-status"), status))
        if "verdict-" + cls not in v.classes():
            problems.append("verdict class %r lacks verdict-%s" % (v.attrs.get("class"), cls))
        w = [n for n in v.walk() if "verdict-word" in n.classes()]
        shown = " ".join(w[0].text().split()).lower() if w else None
        if shown != word:
            problems.append("verdict word %r, not %r (status %s)" % (shown, word, status))
        if "exit status %s" % status not in " ".join(v.text().split()):
            problems.append("verdict text %r lacks 'exit status %s'" % (" ".join(v.text().split()), status))
    if latest is not None:
        for p in (n for n in latest.walk() if n.tag == "pre"):
            if "|---" in p.text():
                problems.append("a markdown table preformatted in the latest section")
        tables = [n for n in latest.walk() if n.tag == "table" and "compare-methods" in n.classes()]
        if methods:
            if not tables:
                problems.append("no <table class=\"compare-methods\"> in the latest section")
            for tb in tables:
                rows = [r for r in tb.walk() if r.tag == "tr"]
                head = [c.text().strip() for c in rows[0].walk() if c.tag == "th"] if rows else []
                if not head or head[0] != "method" or "verdict" not in head:
                    problems.append("table %s: header %r" % (tb.attrs.get("data-set"), head))
                    continue
                vcol = head.index("verdict")
                cells = {}
                for r in rows[1:]:
                    c = [x for x in r.children if isinstance(x, Node) and x.tag in ("td", "th")]
                    if len(c) == len(head):
                        cells[c[0].text().strip()] = c[vcol].text().strip()
                if sorted(cells) != sorted(methods):
                    problems.append("table %s: methods %r, not %r" % (tb.attrs.get("data-set"), sorted(cells),
                                                                      sorted(methods)))
                if regressed and tb.attrs.get("data-set") == "published" \
                        and not cells.get(regressed, "").startswith("regression"):
                    problems.append("table published: %s's verdict %r" % (regressed, cells.get(regressed)))
    if problems:
        print("; ".join(problems))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
