#!/bin/sh
# The Python package installs as docs/python.md says, offline: `pip install
# --no-build-isolation --no-deps ./python` into a fresh virtual environment
# (--system-site-packages: Debian's numpy), then, from another directory,
# `python -c "import offbench; print(offbench.fit(...))"` on this build's
# library through OFFBENCH_LIB; the installed copy is the one imported, and
# without OFFBENCH_LIB it says where it looked and what to set.  An editable
# install (pip install -e) finds the checkout's build/ by itself.  The
# package is installed from a copy of python/ (pip builds in the source
# directory), so the checkout is left as it was.
#
# Needs /usr/bin/python3 (or python3) with numpy, setuptools and venv with
# ensurepip (Debian: python3-numpy python3-setuptools python3-venv): without
# them the checks count as skipped.  Skipped under SAN, as e2e_python.sh.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
ROOT=$(pwd)
NCHECKS=9

case $OB in
*/build-san/offbench|*/build-fuzz/offbench)
    echo "e2e_python_install: $OB is a sanitizer build, whose library python cannot load without preloading ASan: skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0 ;;
esac
LIB=$(e2e_liboffbench) || { echo "0 passed, 1 failed"; exit 1; }  # beside the program (lib_e2e.sh)
build=$(dirname "$LIB")

PY=
for p in /usr/bin/python3 python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import numpy, setuptools, venv, ensurepip' >/dev/null 2>&1; then
        PY=$p; break
    fi
done
if [ -z "$PY" ]; then
    echo "e2e_python_install: no python3 with numpy, setuptools and venv (Debian: apt-get install python3-numpy python3-setuptools python3-venv): skipped"
    echo "0 passed, 0 failed, $NCHECKS skipped"
    exit 0
fi

# the package's source as pip gets it, in a checkout-like tree whose build/
# is this build's (the editable install looks there)
mkdir -p "$T/co" "$T/elsewhere"
cp -R python "$T/co/python"
rm -rf "$T/co/python/build" "$T/co/python"/*.egg-info
find "$T/co/python" -name __pycache__ -prune -exec rm -rf {} +
ln -s "$build" "$T/co/build"
V=$T/venv
"$PY" -m venv --system-site-packages "$V" >"$T/venv.out" 2>&1
check '[ $? -eq 0 ] && [ -x "$V/bin/pip" ]' "python3 -m venv --system-site-packages makes an environment with pip: $(tail -n 3 "$T/venv.out")"

# offline: the system's setuptools builds it, numpy is the system's
"$V/bin/pip" install --no-build-isolation --no-deps --no-index "$T/co/python" >"$T/pip.out" 2>&1
check '[ $? -eq 0 ] && grep -q "Successfully installed offbench" "$T/pip.out"' \
    "pip install --no-build-isolation --no-deps ./python: $(tail -n 3 "$T/pip.out")"

vpy() { (cd "$T/elsewhere" && env -u PYTHONPATH PYTHONDONTWRITEBYTECODE=1 "$@"); }
vpy env OFFBENCH_LIB="$LIB" "$V/bin/python" -c 'import offbench; print(offbench.fit("liu2002_ex1", "tiller", 1, 1e-3))' \
    >"$T/fit.out" 2>&1
check '[ $? -eq 0 ] && grep -q "^Result(curve=.liu2002_ex1., d=1, method=.tiller., .*status=.ok., ctrl_points=85, segments=28" "$T/fit.out"' \
    "the README's line prints the job: $(tail -n 3 "$T/fit.out")"
where=$(vpy env OFFBENCH_LIB="$LIB" "$V/bin/python" -c 'import offbench; print(offbench.__file__); print(offbench.library_path())' 2>&1)
check 'case "$where" in "$V"/lib/python3*/site-packages/offbench/__init__.py"
$LIB") true ;; *) false ;; esac' "the installed copy is imported, the library is OFFBENCH_LIB's: $where"
vpy env OFFBENCH_LIB="$LIB" "$V/bin/python" -c 'import offbench
df = offbench.run("liu2002_ex1", "tiller,sisl", 1e-2, as_frame=True) if offbench.results._pandas() else None
print("ok" if df is None or len(df) == 4 else df)
print(offbench.measure("liu2002_ex1", 1, offbench.fit("liu2002_ex1", "sisl", 1, 1e-2)).status)' >"$T/more.out" 2>&1
check '[ $? -eq 0 ] && [ "$(cat "$T/more.out")" = "ok
ok" ]' "run, measure and sisl's server from the installed package: $(tail -n 3 "$T/more.out")"

# without OFFBENCH_LIB: an installed copy has no checkout to look in; unless
# a system copy is installed, it says where it looked and what to set
vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench
try:
    print("found", offbench.library_path())
except offbench.LibraryNotFound as e:
    print(e)' >"$T/none.out" 2>&1
check 'grep -q "^found " "$T/none.out" || { grep -q "looked in:" "$T/none.out" && grep -q "OFFBENCH_LIB" "$T/none.out" && ! grep -q "checkout.s build" "$T/none.out"; }' \
    "without OFFBENCH_LIB: a system copy, or where it looked: $(cat "$T/none.out")"

"$V/bin/pip" uninstall -y offbench >"$T/un.out" 2>&1
check '[ $? -eq 0 ] && ! vpy "$V/bin/python" -c "import offbench" 2>/dev/null' "pip uninstall offbench: $(tail -n 2 "$T/un.out")"

# editable: the source stays where it is, so the checkout's build/ is found
"$V/bin/pip" install --no-build-isolation --no-deps --no-index -e "$T/co/python" >"$T/pipe.out" 2>&1
check '[ $? -eq 0 ]' "pip install -e ./python: $(tail -n 3 "$T/pipe.out")"
got=$(vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench; print(offbench.library_path()); print(offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status)' 2>&1)
check '[ "$got" = "$T/co/build/liboffbench.so.0
ok" ]' "an editable install finds the checkout's build/liboffbench.so.0 without OFFBENCH_LIB: $got"
e2e_done
