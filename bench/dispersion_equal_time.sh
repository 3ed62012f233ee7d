#!/bin/sh
# Equal-time table on the dispersive showcase (issue 41's performance target): scenes/prism.pbrt
# (an SF10 prism's rainbow under a narrow spot light) at 256x256 for 17 s, pbrt-v4 bdpt's time
# for relMSE 0.0043 at 64 spp against its converged image. The target is a relMSE above the
# reference's own noise of at most 0.0043 / 3. The reference is phos's own: sppm for
# PHOS_REF_TIME seconds (default 900), rendered twice with different seeds; the second measures
# the first's noise (relMSE between two independent renders is about the sum of theirs, so each
# has about half). Both are kept in PHOS_REF_DIR (default BUILD/prism-ref) for later runs.
# Usage: bench/dispersion_equal_time.sh [BUILD_DIR] [INTEGRATORS] [BUDGET]
#   INTEGRATORS: default "sppm vcm bdpt photonmap path"; BUDGET: seconds (default 17).
# Run it on an idle machine (the load average at the start is printed).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
. "$here/metrics.sh"
build=${1:-$here/../build}
integrators=${2:-sppm vcm bdpt photonmap path}
budget=${3:-17}
phos=$build/phos
scene=$here/../scenes/prism.pbrt
refdir=${PHOS_REF_DIR:-$build/prism-ref}
reftime=${PHOS_REF_TIME:-900}
mkdir -p "$refdir"
for seed in 1 2; do
    if [ ! -f "$refdir/ref$seed.pfm" ]; then
        echo "rendering reference $seed (sppm, $reftime s)..."
        "$phos" render "$scene" --integrator sppm --width 256 --height 256 --time "$reftime" --seed "$seed" \
            -o "$refdir/ref$seed.pfm" >/dev/null 2>&1
    fi
done
ref=$refdir/ref1.pfm
set -- $(bench_metrics "$phos" "$refdir/ref2.pfm" "$ref")
noise=$(echo "scale=8; $1 / 2" | bc | xargs printf '%.6f')
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores; reference noise ~$noise (relMSE of two references / 2)"
printf '| %-10s | %6s | %6s | %-14s | %8s | %8s | %6s | %8s |\n' integrator budget wall work relMSE "- noise" ratio target
printf '| %-10s | %6s | %6s | %-14s | %8s | %8s | %6s | %8s |\n' --- --- --- --- --- --- --- ---
for integ in $integrators; do
    start=$(date +%s.%N)
    work=$("$phos" render "$scene" --integrator "$integ" --width 256 --height 256 --time "$budget" \
        -o "$out/$integ.pfm" -v 2>&1 | sed -En 's/.*image: 256x256, ([0-9]+( of [0-9]+)? [a-z]+).*/\1/p')
    end=$(date +%s.%N)
    wall=$(echo "$end - $start" | bc)
    set -- $(bench_metrics "$phos" "$out/$integ.pfm" "$ref")
    above=$(echo "scale=8; $1 - $noise" | bc | xargs printf '%.5f')
    printf '| %-10s | %6s | %6.2f | %-14s | %8s | %8s | %6s | %8s |\n' "$integ" "$budget" "$wall" "$work" "$1" \
        "$above" "$2" 0.00143
done
