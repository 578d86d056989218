# lib_cl.sh - sourced after lib_e2e.sh by the e2e scripts that need an
# OpenCL device (not a test itself).
# cl_device_or_skip N: one small --backend opencl run (into $T/cl_probe,
# which the script may use: its meta.json names the device); without a
# device it says why, counts the script's N checks as skipped and ends it.
CL_PROBE="--curve liu2002_ex1 --methods tiller --tols 1e-2 --backend opencl --metric radial"
cl_device_or_skip() {
    $OB run $CL_PROBE --out "$T/cl_probe" >/dev/null 2>"$T/cl_probe.err" && return 0
    echo "no OpenCL device: $(tail -n 1 "$T/cl_probe.err")"
    skipped=$((skipped + $1))
    e2e_done
    exit $?
}
