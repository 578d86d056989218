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
# the script's last line and exit status: "N passed, N failed[, N skipped]"
e2e_done() {
    if [ "$skipped" -gt 0 ]; then echo "$pass passed, $fail failed, $skipped skipped"; else echo "$pass passed, $fail failed"; fi
    [ "$fail" -eq 0 ]
}
# a results.csv without its timing columns (fit_ns, eval_ns, the spread
# of --reps: time_iqr_ns, time_cv, --certify's cert_ns and --time-fits'
# method_ns, method_iqr_ns), found by name (fit_ns and eval_ns come
# before the message, the one field that may hold a comma; the others are
# counted from the end of the line)
body() {
    awk -F, 'NR==1{n=NF; for(i=1;i<=NF;i++){if($i=="fit_ns"||$i=="eval_ns") drop[i]=1; if($i=="time_iqr_ns"||$i=="time_cv"||$i=="cert_ns"||$i=="method_ns"||$i=="method_iqr_ns") dropend[n-i]=1}}
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
    hascols "$f" "$@" || { _colmiss rcols "$f"; return 2; }
    awk -F, -v cols="$*" 'NR==1{for(i=1;i<=NF;i++){at[$i]=i; if($i=="message")m=i}; n=NF; nc=split(cols,c," "); next}
        {s=""; for(j=1;j<=nc;j++){k=at[c[j]]; s=s (j>1?":":"") (k>m ? $(NF-(n-k)) : $k)}; print s}' "$f"
}
# true when every NAME is a column in FILE's header (hascols FILE NAME...);
# else says which is missing, so that a typo fails loudly instead of reading
# the wrong field
hascols() {
    _hf=$1; shift
    _hh=$(head -n 1 "$_hf" 2>/dev/null | tr , '\n')
    for _hn in "$@"; do
        printf '%s\n' "$_hh" | grep -qxF -- "$_hn" || { echo "no column '$_hn' in $_hf" >&2; return 2; }
    done
}
# a missing column said on stdout too: a test that expects no output, or
# compares two outputs, then fails instead of passing on nothing
_colmiss() { echo "$1: a column named is not in $2"; }
# awk over offbench CSVs with the columns found by name (awkc PROGRAM
# [VAR=VALUE]... FILE...): on every line, the header included, c[NAME] is
# that column's field number, read from each file's header, so the program
# says $c["status"] where it would say $11.  A quoted message may hold
# commas, the columns after it never do: theirs are counted from the end of
# the line.  v(NAME) is a column's text, the whole message included.
# Every $c["NAME"] in the program must be in the first file's header;
# the helper's own variables start with _ (the program's may not).
awkc() {
    _ap=$1; shift
    for _af in "$@"; do case $_af in *=*) ;; *) break ;; esac; done
    hascols "$_af" $(printf '%s\n' "$_ap" | grep -o '\$c\["[^"]*"\]' | sed 's/^\$c\["//; s/"\]$//' | sort -u) || { _colmiss awkc "$_af"; return 2; }
    awk -F, 'function v(name,  s, i) { if (!_m || _at[name] != _m) return $c[name]
                                       s = $_m; for (i = _m + 1; i <= _m + NF - _n; i++) s = s "," $i; return s }
        FNR==1{delete _at; delete c; _n=NF; _m=0; for(_i=1;_i<=NF;_i++){_at[$_i]=_i; if($_i=="message") _m=_i}}
        {for(_k in _at) c[_k] = (_m && _at[_k] > _m) ? NF - _n + _at[_k] : _at[_k]}
        '"$_ap" "$@"
}
# the named columns of an offbench CSV, header included, joined by commas
# (csvcols FILE NAME...): what `cut -d, -f...` printed, found by name
csvcols() {
    _cf=$1; shift
    hascols "$_cf" "$@" || { _colmiss csvcols "$_cf"; return 2; }
    awkc 'FNR==1{nk=split(want, keep, " ")} {s=""; for(j=1;j<=nk;j++) s=s (j>1?",":"") v(keep[j]); print s}' want="$*" "$_cf"
}
# an offbench CSV without the named columns, header included (dropcols FILE
# NAME...), e.g. without the timings: dropcols results.csv fit_ns eval_ns
dropcols() {
    _df=$1; shift
    hascols "$_df" "$@" || { _colmiss dropcols "$_df"; return 2; }
    awkc 'FNR==1{split(drop, d, " "); delete x; for(j in d) x[d[j]]=1; nk=0; for(i=1;i<=NF;i++) if(!($i in x)) keep[++nk]=$i}
        {s=""; for(j=1;j<=nk;j++) s=s (j>1?",":"") v(keep[j]); print s}' drop="$*" "$_df"
}

# e2e_liboffbench: the path of the library beside the program ($OB is
# build/'s, or under `make MPI=1` build-mpi/'s, as .offbench-flavor says),
# made with `make lib` when it is not there (run from the checkout's root);
# 1 after a FAIL line on stderr when make fails.
e2e_liboffbench() {
    _b=$(dirname "$OB")
    [ "$_b" = "$(pwd)" ] && _b=$(pwd)/$(cat .offbench-flavor 2>/dev/null || echo build)
    if [ ! -e "$_b/liboffbench.so.0" ]; then
        _mpi=0; case $_b in */build-mpi) _mpi=1 ;; esac
        env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory MPI=$_mpi lib >"$T/make.out" 2>&1 \
            || { echo "FAIL: make lib: $(tail -n 5 "$T/make.out")" >&2; return 1; }
    fi
    echo "$_b/liboffbench.so.0"
}
# The OpenCASCADE tests (e2e_occt.sh, e2e_occt_method.sh), run from the
# repository root.  occt_nohdr TARGET VAR: `make TARGET` with the headers
# moved away (VAR: the make variable of the program's path) must fail
# naming the Debian packages and build nothing.
occt_nohdr() {
    env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s --no-print-directory OCCT_INC="$T/no-occt" "$2=$T/nobin" "$1" \
        >"$T/nohdr.out" 2>&1
    check '[ $? -ne 0 ] && grep -q "libocct-foundation-dev libocct-modeling-data-dev g++" "$T/nohdr.out" && [ ! -e "$T/nobin" ]' \
        "make $1 without the headers: fails naming the Debian packages: $(tr '\n' ' ' <"$T/nohdr.out")"
}
# occt_require SCRIPT N: when OpenCASCADE's headers or g++ are missing
# (E2E_OCCT_ABSENT=1: as if they were), says why and the install line,
# counts the script's N remaining checks as skipped and ends the script.
occt_require() {
    [ -z "${E2E_OCCT_ABSENT:-}" ] && [ -f /usr/include/opencascade/Geom2d_OffsetCurve.hxx ] &&
        command -v g++ >/dev/null 2>&1 && return 0
    echo "$1: no OpenCASCADE headers (/usr/include/opencascade) or no g++" \
         "(apt-get install libocct-foundation-dev libocct-modeling-data-dev g++, or OB_DEPS_OCCT=1 make deps): $2 checks skipped"
    skipped=$((skipped + $2))
    e2e_done
    exit $?
}
