#!/usr/bin/env bash
# Time to the first image after `vots serve` starts with a study it has never fitted: the exact grid frame
# the viewer shows while the fit runs, then the first Vot frame, then Vot frames at new angles; with the
# server's resident memory at each step.
#
# Usage: bench/first_image.sh VOLUME [SIZE]   (SIZE default 512x512; VOTS_BIN default build/release/cli/vots)
# VOLUME is served alone from a folder of links, with an empty cache folder, so nothing is fitted before.
# A 3000-slice study: build/release/bench/make_scaled_volume data/cranium.nhdr /tmp/s3000.nhdr
#   --size 512x512x3000 --noise 8 --seed 1 (1.5 GB; never in the repo).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
vots=${VOTS_BIN:-build/release/cli/vots}
volume=$(realpath "$1")
size=${2:-512x512}
work=$(mktemp -d)
server=0
trap '((server)) && kill $server 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT

mkdir "$work/data" "$work/cache"
name=$(basename "${volume%.*}")
ln -s "$volume" "$work/data/"
# A detached NRRD names its data file relative to itself: link that too.
if grep -aq '^data file:' "$volume" 2>/dev/null; then
    data=$(grep -a '^data file:' "$volume" | head -1 | sed 's/^data file: *//')
    ln -s "$(dirname "$volume")/${data%%/*}" "$work/data/"
fi
port=$((20000 + RANDOM % 20000))
start=$(date +%s.%N)
"$vots" serve --port "$port" --data "$work/data" --cache-dir "$work/cache" --prepare "$name" --no-warm-up \
    >"$work/log" 2>&1 &
server=$!
elapsed() { echo "$(date +%s.%N) - $start" | bc -l; }
rss_mib() { awk '/VmRSS/ { printf "%.0f", $2 / 1024 }' "/proc/$server/status"; }
base="http://127.0.0.1:$port"
until curl -sf "$base/api/datasets" >/dev/null; do
    kill -0 $server 2>/dev/null || { cat "$work/log"; exit 1; }
    sleep 0.2
done
printf 'server answering       %7.1f s  rss %s MiB\n' "$(elapsed)" "$(rss_mib)"

frame() { # prints "HTTP_STATUS FRAME_MS" of one /render, writing the PNG to $work/$1.png
    curl -s -o "$work/$1.png" -D "$work/headers" -w '%{http_code}' "$base/render?dataset=$name&size=$size&$2" |
        tr -d '\n'
    echo " $(awk -F': ' 'tolower($1) == "x-vots-frame-ms" { print $2 }' "$work/headers" | tr -d '\r')"
}
read -r status ms < <(frame grid "renderer=grid&eps=2%25&cam=az%3D30%2Cel%3D20")
printf 'first image (grid)     %7.1f s  rss %s MiB  (HTTP %s, frame %s ms)\n' "$(elapsed)" "$(rss_mib)" "$status" "$ms"
read -r status ms < <(frame vots "eps=2%25&cam=az%3D30%2Cel%3D20")
printf 'first Vot frame        %7.1f s  rss %s MiB  (HTTP %s, frame %s ms, fit %s s)\n' "$(elapsed)" "$(rss_mib)" \
    "$status" "$ms" "$(awk -F': ' 'tolower($1) == "x-vots-fit-seconds" { print $2 }' "$work/headers" | tr -d '\r')"
for az in 40 50 60 70 80; do
    read -r status ms < <(frame "az$az" "eps=2%25&cam=az%3D$az%2Cel%3D20")
    printf 'Vot frame az=%-3s       %7.1f s  rss %s MiB  (HTTP %s, frame %s ms)\n' "$az" "$(elapsed)" "$(rss_mib)" \
        "$status" "$ms"
done
printf 'peak rss               %s MiB\n' "$(awk '/VmHWM/ { printf "%.0f", $2 / 1024 }' "/proc/$server/status")"
