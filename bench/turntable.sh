#!/usr/bin/env bash
# Whole-process time of `vots render --turntable 36` (PNG frames and WebM) against one frame, same run.
#
# Usage: bench/turntable.sh [VOLUME] [RUNS]   (VOTS_BIN: the vots binary; default build/release/cli/vots)
# Each measurement is the median of RUNS runs (default 3), interleaved so machine load hits all alike.
# The issue's target: 36 frames at 512^2 in under 3 x the time of one frame.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
vots=${VOTS_BIN:-build/release/cli/vots}
volume=${1:-data/cranium.nhdr}
runs=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
common=(render "$volume" --size 512x512 --cam az=30,el=20)

seconds() { # prints the wall seconds of "$@"
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l
}
median() { printf '%s\n' "$@" | sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }

one=() png=() webm=()
for ((i = 0; i < runs; i++)); do
    one+=("$(seconds "$vots" "${common[@]}" -o "$out/one.png")")
    png+=("$(seconds "$vots" "${common[@]}" --turntable 36 -o "$out/%03d.png")")
    webm+=("$(seconds "$vots" "${common[@]}" --turntable 36 -o "$out/turn.webm")")
done
m1=$(median "${one[@]}") mp=$(median "${png[@]}") mw=$(median "${webm[@]}")
echo "volume $volume, 512x512, median of $runs, load $(cut -d' ' -f1 /proc/loadavg)"
printf 'one frame            %6.2f s\n' "$m1"
printf '36 PNG frames        %6.2f s  (%.2f x one frame)\n' "$mp" "$(echo "$mp / $m1" | bc -l)"
printf '36-frame WebM        %6.2f s  (%.2f x one frame)\n' "$mw" "$(echo "$mw / $m1" | bc -l)"
echo "runs (s): one ${one[*]}; PNG frames ${png[*]}; WebM ${webm[*]}"
printf 'sizes: one PNG %d B, 36 PNGs %d B, WebM %d B\n' "$(stat -c %s "$out/one.png")" \
    "$(cat "$out"/0*.png | wc -c)" "$(stat -c %s "$out/turn.webm")"
