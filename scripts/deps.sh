#!/bin/sh
# Checks for what offbench needs to build and run, and installs what is missing
# when it can (root with apt-get, Debian package names); otherwise it says
# exactly what to install.  Run by `make` once (stamp in build/.deps-ok) and by
# `make deps` on demand.
#
#   required to build:     a C11 compiler with OpenMP (gcc), make
#   OpenCL (kernels/):     opencl-headers, ocl-icd-opencl-dev, pocl-opencl-icd
#   SISL (methods/sisl.c): libsisl-dev (required: the build links -lsisl)
#   FLINT (methods/core/offdeg.c): libflint-dev (required: exact offset degrees)
#   expat (host/io/approx_read_svg.c): libexpat1-dev (required: measure's
#                          SVG reader parses the XML with it; the build links -lexpat)
#   Nettle (host/backend/clcache.c): nettle-dev (required: SHA-256 of the
#                          OpenCL binary cache's names and files)
#   MPI (make MPI=1):      libopenmpi-dev, openmpi-bin (only when MPI=1)
#   plots (scripts/*.py):  python3-matplotlib (optional: never fails the build)
#   svg2curves.py check (tests/e2e/svgcheck.py): python3-svgelements, an independent
#                          SVG parser (optional: never fails the build)
#   DXF read-back test (tests/e2e/e2e_export.sh) and results/export's figure:
#                          python3-ezdxf (optional: the test is skipped without it)
#   zsh completion test (tests/e2e/e2e_completion.sh): zsh (optional: the
#                          zsh half of the test is skipped without it)
#   the Python package (python/, tests/e2e/e2e_python.sh and
#   e2e_python_install.sh): python3-numpy, python3-pytest, python3-pandas,
#   python3-setuptools, python3-venv (optional: the tests are skipped
#   without them; pandas only for the DataFrame tests)
#   lint of the CI recipes (tests/e2e/e2e_ci_recipes.sh, scripts/ci/*.yml):
#                          python3-yaml (optional: the lint is skipped without it)
#   browser test of the nightly report (tests/e2e/e2e_report.sh) and
#   results/report.png:    chromium-headless-shell, only with OB_DEPS_BROWSER=1
#                          (optional: never fails the build; the browser
#                          checks are skipped without it)
#   the CAD-kernel example (make occt-example, tests/e2e/e2e_occt.sh,
#   docs/cad-example.md, make occt-trimmed):  libocct-foundation-dev,
#                          libocct-modeling-data-dev, libocct-modeling-algorithms-dev
#                          and g++, only with OB_DEPS_OCCT=1 (optional: never
#                          fails the build; the OCCT checks are skipped
#                          without them)
#   lib2geom's offset as a method (make lib2geom-worker,
#   tests/e2e/e2e_lib2geom_method.sh): lib2geom-dev and g++, only with
#                          OB_DEPS_LIB2GEOM=1 (optional: the checks are
#                          skipped without them)
set -u

missing=""
have_header() { printf '#include <%s>\nint main(void){return 0;}\n' "$1" | ${CC:-cc} -x c -fsyntax-only - >/dev/null 2>&1; }
have_pkg() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }

command -v ${CC:-cc} >/dev/null 2>&1 || { echo "deps: no C compiler: install gcc (Debian: apt-get install gcc make)" >&2; exit 1; }
printf '#include <omp.h>\nint main(void){return omp_get_max_threads() < 1;}\n' | ${CC:-cc} -fopenmp -x c - -o /tmp/ob_omp_probe.$$ >/dev/null 2>&1 \
    || { echo "deps: the C compiler lacks OpenMP (-fopenmp): install gcc with libgomp" >&2; rm -f /tmp/ob_omp_probe.$$; exit 1; }
rm -f /tmp/ob_omp_probe.$$

have_header CL/cl.h || missing="$missing opencl-headers"
have_header sisl.h || missing="$missing libsisl-dev"
have_header flint/fmpz_poly.h || missing="$missing libflint-dev"
have_header expat.h || missing="$missing libexpat1-dev"
have_header nettle/sha2.h || missing="$missing nettle-dev"
if command -v dpkg-query >/dev/null 2>&1; then
    have_pkg ocl-icd-opencl-dev || missing="$missing ocl-icd-opencl-dev"
    have_pkg pocl-opencl-icd || missing="$missing pocl-opencl-icd"
fi
# MPI (make MPI=1 only): Open MPI's compiler wrapper and mpirun
if [ "${MPI:-0}" = 1 ]; then
    command -v mpicc >/dev/null 2>&1 || missing="$missing libopenmpi-dev"
    command -v mpirun >/dev/null 2>&1 || missing="$missing openmpi-bin"
fi

