#!/usr/bin/env bash
# What watching a render costs: the render phase's time (-v "time render") with and without
# --preview (under Xvfb when there is no display) and with --tev streaming to a local listener,
# interleaved runs, the minimum of each kept (shared machines drift: compare within one run).
# Usage: bench/preview_overhead.sh [BUILD_DIR [RUNS [SCENE [options...]]]]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
runs="${2:-5}"
scene="${3:-$here/../shared/bench/scn/cornell-glass-mirror.scn}"
shift $(( $# < 3 ? $# : 3 ))
opts=("$@")
[ ${#opts[@]} -eq 0 ] && opts=(--integrator path --width 384 --height 384 --spp 32)
out="$(mktemp -d)"
trap 'kill %1 2>/dev/null || true; rm -rf "$out"' EXIT
# A stand-in for tev that reads and discards what it is sent.
python3 -c "
import socket
s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1); s.bind(('127.0.0.1', 14199)); s.listen(8)
while True:
    c, _ = s.accept()
    while c.recv(1 << 20): pass
" &
sleep 0.5
wrap=()
[ -z "${DISPLAY:-}" ] && wrap=(xvfb-run -a -s "-screen 0 1280x1024x24")
render_time() {
  "${wrap[@]}" "$build/phos" render "$scene" "${opts[@]}" "$@" -v -o "$out/x.exr" 2>&1 |
    awk '/time render:/ {print $3}'
}
declare -A best=([none]=1e9 [preview]=1e9 [tev]=1e9)
for ((i = 0; i < runs; ++i)); do
  for mode in none preview tev; do
    case $mode in
      none) t=$(render_time) ;;
      preview) t=$(render_time --preview) ;;
      tev) t=$(render_time --tev 127.0.0.1:14199) ;;
    esac
    best[$mode]=$(python3 -c "print(min(${best[$mode]}, $t))")
  done
done
printf "%-8s %10s %8s\n" mode "render s" ratio
for mode in none preview tev; do
  printf "%-8s %10.3f %8.3f\n" "$mode" "${best[$mode]}" "$(python3 -c "print(${best[$mode]} / ${best[none]})")"
done
