#!/bin/sh
# Photon-tracing throughput against the ray-tracing limit, thread scaling, photon-map memory and
# k-d tree build rate, in one table (docs/performance.md keeps the figures):
#   - the anchor: raw Embree 3 single rays on photon-like incoherent rays
#     (../shared/bench/anchors/embree_rays.cpp, built here with its own build line), 1 and 2 threads;
#   - phos's photon tracer on cornell-diffuse (the photonmap command below, 4 M global photons):
#     photon rays per second of `time photon trace` (-v), its ratio to the anchor at the same thread
#     count, and the 1 -> 2 thread scaling of tracing and of the k-d tree build;
#   - with --big: 100 M global photons (2 threads): peak RSS against the map's own bytes (20 B per
#     photon) and the build rate. Needs ~3 GB of memory and a few minutes.
# Ratios, not absolute figures, are what to compare between machines: run it on an idle machine
# (the load average at the start is printed).
# Usage: bench/photon_throughput.sh [BUILD_DIR] [--big]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
big=0
[ "${1:-}" = "--big" ] && big=1
phos=$build/phos
shared=$here/../../shared/bench
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
g++ -O3 -march=native -std=c++17 "$shared/anchors/embree_rays.cpp" -lembree3 -ltbb -o "$out/rays"

# `photonmap THREADS GLOBAL`: runs the issue's command, leaves -v's output in $out/pm.log.
photonmap() {
    "$phos" render "$shared/scn/cornell-diffuse.scn" --integrator photonmap --width 64 --height 64 --spp 1 \
        --gather-rays 1 --global "$2" --no-irradiance-cache -v --no-progress --threads "$1" -o "$out/pm.pfm" \
        2> "$out/pm.log"
}
field() { sed -n "s/.*$1 *\([0-9.e+]*\).*/\1/p" "$out/pm.log" | head -1; }

printf '| %-7s | %13s | %13s | %6s | %8s | %13s |\n' threads "Embree Mray/s" "photon Mray/s" ratio trace-s "build Mphot/s"
printf '| %-7s | %13s | %13s | %6s | %8s | %13s |\n' --- --- --- --- --- ---
for t in 1 2; do
    anchor=$("$out/rays" "$t" 20000000 | sed -n 's/.*: \([0-9.]*\) M incoherent.*/\1/p')
    photonmap "$t" 4000000
    rays=$(sed -n 's/.* \([0-9]*\) photon (.*/\1/p' "$out/pm.log")
    trace=$(field "time photon trace:")
    build_s=$(field "time photon map build:")
    stored=$(sed -n 's/.*global map: \([0-9]*\) photons.*/\1/p' "$out/pm.log")
    rate=$(echo "$rays / $trace / 1000000" | bc -l)
    printf '| %-7s | %13.2f | %13.2f | %6.3f | %8.3f | %13.2f |\n' "$t" "$anchor" "$rate" \
        "$(echo "$rate / $anchor" | bc -l)" "$trace" "$(echo "$stored / $build_s / 1000000" | bc -l)"
    eval "trace_$t=$trace build_$t=$build_s"
done
echo "scaling 1 -> 2 threads: photon tracing $(echo "$trace_1 / $trace_2" | bc -l | cut -c1-4)x," \
    "map build $(echo "$build_1 / $build_2" | bc -l | cut -c1-4)x"

if [ "$big" = 1 ]; then
    photonmap 2 100000000
    stored=$(sed -n 's/.*global map: \([0-9]*\) photons.*/\1/p' "$out/pm.log")
    peak=$(sed -n 's/.*peak memory: \([0-9.]*\) \([MG]B\).*/\1 \2/p' "$out/pm.log")
    build_s=$(field "time photon map build:")
    trace=$(field "time photon trace:")
    peak_gb=$(echo "$peak" | awk '{ print ($2 == "GB") ? $1 : $1 / 1000 }')
    map_gb=$(echo "$stored * 20 / 1000000000" | bc -l)
    printf '100 M photons (2 threads): %s stored, map %.2f GB, peak RSS %s GB (%.2fx the map), trace %s s, build %s s (%.2f M photons/s)\n' \
        "$stored" "$map_gb" "$peak_gb" "$(echo "$peak_gb / $map_gb" | bc -l)" "$trace" "$build_s" \
        "$(echo "$stored / $build_s / 1000000" | bc -l)"
fi
