#!/bin/sh
# compare and merge with certificates (issue 48): a `certified` change shows
# the certificates (err_upper of each side), not the job's time, in every
# format; a certified run against an uncertified one says the certificates
# were not compared; merge names --certify as the difference between a
# certified shard and an uncertified one, and refuses a certify shard whose
# rows have no certificate.
. "$(dirname "$0")/lib_e2e.sh"
R="--curve liu2002_ex1 --methods tiller,ahn --tols 1e-2,1e-3 --backend cpu --threads 2"
$OB run $R --certify --out "$T/c" >/dev/null 2>"$T/c.err"
check '[ $? -eq 0 ]' "run --certify: $(cat "$T/c.err")"
$OB run $R --out "$T/p" >/dev/null 2>&1
check '[ $? -eq 0 ]' "the same run without --certify"
# a job certified within tol in BASE, not in NEW (err_upper 2 x tol)
awk -F, 'BEGIN{OFS=","} NR>1 && !done && $(NF-6)=="yes" {$(NF-8)=$6*2; $(NF-6)="no"; done=1} {print}' "$T/c/results.csv" > "$T/x.csv"
bu=$(awk -F, 'NR>1 && $(NF-6)=="yes" {print $(NF-8); exit}' "$T/c/results.csv")
nu=$(awk -F, 'NR>1 && $(NF-6)=="yes" {print $6*2; exit}' "$T/c/results.csv")
$OB compare "$T/c/results.csv" "$T/x.csv" >"$T/cmp.md" 2>&1
check '[ $? -eq 1 ] && grep -q "| certified | yes (err_upper [0-9.e+-]*) | no (err_upper [0-9.e+-]*) |" "$T/cmp.md"' \
    "md: the certified row shows the certificates: $(grep "| certified |" "$T/cmp.md")"
check '! grep "| certified |" "$T/cmp.md" | grep -q " ms |"' "md: no time in the certified row"
$OB compare "$T/c/results.csv" "$T/x.csv" --format csv >"$T/cmp.csv" 2>&1
check '[ $? -eq 1 ] && [ "$(awk -F, -v bu="$bu" -v nu="$nu" "\$1==\"regression\" && \$8==\"certified\" && \$9+0==bu+0 && \$10+0==nu+0" "$T/cmp.csv" | wc -l)" -eq 1 ]' \
    "csv: base and new are the two err_upper: $(grep certified "$T/cmp.csv")"
$OB compare "$T/c/results.csv" "$T/x.csv" --format json >"$T/cmp.json" 2>/dev/null
check '[ $? -eq 1 ] && python3 -c "
import json,sys
d=json.load(open(sys.argv[1]))
c=[x for x in d[\"changes\"] if x[\"kind\"]==\"regression\" and x[\"field\"]==\"certified\"]
assert len(c)==1 and c[0][\"base\"]==float(sys.argv[2]) and c[0][\"new\"]==float(sys.argv[3]), c
" "$T/cmp.json" "$bu" "$nu"' "json: base and new are the two err_upper: $(grep -o '"field": "certified"[^}]*' "$T/cmp.json")"
# certified against uncertified (either way): OK, saying the certificates were not compared
for pair in "c p BASE NEW" "p c NEW BASE"; do
    set -- $pair
    a=$1 b=$2 cs=$3 us=$4
    $OB compare "$T/$1/results.csv" "$T/$2/results.csv" --no-timing >"$T/u.md" 2>&1
    check '[ $? -eq 0 ] && grep -q "^- note: $cs is certified (run --certify), $us is not: the certificates were not compared" "$T/u.md"' \
        "md, $a vs $b: the note: $(grep note "$T/u.md")"
    $OB compare "$T/$1/results.csv" "$T/$2/results.csv" --no-timing --format csv >"$T/u.csv" 2>&1
    check '[ $? -eq 0 ] && grep -q "^context,,,,,,,note,\"$cs is certified (run --certify)" "$T/u.csv"' "csv, $a vs $b: the note"
    $OB compare "$T/$1/results.csv" "$T/$2/results.csv" --no-timing --format json >"$T/u.json" 2>/dev/null
    check '[ $? -eq 0 ] && python3 -c "
import json,sys
d=json.load(open(sys.argv[1]))
assert any(\"certificates were not compared\" in n for n in d[\"context\"][\"notes\"]), d[\"context\"]
" "$T/u.json"' "json, $a vs $b: the note in context.notes"
done
$OB compare "$T/c/results.csv" "$T/c/results.csv" >"$T/s.md" 2>&1
check '[ $? -eq 0 ] && ! grep -q "certificates were not compared" "$T/s.md"' "both certified: no note"
# merge: a certified shard with an uncertified one names --certify
$OB run $R --certify --shard 0/2 --out "$T/s1" >/dev/null 2>&1
$OB run $R --shard 1/2 --out "$T/u2" >/dev/null 2>&1
$OB merge "$T/s1" "$T/u2" --out "$T/mu" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && [ ! -e "$T/mu/results.csv" ] && grep -q "s1 ran with --certify (mode verdict), .*u2 without it" "$T/e.txt"' \
    "certified with uncertified: refused naming --certify: $(cat "$T/e.txt")"
# a certify shard whose ok rows have no certificate: refused
$OB run $R --certify --shard 1/2 --out "$T/s2" >/dev/null 2>&1
cp -r "$T/s2" "$T/s2e"
awk -F, 'BEGIN{OFS=","} NR>1 && ($11=="ok" || $11=="limit") {$(NF-8)="";$(NF-7)="";$(NF-6)="";$(NF-5)=""} {print}' "$T/s2/results.csv" > "$T/s2e/results.csv"
$OB merge "$T/s1" "$T/s2e" --out "$T/me" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 2 ] && [ ! -e "$T/me/results.csv" ] && grep -q "s2e/results.csv:[0-9]*: .*no certificate" "$T/e.txt"' \
    "a certify shard with empty certificates: refused: $(cat "$T/e.txt")"
$OB merge "$T/s1" "$T/s2" --out "$T/m" >/dev/null 2>"$T/e.txt"
check '[ $? -eq 0 ] && [ "$(cat "$T/m/results.csv" | body /dev/stdin)" = "$(body "$T/c/results.csv")" ]' "certified shards still merge: $(cat "$T/e.txt")"
e2e_done
