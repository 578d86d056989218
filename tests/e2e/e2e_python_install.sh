#!/bin/sh
# The Python package installs as docs/python.md says, offline: `pip install
# --no-build-isolation --no-deps ./python` into a fresh virtual environment
# (--system-site-packages: Debian's numpy), then, from another directory,
# `python -c "import offbench; print(offbench.fit(...))"`; the installed
# copy is the one imported, it ships py.typed, and without OFFBENCH_LIB it
# finds the library whose path pip's build recorded (the checkout's build/,
# or $OFFBENCH_LIB's during pip install); with that gone it says where it
# looked.  An editable install (pip install
# -e) finds the checkout's build/ by itself.  When the python3 on PATH is
# not Debian's (pyenv, conda: no numpy), the online install with it:
# `python3 -m venv` + `pip install './python[pandas]'` fetches numpy and
# pandas from PyPI and fits without OFFBENCH_LIB (skipped, saying why, when
# python3 is Debian's or PyPI cannot be reached).  The package is installed
# from a copy of python/ (pip builds in the source directory), so the
# checkout is left as it was.
#
# Needs /usr/bin/python3 (or python3) with numpy, setuptools and venv with
# ensurepip (Debian: python3-numpy python3-setuptools python3-venv): without
# them the checks count as skipped.  Skipped under SAN, as e2e_python.sh.
. "$(dirname "$0")/lib_e2e.sh"
cd "$(dirname "$0")/../.." || exit 2
ROOT=$(pwd)
NCHECKS=14
NOTHER=3  # the checks of the online install with PATH's python3

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
env -u OFFBENCH_LIB "$V/bin/pip" install --no-build-isolation --no-deps --no-index "$T/co/python" >"$T/pip.out" 2>&1
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

