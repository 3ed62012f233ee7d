#!/bin/sh
# photonmap's two volume estimates on the participating-media benchmark
# (../shared/bench/media/fog-caustic: a point light focused by a glass sphere into fog):
# --volume-estimate march (ray marching, a k-nearest estimate per step) against beam (the beam
# radiance estimate, one query per stretch), at a few budgets, with wall time, relMSE against the
# pbrt-v4 reference and the volume caustic's contrast (as bench/media_equal_time.sh: mean luminance
# in x [120,136) y [184,208) minus the mean of the side windows; 0.0211 in the reference). The
# --fast-global rows leave out the final gather, whose noise and cost otherwise dominate, and add
# march with coarser steps. Budgets alternate the two estimators, so a change in the machine's load
# hits both alike; the load average at the start is printed, and "cpu" (user + system seconds of
# the render, all threads) is the cost to compare when other work shares the machine.
# A second table isolates the volume estimates' own error at --spp 4 --fast-global: relMSE against
# march with a fine step (0.011, a quarter of the default) and the same seed, so that the photon
# maps and every other sample are shared and only the volume estimate differs (beam and march
# converge to slightly different values: march's k-nearest estimate is ~1.7 % higher in a uniform
# density, see docs/media.md).
# Usage: bench/media_volume_estimate.sh [BUILD_DIR] [extra phos options...]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
extra="$*"
scene=$here/../../shared/bench/media/fog-caustic.pbrt
ref=$here/../../shared/bench/media/fog-caustic.exr
. "$here/media_common.sh"
printf '| %-8s | %-40s | %7s | %7s | %8s | %6s | %8s |\n' estimate budget wall cpu relMSE ratio contrast
printf '| %-8s | %-40s | %7s | %7s | %8s | %6s | %8s |\n' --- --- --- --- --- --- ---
run() {  # image name, estimate, phos options...
    img=$out/$1.exr est=$2
    shift 2
    t0=$(date +%s.%N)
    # shellcheck disable=SC2086
    /usr/bin/time -f '%U %S' -o "$out/time" \
        "$phos" render "$scene" --integrator photonmap --volume-estimate "$est" "$@" $extra --quiet -o "$img"
    wall=$(seconds_since "$t0")
    cpu=$(awk '{print $1 + $2}' "$out/time")
    measure "$img" "$ref"
    printf '| %-8s | %-40s | %7.1f | %7.1f | %8.5f | %6.3f | %8s |\n' "$est" "$*" "$wall" "$cpu" "$rel" "$ratio" \
        "$(caustic_contrast "$img")"
}
fg="--spp 4 --fast-global"
run m1 march --spp 1
run b1 beam --spp 1
run m4 march --spp 4
run b4 beam --spp 4
# shellcheck disable=SC2086
{
    run fg-march march $fg
    run fg-beam beam $fg
    run fg-march-0.1 march $fg --volume-step 0.1
    run fg-march-0.2 march $fg --volume-step 0.2
    run fg-march-0.4 march $fg --volume-step 0.4
    run p-march march $fg --volume-photons 800000 --volume-caustic-photons 800000
    run p-beam beam $fg --volume-photons 800000 --volume-caustic-photons 800000
    "$phos" render "$scene" --integrator photonmap --volume-estimate march $fg --volume-step 0.011 $extra --quiet \
        -o "$out/fine.exr"
}
echo
echo "volume estimate's own error at $fg (relMSE against march --volume-step 0.011):"
for img in fg-beam fg-march fg-march-0.1 fg-march-0.2 fg-march-0.4; do
    printf '  %-14s %s\n' "$img" "$("$phos" diff "$out/$img.exr" "$out/fine.exr" | awk '/relMSE/ {print $2}')"
done
