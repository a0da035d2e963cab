#!/usr/bin/env bash
# Load test: wrk with 200 connections against /render and /api/datasets of a loopback `vots serve`.
#
# Usage: tests/reliability/load.sh [--connections N] [--seconds S]   (default 200 connections, 60 s each)
# Builds build/rel (Release) unless VOTS_BIN names a binary; needs wrk (apt-get install -y wrk).
# Fails when any response is not 2xx, any socket error or timeout occurs, or the server dies.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source tests/reliability/common.sh

connections=200
seconds=60
while [[ $# -gt 0 ]]; do
    case "$1" in
    --connections) connections="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    *) echo "unknown argument $1"; exit 2 ;;
    esac
done
command -v wrk >/dev/null || { echo "wrk is missing: apt-get install -y wrk"; exit 2; }
build_rel

make_work
serve_volumes "$work/data"
# Every wrk connection comes from 127.0.0.1: without --renders-per-client 0 all but 4 would be 429.
start_server "$work/server.log" --data "$work/data" --cache-dir "$work/cache" --renders-per-client 0
base=http://127.0.0.1:$SERVER_PORT
render="$base/render?dataset=mri-brain_33x41x25_int16&size=256x256&eps=2%25"

# Warm up: the first /render fits the Vot-Space; the load then measures serving, not fitting.
curl -sf -o /dev/null "$render" && curl -sf -o /dev/null "$base/api/datasets"
echo "server pid $SERVER_PID, $(grep -m1 renderer "$work/server.log" | sed 's/^ *//')"
echo "rss before: $(rss_kib "$SERVER_PID") KiB"

failed=0
for url in "$render" "$base/api/datasets"; do
    # /render: a new camera angle per request (wrk script), so every answer is a rendered frame.
    script=()
    [[ $url == "$render" ]] && script=(-s tests/reliability/new_angle_each_request.lua)
    echo "== wrk -t2 -c$connections -d${seconds}s --latency --timeout 30s ${script[*]} $url"
    wrk -t2 -c"$connections" -d"${seconds}s" --latency --timeout 30s "${script[@]}" "$url" | tee "$work/wrk.txt"
    if grep -qE 'Non-2xx or 3xx responses|Socket errors' "$work/wrk.txt"; then failed=1; fi
    kill -0 "$SERVER_PID" 2>/dev/null || { echo "server died"; failed=1; break; }
    echo "rss after: $(rss_kib "$SERVER_PID") KiB"
done
curl -sf "$base/api/stats" |
    python3 -c 'import json, sys; d = json.load(sys.stdin); print({k: d[k] for k in ("frames", "frameCache")})'
[[ $failed -eq 0 ]] && echo "load: OK (no errors, server alive)" || echo "load: FAILED"
exit $failed
