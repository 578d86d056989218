#!/bin/sh
# e2e_cl_oom.sh - an OpenCL platform that is installed but cannot start for
# want of memory is said as out of memory, exit 1, never as "install an
# ICD" or "no device with double precision", exit 2, and never as a crash
# (issue 48, class 12).  Under `ulimit -v` PoCL fails in three ways (found
# on PoCL 3.1): the ICD loader cannot map libpocl and reports no platform
# (CL_PLATFORM_NOT_FOUND_KHR, as with no ICD at all), clGetDeviceIDs gives
# CL_OUT_OF_HOST_MEMORY, or PoCL aborts starting its threads.  A scan of
# limits (which limit fails where depends on the machine) checks that every
# run either works (exit 0) or says out of memory (exit 1).  And the other
# side: no ICD at all, or an ICD naming a library that is not there, is
# still a setup error, exit 2, said as such.  Skipped without a device.
. "$(dirname "$0")/lib_e2e.sh"
. "$(dirname "$0")/lib_cl.sh"
C=$CL_PROBE
export OFFBENCH_CL_CACHE="$T/cache"
cl_device_or_skip 4

# no ICD: an empty vendors directory
mkdir -p "$T/none"
OCL_ICD_VENDORS="$T/none" $OB run $C --out "$T/n" >/dev/null 2>"$T/n.err"
check '[ $? -eq 2 ] && grep -q "install an ICD" "$T/n.err" && ! grep -qi "memory" "$T/n.err"' \
    "no ICD: exit 2, install one: $(cat "$T/n.err")"
# an ICD whose library is missing: named, exit 2
mkdir -p "$T/bad"
echo "$T/no/libnothere.so" > "$T/bad/nothere.icd"
OCL_ICD_VENDORS="$T/bad" $OB run $C --out "$T/b" >/dev/null 2>"$T/b.err"
check '[ $? -eq 2 ] && grep -q "nothere.icd" "$T/b.err" && grep -q "libnothere.so" "$T/b.err"' \
    "an ICD naming a missing library: exit 2, both named: $(cat "$T/b.err")"

# the scan: each limit (KiB) a run that works or says out of memory; a
# build that cannot start under the smallest at all (a sanitizer's shadow
# memory needs terabytes of address space) is skipped
if ! (ulimit -v 160000; $OB --version) >/dev/null 2>&1; then
    echo "skipped: this build does not start under ulimit -v 160000 (a sanitizer build?): the scan is left out"
    skipped=$((skipped + 2))
    e2e_done
    exit $?
fi
said=0 wrong=""
for v in $(seq 160000 10000 420000); do
    (ulimit -v "$v"; timeout -s KILL 120 $OB run $C --out "$T/m$v" >/dev/null 2>"$T/m$v.err")
    rc=$?
    if [ $rc -eq 1 ] && grep -q "out of memory" "$T/m$v.err"; then
        grep -q "OpenCL" "$T/m$v.err" && said=$((said + 1))
    elif [ $rc -ne 0 ]; then
        wrong="$wrong [ulimit -v $v: exit $rc: $(tail -n 1 "$T/m$v.err")]"
    fi
done
check '[ -z "$wrong" ]' "every limit: exit 0, or exit 1 saying out of memory:$wrong"
if [ $said -gt 0 ]; then
    check 'true' "the OpenCL platform said out of memory under $said limits"
else
    echo "skipped: no limit of the scan failed the OpenCL platform itself on this machine"
    skipped=$((skipped + 1))
fi
e2e_done
