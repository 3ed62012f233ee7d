# Shared by the window-driving test scripts (preview_keys.sh, photon_viewer_keys.sh), sourced after
# they set $dir and started the program as $pid: find_window NAME sets $wid to the window whose
# title holds NAME (waiting up to 30 s; on failure it records "no window", stops $pid and exits);
# wait_title TEXT waits (up to 10 s) until the window's title holds TEXT and appends the title to
# $dir/titles (or a timeout line), then gives the window the keyboard focus.
find_window() {
  wid=$(timeout 30 xdotool search --sync --name "$1" | head -1)
  [ -n "$wid" ] || { echo "no window" >>"$dir/titles"; kill "$pid"; exit 1; }
}
wait_title() {
  local t=""
  for _ in $(seq 100); do
    t=$(xdotool getwindowname "$wid")
    case "$t" in *"$1"*) echo "$t" >>"$dir/titles"; xdotool windowfocus --sync "$wid" 2>/dev/null; return 0 ;; esac
    sleep 0.1
  done
  echo "timed out waiting for '$1' in '$t'" >>"$dir/titles"
  return 1
}
