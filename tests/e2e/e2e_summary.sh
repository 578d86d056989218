#!/bin/sh
# End-to-end tests of ./offbench summary RUN_DIR on real small runs: the
# Markdown tables against results.csv (each curve cell, each family median
# and quartiles recomputed here by Python's statistics module, whose
# 'inclusive' quartiles are R's type 7), CSV and LaTeX, --out, the filters,
# --sections, --baseline, and bad input (exit 2 naming the file, line or
# option; exit 1 for an output that cannot be written).
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3

$OB run --random 8:3 --methods tiller,cobb --tols 1e-1,1e-2 --threads 2 --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/r/results.csv" ]' "offbench run --random 8:3"
$OB run --random 8:3 --methods tiller,cobb --tols 1e-1,1e-2 --metric radial --threads 2 --out "$T/b" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/b/results.csv" ]' "offbench run --random 8:3 --metric radial (the baseline)"

# --- Markdown to stdout ---
$OB summary "$T/r" >"$T/s.md" 2>"$T/s.err"
check '[ $? -eq 0 ] && [ ! -s "$T/s.err" ]' "summary RUN_DIR exits 0: $(head -c 300 "$T/s.err")"
for h in "# Summary of $T/r/results.csv" "## Control points per curve and d" "## Control points per family" \
         "## Time and failures per method" "| curve | d | tol | tiller | cobb |" "| family | pairs | tol | tiller | cobb |" \
         "| method | jobs | ok | limit | fail | skip | timeout | time/job (ms) |"; do
    check 'grep -qxF -- "$h" "$T/s.md"' "Markdown has the line '$h'"
done
njobs=$(($(wc -l <"$T/r/results.csv") - 1))
check 'grep -q "^$njobs jobs on .* of 8 curves in 8 families; methods tiller, cobb; tolerances 0.1, 0.01; metric hausdorff, split mid.$" "$T/s.md"' \
    "the scope line: $(grep ' jobs on ' "$T/s.md")"
# every job's cell as results.csv has it: ctrl_points when ok, else the status
"$PY" - "$T/r/results.csv" "$T/s.md" >"$T/cells.txt" 2>&1 <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
want = {}
for r in rows:
    want[(r["curve"], float(r["d"]), r["method"], float(r["tol"]))] = r["ctrl_points"] if r["status"] == "ok" else r["status"]
lines = open(sys.argv[2]).read().split("## Control points per family")[0].splitlines()
head = next(l for l in lines if l.startswith("| curve |"))
methods = [c.strip() for c in head.strip("|").split("|")][3:]
got, curve, d, bad = {}, None, None, 0
for l in lines[lines.index(head) + 2:]:
    if not l.startswith("|"):
        break
    c = [x.strip() for x in l.strip("|").split("|")]
    curve = c[0] or curve
    d = float(c[1]) if c[1] else d
    for m, v in zip(methods, c[3:]):
        got[(curve, d, m, float(c[2]))] = v
# d is printed to 6 digits: match each job to the printed pair nearest it
for (cv, dv, m, t), v in want.items():
    keys = [k for k in got if k[0] == cv and k[2] == m and k[3] == t and abs(k[1] - dv) <= 1e-5 * max(1, abs(dv))]
    if len(keys) != 1 or got[keys[0]] != v:
        bad += 1
        print("differs:", cv, dv, m, t, v, [got[k] for k in keys])
print(f"{len(want)} jobs, {len(got)} cells, {bad} differ")
EOF
check 'grep -q "^$njobs jobs, $njobs cells, 0 differ$" "$T/cells.txt"' "every cell is its job's: $(tail -n 3 "$T/cells.txt")"
# every family cell: median [q1, q3] of the ok jobs (type 7), (k non-ok)
"$PY" - "$T/r/results.csv" "$T/s.md" >"$T/fam.txt" 2>&1 <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def g(v):
    return f"{v:.6g}"
want = {}
for fam in dict.fromkeys(r["family"] for r in rows):
    for m in dict.fromkeys(r["method"] for r in rows):
        for t in dict.fromkeys(r["tol"] for r in rows):
            sel = [r for r in rows if (r["family"], r["method"], r["tol"]) == (fam, m, t)]
            ok = sorted(float(r["ctrl_points"]) for r in sel if r["status"] == "ok")
            if len(ok) >= 2:
                q1, med, q3 = statistics.quantiles(ok, n=4, method="inclusive")
            elif ok:
                q1 = med = q3 = ok[0]
            cell = f"{g(med)} [{g(q1)}, {g(q3)}]" if ok else "-"
            nonok = len(sel) - len(ok)
            want[(fam, m, float(t))] = cell + (f" ({nonok} non-ok)" if nonok else "")
