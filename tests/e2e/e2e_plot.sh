#!/bin/sh
# End-to-end tests of scripts/plot.py on small runs of ./offbench: the SVG
# (default), PDF and PNG files it writes, family summaries instead of
# per-curve plots for random curves, --methods, --highlight, axis labels,
# --trace on a synthetic trace CSV, exit status 2 naming the file on bad
# input, and the message naming the interpreter without matplotlib.  Needs
# /usr/bin/python3 with matplotlib (Debian's python3-matplotlib); without it
# every check counts as skipped.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PLOT=$(cd "$(dirname "$0")/../.." && pwd)/scripts/plot.py
PY=/usr/bin/python3

NCHECKS=44
if ! "$PY" -c 'import matplotlib' >/dev/null 2>&1; then
    echo "e2e_plot: $PY cannot import matplotlib (apt-get install python3-matplotlib): skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0
fi

plot() { "$PY" "$PLOT" "$@"; }
is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
is_pdf() { [ -s "$1" ] && [ "$(head -c 5 "$1")" = "%PDF-" ]; }
is_svg() { [ -s "$1" ] && "$PY" -c 'import sys, xml.etree.ElementTree as E
sys.exit(0 if E.parse(sys.argv[1]).getroot().tag.endswith("svg") else 1)' "$1" 2>/dev/null; }
# the text of an SVG's <text> elements, one per line (text is kept as text)
svg_text() { "$PY" -c 'import sys, xml.etree.ElementTree as E
print("\n".join("".join(e.itertext()) for e in E.parse(sys.argv[1]).iter() if e.tag.endswith("}text")))' "$1"; }
# every file in $2 is listed in $1 (the printed paths) and vice versa
same_list() { ls "$2" | sed "s|^|$2/|" | sort > "$T/ls.txt"; sort "$1" | cmp -s - "$T/ls.txt"; }

# --- a published curve, default output directory beside results.csv: SVG ---
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-2,1e-3 --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/r/results.csv" ]' "offbench run on liu2002_ex1"
plot "$T/r/results.csv" >"$T/r.out" 2>"$T/r.err"
check '[ $? -eq 0 ]' "plot.py RESULTS.csv exits 0: $(cat "$T/r.err")"
P=$T/r/plots
for f in ctrl_liu2002_ex1_d1 ctrl_liu2002_ex1_d-1 time_per_job; do
    check 'is_svg "$P/$f.svg"' "$f.svg is an SVG document"
done
check '[ -z "$(ls "$P" | grep -v "\.svg$")" ]' "vector output by default: SVG only: $(ls "$P" | tr '\n' ' ')"
check '[ ! -e "$P/summary_families.svg" ]' "no family summary without random curves"
check 'same_list "$T/r.out" "$P" && [ "$(wc -l < "$T/r.out")" -eq 3 ]' "prints the 3 files written"
svg_text "$P/ctrl_liu2002_ex1_d1.svg" > "$T/labels.txt"
check 'grep -q "^tolerance (maximum error, curve units, log scale" "$T/labels.txt" && grep -q "^control points (count, log scale)" "$T/labels.txt"' \
    "axis labels with units, kept as text: $(grep -E "^(tolerance|control)" "$T/labels.txt" | tr '\n' ' ')"
check 'grep -q "^tiller" "$T/labels.txt" && grep -q "^ahn" "$T/labels.txt"' "both methods in the legend"
plot "$T/r/results.csv" --out "$T/pdf" --format pdf >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && is_pdf "$T/pdf/ctrl_liu2002_ex1_d1.pdf" && is_pdf "$T/pdf/time_per_job.pdf" && [ -z "$(ls "$T/pdf" | grep -v "\.pdf$")" ]' \
    "--format pdf: PDFs only: $(cat "$T/e.txt")"
plot "$T/r/results.csv" --out "$T/m1" --methods ahn >/dev/null 2>"$T/e.txt"
svg_text "$T/m1/ctrl_liu2002_ex1_d1.svg" > "$T/m1.txt"
check '[ $? -eq 0 ] && grep -q "^ahn" "$T/m1.txt" && ! grep -q "^tiller" "$T/m1.txt"' "--methods ahn: tiller left out: $(cat "$T/e.txt")"
plot "$T/r/results.csv" --out "$T/hl" --highlight ahn >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && is_svg "$T/hl/ctrl_liu2002_ex1_d1.svg" && is_svg "$T/hl/time_per_job.svg"' "--highlight ahn: $(cat "$T/e.txt")"
svg_text "$T/hl/ctrl_liu2002_ex1_d1.svg" > "$T/hl.txt"
check 'grep -q "^ahn" "$T/hl.txt" && grep -q "^other methods (grey): tiller" "$T/hl.txt"' "--highlight: the method, then the others in grey: $(tail -n 3 "$T/hl.txt" | tr '\n' ' ')"
check 'grep -q "stroke: *#1f77b4" "$T/hl/ctrl_liu2002_ex1_d1.svg" && grep -q "stroke: *#a6a6a6" "$T/hl/ctrl_liu2002_ex1_d1.svg" && [ "$(grep -c "stroke: *#ff7f0e" "$T/hl/ctrl_liu2002_ex1_d1.svg")" -eq 0 ]' \
    "--highlight: the method in colour, the rest grey"
plot "$T/r/results.csv" --out "$T/ep" --highlight nosuch >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--highlight.*nosuch" "$T/e.txt" && [ ! -e "$T/ep" ]' "--highlight of a method without rows: exit 2: $(cat "$T/e.txt")"
plot "$T/r/results.csv" --out "$T/ep" --methods tiller,nosuch >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--methods.*nosuch" "$T/e.txt" && [ ! -e "$T/ep" ]' "--methods with a method without rows: exit 2: $(cat "$T/e.txt")"
plot "$T/r/results.csv" --out "$T/ep" --methods ahn --highlight tiller >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--highlight" "$T/e.txt"' "--highlight of a method --methods leaves out: exit 2"

# --- random families: summaries by default, --per-curve, --max-curves, --curve, --formats ---
$OB run --random 12:3 --methods tiller,ahn --tols 1e-1,1e-2 --out "$T/q" 2>/dev/null
check '[ $? -eq 0 ]' "offbench run --random 12:3"
plot "$T/q/results.csv" --out "$T/qd" >"$T/qd.out" 2>"$T/qd.err"
check '[ $? -eq 0 ] && [ "$(ls "$T/qd" | tr "\n" " ")" = "summary_families.svg time_per_job.svg " ] && same_list "$T/qd.out" "$T/qd"' \
    "a random run: the family summary and the time, no per-curve files: $(ls "$T/qd" | head -n 5 | tr '\n' ' ')"
check 'grep -q "per-curve" "$T/qd.err"' "says how to get the per-curve plots: $(cat "$T/qd.err")"
svg_text "$T/qd/summary_families.svg" > "$T/fam.txt"
check 'grep -q "^tolerance (curve units, log scale" "$T/fam.txt" && grep -q "^control points (count, log scale)" "$T/fam.txt"' \
    "family summary axis labels with units"
plot "$T/q/results.csv" --out "$T/qp" --per-curve --max-curves 1 --formats png >"$T/q.out" 2>"$T/q.err"
check '[ $? -eq 0 ] && is_png "$T/qp/summary_families.png" && is_png "$T/qp/time_per_job.png"' \
    "summary_families.png and time_per_job.png: $(cat "$T/q.err")"
curves=$(ls "$T/qp" | sed -n 's/^ctrl_\(rnd3_[0-9]*\)_d.*\.png$/\1/p' | sort -u | tr '\n' ' ')
check '[ "$curves" = "rnd3_000000 " ]' "--per-curve --max-curves 1 plots one curve: '$curves'"
check '[ -z "$(ls "$T/qp" | grep -v "\.png$")" ] && same_list "$T/q.out" "$T/qp"' "--formats png writes only PNGs, all listed"
check '[ -z "$(ls "$T/qp" | grep -E "_d-?[0-9]*\.[0-9]{7,}")" ]' "file names carry d to 6 digits, not 17: $(ls "$T/qp" | grep ^ctrl_ | head -n 2 | tr '\n' ' ')"
# without matplotlib: a clear message naming the interpreter, a non-zero exit, not a traceback
mkdir -p "$T/nompl/matplotlib" && echo 'raise ImportError("matplotlib hidden by the test")' > "$T/nompl/matplotlib/__init__.py"
PYTHONPATH="$T/nompl" "$PY" "$PLOT" "$T/q/results.csv" --out "$T/nm" >/dev/null 2>"$T/nm.err"
check '[ $? -ne 0 ] && grep -q "^plot.py: matplotlib is not installed for $PY (Python 3\.[0-9]*); on Debian: apt-get install python3-matplotlib" "$T/nm.err" && ! grep -q Traceback "$T/nm.err"' \
    "plot.py without matplotlib names the interpreter and what to install: $(head -c 300 "$T/nm.err")"
plot "$T/q/results.csv" --out "$T/qc" --curve rnd3_000005 --formats svg >/dev/null 2>&1
check '[ $? -eq 0 ] && [ "$(ls "$T/qc" | grep ^ctrl_ | grep -vc ^ctrl_rnd3_000005_d)" -eq 0 ] && ls "$T/qc" | grep -q "^ctrl_rnd3_000005_d.*\.svg$" && is_svg "$T/qc/summary_families.svg"' \
    "--curve selects the curve"
plot "$T/q/results.csv" --out "$T/qh" --highlight tiller --methods ahn,tiller >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && is_svg "$T/qh/summary_families.svg"' "family summary with --highlight: $(cat "$T/e.txt")"
check 'grep -q "stroke: *#a6a6a6" "$T/qh/summary_families.svg" && grep -q "stroke: *#1f77b4" "$T/qh/summary_families.svg"' \
    "family summary: the highlighted method in colour, the other grey"

# --- a hand-made results file: quoted messages, limit / fail / skip rows ---
H=curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family
{ echo "$H"
  echo 'my/curve,0.5,m1,radial,mid,0.1,4,1,3,0.05,ok,100,2000,,published'
  echo 'my/curve,0.5,m1,radial,mid,0.01,40,13,3,0.02,limit,100,9000,"stalls, at t = 0",published'
  echo 'my/curve,0.5,m2,radial,mid,0.1,0,0,0,,fail,100,0,"singular, system",published'
  echo 'my/curve,0.5,m3,radial,mid,0.1,0,0,0,,skip,0,0,not applicable,published'; } > "$T/h.csv"
plot "$T/h.csv" --out "$T/hp" --format png,svg >"$T/h.out" 2>"$T/h.err"
check '[ $? -eq 0 ] && is_png "$T/hp/ctrl_my_curve_d0.5.png" && is_svg "$T/hp/ctrl_my_curve_d0.5.svg"' \
    "quoted messages, limit/fail/skip rows, a '/' in the id: $(cat "$T/h.err")"
{ echo "$H"; grep ',skip,' "$T/h.csv"; } > "$T/none.csv"
plot "$T/none.csv" --out "$T/np" >"$T/n.out" 2>"$T/n.err"
check '[ $? -eq 0 ] && [ ! -e "$T/np" ] && [ ! -s "$T/n.out" ] && grep -q "none.csv.*nothing written" "$T/n.err"' \
    "no plottable rows: exit 0, nothing written, says so"

# --- --trace on a synthetic trace (3 pieces) ---
"$PY" - "$T/trace.csv" <<'EOF'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("curve,d,method,metric,split,tol,seg,piece,t,u,err,x,y\n")
    for p, (a, b) in enumerate([(0, 0.25), (0.25, 0.5), (0.5, 1)]):
        for i in range(33):
            t = i / 32
            u = a + (b - a) * t
            err = 1e-9 + 8e-4 * t * (1 - t) * (p + 1) / 3
            f.write(f"liu2002_ex1,1,tiller,hausdorff,mid,0.001,0,{p},{u!r},{u!r},{err!r},"
                    f"{math.cos(u)!r},{math.sin(u)!r}\n")
EOF
plot --trace "$T/trace.csv" --out "$T/tp" >"$T/t.out" 2>"$T/t.err"
check '[ $? -eq 0 ] && is_svg "$T/tp/trace_liu2002_ex1_tiller.svg" && [ "$(ls "$T/tp" | wc -l)" -eq 1 ]' \
    "--trace writes trace_liu2002_ex1_tiller.svg: $(cat "$T/t.err")"
check 'same_list "$T/t.out" "$T/tp"' "--trace prints the files written"
sed '2s/,1e-09,/,0.0,/' "$T/trace.csv" > "$T/trace0.csv"   # an err of 0: linear axis
plot --trace "$T/trace0.csv" --out "$T/tp0" --formats png >/dev/null 2>&1
check '[ $? -eq 0 ] && is_png "$T/tp0/trace_liu2002_ex1_tiller.png"' "--trace with a zero error"

# --- bad input: exit 2 naming the file (and line) ---
plot "$T/nosuch.csv" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "nosuch.csv" "$T/e.txt"' "missing file: exit 2, named"
printf 'curve,d,method,tol\nx,1,m,0.1\n' > "$T/cols.csv"
plot "$T/cols.csv" --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "cols.csv:1: missing columns.*ctrl_points" "$T/e.txt" && [ ! -e "$T/ep" ]' \
    "missing column: exit 2, file:1 and the column"
{ echo "$H"; sed -n 2p "$T/h.csv"; sed -n 2p "$T/h.csv" | sed 's/,0\.1,/,0.1x,/'; } > "$T/num.csv"
plot "$T/num.csv" --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "num.csv:3: tol is not a number" "$T/e.txt" && [ ! -e "$T/ep" ]' \
    "malformed number: exit 2, file:line"
{ echo "$H"; sed -n 2p "$T/h.csv" | sed 's/,100,2000,/,100,2e3ns,/'; } > "$T/ns.csv"
plot "$T/ns.csv" --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "ns.csv:2: eval_ns is not a number" "$T/e.txt"' "malformed eval_ns: exit 2, file:line"
sed '5s/,0\.001,/,1e-3e,/' "$T/trace.csv" > "$T/tbad.csv"
plot --trace "$T/tbad.csv" --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "tbad.csv:5: tol is not a number" "$T/e.txt"' "malformed trace number: exit 2, file:line"
plot --trace "$T/r/results.csv" --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.csv:1: missing columns" "$T/e.txt"' "results.csv as a trace: exit 2, missing columns"
plot "$T/r/results.csv" --curve nosuch --out "$T/ep" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q "results.csv: no rows for curve nosuch" "$T/e.txt"' "--curve of an unknown curve: exit 2"
plot >/dev/null 2>&1
check '[ $? -eq 2 ]' "no input: exit 2"
plot "$T/r/results.csv" --out "$T/ep" --format gif >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && grep -q -- "--format" "$T/e.txt"' "--format of an unsupported format: exit 2"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
