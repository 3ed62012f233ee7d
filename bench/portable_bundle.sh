#!/bin/sh
# Packs what bench/photon_throughput.sh needs into one folder that runs on another x86-64 Linux
# machine with none of phos's packages installed (a many-core machine lent for a few minutes, for
# the 1-16 thread scaling curve): the built phos, the shared libraries it and the anchor link
# except the C library's own (xz-compressed: ~20 MB in all), the anchor built here with its own
# build line, bench/memory_bandwidth, the benchmark scene and the bench script. On the other machine:
# `sh DIR/run.sh [--big | --contend]` prints the machine's memory bandwidth at each thread count
# (a 2 GiB array; PHOS_BANDWIDTH_GIB=0 skips it), then the table for PHOS_THREADS (default
# "1 2 4 8 16") with PHOS_PHOTONS (default 64 M) and PHOS_ANCHOR_RAYS (default 100 M), enough
# work for 16 cores to run a few seconds per row; --big and --contend go to the script.
# The anchor is built with -march=native here: the other machine needs every instruction set this
# one has (check with `grep flags /proc/cpuinfo` on both), and a C library at least as new.
# Usage: bench/portable_bundle.sh [BUILD_DIR] OUT_DIR
set -eu
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -ge 2 ]; then
    build=$1
    out=$2
else
    build=$here/../build
    out=${1:?usage: bench/portable_bundle.sh [BUILD_DIR] OUT_DIR}
fi
shared=${PHOS_BENCH_DIR:-$here/../../shared/bench}
[ -x "$build/phos" ] || { echo "no phos in $build: build it first (scripts/setup.sh)" >&2; exit 2; }
[ -x "$build/memory_bandwidth" ] || { echo "no memory_bandwidth in $build: build the benches first" >&2; exit 2; }
command -v xz > /dev/null || { echo "the libraries are packed with xz: apt-get install xz-utils" >&2; exit 2; }
rm -rf "$out"
mkdir -p "$out/bin" "$out/bench/scn" "$out/lib"
cp "$build/phos" "$out/bin/phos"
cp "$build/memory_bandwidth" "$out/bin/memory_bandwidth"
g++ -O3 -march=native -std=c++17 "$shared/anchors/embree_rays.cpp" -lembree3 -ltbb -o "$out/rays"
cp "$shared/scn/cornell-diffuse.scn" "$out/bench/scn/"
cp "$here/photon_throughput.sh" "$out/"
# Every library the two programs load, but the C library's (it must be the other machine's own).
{ ldd "$out/bin/phos"; ldd "$out/bin/memory_bandwidth"; ldd "$out/rays"; } | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u |
    grep -Ev '/(libc|libm|libdl|librt|libpthread|libresolv|ld-linux[^/]*)\.so' | while read -r lib; do
    cp -L "$lib" "$out/lib/"
done
tar -cJf "$out/lib.tar.xz" -C "$out/lib" .
rm -rf "$out/lib"
cat > "$out/run.sh" << 'EOF'
#!/bin/sh
# The scaling table of bench/photon_throughput.sh with the libraries packed beside it.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
[ -d "$here/lib" ] || { mkdir -p "$here/lib" && tar -xJf "$here/lib.tar.xz" -C "$here/lib"; }
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
grep -m1 'model name' /proc/cpuinfo || true
threads=${PHOS_THREADS:-1 2 4 8 16}
if [ "${PHOS_BANDWIDTH_GIB:-2}" != 0 ]; then
    # shellcheck disable=SC2086 # the thread counts are words
    "$here/bin/memory_bandwidth" "${PHOS_BANDWIDTH_GIB:-2}" $threads
fi
PHOS_THREADS=$threads PHOS_PHOTONS=${PHOS_PHOTONS:-64000000} \
    PHOS_ANCHOR_RAYS=${PHOS_ANCHOR_RAYS:-100000000} PHOS_ANCHOR="$here/rays" PHOS_BENCH_DIR="$here/bench" \
    sh "$here/photon_throughput.sh" "$here/bin" "$@"
EOF
chmod +x "$out/run.sh"
du -sh "$out" | awk '{ print "bundle: " $1 }'