# without OFFBENCH_LIB: the path pip's build recorded (the checkout's build/)
got=$(vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench, os
print(offbench.library_path()); print(offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status)
print(os.path.isfile(os.path.join(os.path.dirname(offbench.__file__), "py.typed")))' 2>&1)
check '[ "$got" = "$T/co/build/liboffbench.so.0
ok
True" ]' "without OFFBENCH_LIB the installed copy fits on the library recorded at install, and ships py.typed: $got"

# the recorded library gone (the checkout moved): unless a system copy is
# installed, it says where it looked and what to do
mv "$T/co/build" "$T/co/build.away"
vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench
try:
    print("found", offbench.library_path())
except offbench.LibraryNotFound as e:
    print(e)' >"$T/none.out" 2>&1
mv "$T/co/build.away" "$T/co/build"
check 'grep -q "^found " "$T/none.out" || { grep -q "looked in:" "$T/none.out" && grep -qF "the path recorded at install: $T/co/build/liboffbench.so.0" "$T/none.out" && grep -q "OFFBENCH_LIB" "$T/none.out" && ! grep -q "checkout.s build" "$T/none.out"; }' \
    "without the recorded library: a system copy, or where it looked: $(cat "$T/none.out")"

# OFFBENCH_LIB set during pip install is the path recorded (a library
# installed elsewhere): reinstalled so, the package loads that one
mkdir "$T/lib2" && ln -s "$LIB" "$T/lib2/liboffbench.so.0"
env OFFBENCH_LIB="$T/lib2/liboffbench.so.0" "$V/bin/pip" install --no-build-isolation --no-deps --no-index \
    --force-reinstall "$T/co/python" >"$T/pip3.out" 2>&1
got=$(vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench; print(offbench.library_path())' 2>&1)
check '[ "$got" = "$T/lib2/liboffbench.so.0" ]' "OFFBENCH_LIB during pip install is recorded: $got ($(tail -n 1 "$T/pip3.out"))"

"$V/bin/pip" uninstall -y offbench >"$T/un.out" 2>&1
check '[ $? -eq 0 ] && ! vpy "$V/bin/python" -c "import offbench" 2>/dev/null' "pip uninstall offbench: $(tail -n 2 "$T/un.out")"

# editable: the source stays where it is, so the checkout's build/ is found
"$V/bin/pip" install --no-build-isolation --no-deps --no-index -e "$T/co/python" >"$T/pipe.out" 2>&1
check '[ $? -eq 0 ]' "pip install -e ./python: $(tail -n 3 "$T/pipe.out")"
got=$(vpy env -u OFFBENCH_LIB "$V/bin/python" -c 'import offbench; print(offbench.library_path()); print(offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status)' 2>&1)
check '[ "$got" = "$T/co/build/liboffbench.so.0
ok" ]' "an editable install finds the checkout's build/liboffbench.so.0 without OFFBENCH_LIB: $got"

# PATH's python3, when it is not Debian's (pyenv, conda): online, pip
# fetches numpy (a dependency) and pandas (the extra) into a plain venv
# (wheels only: a Python without them would build them for many minutes;
# it then finds no distribution, and the online part skips)
other_python() {
    command -v python3 >/dev/null 2>&1 || { echo "no python3 on PATH"; return 1; }
    [ "$(python3 -c 'import os, sys; print(os.path.realpath(sys.executable))' 2>/dev/null)" != \
      "$(/usr/bin/python3 -c 'import os, sys; print(os.path.realpath(sys.executable))' 2>/dev/null)" ] \
        || { echo "python3 on PATH is /usr/bin/python3"; return 1; }
    python3 -c 'import venv, ensurepip' 2>/dev/null || { echo "python3 on PATH has no venv with ensurepip"; return 1; }
}
if why=$(other_python); then
    V2=$T/venv-other
    python3 -m venv "$V2" >"$T/venv2.out" 2>&1 && env -u OFFBENCH_LIB "$V2/bin/pip" install --disable-pip-version-check --timeout 20 --only-binary=numpy,pandas \
        "$T/co/python[pandas]" >"$T/pip2.out" 2>&1
    rc=$?
    # any trouble reaching or reading PyPI (refused, unresolved, timed out,
    # cut short, a proxy's error) is the network's, not the package's: the
    # test then skips, so that make test never depends on the network
    if [ $rc -ne 0 ] && grep -qiE "NewConnectionError|Failed to establish|Temporary failure in name resolution|Network is unreachable|Connection(Error| reset| aborted| refused)|Read ?timed ?out|ReadTimeout|timed out|ProxyError|SSLError|IncompleteRead|HTTP error [0-9]+|Retrying \\(Retry|hash(es)? (do not|don't) match|No matching distribution found for (setuptools|numpy|pandas|wheel)|Could not find a version that satisfies the requirement (setuptools|numpy|pandas|wheel)" "$T/pip2.out"; then
        echo "e2e_python_install: PATH's python3 ($(python3 --version 2>&1)): pip cannot fetch from PyPI here: $NOTHER skipped"
        skipped=$((skipped + NOTHER))
    else
        check '[ $rc -eq 0 ] && grep -q "Successfully installed.*numpy" "$T/pip2.out" && grep -q "Successfully installed.*pandas" "$T/pip2.out"' \
            "$(python3 --version 2>&1) -m venv + pip install './python[pandas]' fetches numpy and pandas: $(tail -n 3 "$T/pip2.out")"
        got=$(vpy env -u OFFBENCH_LIB "$V2/bin/python" -c 'import offbench; print(offbench.library_path()); print(offbench.fit("liu2002_ex1", "tiller", 1, 1e-2).status)' 2>&1)
        check '[ "$got" = "$T/co/build/liboffbench.so.0
ok" ]' "PATH's python3, installed online, fits without OFFBENCH_LIB: $got"
        got=$(vpy env -u OFFBENCH_LIB "$V2/bin/python" -c 'import offbench
print(type(offbench.run("liu2002_ex1", "tiller", [1e-2, 1e-3], as_frame=True)).__name__)' 2>&1)
        check '[ "$got" = "DataFrame" ]' "the [pandas] extra gives run(as_frame=True) a DataFrame: $got"
    fi
else
    echo "e2e_python_install: the online install with PATH's python3: $why: $NOTHER skipped"
    skipped=$((skipped + NOTHER))
fi
e2e_done
