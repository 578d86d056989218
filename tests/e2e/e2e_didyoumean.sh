#!/bin/sh
# "did you mean": a mistyped command, option, method, curve id or list
# subject is refused with exit 2 as before, its message unchanged at the
# start, and the closest name added when one is close (host/cli/suggest.h).
. "$(dirname "$0")/lib_e2e.sh"

# refused CMD... EXPECTED: exit 2 and stderr holds EXPECTED
refused() {
    want=$1; shift
    "$OB" "$@" >"$T/out" 2>"$T/err"
    rc=$?
    check '[ $rc -eq 2 ] && grep -qF -- "$want" "$T/err"' "$*: exit $rc, want '$want' in: $(head -c 300 "$T/err")"
}
refused "unknown command 'rn' (did you mean 'run'?)" rn
refused "unknown command 'compre' (did you mean 'compare'?)" compre
refused "unknown command '--versoin' (did you mean '--version'?)" --versoin
refused "unknown command 'frobnicate'" frobnicate
check '! grep -q "did you mean" "$T/err"' "nothing close: no suggestion"
refused "run: unknown option '--threds' (did you mean '--threads'?)" run --threds 2
refused "compare: unknown option '--formt' (did you mean '--format'?)" compare a b --formt md
refused "--methods: unknown method 'tiler' (see './offbench list methods') (did you mean 'tiller'?)" \
    run --methods tiler --out "$T/o"
refused "--param: unknown method 'zhoa' (did you mean 'zhao'?)" run --param zhoa.degree=3 --out "$T/o"
refused "--method: unknown method 'ahm' (see './offbench list methods') (did you mean 'ahn'?)" \
    draw --curve liu2002_ex1 --method ahm --tol 1e-2 --out "$T/o.svg"
refused "(did you mean 'liu2002_ex1'?)" run --curve liu2002_ex3 --methods tiller --out "$T/o"
refused "--curve: no curve 'liu2002_ex3' in " run --curve liu2002_ex3 --methods tiller --out "$T/o"
refused "(did you mean 'liu2002_ex1'?)" measure --curve liu2002_ex3 --d 1 --approx "$T/none.json"
refused "list: unknown subject 'curvs'" list curvs
check 'grep -qF "(did you mean '"'"'curves'"'"'?)" "$T/err"' "list curvs: did you mean curves"
e2e_done
