#!/bin/sh
# e2e_cl_cache_trust.sh - the OpenCL program binary cache runs only what the
# user's own build stored (issue 48, class 1).  A PoCL binary is native code:
# a cache file is loaded only from a directory and as a file that are the
# user's own, not group- or other-writable, opened without following links.
# Each case plants a valid binary (the legitimate one, copied: an attacker's
# would pass the checksum just as well) where the run looks for it, and the
# run must refuse it: one warning on stderr naming the path and why, the
# program built from source (meta.json's binary_cache not a hit), exit 0 and
# the rows of a clean run.  A FIFO named like the cache file must not block
# the run (timeout -s KILL guards the test: it fails rather than hangs).
# Also: names are SHA-256 (64 hex digits), files 0600, the directory 0700.
# Skipped without an OpenCL device.
. "$(dirname "$0")/lib_e2e.sh"
. "$(dirname "$0")/lib_cl.sh"
C=$CL_PROBE
unset OFFBENCH_CL_LAYOUT
# what the run's meta.json says the cache did, its first word
word() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["opencl"]["binary_cache"].split(":")[0].split(" ")[0])' "$1" 2>&1; }

export OFFBENCH_CL_CACHE="$T/good"
cl_device_or_skip 34
body "$T/cl_probe/results.csv" > "$T/ref.txt"
bin=$(ls "$T/good"/*.bin 2>/dev/null | head -n 1)
name=$(basename "$bin")
check 'echo "$name" | grep -Eq "^cl-[0-9a-f]{64}\.bin$"' "the cache file is named by a SHA-256 of its key: $name"
check '[ "$(stat -c %a "$bin")" = 600 ] && [ "$(stat -c %a "$T/good")" = 700 ]' \
    "the cache file 0600, its directory 0700: $(stat -c '%a %n' "$bin" "$T/good" | tr '\n' ' ')"
$OB run $C --out "$T/r1" >/dev/null 2>"$T/r1.err"
check '[ "$(word "$T/r1/meta.json")" = hit ] && ! grep -q warning "$T/r1.err"' \
    "the user's own cache is used, silently: $(word "$T/r1/meta.json"); $(grep warning "$T/r1.err")"

# refused DIR WHY [SETUP]: a cache in DIR (the good binary copied in, then
# SETUP run) is refused with one warning naming PATH and WHY
refused() {
    d=$1 why=$2 out=$T/o$n
    n=$((n + 1))
    OFFBENCH_CL_CACHE="$d" timeout -s KILL 60 $OB run $C --out "$out" >/dev/null 2>"$out.err"
    rc=$?
    check '[ $rc -eq 0 ] && body "$out/results.csv" | cmp -s - "$T/ref.txt"' \
        "$why: the run goes on from source: exit $rc; $(tail -n 2 "$out.err")"
    check '[ "$(word "$out/meta.json")" != hit ]' "$why: not loaded: $(word "$out/meta.json")"
    check '[ "$(grep -c "warning:.*cache" "$out.err")" = 1 ] && grep "warning:.*cache" "$out.err" | grep -qF "$d" && grep "warning:.*cache" "$out.err" | grep -q "$why"' \
        "$why: one warning naming the path and why: $(grep warning "$out.err")"
}
n=0
plant() { rm -rf "$1"; mkdir -p "$1" && chmod 700 "$1" && cp "$bin" "$1/$name" && chmod 600 "$1/$name"; }

plant "$T/ww"; chmod 777 "$T/ww"
refused "$T/ww" "writable by others"
plant "$T/gw"; chmod 770 "$T/gw"
refused "$T/gw" "writable by others"
plant "$T/real"; ln -s "$T/real" "$T/link"
refused "$T/link" "symbolic link"
plant "$T/fl"; rm "$T/fl/$name"; ln -s "$bin" "$T/fl/$name"
refused "$T/fl" "symbolic link"
plant "$T/fw"; chmod 666 "$T/fw/$name"
refused "$T/fw" "writable by others"
plant "$T/fifo"; rm "$T/fifo/$name"; mkfifo "$T/fifo/$name"
refused "$T/fifo" "not a regular file"
mkfifo "$T/dfifo"
refused "$T/dfifo" "Not a directory"
plant "$T/sum"; printf 'X' | dd of="$T/sum/$name" bs=1 seek=$(($(stat -c %s "$bin") - 10)) conv=notrunc 2>/dev/null
refused "$T/sum" "checksum"
if [ "$(id -u)" = 0 ]; then
    plant "$T/od"; chown nobody "$T/od"
    refused "$T/od" "owned by another user"
    plant "$T/of"; chown nobody "$T/of/$name"
    refused "$T/of" "owned by another user"
else
    echo "skipped: the other-owner cases need root to chown to nobody (running as uid $(id -u))"
    skipped=$((skipped + 6))
fi
# a refused directory is left as it was: nothing written into it
check '[ "$(ls "$T/ww" | wc -l)" = 1 ] && [ "$(stat -c %a "$T/ww")" = 777 ]' "a refused directory gets no file: $(ls "$T/ww")"
e2e_done
