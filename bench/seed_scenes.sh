#!/usr/bin/env bash
# Renders every .scn scene in a folder as a new user would (phos's defaults, `phos X.scn out`) and
# reports per scene: exit code, wall time, warnings, image mean, fraction of black pixels and
# non-finite values; writes the renders and a contact sheet (contact.png) to OUT.
# Usage: bench/seed_scenes.sh DIR [OUT [extra phos options...]]
#   e.g. bench/seed_scenes.sh ~/seed/scenes out/seed --width 200 --height 200 --spp 4
# Needs build/phos (bash scripts/run.sh builds it).
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
phos="${PHOS:-$here/build/phos}"
dir="${1:?usage: bench/seed_scenes.sh DIR [OUT [phos options...]]}"
out="${2:-out/seed-scenes}"
shift $(( $# >= 2 ? 2 : 1 ))
mkdir -p "$out"
printf '%-28s %4s %8s %5s %10s %7s %9s\n' scene exit seconds warn mean black nonfinite
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
    read -r _ _ _ mean _ black _ nonfinite _ _ _ < <("$phos" info "$image")
    images+=("$image")
  else
    mean=-; black=-; nonfinite=-
  fi
  printf '%-28s %4s %8s %5s %10s %7s %9s\n' "$name" "$code" "$(awk "BEGIN { printf \"%.2f\", $end - $start }")" \
    "$warnings" \
    "$mean" "$black" "$nonfinite"
done
if [ ${#images[@]} -gt 0 ]; then
  "$phos" montage "$out/contact.png" "${images[@]}" --cell 160 && echo "contact sheet: $out/contact.png"
fi
