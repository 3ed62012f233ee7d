#!/bin/sh
# Equal-time table of issue 16 (docs/bidirectional.md): path, bdpt, sppm and vcm on the three bench
# scenes at 256x256 with the bench budgets (15 s cornell-diffuse, 16 s cornell-glass-mirror, 24 s
# caustic-point; --time bounds the whole command, the render stops at the end of the pass or
# iteration that crosses it), relMSE against ../shared/bench/ref. One row per scene and
# integrator: wall time, the work done (samples per pixel or iterations), relMSE, mean ratio and
# the caustic window where the scene has one. Run it on an idle machine (the load average at the
# start is printed): figures scale with the CPU time the renders get.
# Usage: bench/bidirectional_equal_time.sh [BUILD_DIR] [INTEGRATORS] [extra phos options...]
#   INTEGRATORS: a quoted list (default "path bdpt sppm vcm"); an entry may carry options joined
#   by commas, e.g. "vcm,--radius-pixels,2".
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/metrics.sh"
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
integrators=${1:-path bdpt sppm vcm}
[ $# -gt 0 ] && shift
extra="$*"
phos=$build/phos
shared=$here/../../shared/bench
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores; extra options: ${extra:-none}"
printf '| %-20s | %-28s | %6s | %6s | %9s | %8s | %6s | %-14s |\n' scene integrator budget wall work relMSE ratio \
    "window (ref)"
printf '| %-20s | %-28s | %6s | %6s | %9s | %8s | %6s | %-14s |\n' --- --- --- --- --- --- --- ---
for spec in "cornell-diffuse 15.0 - - - - -" "cornell-glass-mirror 16.0 168 200 226 242 0.680" \
    "caustic-point 24.0 104 128 132 156 4.58"; do
    set -- $spec
    scene=$1 budget=$2 x0=$3 x1=$4 y0=$5 y1=$6 wref=$7
    for entry in $integrators; do
        opts=$(echo "$entry" | tr ',' ' ')
        name=$(echo "$entry" | cut -d, -f1)
        start=$(date +%s.%N)
        log=$("$phos" render "$shared/scn/$scene.scn" --integrator $opts --width 256 --height 256 \
            --time "$budget" $extra -o "$out/$scene.pfm" -v 2>&1)
        end=$(date +%s.%N)
        wall=$(echo "$end - $start" | bc)
        # The work done: "N iterations" (ppm, sppm, bdpt, vcm) or the samples per pixel.
        work=$(echo "$log" | sed -n "s/.*$name: \([0-9]*\) iterations.*/\1 it/p" | head -1)
        [ -n "$work" ] || work=$(echo "$log" | sed -n 's/.*image: [0-9x]*, \([0-9.]*\) of.*/\1 spp/p; s/.*image: [0-9x]*, \([0-9.]*\) samples per pixel.*/\1 spp/p' | head -1)
        set -- $(bench_metrics "$phos" "$out/$scene.pfm" "$shared/ref/$scene.pfm" "$x0" "$x1" "$y0" "$y1")
        win=$(bench_window_text "$3" "$wref")
        printf '| %-20s | %-28s | %6s | %6.2f | %9s | %8s | %6s | %-14s |\n' "$scene" "$opts" "$budget" "$wall" \
            "$work" "$1" "$2" "$win"
    done
done
