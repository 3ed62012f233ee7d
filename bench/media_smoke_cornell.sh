#!/bin/sh
# Equal-time comparison on a smoke-filled Cornell box (bench/media/smoke-cornell.pbrt: 256x256,
# homogeneous smoke sigma_a 0.1, sigma_s 1 per m, g 0.2, the ceiling light inside the smoke), the
# scene of issue 10's anchor (pbrt-v4's volpath: ~0.27 s per sample per pixel on 2 threads,
# relMSE ~0.017 after 30 s). The reference is phos's path tracer at 8192 spp (unbiased; its own
# relMSE against the truth is ~0.0004: relMSE at 64 spp ~0.055 / 128). Rows: path at the sample
# counts that take about 10 / 30 / 60 s on an idle 2-core machine, photonmap at 1 / 4 / 16 spp,
# sppm at 10 / 30 / 60 s.
# Usage: bench/media_smoke_cornell.sh [BUILD_DIR] [extra phos options...]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
extra="$*"
scene=$here/media/smoke-cornell.pbrt
ref=$here/media/smoke-cornell-ref.exr
. "$here/media_common.sh"
printf '| %-9s | %-12s | %7s | %8s | %6s |\n' integrator budget wall relMSE ratio
printf '| %-9s | %-12s | %7s | %8s | %6s |\n' --- --- --- --- ---
run() {  # integrator, budget text, phos options...
    integ=$1 budget=$2
    shift 2
    img=$out/$integ.exr
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$phos" render "$scene" --integrator "$integ" "$@" $extra --quiet -o "$img"
    wall=$(seconds_since "$t0")
    measure "$img" "$ref"
    printf '| %-9s | %-12s | %7.1f | %8.5f | %6.3f |\n' "$integ" "$budget" "$wall" "$rel" "$ratio"
}
for spp in 128 352 704; do run path "--spp $spp" --spp "$spp"; done
for spp in 1 4 16; do run photonmap "--spp $spp" --spp "$spp"; done
for t in 10 30 60; do run sppm "--time $t" --time "$t"; done
