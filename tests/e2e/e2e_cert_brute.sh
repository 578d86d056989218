#!/bin/sh
# scripts/cert_brute.py (issue 47), the independent brute-force judge of
# run --certify: on a tiny certified run of an ordinary curve it finds no
# violation (err_lower <= B <= err_upper up to its slack, on every job with
# an approximation); and it can fail: the same run with one job's err_upper
# lowered below the distance is an upper_violation (exit 1), with err_lower
# raised above it a lower_violation, with a tol below it and certified yes a
# verdict_violation.  Skipped when /usr/bin/python3 lacks numpy, scipy or
# mpmath.
. "$(dirname "$0")/lib_e2e.sh"
NTESTS=8
PY=${CERT_BRUTE_PYTHON:-/usr/bin/python3}
# fewer samples than the script's default (20000 per piece and side): a
# smoke test of the checker, not a measurement
NS=${CERT_BRUTE_SAMPLES:-4000}
SCRIPT=$(cd "$(dirname "$0")/../.." && pwd)/scripts/cert_brute.py
if ! "$PY" -c 'import numpy, scipy.spatial, mpmath' >/dev/null 2>&1; then
    echo "e2e_cert_brute: $PY does not import numpy, scipy and mpmath: skipped"
    echo "0 passed, 0 failed, $NTESTS skipped"
    exit 0
fi
$OB run --curve liu2002_ex1 --methods tiller,ahn --tols 1e-2 --backend cpu --threads 2 \
    --certify --out "$T/r" --export "$T/x" >/dev/null 2>"$T/r.err"
check '[ $? -eq 0 ]' "the run: $(cat "$T/r.err")"
napprox=$(awkc 'NR>1 && ($c["status"]=="ok" || $c["status"]=="limit")' "$T/r/results.csv" | wc -l)
"$PY" "$SCRIPT" --samples "$NS" "$T/r" "$T/x" --procs 2 --out "$T/b.csv" >"$T/b.out" 2>"$T/b.err"
rc=$?
check '[ $rc -eq 0 ] && grep -q "^cert_brute: $napprox jobs checked; upper_violation 0, lower_violation 0, verdict_violation 0" "$T/b.out"' \
    "no violation on an ordinary curve ($napprox jobs; exit $rc): $(cat "$T/b.out" "$T/b.err")"
# every row: flags empty and err_lower <= B <= err_upper within the slack
bad=$("$PY" - "$T/b.csv" <<'EOF'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    B, lo, up = float(r["B"]), float(r["err_lower"]), float(r["err_upper"])
    if r["flags"] or not (lo <= B * (1 + 1e-6) + 1e-15 and B <= up * (1 + 1e-9) + 1e-15) or not B > 0:
        print(r["curve"], r["d"], r["method"], r["tol"], B, lo, up, r["flags"])
EOF
)
check '[ -z "$bad" ] && [ "$(($(wc -l <"$T/b.csv") - 1))" -eq "$napprox" ]' "err_lower <= B <= err_upper on every job: $bad"
# a results.csv doctored by (column, factor, also certified=yes) on the
# first job with an approximation: the checker must see it
doctor() {
    rm -rf "$T/$1" && mkdir "$T/$1" && cp "$T/r/meta.json" "$T/$1/"
    "$PY" - "$T/r/results.csv" "$T/$1/results.csv" "$2" "$3" <<'EOF'
import csv, sys
src, dst, col, factor = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
rows = list(csv.reader(open(src)))
h = rows[0]
for r in rows[1:]:
    if r[h.index("status")] in ("ok", "limit"):
        r[h.index(col)] = repr(float(r[h.index(col)]) * factor)
        r[h.index("certified")] = "yes"
        print(r[h.index("curve")], r[h.index("d")], r[h.index("method")], r[h.index("tol")], file=sys.stderr)
        break
csv.writer(open(dst, "w", newline=""), lineterminator="\n").writerows(rows)
EOF
}
doctor up err_upper 0.9 2>"$T/up.job"
"$PY" "$SCRIPT" --samples "$NS" "$T/up" "$T/x" --procs 2 --out "$T/up.csv" >"$T/up.out" 2>&1
rc=$?
check '[ $rc -eq 1 ] && grep -q "upper_violation 1, " "$T/up.out"' "err_upper lowered by 10 %: one upper_violation, exit 1 ($rc): $(cat "$T/up.out")"
read -r jc jd jm jt <"$T/up.job"
flagged=$(awk -F, '$11 ~ /upper_violation/ {print $1, $2, $3, $4}' "$T/up.csv")
check '[ "$flagged" = "$jc $jd $jm $jt" ]' "the flagged job is the doctored one ($jc $jd $jm $jt): $flagged"
doctor lo err_lower 1.1 2>/dev/null
"$PY" "$SCRIPT" --samples "$NS" "$T/lo" "$T/x" --procs 1 --limit 1 --out "$T/lo.csv" >"$T/lo.out" 2>&1
rc=$?
check '[ $rc -eq 1 ] && grep -q "lower_violation 1, " "$T/lo.out" && grep -q "refined" "$T/lo.csv"' \
    "err_lower raised by 10 %: a lower_violation after refinement, exit 1 ($rc): $(cat "$T/lo.out")"
# a job certified yes whose tol is below the distance: a verdict_violation
# (its tol changed in results.csv and in the export's index alike, so that
# the job is still found)
rm -rf "$T/ve" "$T/xv" && mkdir "$T/ve" "$T/xv" && cp "$T/x/"*.json "$T/xv/"
"$PY" - "$T/r/results.csv" "$T/ve/results.csv" "$T/x/index.csv" "$T/xv/index.csv" <<'EOF'
import csv, sys
for src, dst in ((sys.argv[1], sys.argv[2]), (sys.argv[3], sys.argv[4])):
    rows = list(csv.reader(open(src)))
    h = rows[0]
    for r in rows[1:]:
        if r[h.index("curve")] == "liu2002_ex1" and r[h.index("method")] == "tiller" and r[h.index("d")] == "1":
            r[h.index("tol")] = "1e-9"
    csv.writer(open(dst, "w", newline=""), lineterminator="\n").writerows(rows)
EOF
"$PY" "$SCRIPT" --samples "$NS" "$T/ve" "$T/xv" --procs 2 --methods tiller --out "$T/ve.csv" >"$T/ve.out" 2>&1
rc=$?
check '[ $rc -eq 1 ] && grep -q "upper_violation 0, lower_violation 0, verdict_violation 1;" "$T/ve.out"' \
    "certified yes at a tol below the distance: a verdict_violation ($rc): $(cat "$T/ve.out")"
# an export without the base segments (an older offbench): exit 2, said
sed 's/"base_homogeneous"/"base_h"/' "$T/x/$(awk -F, 'NR==2{print $8}' "$T/x/index.csv").json" >"$T/old.json"
mkdir "$T/xo" && cp "$T/x/index.csv" "$T/xo/" && cp "$T/x/"*.json "$T/xo/"
cp "$T/old.json" "$T/xo/$(awk -F, 'NR==2{print $8}' "$T/x/index.csv").json"
"$PY" "$SCRIPT" --samples "$NS" "$T/r" "$T/xo" --procs 1 --limit 1 --out "$T/o.csv" >"$T/o.out" 2>&1
rc=$?
check '[ $rc -eq 2 ] && grep -q "base_homogeneous" "$T/o.out"' "an export without base_homogeneous: exit 2, named ($rc): $(cat "$T/o.out")"
e2e_done
