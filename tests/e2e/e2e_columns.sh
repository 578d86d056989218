#!/bin/sh
# End-to-end test of the e2e helpers that read offbench CSVs by column name
# (lib_e2e.sh: awkc, rcols, csvcols, dropcols; issue 17): on a results.csv
# as a newer build may write it, with a quoted message holding commas and a
# column appended at the end, they still read the right values, where a
# read by position ($11, cut -f20) shifts.  Uses $OFFBENCH (set by make) or
# ./offbench.
. "$(dirname "$0")/lib_e2e.sh"

"$OB" run --curve liu2002_ex1 --methods ahn,cobb --tols 1e-1,1e-3 --backend cpu --out "$T/r" 2>/dev/null
check '[ $? -eq 0 ]' "run: exit 0"
R=$T/r/results.csv
# the fixture: row 2's message holds commas, and every line gains a last column
awkc 'BEGIN{OFS=","} NR==2{$c["message"]="\"one, two, three\""} {print}' "$R" > "$T/msg.csv"
awk '{print $0 "," (NR==1 ? "newer_column" : "x" NR)}' "$T/msg.csv" > "$T/wide.csv"
W=$T/wide.csv
dropcols "$R" message > "$T/nomsg.csv"
nf() { sed -n 2p "$1" | awk -F, '{print NF}'; }
check '[ "$(nf "$W")" -eq $(($(nf "$R") + 3)) ]' \
    "the fixture has 3 more fields in row 2 (the commas and the new column)"
# what a read by position sees: continuity (field 20) is no longer field 20
check '[ "$(awk -F, "NR==2{print \$20}" "$W")" != "$(awk -F, "NR==2{print \$20}" "$R")" ]' \
    "the fixture shifts a positional read"

# the columns before the message and after it, by name
NAMES="curve d method tol segments status family offset_degree max_gap continuity time_cv"
want=$(rcols "$R" $NAMES)
got=$(awkc 'BEGIN{OFS=":"} NR>1{print $c["curve"], $c["d"], $c["method"], $c["tol"], $c["segments"], $c["status"],
                $c["family"], $c["offset_degree"], $c["max_gap"], $c["continuity"], $c["time_cv"]}' "$W")
check '[ -n "$want" ] && [ "$got" = "$want" ]' "awkc reads every column by name: got '$got', want '$want'"
check '[ "$(rcols "$W" $NAMES)" = "$want" ]' "rcols reads every column by name: $(rcols "$W" $NAMES | head -n 1)"
check '[ "$(awkc "NR==2{print v(\"message\")}" "$W")" = "\"one, two, three\"" ]' "v(\"message\") is the whole message"
check '[ "$(awkc "NR==2{print \$c[\"newer_column\"]}" "$W")" = "x2" ]' "the appended column is read from the end"
# what the conversions of the tests use: selected columns, and all but some
check '[ "$(csvcols "$W" $NAMES)" = "$(csvcols "$R" $NAMES)" ]' "csvcols reads the same columns from both"
check '[ "$(csvcols "$W" curve message status | sed -n 2p)" = "liu2002_ex1,\"one, two, three\",ok" ]' \
    "csvcols keeps the message whole: $(csvcols "$W" curve message status | sed -n 2p)"
check 'dropcols "$W" newer_column message | cmp -s - "$T/nomsg.csv"' "dropcols drops by name"
check 'dropcols "$W" newer_column | cmp -s - "$T/msg.csv"' "dropcols keeps the message whole"
# a name that is not in the header is an error, not a silent $0, and is
# said on stdout too (a check for no output, or two equal ones, then fails)
awkc 'NR>1{print $c["contiunity"]}' "$W" > "$T/typo.out" 2> "$T/typo.err"
check '[ $? -eq 2 ] && grep -q "awkc: a column named is not in" "$T/typo.out" && grep -q "no column .contiunity." "$T/typo.err"' \
    "a typo in a column name: exit 2 and a message: $(cat "$T/typo.err")"
check '[ "$(dropcols "$W" nosuch 2>/dev/null)" != "$(dropcols "$R" nosuch 2>/dev/null)" ]' \
    "dropcols of a missing column does not compare equal"
check '[ "$(rcols "$W" status nosuch 2>/dev/null)" = "rcols: a column named is not in $W" ]' "rcols of a missing column says so"
echo "$pass passed, $fail failed, $skipped skipped"
[ $fail -eq 0 ]
