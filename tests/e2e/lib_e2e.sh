# lib_e2e.sh - sourced by the tests/e2e_*.sh scripts (not a test itself):
# the program under test ($OFFBENCH, set by make, else ./offbench) as an
# absolute path in $OB, a scratch directory $T removed on exit, and the
# counters behind the "N passed, N failed[, N skipped]" line.
OB=${OFFBENCH:-./offbench}
OB=$(cd "$(dirname "$OB")" && pwd)/$(basename "$OB")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0 skipped=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
check() { if eval "$1"; then ok; else bad "$2"; fi; }
# a results.csv without its timing columns (fit_ns, eval_ns, and the spread
# of --reps: time_iqr_ns, time_cv), found by name (fit_ns and eval_ns come
# before the message, the one field that may hold a comma; the others are
# counted from the end of the line)
body() {
    awk -F, 'NR==1{n=NF; for(i=1;i<=NF;i++){if($i=="fit_ns"||$i=="eval_ns") drop[i]=1; if($i=="time_iqr_ns"||$i=="time_cv") dropend[n-i]=1}}
        {s=""; for(i=1;i<=NF;i++) if(!(i in drop) && !((NF-i) in dropend)) s=s (s=="" ? "" : ",") $i; print s}' "$1"
}
# a results.csv as builds before the joint columns wrote it (max_gap,
# max_kink and continuity dropped, by name counted from the end of the
# line: they never hold commas, and neither do the columns after them)
nojoints() {
    awk -F, 'BEGIN{OFS=","} NR==1{n=NF; for(i=1;i<=NF;i++) if($i=="max_gap"||$i=="max_kink"||$i=="continuity") drop[n-i]=1}
        {s=""; for(i=1;i<=NF;i++) if(!((NF-i) in drop)) s=s (s=="" ? "" : ",") $i; print s}' "$1"
}
# columns of a results.csv by name, one line per row, values joined by ':'
# (rcols FILE NAME...).  A quoted message may hold commas, the columns after
# it never do: those are counted from the end of the line.
rcols() {
    f=$1; shift
    awk -F, -v cols="$*" 'NR==1{for(i=1;i<=NF;i++){at[$i]=i; if($i=="message")m=i}; n=NF; nc=split(cols,c," "); next}
        {s=""; for(j=1;j<=nc;j++){k=at[c[j]]; s=s (j>1?":":"") (k>m ? $(NF-(n-k)) : $k)}; print s}' "$f"
}