text = open(sys.argv[2]).read().split("## Control points per family")[1].split("## Time")[0]
lines = [l for l in text.splitlines() if l.startswith("|")]
methods = [c.strip() for c in lines[0].strip("|").split("|")][3:]
got, fam = {}, None
for l in lines[2:]:
    c = [x.strip() for x in l.strip("|").split("|")]
    fam = c[0] or fam
    for m, v in zip(methods, c[3:]):
        got[(fam, m, float(c[2]))] = v
bad = [k for k in want if got.get(k) != want[k]]
for k in bad:
    print("differs:", k, repr(want[k]), repr(got.get(k)))
print(f"{len(want)} family cells, {len(bad)} differ")
EOF
check 'grep -q "^32 family cells, 0 differ$" "$T/fam.txt"' "every family cell (8 families x 2 methods x 2 tols): $(tail -n 3 "$T/fam.txt")"
ntiller=$(awkc 'NR>1 && $c["method"]=="tiller"' "$T/r/results.csv" | wc -l)
check 'grep -q "^| tiller | $ntiller | " "$T/s.md"' "the method table counts tiller's $ntiller jobs"

# --- a results.csv operand; --out; CSV; LaTeX ---
$OB summary "$T/r/results.csv" >"$T/s2.md" 2>/dev/null
check '[ $? -eq 0 ] && cmp -s "$T/s.md" "$T/s2.md"' "RUN_DIR/results.csv as the operand: the same summary"
$OB summary "$T/r" --out "$T/out.md" >"$T/o.out" 2>&1
check '[ $? -eq 0 ] && [ ! -s "$T/o.out" ] && cmp -s "$T/s.md" "$T/out.md"' "--out FILE: the same text, nothing on stdout"
$OB summary "$T/r" --format csv >"$T/s.csv" 2>/dev/null
check '[ $? -eq 0 ] && [ "$(head -n 1 "$T/s.csv")" = "section,family,curve,d,method,tol,status,value,q1,q3,n,n_nonok,base_status,base_value,base_q1,base_q3,base_n,ratio" ]' \
    "CSV header: $(head -n 1 "$T/s.csv")"
check '[ "$(grep -c ^curve, "$T/s.csv")" -eq $njobs ] && [ "$(grep -c ^family, "$T/s.csv")" -eq 32 ] && [ "$(grep -c ^time, "$T/s.csv")" -eq 2 ] && [ "$(grep -c ^status, "$T/s.csv")" -eq 10 ]' \
    "CSV: a line per job, family cell, method time and method status"
"$PY" -c 'import csv, sys
r = list(csv.reader(open(sys.argv[1])))
sys.exit(0 if all(len(x) == 18 for x in r) else 1)' "$T/s.csv"
check '[ $? -eq 0 ]' "CSV: 18 fields on every line"
$OB summary "$T/r" --format latex >"$T/s.tex" 2>/dev/null
check '[ $? -eq 0 ] && [ "$(grep -c "^\\\\toprule$" "$T/s.tex")" -eq 3 ] && [ "$(grep -c "^\\\\bottomrule$" "$T/s.tex")" -eq 3 ] && [ "$(grep -c "^\\\\begin{tabular}" "$T/s.tex")" -eq 3 ]' \
    "LaTeX: three booktabs tabulars"
check '[ -z "$(grep -v "^%" "$T/s.tex" | grep "[^\\\\]_")" ] && grep -q "^rnd3\\\\_000000 & " "$T/s.tex"' "LaTeX: every _ escaped"

# --- filters and sections ---
$OB summary "$T/r" --methods cobb --curves rnd3_000001,rnd3_000006 >"$T/f.md" 2>"$T/f.err"
check '[ $? -eq 0 ] && grep -qxF "| curve | d | tol | cobb |" "$T/f.md" && [ "$(grep -c "^| rnd3_" "$T/f.md")" -eq 2 ] && grep -q "^| rnd3_000006 |" "$T/f.md"' \
    "--methods cobb --curves two ids: $(head -c 200 "$T/f.err")"
check 'grep -q "^| quintic | " "$T/f.md" && grep -q "^| loop | " "$T/f.md" && [ "$(grep -cE "^\| (cubic|septic|tight) \|" "$T/f.md")" -eq 0 ]' \
    "the families of the chosen curves only"
$OB summary "$T/r" --family loop --sections families,methods >"$T/l.md" 2>/dev/null
check '[ $? -eq 0 ] && ! grep -q "| curve |" "$T/l.md" && [ "$(grep -c "^| [a-z]* | [0-9]* | 0.1 |" "$T/l.md")" -eq 1 ] && grep -q "^| loop | " "$T/l.md"' \
    "--family loop --sections families,methods"
