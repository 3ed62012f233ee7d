#!/usr/bin/env bash
# MPI scaling of phos renders (docs/distributed.md): wall time of one process with one thread
# against N ranks of one thread each (and, for comparison, one process with N threads), the
# parallel efficiency T1 / (N * TN), the bytes exchanged (from -v), and whether the images are
# byte-identical to the single process's. Interleaved runs, the minimum of each kept (shared
# machines drift: compare within one run).
# Usage: bench/mpi_scaling.sh [BUILD_DIR [RUNS [RANKS...]]]   (default: build 3 2)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
runs="${2:-3}"
shift $(( $# < 2 ? $# : 2 ))
rank_counts=("$@")
[ ${#rank_counts[@]} -eq 0 ] && rank_counts=(2)
scene="$here/../shared/bench/scn/cornell-glass-mirror.scn"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
command -v mpirun >/dev/null || { echo "mpi_scaling: mpirun is missing (scripts/setup.sh installs openmpi-bin)" >&2; exit 2; }
mpi=(mpirun --allow-run-as-root --oversubscribe --bind-to none)

declare -A cases=(
  [path]="--integrator path --width 256 --height 256 --spp 64"
  [photonmap]="--integrator photonmap --width 256 --height 256 --spp 4 --global 400000 --caustic 400000"
  [sppm]="--integrator sppm --width 256 --height 256 --iterations 24 --photons-per-iter 200000"
)
wall() {  # seconds of the command's wall time
  local t0 t1
  t0=$(date +%s.%N); "$@" >"$out/log" 2>&1; t1=$(date +%s.%N)
  python3 -c "print($t1 - $t0)"
}
min() { python3 -c "print(min($1, $2))"; }

printf "%-10s %5s %10s %10s %10s %12s %10s\n" case ranks "1 proc s" "N ranks s" "N thr s" efficiency "MB moved"
for name in path photonmap sppm; do
  opts=(${cases[$name]})
  for n in "${rank_counts[@]}"; do
    t1=1e9 tn=1e9 tt=1e9
    for ((i = 0; i < runs; ++i)); do
      t1=$(min "$t1" "$(wall "$build/phos" render "$scene" "${opts[@]}" --threads 1 -q -o "$out/one.pfm")")
      tn=$(min "$tn" "$(wall "${mpi[@]}" -np "$n" "$build/phos" render "$scene" "${opts[@]}" --threads 1 -v -o "$out/ranks.pfm")")
      moved=$(sed -n "s/.*rank 0 of $n: .*, \([0-9.e+-]*\) MB exchanged.*/\1/p" "$out/log" | head -1)
      tt=$(min "$tt" "$(wall "$build/phos" render "$scene" "${opts[@]}" --threads "$n" -q -o "$out/threads.pfm")")
    done
    same=$(cmp -s "$out/one.pfm" "$out/ranks.pfm" && echo identical || echo DIFFERENT)
    eff=$(python3 -c "print(f'{$t1 / ($n * $tn):.2f}')")
    printf "%-10s %5d %10.2f %10.2f %10.2f %12s %10s  %s\n" "$name" "$n" "$t1" "$tn" "$tt" "$eff" "${moved:-?}" "$same"
  done
done
