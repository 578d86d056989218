#!/bin/sh
# No write through a planted link (issue 36, class 4): a symbolic or hard
# link at a name offbench writes - a run's .lock, results.csv.tmp,
# meta.json.tmp, results.fingerprint.tmp, results.journal.csv, an --export
# file, compare/draw/trace/tables/atlas/merge --out - never changes the
# file it points to.  The rule (docs/reliability.md "What a run directory guarantees"):
# a file written afresh replaces the link (a new file and a rename); a file
# updated in place (.lock, a resumed journal) that is a link is refused,
# exit 2, naming the path.
. "$(dirname "$0")/lib_e2e.sh"

R="--curve liu2002_ex1 --methods tiller --tols 1e-2 --backend cpu --threads 2"
mkdir -p "$T/outside"
n=0
# plant KIND LINK: a new file outside the run, and LINK (symbolic: kind s,
# hard: kind h) to it; its path in $V, a copy of its bytes in $V.orig
plant() {
    n=$((n + 1))
    V="$T/outside/victim$n"
    printf 'precious %s\n' "$n" > "$V"
    cp "$V" "$V.orig"
    mkdir -p "$(dirname "$2")"
    rm -f "$2"
    if [ "$1" = h ]; then ln "$V" "$2"; else ln -s "$V" "$2"; fi
}
# the victim is byte for byte as planted
intact() { cmp -s "$1" "$1.orig"; }
# NAME is now a regular file of one name (the link replaced)
replaced() { [ -f "$1" ] && [ ! -L "$1" ] && [ "$(stat -c %h "$1")" -eq 1 ]; }

# 1. a run's temporaries: the link is replaced, the run writes its files
for name in results.csv.tmp meta.json.tmp results.fingerprint.tmp; do
    for kind in s h; do
        rm -rf "$T/r"
        plant $kind "$T/r/$name"
        v=$V
        $OB run $R --out "$T/r" >/dev/null 2>"$T/err"
        rc=$?
        check 'intact "$v"' "run with $kind-link at $name: the target changed: $(cat "$v")"
        check '[ $rc -eq 0 ] && replaced "$T/r/results.csv" && replaced "$T/r/meta.json" && [ ! -e "$T/r/$name" ]' \
            "run with $kind-link at $name: exit $rc, files: $(ls -la "$T/r"): $(cat "$T/err")"
    done
done

# 2. a finished run's files as links (a rerun replaces them)
rm -rf "$T/r"
$OB run $R --out "$T/r" >/dev/null 2>&1
plant s "$T/r/results.csv"; v1=$V
plant h "$T/r/meta.json"; v2=$V
$OB run $R --force --out "$T/r" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && intact "$v1" && intact "$v2" && replaced "$T/r/results.csv" && replaced "$T/r/meta.json"' \
    "rerun over links at results.csv and meta.json: $(cat "$T/err")"

# 3. .lock: refused (exit 2, naming it), the target untouched
for kind in s h; do
    rm -rf "$T/l"
    plant $kind "$T/l/.lock"
    $OB run $R --out "$T/l" >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 2 ] && grep -q "l/\.lock" "$T/err" && [ ! -e "$T/l/results.csv" ]' \
        "$kind-link at .lock: exit $rc: $(cat "$T/err")"
done

# 4. the journal.  A fresh run (--force) replaces a link there; --resume
# refuses one, leaving the linked journal (valid, with a partial last line
# a resume would cut) as it was
rm -rf "$T/j"
$OB run $R --out "$T/j" >/dev/null 2>&1
{ printf '#offbench-journal 1 %s\n' "$(cat "$T/j/results.fingerprint")"; head -n 2 "$T/j/results.csv"; printf 'liu2002'; } > "$T/journal"
rm -f "$T/j/results.csv" "$T/j/results.fingerprint" "$T/j/meta.json"
for kind in s h; do
    plant $kind "$T/j/results.journal.csv"
    cp "$T/journal" "$V" && cp "$T/journal" "$V.orig"
    $OB run $R --resume "$T/j" >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 2 ] && grep -q "results.journal.csv" "$T/err" && [ ! -e "$T/j/results.csv" ]' \
        "--resume with a $kind-link at results.journal.csv: exit $rc: $(cat "$T/err")"
    $OB run $R --out "$T/j" --force >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/j/results.csv"' \
        "run --force over a $kind-link at results.journal.csv: exit $rc: $(cat "$T/err")"
    rm -f "$T/j/results.csv" "$T/j/results.fingerprint" "$T/j/meta.json"