$OB summary "$T/r" --methods cobb,tiller --sections curves >"$T/o.md" 2>/dev/null
check 'grep -qxF "| curve | d | tol | cobb | tiller |" "$T/o.md"' "--methods gives the column order"
$OB summary "$T/r" --metric=hausdorff --split=mid --format=md >"$T/m.md" 2>/dev/null
check '[ $? -eq 0 ] && cmp -s "$T/s.md" "$T/m.md"' "--metric and --split of the run: the same summary"

# --- a baseline ---
$OB summary "$T/r" --baseline "$T/b" >"$T/bl.md" 2>"$T/bl.err"
check '[ $? -eq 0 ] && grep -qxF "| curve | d | tol | tiller | base | new/base | cobb | base | new/base |" "$T/bl.md"' \
    "--baseline: a base and new/base column beside each method: $(head -c 200 "$T/bl.err")"
check 'grep -qxF "Baseline: $T/b/results.csv (metric radial, split mid): $njobs of $njobs jobs joined." "$T/bl.md"' \
    "the baseline named, every job joined: $(grep ^Baseline "$T/bl.md")"
check 'grep -qF "| base ok | base time/job (ms) | new/base |" "$T/bl.md"' "the method table beside the baseline's"
$OB summary "$T/r" --baseline "$T/r" --format csv >"$T/self.csv" 2>/dev/null
check '[ $? -eq 0 ] && [ -z "$(awk -F, "NR>1 && (\$1==\"curve\" || \$1==\"family\") && \$8!=\"\" && \$18!=\"1\"" "$T/self.csv")" ]' \
    "a run beside itself: every ratio 1"

# --- bad input ---
$OB summary "$T/nosuch" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "nosuch" "$T/e.txt"' "a missing run: exit 2, named: $(cat "$T/e.txt")"
mkdir -p "$T/bad"
awk 'NR==3{sub(/,ok,/, ",okay,")} {print}' "$T/r/results.csv" >"$T/bad/results.csv"
$OB summary "$T/bad" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "bad/results.csv:3: status" "$T/e.txt"' "a malformed results.csv: exit 2, FILE:LINE: $(cat "$T/e.txt")"
$OB summary "$T/r" --methods tiller,nosuch >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods: unknown method .nosuch." "$T/e.txt"' "an unknown method: exit 2: $(cat "$T/e.txt")"
$OB summary "$T/r" --methods lee >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods: no rows of method .lee." "$T/e.txt"' "a method the run lacks: exit 2: $(cat "$T/e.txt")"
$OB summary "$T/r" --curves rnd3_000099 >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--curves: no rows of curve .rnd3_000099." "$T/e.txt"' "an unknown curve: exit 2"
$OB summary "$T/r" --family nosuch >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--family" "$T/e.txt"' "an unknown family: exit 2"
$OB summary "$T/r" --metric radial >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--metric: no rows with metric .radial." "$T/e.txt"' "a metric the run lacks: exit 2"
$OB summary "$T/r" --format pdf >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--format" "$T/e.txt"' "--format pdf: exit 2"
$OB summary "$T/r" --sections nosuch >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--sections" "$T/e.txt"' "--sections nosuch: exit 2"
$OB summary "$T/r" --methods tiller,tiller >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods: .tiller. is listed twice" "$T/e.txt"' "a method twice: exit 2"
$OB summary "$T/r" --baseline "$T/nosuch" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "nosuch" "$T/e.txt"' "a missing baseline: exit 2, named"
$OB summary >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "RUN_DIR" "$T/e.txt"' "no operand: exit 2"
$OB summary "$T/r" "$T/b" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ]' "two operands: exit 2"
cp "$T/r/results.csv" "$T/keep.csv"
$OB summary "$T/r" --out "$T/r/results.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && cmp -s "$T/r/results.csv" "$T/keep.csv"' "--out over the input: exit 2, the input kept: $(cat "$T/e.txt")"
$OB summary "$T/r" --out "$T/nodir/x.md" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 1 ] && grep -q "nodir" "$T/e.txt"' "an output that cannot be written: exit 1: $(cat "$T/e.txt")"
$OB summary --help >"$T/h.out" 2>"$T/h.err"
check '[ $? -eq 0 ] && grep -q "usage: ./offbench summary RUN_DIR" "$T/h.out" && grep -q -- "--baseline" "$T/h.out" && [ ! -s "$T/h.err" ]' \
    "summary --help: exit 0, on stdout"
$OB help | grep -q "offbench summary"
check '[ $? -eq 0 ]' "offbench help lists summary"

e2e_done
