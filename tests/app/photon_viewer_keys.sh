#!/usr/bin/env bash
# Drives `phos photons --view` with real key presses and a click (xdotool through XTEST) inside
# Xvfb, for photon_viewer_test.cpp: c cycles the colouring, 1 hides the first map, = enlarges the
# points, a click on the box prints a photon, q closes. Titles seen go to DIR/titles, the viewer's
# output to DIR/log, then "exit N".
# Usage (under xvfb-run): photon_viewer_keys.sh PHOS SCENE DIR
set -u
phos=$1 scene=$2 dir=$3
"$phos" photons "$scene" --global 20000 --caustic 20000 --view >"$dir/log" 2>&1 &
pid=$!
. "$(dirname "$0")/window_keys.sh"
find_window "phos photons"
wait_title "[colour power; maps global caustic; points 2 px]"
xdotool key c && wait_title "[colour map;"
xdotool key c && wait_title "[colour bounces;"
xdotool key c && wait_title "[colour power;"
xdotool key 1 && wait_title "maps caustic;"
xdotool key 1 && wait_title "maps global caustic;"
xdotool key equal && wait_title "points 3 px]"
# A click in the middle of the window (the box's back wall, covered with global photons).
xdotool mousemove --window "$wid" 512 384 click 1
for _ in $(seq 100); do grep -q "^photon " "$dir/log" && break; sleep 0.1; done
xdotool key q
wait "$pid"
echo "exit $?" >>"$dir/titles"
