#!/bin/sh
# device_bundle.sh DIR - ./offbench with every shared library it loads (its
# C library and loader included, and the OpenCL ICD loader it opens at run
# time), for a machine that lacks the packages or has another C library:
# DIR/offbench is a wrapper that runs the program through the carried
# loader (OB=DIR/offbench scripts/device_check.sh).  NVIDIA's or any other
# vendor's OpenCL driver stays the machine's own (an ICD file names it).
set -eu
cd "$(dirname "$0")/.."
dir=${1:?usage: scripts/device_bundle.sh DIR}
[ -x ./offbench ] || { echo "device_bundle: build ./offbench first (make)" >&2; exit 2; }
mkdir -p "$dir/lib"
cp ./offbench "$dir/offbench.bin"
ldd ./offbench | awk '/=>/ {print $3} /ld-linux/ {print $1}' | while read -r lib; do
    [ -f "$lib" ] && cp -L "$lib" "$dir/lib/"
done
for lib in libOpenCL.so.1; do
    p=$(ldconfig -p | awk -v l="$lib" '$1 == l {print $NF; exit}')
    [ -n "$p" ] && cp -L "$p" "$dir/lib/"
done
loader=$(basename "$(ldd ./offbench | awk '/ld-linux/ {print $1}')")
cat > "$dir/offbench" <<WRAP
#!/bin/sh
here=\$(cd "\$(dirname "\$0")" && pwd)
exec "\$here/lib/$loader" --library-path "\$here/lib" "\$here/offbench.bin" "\$@"
WRAP
chmod +x "$dir/offbench"
du -sh "$dir" | sed 's/^/device_bundle: /'
