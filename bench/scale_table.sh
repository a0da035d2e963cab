#!/usr/bin/env bash
# The scale table: for each slice count, fit time and peak, one-shot render vs reference, walk frames.
#
# Usage: bench/scale_table.sh [SLICES...]   (default: 108 432 1000 3000; 108 is the Cranium itself)
#        VOTS_BUILD=build/release  VOTS_SCALE_DIR=/tmp/vots-scale   (generated volumes, never in the repo)
#
# Prints one Markdown row per slice count; bench/RESULTS.md keeps the measured tables. Needs the
# release build (cmake --preset release && cmake --build --preset release) and data/cranium.nhdr
# (scripts/fetch-ct). A 3000-slice run needs about 1.6 GB of disk for the volume and several GB of RAM.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

build=${VOTS_BUILD:-build/release}
dir=${VOTS_SCALE_DIR:-/tmp/vots-scale}
vots=$build/cli/vots
mkdir -p "$dir"
[[ $# -gt 0 ]] || set -- 108 432 1000 3000

# "SECONDS PEAK_MIB" of one run of the command, from GNU time.
measure() {
    local out
    out=$(/usr/bin/time -f '%e %M' "$@" 2>&1 >/dev/null | tail -1)
    awk '{ printf "%.2f %.0f\n", $1, $2 / 1024 }' <<<"$out"
}

echo "| slices | samples | Vots | fit s | fit peak MiB | one-shot vots render s (peak MiB) | one-shot reference s (peak MiB) | upload ms | strategy used | walk ms anterior / oblique / persp, 512^2 | walk ms, 1024^2 |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in "$@"; do
    if [[ $n == 108 ]]; then
        volume=data/cranium.nhdr
    else
        volume=$dir/s$n.nhdr
        [[ -f $volume ]] ||
            "$build/bench/make_scaled_volume" data/cranium.nhdr "$volume" --size "512x512x$n" --noise 8 --seed 1 >/dev/null
    fi
    fitted=$dir/s$n.vots
    read -r fit_s fit_mib < <(measure "$vots" fit "$volume" --eps 2% --certify cells -o "$fitted")
    vot_count=$("$vots" info "$fitted" 2>/dev/null | awk '$1 == "Vots" { print $2; exit }')
    read -r one_s one_mib < <(measure "$vots" render "$fitted" --cam az=30,el=20 -o "$dir/one$n.png")
    read -r ref_s ref_mib < <(measure "$vots" render "$fitted" --mode reference --volume "$volume" --cam az=30,el=20 \
        -o "$dir/ref$n.png")
    # render_bench at one size: its table on stdout, its upload line on stderr.
    "$build/bench/render_bench" "$volume" --vots "$fitted" --size 512 --frames 5 --warmup 1 --strategy walk \
        --no-reference >"$dir/bench$n-512.txt" 2>"$dir/bench$n-512.err"
    "$build/bench/render_bench" "$volume" --vots "$fitted" --size 1024 --frames 5 --warmup 1 --strategy walk \
        --no-reference >"$dir/bench$n-1024.txt" 2>/dev/null
    walk() { # medians of the three views, "a / o / p"
        awk -F'|' '/\| (anterior|oblique|persp) \|/ { gsub(/ /, "", $8); v[$3] = $8 }
            END { printf "%s / %s / %s", v[" anterior "], v[" oblique "], v[" persp "] }' "$1"
    }
    strategies=$(awk -F'|' '/\| (anterior|oblique|persp) \|/ { gsub(/ /, "", $5); print $5 }' "$dir/bench$n-512.txt" "$dir/bench$n-1024.txt" |
        sort -u | paste -sd, -)
    upload_ms=$(sed -n 's/.*upload \([0-9.]*\) ms (walk).*/\1/p' "$dir/bench$n-512.err" | head -1)
    samples=$(awk -v n="$n" 'BEGIN { printf "%.0f M", (n == 108 ? 256 * 256 * 108 : 512 * 512 * n) / 1e6 }')
    echo "| $n | $samples | $vot_count | $fit_s | $fit_mib | $one_s ($one_mib) | $ref_s ($ref_mib) | ${upload_ms%.*} | $strategies | $(walk "$dir/bench$n-512.txt") | $(walk "$dir/bench$n-1024.txt") |"
done
