#!/usr/bin/env bash
# Renders every .scn scene in a folder as a new user would (phos's defaults, `phos X.scn out`) and
# reports per scene: exit code, wall time, warnings, image mean, fraction of black pixels,
# non-finite values and isolated bright pixels (`phos info`'s speckle fraction, on the displayed
# and on the linear image); writes the renders and a contact sheet (contact.png) to OUT. With
# GALLERY=DIR, a scene's own image DIR/NAME.png (the seed renderer's gallery) is compared too: the
# 16 x 16 block correlation of the two, and the contact sheet pairs phos's render with it.
# Usage: [GALLERY=DIR] bench/seed_scenes.sh DIR [OUT [extra phos options...]]
#   e.g. bench/seed_scenes.sh ~/seed/scenes out/seed --width 200 --height 200 --spp 4
#   GALLERY=~/Global-Illumination/gallery/results bench/seed_scenes.sh ~/Global-Illumination/input out/art --width 256 --height 256
# Needs build/phos (bash scripts/run.sh builds it).
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
phos="${PHOS:-$here/build/phos}"
dir="${1:?usage: bench/seed_scenes.sh DIR [OUT [phos options...]]}"
out="${2:-out/seed-scenes}"
shift $(( $# >= 2 ? 2 : 1 ))
mkdir -p "$out"
gallery="${GALLERY:-}"
printf '%-28s %4s %8s %5s %10s %7s %9s %8s %8s %7s\n' scene exit seconds warn mean black nonfinite speckle spk_lin corr16
images=()
shopt -s nullglob
for scene in "$dir"/*.scn; do
  name="$(basename "$scene" .scn)"
  image="$out/$name.exr"
  start=$(date +%s.%N)
  "$phos" "$scene" "$image" "$@" > "$out/$name.log" 2>&1
  code=$?
  end=$(date +%s.%N)
  warnings=$(grep -c '^warning' "$out/$name.log")
  if [ "$code" -eq 0 ] && [ -f "$image" ]; then
    read -r _ _ _ mean _ black _ nonfinite _ speckle _ speckle_linear < <("$phos" info "$image")
    images+=("$image")
    corr=-
    if [ -n "$gallery" ] && [ -f "$gallery/$name.png" ]; then
      corr=$("$phos" diff "$image" "$gallery/$name.png" --block-correlation 16 | awk '$1 == "block_correlation" { printf "%.3f", $2 }')
      images+=("$gallery/$name.png")
    fi
  else
    mean=-; black=-; nonfinite=-; speckle=-; speckle_linear=-; corr=-
  fi
  printf '%-28s %4s %8s %5s %10s %7s %9s %8s %8s %7s\n' "$name" "$code" \
    "$(awk "BEGIN { printf \"%.2f\", $end - $start }")" "$warnings" \
    "$mean" "$black" "$nonfinite" "$speckle" "$speckle_linear" "${corr:--}"
done
if [ ${#images[@]} -gt 0 ]; then
  "$phos" montage "$out/contact.png" "${images[@]}" --cell 160 && echo "contact sheet: $out/contact.png"
fi
