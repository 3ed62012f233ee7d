#!/bin/sh
# Equal-time benchmark of phos's SPPM against pbrt-v4's (figures in ../shared/bench/README.md):
# renders each bench scene at 256x256 with a wall-time budget (--time bounds the whole command,
# load included; the render stops at the end of the iteration that crosses it) and prints one table
# row per run: wall time, iterations, relMSE, mean ratio, caustic window, pbrt-v4's relMSE at that
# time and the goal (a fifth of pbrt-v4's error above the reference's noise). Run it on an idle
# machine: iterations scale with the
# CPU time the render actually gets (the load average at the start is printed).
# Usage: bench/sppm_equal_time.sh [BUILD_DIR] [COLUMNS] [extra phos options...]
#   COLUMNS: which of pbrt's time columns to run, a subset of "1 2 3 4" (1.5-0.8 s ... 57.6-24 s;
#   "1 2 3 4" runs the whole table, about 4 minutes), or "goal" (default): the product goal's
#   budgets, 15 s, 16 s and 24 s (column 3 for the Cornell boxes, 4 for caustic-point).
# goal = floor + (pbrt - floor) / 5, floor = the reference's own noise (the README's "error above
# the reference's noise", at most a fifth of pbrt-v4's).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/metrics.sh"
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
columns=${1:-goal}
[ $# -gt 0 ] && shift
extra="$*"  # extra phos options (word-split when used)
phos=$build/phos
shared=$here/../../shared/bench
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores; options: --integrator sppm $extra"
printf '| %-20s | %6s | %6s | %5s | %8s | %6s | %-14s | %8s | %8s |\n' scene budget wall iters relMSE ratio \
    "window (ref)" pbrt goal
printf '| %-20s | %6s | %6s | %5s | %8s | %6s | %-14s | %8s | %8s |\n' --- --- --- --- --- --- --- --- ---
# scene, window (x0 x1 y0 y1, "-" = none), reference window mean, reference noise floor, then per
# column: budget s, pbrt relMSE.
for col in $columns; do
    for spec in "cornell-diffuse - - - - - 0.00013 1.5 0.0088 4.5 0.0033 15.0 0.0013 57.6 0.00062" \
        "cornell-glass-mirror 168 200 226 242 0.680 0.0003 2.3 0.020 6.5 0.0063 16.0 0.0026 70.5 0.0013" \
        "caustic-point 104 128 132 156 4.58 0.001 0.8 0.32 1.8 0.087 6.0 0.024 24.0 0.0072"; do
        set -- $spec
        scene=$1 x0=$2 x1=$3 y0=$4 y1=$5 wref=$6 floor=$7
        shift 7
        c=$col
        if [ "$c" = goal ]; then
            c=3
            [ "$scene" = caustic-point ] && c=4
        fi
        i=1
        while [ $i -lt "$c" ]; do shift 2; i=$((i + 1)); done
        budget=$1 pbrt=$2
        start=$(date +%s.%N)
        iters=$("$phos" render "$shared/scn/$scene.scn" --integrator sppm --width 256 --height 256 \
            --time "$budget" $extra -o "$out/$scene.pfm" -v 2>&1 | sed -n 's/.*sppm: \([0-9]*\) iterations.*/\1/p')
        end=$(date +%s.%N)
        wall=$(echo "$end - $start" | bc)
        set -- $(bench_metrics "$phos" "$out/$scene.pfm" "$shared/ref/$scene.pfm" "$x0" "$x1" "$y0" "$y1")
        win=$(bench_window_text "$3" "$wref")
        goal=$(echo "scale=6; $floor + ($pbrt - $floor) / 5" | bc | sed 's/^\./0./')
        printf '| %-20s | %6s | %6.2f | %5s | %8s | %6s | %-14s | %8s | %8s |\n' "$scene" "$budget" "$wall" \
            "$iters" "$1" "$2" "$win" "$pbrt" "$goal"
    done
done
