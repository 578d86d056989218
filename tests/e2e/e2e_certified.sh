#!/bin/sh
# The certified metric through the program (issue 41): `run --metric
# certified` ends its jobs ok only when the certified upper bound of each
# piece's Hausdorff distance is within tol; on the jobs that end with the
# same pieces as under the sampled hausdorff metric the bound is at least
# the sampled value and within the enclosure's relative target (1e-3) of
# it; the OpenCL backend measures it on the CPU (the same rows); `measure
# --metric certified` gives it for a file's pieces.
. "$(dirname "$0")/lib_e2e.sh"
R="--curve liu2002_ex1,liu2002_ex2 --methods tiller,ahn,zhao,cobb --tols 1e-2,1e-3"
$OB run $R --metric certified --backend cpu --out "$T/c" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ]' "run --metric certified: $(cat "$T/err")"
$OB run $R --metric hausdorff --backend cpu --out "$T/h" >/dev/null 2>&1
check '[ $? -eq 0 ]' "run --metric hausdorff"
n=$(awkc 'NR>1' "$T/c/results.csv" | wc -l)
check '[ "$n" -ge 16 ] && [ "$n" -eq "$(awkc "NR>1" "$T/h/results.csv" | wc -l)" ]' "the same jobs as under hausdorff: $n"
over=$(awkc 'NR>1 && $c["status"]=="ok" && !($c["max_err"] <= $c["tol"])' "$T/c/results.csv" | wc -l)
check '[ "$over" -eq 0 ]' "every ok job's certified max_err is within tol: $over are not"
check '[ "$(awkc "NR>1 && \$c[\"metric\"]!=\"certified\"" "$T/c/results.csv" | wc -l)" -eq 0 ]' "the metric column says certified"
# the jobs with the same pieces: bound >= sampled, within 2e-3 relative
key='NR>1{print $c["curve"] "|" $c["d"] "|" $c["method"] "|" $c["tol"] "|" $c["ctrl_points"] "|" $c["segments"], $c["max_err"]}'
awkc "$key" "$T/h/results.csv" | sort > "$T/h.txt"
awkc "$key" "$T/c/results.csv" | sort > "$T/c.txt"
join "$T/h.txt" "$T/c.txt" > "$T/j.txt"
same=$(wc -l < "$T/j.txt")
check '[ "$same" -ge 8 ]' "at least 8 jobs end with the same pieces under both metrics: $same"
badlo=$(awk '!($3 >= $2 * (1 - 1e-9))' "$T/j.txt" | wc -l)
badhi=$(awk '!($3 <= $2 * (1 + 2e-3) + 1e-9)' "$T/j.txt" | wc -l)
check '[ "$badlo" -eq 0 ]' "certified >= sampled hausdorff on the same pieces: $(awk '!($3 >= $2 * (1 - 1e-9))' "$T/j.txt" | head -n 3)"
check '[ "$badhi" -eq 0 ]' "certified within 2e-3 of sampled on the same pieces: $(awk '!($3 <= $2 * (1 + 2e-3) + 1e-9)' "$T/j.txt" | head -n 3)"
# the OpenCL backend: the certified records go to the CPU, the same rows
if $OB run --curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --out "$T/probe" >/dev/null 2>&1; then
    $OB run $R --metric certified --backend opencl --out "$T/cl" >/dev/null 2>&1
    check '[ $? -eq 0 ] && [ "$(body "$T/cl/results.csv")" = "$(body "$T/c/results.csv")" ]' \
        "--backend opencl --metric certified: the CPU's rows"
else
    skipped=$((skipped + 1)); echo "SKIP: no OpenCL device" >&2
fi
# measure: a run's exported pieces, certified >= hausdorff
$OB run --curve liu2002_ex1 --methods ahn --tols 1e-3 --backend cpu --out "$T/x" --export "$T/x/ex" >/dev/null 2>&1
f=$(ls "$T/x/ex/"*d1__ahn*.json)
$OB measure --curve liu2002_ex1 --d 1 --approx "$f" --metric certified > "$T/m.csv" 2>"$T/err"
check '[ $? -eq 0 ] && [ "$(awkc "NR>1 && \$c[\"metric\"]==\"certified\" && \$c[\"status\"]==\"ok\"" "$T/m.csv" | wc -l)" -eq 1 ]' \
    "measure --metric certified: one ok row: $(cat "$T/m.csv" "$T/err")"
$OB measure --curve liu2002_ex1 --d 1 --approx "$f" --metric hausdorff > "$T/mh.csv" 2>/dev/null
hc=$(awkc 'NR>1 && $c["metric"]=="hausdorff"{print $c["max_err"]}' "$T/mh.csv")
cc=$(awkc 'NR>1 && $c["metric"]=="certified"{print $c["max_err"]}' "$T/m.csv")
check "awk -v h=\"$hc\" -v c=\"$cc\" 'BEGIN{exit !(h > 0 && c >= h && c <= h * (1 + 2e-3))}'" "measure: certified $cc vs hausdorff $hc"
e2e_done
