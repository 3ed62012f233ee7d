# Sourced by the bench scripts: `bench_metrics PHOS IMAGE REFERENCE [X0 X1 Y0 Y1]` prints
# "relMSE mean_ratio window_mean" (window "-" without a window, or when X0 is "-"), computed by
# `phos diff`.
bench_metrics() {
    _phos=$1 _img=$2 _ref=$3
    shift 3
    if [ $# -eq 4 ] && [ "$1" != "-" ]; then "$_phos" diff "$_img" "$_ref" --window "$@"; else "$_phos" diff "$_img" "$_ref"; fi |
        awk '$1 == "relMSE" { e = $2 } $1 == "mean_ratio" { r = $2 } $1 == "window_mean" { w = $2 }
             END { printf "%.5f %.4f %s\n", e, r, (w == "" ? "-" : sprintf("%.3f", w)) }'
}

# `bench_window_text WINDOW_MEAN REFERENCE_MEAN`: "w (ref)", or "-" without a window.
bench_window_text() {
    if [ "$1" = "-" ]; then echo "-"; else echo "$1 ($2)"; fi
}
