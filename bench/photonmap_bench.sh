#!/bin/sh
# Benchmark of the two-pass photon mapper (--integrator photonmap) on the three bench scenes at
# 256x256 with the recommended defaults (plus any extra options given, applied to every scene):
# wall time of the whole `phos render` command, relMSE, mean ratio and caustic window against the
# reference, photon tracing rate, map build time and render-pass time (from -v).
# Usage: bench/photonmap_bench.sh [BUILD_DIR] [extra phos options...]
# Needs BUILD_DIR/phos (metrics from `phos diff`).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/metrics.sh"
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
phos=$build/phos
shared=$here/../../shared/bench
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load: $(cat /proc/loadavg)"
printf '%-21s %7s %9s %7s %8s %14s %8s %8s\n' scene wall-s relMSE ratio window trace-rate build-s render-s
for spec in "cornell-diffuse - - - -" "cornell-glass-mirror 168 200 226 242" "caustic-point 104 128 132 156"; do
    set -- $spec "$@"
    scene=$1
    if [ "$2" = "-" ]; then win=""; else win="$2 $3 $4 $5"; fi
    shift 5
    start=$(date +%s.%N)
    "$phos" render "$shared/scn/$scene.scn" --integrator photonmap --width 256 --height 256 --no-progress -q -v \
        -o "$out/$scene.pfm" "$@" 2> "$out/$scene.log"
    end=$(date +%s.%N)
    rate=$(sed -n 's/.*photon tracing rate: \([^ ]*\).*/\1/p' "$out/$scene.log")
    build_s=$(sed -n 's/.*time photon map build: *\([^ ]*\) s/\1/p' "$out/$scene.log")
    render_s=$(sed -n 's/.*time photon map render pass: *\([^ ]*\) s/\1/p' "$out/$scene.log")
    m=$(bench_metrics "$phos" "$out/$scene.pfm" "$shared/ref/$scene.pfm" $win)
    e=$(echo "$m" | cut -d' ' -f1)
    ratio=$(echo "$m" | cut -d' ' -f2)
    w=-
    [ -n "$win" ] && w=$(echo "$m" | cut -d' ' -f3)
    printf '%-21s %7.2f %9s %7s %8s %14s %8s %8s\n' "$scene" "$(echo "$end - $start" | bc)" "$e" "$ratio" "$w" \
        "$rate" "$build_s" "$render_s"
done
