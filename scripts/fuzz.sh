#!/usr/bin/env bash
# Fuzzes phos's readers with libFuzzer (fuzz/, docs/testing.md): installs what is missing, builds
# build-fuzz with clang-14 (-fsanitize=fuzzer,address,undefined), assembles the seed corpora and
# runs each target in turn, then prints executions, coverage and findings per target.
# Usage: scripts/fuzz.sh [--smoke] [--runs N] [SECONDS] [TARGET...]
#   SECONDS  fuzzing time per target (default 60); TARGET: scn pbrt scene_format off ply obj gzip image
#            volume checkpoint photon_maps rgl_bsdf (default: all). --smoke (CI): every seed plus a few seconds per target.
#   --runs N also stops a target after N executions (whichever comes first: `--runs 10000000 3600`
#            is the "10 M executions or one hour" campaign of docs/testing.md).
# PHOS_FUZZ_TIMEOUT (seconds, default 10): what counts as a hang. libFuzzer times wall clock, so a
# campaign sharing the machine with builds may raise it rather than report a starved input.
# Exits 1 if any target crashed, hung, leaked, ran out of memory or tripped a sanitizer; the inputs
# are in build-fuzz/artifacts/, the logs in build-fuzz/logs/.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build-fuzz"
shared="${PHOS_SHARED_DIR:-$here/../shared}"
all_targets=(scn pbrt scene_format off ply obj gzip image volume checkpoint photon_maps rgl_bsdf)

smoke=0
seconds=60
runs=-1
targets=()
want_runs=0
for a in "$@"; do
  if [ "$want_runs" = 1 ]; then
    [[ "$a" =~ ^[0-9]+$ ]] || { echo "fuzz: --runs needs a count, not '$a'" >&2; exit 2; }
    runs="$a"; want_runs=0; continue
  fi
  case "$a" in
    --smoke) smoke=1 ;;
    --runs) want_runs=1 ;;
    ''|*[!0-9]*) targets+=("$a") ;;
    *) seconds="$a" ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || { echo "fuzz: unknown target '$t' (${all_targets[*]})" >&2; exit 2; }
done
if [ "$smoke" = 1 ]; then seconds="${PHOS_FUZZ_SMOKE_SECONDS:-4}"; fi

# ---- packages (only the missing ones) ----
packages=(clang-14 libclang-rt-14-dev cmake pkg-config python3 libembree-dev libtbb-dev libopenexr-dev
          libpng-dev libstb-dev libtinyobjloader-dev libopenvdb-dev libnanovdb-dev libboost-iostreams-dev
          libblosc-dev zlib1g-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "fuzz: installing ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# ---- build ----
cmake -S "$here" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DPHOS_FUZZ=ON -DPHOS_BUILD_TESTS=OFF \
  -DPHOS_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" >/dev/null
build_targets=()
for t in "${targets[@]}"; do build_targets+=(--target "${t}_fuzzer"); done
[[ " ${targets[*]} " == *" volume "* ]] && build_targets+=(--target volume_seeds)
[[ " ${targets[*]} " == *" photon_maps "* ]] && build_targets+=(--target photon_maps_seeds)
[[ " ${targets[*]} " == *" rgl_bsdf "* ]] && build_targets+=(--target rgl_bsdf_seeds)
cmake --build "$build" -j"$(nproc)" "${build_targets[@]}"

# ---- corpora: generated and shipped seeds (fresh each run) plus what earlier runs found ----
# (one seed folder per invocation, so that campaigns over different targets can run side by side)
seeds="$build/seeds.$$"
trap 'rm -rf "$seeds"' EXIT
python3 "$here/fuzz/make_seeds.py" "$seeds" "$here" "$shared"
if [[ " ${targets[*]} " == *" volume "* ]]; then "$build/fuzz/volume_seeds" "$seeds/volume"; fi
if [[ " ${targets[*]} " == *" photon_maps "* ]]; then "$build/fuzz/photon_maps_seeds" "$seeds/photon_maps"; fi
if [[ " ${targets[*]} " == *" rgl_bsdf "* ]]; then "$build/fuzz/rgl_bsdf_seeds" "$seeds/rgl_bsdf"; fi
mkdir -p "$build/artifacts" "$build/logs"

dict_of() { case "$1" in scene_format) echo scene ;; *) echo "$1" ;; esac; }
# Input size caps. Images: a header may claim up to 32768 pixels per byte of file (io/image), so
# 1 KB keeps valid but extreme images (a 1-bit PNG of 30 million pixels) within -rss_limit_mb.
max_len_of() { case "$1" in image) echo 1024 ;; checkpoint|volume|photon_maps|rgl_bsdf) echo 4096 ;; *) echo 8192 ;; esac; }

failed=()
rows=()
for t in "${targets[@]}"; do
  if [ "$smoke" = 1 ]; then
    corpus="$build/smoke-corpus/$t"  # seeds only: the same work every time
    rm -rf "$corpus"
  else
    corpus="$build/corpus/$t"
  fi
  mkdir -p "$corpus" "$seeds/$t"
  log="$build/logs/$t.log"
  before=$(find "$build/artifacts" -name "$t-*" | wc -l)
  echo "fuzz: $t for ${seconds}s" >&2
  rc=0
  start=$SECONDS
  ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}" \
  "$build/fuzz/${t}_fuzzer" "$corpus" "$seeds/$t" \
    -dict="$here/fuzz/$(dict_of "$t").dict" -max_len="$(max_len_of "$t")" \
    -max_total_time="$seconds" -runs="$runs" -timeout="${PHOS_FUZZ_TIMEOUT:-10}" -rss_limit_mb=2048 -detect_leaks=1 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" >"$log" 2>&1 || rc=$?
  took=$((SECONDS - start))
  after=$(find "$build/artifacts" -name "$t-*" | wc -l)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  findings=$((after - before))
  status=ok
  if [ "$rc" -ne 0 ] || [ "$findings" -gt 0 ]; then
    status="FINDING (exit $rc, $findings new artefact(s); see $log)"
    failed+=("$t")
  fi
  rows+=("$(printf '%-13s %12s  %-22s %6s  %s' "$t" "${execs:-?}" "${cov:-?}" "$took" "$status")")
done

printf '\n%-13s %12s  %-22s %6s  %s\n' target executions coverage 'time s' result
printf '%s\n' "${rows[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]} (inputs in $build/artifacts/)" >&2
  exit 1
fi
