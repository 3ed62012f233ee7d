#!/bin/sh
# Photon-tracing throughput against the ray-tracing limit, thread scaling, photon-map memory and
# k-d tree build rate, in one table (docs/performance.md keeps the figures):
#   - the anchor: raw Embree 3 single rays on photon-like incoherent rays
#     (../shared/bench/anchors/embree_rays.cpp, built here with its own build line), 1 and 2 threads;
#   - phos's photon tracer on cornell-diffuse (the photonmap command below, 4 M global photons):
#     photon rays per second of `time photon trace` (-v), its ratio to the anchor at the same thread
#     count, and the 1 -> 2 thread scaling of tracing and of the k-d tree build; fault-in-s is the
#     part of the trace that first touched the map's reserved pages (-v; on virtual machines whose
#     host takes freed memory back it swings from a few ms to ~0.1 s per 80 MB);
#     busy is how much of the pipeline's time the threads spent in batches (-v; near 100 % a
#     rate that grows less than the thread count is the cores' own speed, not phos waiting);
#     top-s and below-s are the k-d build's thread time (-v, summed over threads) in its top levels'
#     passes over the whole map (ranges of 2^18 photons and more) and below them: a share that
#     grows with the threads while the work stays the same is time spent waiting for memory;
#   - with --big: 100 M global photons (2 threads): peak RSS against the map's own bytes (24 B per
#     photon) and the build rate. Needs ~3 GB of memory and a few minutes;
#   - with --contend: the stand-in, on a few cores, for many cores' memory pressure. The photonmap
#     command on 1 thread pinned to the first core, alone and while `memory_bandwidth --contend`
#     streams read-modify-write passes on all the other cores (PHOS_CONTENDERS threads, default
#     all), runs alternating: how much each part's time grows (the tracing batches' own time, the
#     build, and the build's top-s and below-s) says how much of it waits for memory. PHOS_PHOTONS
#     defaults to 16 M here, enough top levels to time. Needs taskset (util-linux), 2 cores or more.
# Ratios, not absolute figures, are what to compare between machines: run it on an idle machine
# (the load average at the start is printed).
# Usage: bench/photon_throughput.sh [BUILD_DIR] [--big | --contend]
# Environment: PHOS_THREADS (thread counts, default "1 2"; e.g. "1 2 4 8 16" for a scaling curve:
# each row's scaling is against the first count), PHOS_ANCHOR (a prebuilt anchor binary, for a
# machine without Embree's headers), PHOS_BENCH_DIR (the shared bench folder, default
# ../shared/bench), PHOS_PHOTONS (global photons of the tracing rows, default 4000000) and
# PHOS_ANCHOR_RAYS (the anchor's rays, default 20000000): raise both for many cores; PHOS_REPEAT
# (runs per row, default 1): each figure of a row is then the median of that many runs, the
# anchor's and phos's alternating (single runs on shared machines swing by +-0.05 in the ratio);
# PHOS_ARGS: more options for phos's runs (e.g. "--embree-config frequency_level=simd256").
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
[ $# -gt 0 ] && shift
big=0 contend=0
[ "${1:-}" = "--big" ] && big=1
[ "${1:-}" = "--contend" ] && contend=1
phos=$build/phos
if [ "$contend" = 1 ]; then  # checked before the table, not after it
    cores=$(nproc)
    [ "$cores" -ge 2 ] || { echo "--contend needs at least 2 cores" >&2; exit 2; }
    command -v taskset > /dev/null || { echo "--contend needs taskset (util-linux)" >&2; exit 2; }
    [ -x "$build/memory_bandwidth" ] || { echo "no memory_bandwidth in $build: build the benches first" >&2; exit 2; }
    contenders=${PHOS_CONTENDERS:-$((cores - 1))}
    [ "$contenders" -ge 1 ] && [ "$contenders" -lt "$cores" ] ||
        { echo "PHOS_CONTENDERS must be 1 to $((cores - 1)) (the cores but the first)" >&2; exit 2; }
fi
shared=${PHOS_BENCH_DIR:-$here/../../shared/bench}
threads=${PHOS_THREADS:-1 2}
out=$(mktemp -d)
hog=""  # with --contend, the contenders' process while it runs
trap 'rm -rf "$out"; [ -z "$hog" ] || kill "$hog" 2> /dev/null' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
if [ -n "${PHOS_ANCHOR:-}" ]; then
    cp "$PHOS_ANCHOR" "$out/rays"
else
    g++ -O3 -march=native -std=c++17 "$shared/anchors/embree_rays.cpp" -lembree3 -ltbb -o "$out/rays"
fi

# `photonmap THREADS GLOBAL`: runs the issue's command (behind $pin, if set), leaves -v's output in
# $out/pm.log.
photonmap() {
    # shellcheck disable=SC2086 # $pin is a command and its arguments
    ${pin:-} "$phos" render "$shared/scn/cornell-diffuse.scn" --integrator photonmap --width 64 --height 64 --spp 1 \
        --gather-rays 1 --global "$2" --no-irradiance-cache -v --no-progress --threads "$1" -o "$out/pm.pfm" \
        ${PHOS_ARGS:-} 2> "$out/pm.log" || { cat "$out/pm.log" >&2; exit 2; }
}
calc() { awk "BEGIN { print $1 }"; }
# The median of the numbers on stdin (one per word); - if any word is not a number.
median() {
    tr ' ' '\n' | grep -v '^$' | sort -g | awk '
        $1 !~ /^[0-9.e+-]+$/ || $1 == "-" { bad = 1 }
        { v[NR] = $1 }
        END { if (bad || NR == 0) print "-"; else print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
field() { sed -n "s/.*$1 *\([0-9.e+]*\).*/\1/p" "$out/pm.log" | head -1; }
# The build's thread time in $out/pm.log (-v): "TOP BELOW", or "- -" from a phos whose -v lacks it.
build_split() {
    split=$(sed -n 's/.*photon map build thread time: top levels \([0-9.]*\) s, below them \([0-9.]*\) s.*/\1 \2/p' "$out/pm.log")
    echo "${split:-- -}"
}

printf '| %-7s | %13s | %13s | %6s | %8s | %10s | %6s | %13s | %6s | %7s | %13s | %13s | %13s |\n' threads "Embree Mray/s" \
    "photon Mray/s" ratio trace-s fault-in-s busy "build Mphot/s" top-s below-s "Embree scaling" "trace scaling" \
    "build scaling"
printf '| %-7s | %13s | %13s | %6s | %8s | %10s | %6s | %13s | %6s | %7s | %13s | %13s | %13s |\n' --- --- --- --- --- --- --- \
    --- --- --- --- --- ---
first=""
repeat=${PHOS_REPEAT:-1}
for t in $threads; do
    anchors="" traces="" builds="" faults="" busies="" tops="" belows=""
    run=0
    while [ "$run" -lt "$repeat" ]; do
        anchors="$anchors $("$out/rays" "$t" "${PHOS_ANCHOR_RAYS:-20000000}" | sed -n 's/.*: \([0-9.]*\) M incoherent.*/\1/p')"
        photonmap "$t" "${PHOS_PHOTONS:-4000000}"
        traces="$traces $(field "time photon trace:")"
        builds="$builds $(field "time photon map build:")"
        # (-: a phos whose -v has no such line)
        fault=$(sed -n 's/.*pages faulted in: .* in \([0-9.]*\) s.*/\1/p' "$out/pm.log")
        faults="$faults ${fault:--}"
        busy=$(sed -n 's/.*photon tracing threads busy: \([0-9.]*\) %.*/\1/p' "$out/pm.log")
        busies="$busies ${busy:--}"
        split=$(build_split)
        top=${split% *} below=${split#* }
        tops="$tops $top" belows="$belows $below"
        run=$((run + 1))
    done
    # The photon rays and stored photons are the same in every run at a thread count.
    rays=$(sed -n 's/.* \([0-9]*\) photon (.*/\1/p' "$out/pm.log")
    stored=$(sed -n 's/.*global map: \([0-9]*\) photons.*/\1/p' "$out/pm.log")
    anchor=$(echo "$anchors" | median)
    trace=$(echo "$traces" | median)
    build_s=$(echo "$builds" | median)
    fault=$(echo "$faults" | median)
    busy=$(echo "$busies" | median)
    top=$(echo "$tops" | median)
    below=$(echo "$belows" | median)
    [ "$busy" = - ] || busy="$busy %"
    rate=$(calc "$rays / $trace / 1000000")
    [ -z "$first" ] && first=$t anchor_1=$anchor trace_1=$trace build_1=$build_s
    printf '| %-7s | %13.2f | %13.2f | %6.3f | %8.3f | %10s | %6s | %13.2f | %6s | %7s | %12.2fx | %12.2fx | %12.2fx |\n' \
        "$t" "$anchor" "$rate" "$(calc "$rate / $anchor")" "$trace" "$fault" "$busy" \
        "$(calc "$stored / $build_s / 1000000")" "$top" "$below" "$(calc "$anchor / $anchor_1")" \
        "$(calc "$trace_1 / $trace")" "$(calc "$build_1 / $build_s")"
done
echo "(scaling: against $first thread(s); each figure the median of $repeat run(s))"

if [ "$big" = 1 ]; then
    photonmap 2 100000000
    stored=$(sed -n 's/.*global map: \([0-9]*\) photons.*/\1/p' "$out/pm.log")
    peak=$(sed -n 's/.*peak memory: \([0-9.]*\) \([MG]B\).*/\1 \2/p' "$out/pm.log")
    build_s=$(field "time photon map build:")
    trace=$(field "time photon trace:")
    peak_gb=$(echo "$peak" | awk '{ print ($2 == "GB") ? $1 : $1 / 1000 }')
    map_gb=$(calc "$stored * 24 / 1000000000")
    printf '100 M photons (2 threads): %s stored, map %.2f GB, peak RSS %s GB (%.2fx the map), trace %s s, build %s s (%.2f M photons/s)\n' \
        "$stored" "$map_gb" "$peak_gb" "$(calc "$peak_gb / $map_gb")" "$trace" "$build_s" \
        "$(calc "$stored / $build_s / 1000000")"
fi

if [ "$contend" = 1 ]; then
    photons=${PHOS_PHOTONS:-16000000}
    # `one_thread MODE`: the photonmap command on 1 thread pinned to core 0; with MODE "contended"
    # the contenders run on cores 1.. meanwhile. Appends "BATCHES BUILD TOP BELOW" to $out/MODE
    # (BATCHES: the tracing batches' own time, without the pages faulted in: a contender's array
    # makes the kernel find fresh memory for those, which is not what is measured here).
    one_thread() {
        if [ "$1" = contended ]; then
            taskset -c "1-$contenders" "$build/memory_bandwidth" --contend 1 "$contenders" &
            hog=$!
            sleep 2  # its array written, its passes running
        fi
        pin="taskset -c 0"
        photonmap 1 "$photons"
        pin=""
        if [ "$1" = contended ]; then
            kill "$hog" 2> /dev/null || true
            wait "$hog" 2> /dev/null || true
            hog=""
        fi
        batches=$(sed -n 's/.*photon tracing threads busy: .*(batches \([0-9.]*\) s.*/\1/p' "$out/pm.log")
        echo "${batches:--} $(field "time photon map build:") $(build_split)" >> "$out/$1"
    }
    : > "$out/alone"
    : > "$out/contended"
    run=0
    while [ "$run" -lt "$repeat" ]; do
        one_thread alone
        one_thread contended
        run=$((run + 1))
    done
    # `column N FILE`: the median of column N of FILE's lines.
    column() { cut -d' ' -f"$1" "$2" | median; }
    printf '\n| 1 thread, %s photons | batches-s | build-s | top-s | below-s |\n| --- | --- | --- | --- | --- |\n' "$photons"
    printf '| alone | %s | %s | %s | %s |\n' "$(column 1 "$out/alone")" "$(column 2 "$out/alone")" \
        "$(column 3 "$out/alone")" "$(column 4 "$out/alone")"
    printf '| %s contending thread(s) | %s | %s | %s | %s |\n' "$contenders" "$(column 1 "$out/contended")" \
        "$(column 2 "$out/contended")" "$(column 3 "$out/contended")" "$(column 4 "$out/contended")"
    growth() {
        a=$(column "$1" "$out/alone") c=$(column "$1" "$out/contended")
        if [ "$a" = - ] || [ "$c" = - ]; then echo -; else awk "BEGIN { printf \"%+.1f %%\", ($c / $a - 1) * 100 }"; fi
    }
    printf '| growth | %s | %s | %s | %s |\n' "$(growth 1)" "$(growth 2)" "$(growth 3)" "$(growth 4)"
    echo "(each figure the median of $repeat run(s), alone and contended alternating)"
fi
