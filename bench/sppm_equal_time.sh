#!/bin/sh
# Equal-time benchmark of phos's SPPM against pbrt-v4's (figures in ../shared/bench/README.md):
# renders each bench scene at 256x256 with a wall-time budget (--time bounds the whole command,
# load included; the render stops at the end of the iteration that crosses it) and prints the
# measured wall time, iterations, relMSE, mean ratio and caustic window against the reference.
# Usage: bench/sppm_equal_time.sh [BUILD_DIR] [extra phos options...]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
phos=$build/phos
diff_tool=$build/sppm_metrics
shared=$here/../../shared/bench
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-22s %6s %7s %6s %9s %7s %8s %s\n' scene budget wall iters relMSE ratio window pbrt-relMSE
for spec in "cornell-diffuse 15.0 0.0013 - - - -" "cornell-glass-mirror 16.0 0.0026 168 200 226 242" \
            "caustic-point 24.0 0.0072 104 128 132 156" \
            "cornell-diffuse 4.5 0.0033 - - - -" "cornell-glass-mirror 6.5 0.0063 168 200 226 242" \
            "caustic-point 6.0 0.024 104 128 132 156"; do
    set -- $spec "$@"
    scene=$1 budget=$2 pbrt=$3
    start=$(date +%s.%N)
    iters=$("$phos" render "$shared/scn/$scene.scn" --integrator sppm --width 256 --height 256 \
        --time "$budget" -o "$out/$scene.pfm" -v 2>&1 | sed -n 's/.*sppm: \([0-9]*\) iterations.*/\1/p')
    end=$(date +%s.%N)
    wall=$(echo "$end - $start" | bc)
    if [ "$4" = "-" ]; then win=""; else win="$4 $5 $6 $7"; fi
    metrics=$("$diff_tool" "$out/$scene.pfm" "$shared/ref/$scene.pfm" $win)
    printf '%-22s %6s %7.2f %6s %s %s\n' "$scene" "$budget" "$wall" "$iters" "$metrics" "$pbrt"
    shift 7
done
