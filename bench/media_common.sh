# Shared by the media benchmark scripts (sourced, not run): the build's phos, a scratch folder
# removed on exit, the machine's load, and the measures every row reports.
# Before sourcing: build=BUILD_DIR, extra="extra phos options".
phos=$build/phos
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores; extra options: ${extra:-none}"

# measure IMAGE REFERENCE: sets rel (relMSE) and ratio (mean ratio) from `phos diff`.
measure() {
    d=$("$phos" diff "$1" "$2")
    rel=$(echo "$d" | awk '/relMSE/ {print $2}')
    ratio=$(echo "$d" | awk '/mean_ratio/ {print $2}')
}

# caustic_contrast IMAGE: fog-caustic's volume-caustic contrast, the mean luminance in
# x [120,136) y [184,208) minus the mean of the side windows x [96,112) and [144,160) at the same
# rows (0.0211 in the reference, ~0 without the volume caustic).
caustic_contrast() {
    "$phos" info "$1" --window 120 136 184 208 --window 96 112 184 208 --window 144 160 184 208 |
        awk '/window/ {v[n++] = $NF} END {printf "%.4f", v[0] - (v[1] + v[2]) / 2}'
}

# seconds_since T0: wall seconds since T0 (a `date +%s.%N` value).
seconds_since() { awk "BEGIN {print $(date +%s.%N) - $1}"; }