# Optional: Python modules of the scripts, run as /usr/bin/python3:
# python3-matplotlib for the plots (scripts/plot.py, scripts/plot_tables.py),
# python3-svgelements for tests/e2e/svgcheck.py (an independent check of
# scripts/svg2curves.py, which itself needs only the standard library),
# python3-ezdxf for the DXF read-back of `run --export` (tests/e2e/e2e_export.sh)
# and results/export/*.png (scripts/dxf_png.py), python3-yaml for the lint of
# the CI recipes in scripts/ci/ (tests/e2e/e2e_ci_recipes.sh).
# Installed when missing and possible; never fail the build: the C build does
# not need them, and their tests count as skipped without them.
optional_apt() { # PACKAGE WHAT: installs PACKAGE when root with apt-get, else says how
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "deps: installing (optional, for $2): $1"
        if DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "$1" \
                >>/tmp/offbench-deps.log 2>&1 \
           || { apt-get update >>/tmp/offbench-deps.log 2>&1 \
                && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
                       "$1" >>/tmp/offbench-deps.log 2>&1; }; then
            echo "deps: installed: $1"
        else
            echo "deps: could not install $1 (see /tmp/offbench-deps.log);" \
                 "optional: only $2 uses it" >&2
        fi
    else
        echo "deps: optional: $1 (for $2):" \
             "sudo apt-get install $1" >&2
    fi
}
optional_py() { # MODULE PACKAGE WHAT
    /usr/bin/python3 -c "import $1" >/dev/null 2>&1 && return 0
    optional_apt "$2" "$3"
}
optional_py matplotlib python3-matplotlib "the plots"
optional_py svgelements python3-svgelements "the svg2curves.py check"
optional_py ezdxf python3-ezdxf "the DXF read-back test"
# Optional: zsh, to test the zsh completion (scripts/completion/_offbench).
command -v zsh >/dev/null 2>&1 || optional_apt zsh "the zsh completion test"
optional_py yaml python3-yaml "the CI recipes' lint"
# Optional: the Python package (python/) and its tests: numpy (its one
# dependency), pytest, pandas (read_results' DataFrame), setuptools and venv
# (pip install ./python into a fresh virtual environment, offline).
optional_py numpy python3-numpy "the Python package"
optional_py pytest python3-pytest "the Python package's tests"
optional_py pandas python3-pandas "the Python package's DataFrames"
optional_py setuptools python3-setuptools "pip install ./python"
optional_py ensurepip python3-venv "the Python package's install test"

# Optional, asked for with OB_DEPS_BROWSER=1 (about 100 MB): a headless
# Chromium for the nightly report's browser test and its screenshot.
optional_browser() {
    [ "${OB_DEPS_BROWSER:-0}" = 1 ] || return 0
    command -v chromium-headless-shell >/dev/null 2>&1 || command -v chromium >/dev/null 2>&1 && return 0
    optional_apt chromium-headless-shell "the report's browser test (tests/e2e/e2e_report.sh)"
}
optional_browser

# Optional, asked for with OB_DEPS_OCCT=1 (CI asks: .ci/run): OpenCASCADE's
# headers and libraries (TKernel, TKMath, TKG2d, TKGeomBase) and a C++
# compiler, for examples/occt/occt_offset.cpp.  Not by default: some
# 100 MB that nothing but the example needs.
optional_occt() {
    [ "${OB_DEPS_OCCT:-0}" = 1 ] || return 0
    for p in libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev g++; do
        have_pkg "$p" || optional_apt "$p" "the CAD-kernel example (make occt-example, occt-trimmed)"
    done
}
optional_occt

# Optional, asked for with OB_DEPS_LIB2GEOM=1 (CI asks: .ci/run): lib2geom
# (Inkscape's geometry library) and a C++ compiler, for the graphics
# library's offset as an external method (make lib2geom-worker,
# tests/e2e/e2e_lib2geom_method.sh).
optional_lib2geom() {
    [ "${OB_DEPS_LIB2GEOM:-0}" = 1 ] || return 0
    for p in lib2geom-dev g++; do
        have_pkg "$p" || optional_apt "$p" "the lib2geom method (make lib2geom-worker)"
    done
}
optional_lib2geom

[ -z "$missing" ] && exit 0

if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "deps: installing:$missing"
    export DEBIAN_FRONTEND=noninteractive
    if ! apt-get install -y --no-install-recommends $missing >/tmp/offbench-deps.log 2>&1; then
        apt-get update >>/tmp/offbench-deps.log 2>&1
        apt-get install -y --no-install-recommends $missing >>/tmp/offbench-deps.log 2>&1 \
            || { echo "deps: apt-get install$missing failed (see /tmp/offbench-deps.log);" \
                      "the CPU path builds without them" >&2
              have_header sisl.h || { echo "deps: libsisl-dev is required (the build links -lsisl)" >&2; exit 1; }
              have_header flint/fmpz_poly.h || { echo "deps: libflint-dev is required (the build links -lflint)" >&2; exit 1; }
              have_header expat.h || { echo "deps: libexpat1-dev is required (the build links -lexpat)" >&2; exit 1; }
              have_header nettle/sha2.h || { echo "deps: nettle-dev is required (the build links -lnettle)" >&2; exit 1; }
              exit 0; }
    fi
    echo "deps: installed:$missing"
else
    case "$missing" in *libsisl-dev*|*libflint-dev*|*libexpat1-dev*|*nettle-dev*)
        echo "deps: missing:$missing (libsisl-dev, libflint-dev, libexpat1-dev and nettle-dev are required: the build links -lsisl -lflint -lexpat -lnettle)" >&2
        echo "deps: install them with: sudo apt-get install$missing" >&2
        exit 1 ;;
    esac
    echo "deps: missing:$missing" >&2
    echo "deps: install them with: sudo apt-get install$missing" >&2
    echo "deps: (the OpenCL backend needs them; the CPU path builds without)" >&2
fi
exit 0
