#!/bin/sh
# relMSE against time on the participating-media benchmark (../shared/bench/media/fog-caustic: a
# point light focused by a glass sphere into fog) for path, photonmap and sppm, with the volume
# caustic's contrast: mean luminance in x [120,136) y [184,208) minus the mean of the side windows
# x [96,112) and [144,160) (0.0211 in the reference, ~0 without the volume caustic). One table row
# per run; run it on an idle machine (the load average at the start is printed).
# Usage: bench/media_equal_time.sh [BUILD_DIR] [extra phos options...]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
extra="$*"
scene=$here/../../shared/bench/media/fog-caustic.pbrt
ref=$here/../../shared/bench/media/fog-caustic.exr
. "$here/media_common.sh"
printf '| %-9s | %-27s | %7s | %8s | %6s | %8s |\n' integrator budget wall relMSE ratio contrast
printf '| %-9s | %-27s | %7s | %8s | %6s | %8s |\n' --- --- --- --- --- ---
run() {  # integrator, budget text, phos options...
    integ=$1 budget=$2
    shift 2
    img=$out/$integ.exr
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$phos" render "$scene" --integrator "$integ" "$@" $extra --quiet -o "$img"
    wall=$(seconds_since "$t0")
    measure "$img" "$ref"
    printf '| %-9s | %-27s | %7.1f | %8.5f | %6.3f | %8s |\n' "$integ" "$budget" "$wall" "$rel" "$ratio" \
        "$(caustic_contrast "$img")"
}
for spp in 16 64 256; do run path "--spp $spp --regularize 0" --spp "$spp" --regularize 0; done
for spp in 16 64 256; do run path "--spp $spp" --spp "$spp"; done
for spp in 1 4 16; do run photonmap "--spp $spp" --spp "$spp"; done
for t in 10 30 60; do run sppm "--time $t" --time "$t"; done
