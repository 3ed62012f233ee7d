#!/usr/bin/env bash
# Drives the --preview window with real key presses (xdotool through the XTEST extension) inside
# Xvfb, for preview_test.cpp: = raises the exposure, - lowers it, l shows the next layer, s saves
# a snapshot, q ends the render as Ctrl-C does. Each title seen goes to DIR/titles, then "exit N".
# Usage (under xvfb-run): preview_keys.sh PHOS SCENE DIR
set -u
phos=$1 scene=$2 dir=$3
"$phos" render "$scene" --integrator path --width 64 --height 48 --spp 1000000 --layers --preview \
  -o "$dir/out.exr" >"$dir/log" 2>&1 &
pid=$!
. "$(dirname "$0")/window_keys.sh"
find_window "phos"
wait_title "exposure +0.0"
xdotool key equal && wait_title "exposure +0.5"
xdotool key minus && xdotool key minus && wait_title "exposure -0.5"
xdotool key l && wait_title "[caustic,"
xdotool key s
for _ in $(seq 100); do [ -e "$dir/out.snapshot-1.exr" ] && break; sleep 0.1; done
xdotool key q
wait "$pid"
echo "exit $?" >>"$dir/titles"