done

# 5. --export: every kind of file, and index.csv
S=liu2002_ex1__d1__tiller__tol0.01
for name in $S.json $S.curves $S.dxf $S.svg index.csv $S.json.tmp index.csv.tmp; do
    for kind in s h; do
        rm -rf "$T/x"
        plant $kind "$T/x/$name"
        $OB run $R --force --out "$T/rx" --export "$T/x" >/dev/null 2>"$T/err"
        rc=$?
        check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/x/${name%.tmp}" && [ ! -e "$T/x/$name.tmp" ]' \
            "--export with a $kind-link at $name: exit $rc: $(cat "$T/err")"
    done
done
rm -rf "$T/x"
plant s "$T/x/index.csv"
$OB draw --curve liu2002_ex1 --method tiller --tol 1e-2 --backend cpu --out "$T/d.svg" --export "$T/x" >/dev/null 2>"$T/err"
check '[ $? -eq 0 ] && intact "$V" && replaced "$T/x/index.csv"' "draw --export with a link at index.csv: $(cat "$T/err")"

# 6. compare --out FILE (and its temporary)
$OB run $R --out "$T/b" >/dev/null 2>&1
for name in report.md report.md.tmp; do
    for kind in s h; do
        plant $kind "$T/c/$name"
        $OB compare "$T/b" "$T/b" --out "$T/c/report.md" >/dev/null 2>"$T/err"
        rc=$?
        check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/c/report.md" && [ ! -e "$T/c/report.md.tmp" ]' \
            "compare --out with a $kind-link at $name: exit $rc: $(cat "$T/err")"
    done
done

# 7. draw --out and trace --out (and a temporary beside them)
for cmd in draw trace; do
    for name in fig fig.tmp; do
        for kind in s h; do
            rm -rf "$T/f"
            plant $kind "$T/f/$name"
            $OB $cmd --curve liu2002_ex1 --method tiller --tol 1e-2 --backend cpu --out "$T/f/fig" >/dev/null 2>"$T/err"
            rc=$?
            check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/f/fig" && [ -s "$T/f/fig" ] && [ ! -e "$T/f/fig.tmp" ]' \
                "$cmd --out with a $kind-link at $name: exit $rc: $(cat "$T/err")"
        done
    done
done

# 8. tables --out, atlas --out, merge --out
for name in tables.csv tables.md tables.md.tmp; do
    rm -rf "$T/t"
    plant s "$T/t/$name"
    $OB tables --table liu2002:2 --protocols paper --out "$T/t" >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/t/${name%.tmp}"' "tables --out with a link at $name: exit $rc: $(cat "$T/err")"
done
for name in atlas.csv atlas.csv.tmp; do
    rm -rf "$T/a"
    plant h "$T/a/$name"
    $OB atlas --out "$T/a" >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/a/atlas.csv"' "atlas --out with a link at $name: exit $rc: $(cat "$T/err")"
done
rm -rf "$T/s0" "$T/s1"
$OB run $R --shard 0/2 --out "$T/s0" >/dev/null 2>&1 && $OB run $R --shard 1/2 --out "$T/s1" >/dev/null 2>&1
for name in results.csv meta.json.tmp; do
    rm -rf "$T/m"
    plant s "$T/m/$name"
    $OB merge "$T/s0" "$T/s1" --out "$T/m" >/dev/null 2>"$T/err"
    rc=$?
    check 'intact "$V" && [ $rc -eq 0 ] && replaced "$T/m/results.csv" && replaced "$T/m/meta.json"' \
        "merge --out with a link at $name: exit $rc: $(cat "$T/err")"
done

e2e_done
