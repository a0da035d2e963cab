#!/usr/bin/env bash
# Everything to measure on a machine with a GPU, in one go: which EGL platform and renderer were chosen,
# render_bench at 512^2 and 1024^2 with the walk as a compute and as a fragment shader, a 1024^2 image
# to look at, /render latency with 1 and 8 clients, and the viewer socket's drafts for 1 and 8 viewers
# dragging at 1140x900 (issue 37: 60 frames/s at full resolution). Writes the logs to OUT_DIR and prints
# the tables.
#
# Usage: bench/gpu_bench.sh [OUT_DIR]   (default bench/out/gpu)
# Environment: BUILD=build/release, PORT=18080, FRAMES=21, WARMUP=3, STRATEGY=both (walk: no raster).
# Needs a build (scripts/setup; cmake --workflow --preset release) and the CT (scripts/fetch-ct).
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${1:-bench/out/gpu}
build=${BUILD:-build/release}
port=${PORT:-18080}
frames=${FRAMES:-21}
warmup=${WARMUP:-3}
strategy=${STRATEGY:-both}
mkdir -p "$out"
vots=$build/cli/vots

echo "== context and a 1024x1024 oblique MIP ($out/ct_oblique_1024.png)"
"$vots" render data/cranium.nhdr -o "$out/ct_oblique_1024.png" --eps 1% --cam az=30,el=20 --size 1024x1024 \
    --window 1400,2800 --colormap bone 2>&1 | grep "EGL platform"

for size in 512 1024; do
    for shader in compute fragment; do
        echo "== render_bench ${size}x${size}, walk as a $shader shader"
        timeout 600 "$build/bench/render_bench" data/cranium.nhdr --eps-percent 1,2,5 --frames "$frames" \
            --warmup "$warmup" --strategy "$strategy" --size "$size" --walk-shader "$shader" >"$out/render_${size}_$shader.txt" 2>&1
        grep -E "^\| [0-9]" "$out/render_${size}_$shader.txt"
    done
done

echo "== /render latency (vots serve on port $port)"
"$vots" serve --port "$port" --data data --cache-dir "$out/cache" >"$out/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT
stats() { python3 -c 'import json,sys,urllib.request; print(json.load(urllib.request.urlopen(sys.argv[1]))["renderer"])' \
    "http://127.0.0.1:$port/api/stats"; }
for _ in $(seq 100); do
    stats >/dev/null 2>&1 && break
    sleep 0.2
done
for size in 512x512 1024x1024; do
    timeout 300 python3 bench/server_latency.py --url "http://127.0.0.1:$port" --dataset cranium --requests 20 \
        --size "$size" 2>&1 | tee "$out/latency_$size.txt"
done
stats
for viewers in 1 8; do
    echo "== viewer socket, $viewers viewer(s) dragging at 1140x900 (bench/viewer_capacity.py)"
    timeout 120 python3 bench/viewer_capacity.py --port "$port" --viewers "$viewers" --seconds 10 --pid "$server" \
        2>&1 | tee "$out/viewers_$viewers.txt"
done
