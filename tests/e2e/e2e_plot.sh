#!/bin/sh
# End-to-end tests of scripts/plot.py on small runs of ./offbench: the PNG and
# SVG files it writes, --trace on a synthetic trace CSV, and exit status 2
# naming the file on bad input.  Needs /usr/bin/python3 with matplotlib
# (Debian's python3-matplotlib); without it every check counts as skipped.
# Uses $OFFBENCH (set by make) or ./offbench.
. "$(dirname "$0")/lib_e2e.sh"
PLOT=$(cd "$(dirname "$0")/../.." && pwd)/scripts/plot.py
PY=/usr/bin/python3

NCHECKS=30
if ! "$PY" -c 'import matplotlib' >/dev/null 2>&1; then
    echo "e2e_plot: $PY cannot import matplotlib (apt-get install python3-matplotlib): skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0
fi

plot() { "$PY" "$PLOT" "$@"; }
is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
is_svg() { [ -s "$1" ] && "$PY" -c 'import sys, xml.etree.ElementTree as E
sys.exit(0 if E.parse(sys.argv[1]).getroot().tag.endswith("svg") else 1)' "$1" 2>/dev/null; }
# every file in $2 is listed in $1 (the printed paths) and vice versa
same_list() { ls "$2" | sed "s|^|$2/|" | sort > "$T/ls.txt"; sort "$1" | cmp -s - "$T/ls.txt"; }

# --- a published curve, default output directory beside results.csv ---
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e-1,1e-2,1e-3 --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ] && [ -s "$T/r/results.csv" ]' "offbench run on liu2002_ex1"
plot "$T/r/results.csv" >"$T/r.out" 2>"$T/r.err"
check '[ $? -eq 0 ]' "plot.py RESULTS.csv exits 0: $(cat "$T/r.err")"
P=$T/r/plots
for f in ctrl_liu2002_ex1_d1 ctrl_liu2002_ex1_d-1 time_per_job; do
    check 'is_png "$P/$f.png"' "$f.png is a PNG"
    check 'is_svg "$P/$f.svg"' "$f.svg is an SVG document"
done
check '[ ! -e "$P/summary_families.png" ]' "no family summary without random curves"
check 'same_list "$T/r.out" "$P" && [ "$(wc -l < "$T/r.out")" -eq 6 ]' "prints the 6 files written"

# --- random families: summary, --max-curves, --curve, --formats ---
$OB run --random 12:3 --methods tiller,ahn --tols 1e-1,1e-2 --out "$T/q" 2>/dev/null
check '[ $? -eq 0 ]' "offbench run --random 12:3"
plot "$T/q/results.csv" --out "$T/qp" --max-curves 1 --formats png >"$T/q.out" 2>"$T/q.err"
check '[ $? -eq 0 ] && is_png "$T/qp/summary_families.png" && is_png "$T/qp/time_per_job.png"' \
    "summary_families.png and time_per_job.png: $(cat "$T/q.err")"
curves=$(ls "$T/qp" | sed -n 's/^ctrl_\(rnd3_[0-9]*\)_d.*\.png$/\1/p' | sort -u | tr '\n' ' ')
check '[ "$curves" = "rnd3_000000 " ]' "--max-curves 1 plots one curve: '$curves'"
check '[ -z "$(ls "$T/qp" | grep -v "\.png$")" ] && same_list "$T/q.out" "$T/qp"' "--formats png writes only PNGs, all listed"
check '[ -z "$(ls "$T/qp" | grep -E "_d-?[0-9]*\.[0-9]{7,}")" ]' "file names carry d to 6 digits, not 17: $(ls "$T/qp" | grep ^ctrl_ | head -n 2 | tr '\n' ' ')"
# without matplotlib: a clear message and a non-zero exit, not a traceback
mkdir -p "$T/nompl/matplotlib" && echo 'raise ImportError("matplotlib hidden by the test")' > "$T/nompl/matplotlib/__init__.py"
PYTHONPATH="$T/nompl" "$PY" "$PLOT" "$T/q/results.csv" --out "$T/nm" >/dev/null 2>"$T/nm.err"
check '[ $? -ne 0 ] && grep -q "matplotlib is not installed: apt-get install python3-matplotlib" "$T/nm.err" && ! grep -q Traceback "$T/nm.err"' \
    "plot.py without matplotlib says what to install: $(head -c 200 "$T/nm.err")"
plot "$T/q/results.csv" --out "$T/qc" --curve rnd3_000005 --formats svg >/dev/null 2>&1
check '[ $? -eq 0 ] && [ "$(ls "$T/qc" | grep ^ctrl_ | grep -vc ^ctrl_rnd3_000005_d)" -eq 0 ] && ls "$T/qc" | grep -q "^ctrl_rnd3_000005_d.*\.svg$" && is_svg "$T/qc/summary_families.svg"' \
    "--curve selects the curve"

# --- a hand-made results file: quoted messages, limit / fail / skip rows ---
H=curve,d,method,metric,split,tol,ctrl_points,segments,out_degree,max_err,status,fit_ns,eval_ns,message,family
{ echo "$H"
  echo 'my/curve,0.5,m1,radial,mid,0.1,4,1,3,0.05,ok,100,2000,,published'
  echo 'my/curve,0.5,m1,radial,mid,0.01,40,13,3,0.02,limit,100,9000,"stalls, at t = 0",published'
  echo 'my/curve,0.5,m2,radial,mid,0.1,0,0,0,,fail,100,0,"singular, system",published'
  echo 'my/curve,0.5,m3,radial,mid,0.1,0,0,0,,skip,0,0,not applicable,published'; } > "$T/h.csv"
plot "$T/h.csv" --out "$T/hp" >"$T/h.out" 2>"$T/h.err"
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
check '[ $? -eq 0 ] && is_png "$T/tp/trace_liu2002_ex1_tiller.png" && is_svg "$T/tp/trace_liu2002_ex1_tiller.svg"' \
    "--trace writes trace_liu2002_ex1_tiller.png/.svg: $(cat "$T/t.err")"
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

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
