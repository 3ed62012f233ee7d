#!/usr/bin/env bash
# MPI scaling of phos renders (docs/distributed.md): wall time of one process with one thread
# against N ranks of one thread each (and, for comparison, one process with N threads), the
# parallel efficiency T1 / (N * TN), the bytes exchanged (from -v), and whether the images are
# byte-identical to the single process's. Interleaved runs, the minimum of each kept (shared
# machines drift: compare within one run).
# Usage: bench/mpi_scaling.sh [BUILD_DIR [RUNS [RANKS...]]]   (default: build 3 2)
#   RANKS: N (N ranks of one thread, against one process of N threads) or NxT (N ranks of T threads
#   each, against one process of N*T threads), e.g. `build 1 2 4 8 16 4x4 2x8` on 16 cores.
# PHOS_BENCH_DIR: the shared bench folder (default ../shared/bench). The single-thread time of each
# case is measured once per run and reused for every rank count.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
runs="${2:-3}"
shift $(( $# < 2 ? $# : 2 ))
rank_counts=("$@")
[ ${#rank_counts[@]} -eq 0 ] && rank_counts=(2)
scene="${PHOS_BENCH_DIR:-$here/../shared/bench}/scn/cornell-glass-mirror.scn"
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
  awk "BEGIN { print $t1 - $t0 }"
}
min() { awk "BEGIN { print ($1 < $2) ? $1 : $2 }"; }

printf "%-10s %7s %10s %10s %10s %12s %10s\n" case ranks "1 proc s" "N ranks s" "N thr s" efficiency "MB moved"
for name in path photonmap sppm; do
  opts=(${cases[$name]})
  t1=1e9
  for ((i = 0; i < runs; ++i)); do
    t1=$(min "$t1" "$(wall "$build/phos" render "$scene" "${opts[@]}" --threads 1 -q -o "$out/one.pfm")")
  done
  for spec in "${rank_counts[@]}"; do
    n=${spec%x*} threads=1
    [[ "$spec" == *x* ]] && threads=${spec#*x}
    cores=$((n * threads))
    tn=1e9 tt=1e9
    for ((i = 0; i < runs; ++i)); do
      tn=$(min "$tn" "$(wall "${mpi[@]}" -np "$n" "$build/phos" render "$scene" "${opts[@]}" --threads "$threads" -v -o "$out/ranks.pfm")")
      moved=$(sed -n "s/.*rank 0 of $n: .*, \([0-9.e+-]*\) MB exchanged.*/\1/p" "$out/log" | head -1)
      tt=$(min "$tt" "$(wall "$build/phos" render "$scene" "${opts[@]}" --threads "$cores" -q -o "$out/threads.pfm")")
    done
    same=$(cmp -s "$out/one.pfm" "$out/ranks.pfm" && echo identical || echo DIFFERENT)
    eff=$(awk "BEGIN { printf \"%.2f\", $t1 / ($cores * $tn) }")
    printf "%-10s %7s %10.2f %10.2f %10.2f %12s %10s  %s\n" "$name" "${n}x$threads" "$t1" "$tn" "$tt" "$eff" "${moved:-?}" "$same"
  done
done
