#!/usr/bin/env bash
# Each process's memory while `vots serve` draws a study, one process against `mpirun -np N` (issue 23):
# the seconds from the launch to the first 2 % frame (both --prepare the study: the load or the ranks'
# summary, the fit and the frame), then VmRSS and VmHWM of every rank from /proc after it. Under mpirun no
# rank should hold the whole volume: rank 0 keeps the grid alone, each rank its cells' fit.
#
# Usage: bench/mpi_serve_memory.sh VOLUME [RANKS]    VOTS_BUILD=build/release (default)
# A 512x512x1000 volume: build/release/bench/make_scaled_volume data/cranium.nhdr /tmp/s1000.nhdr \
#   --size 512x512x1000 --noise 8 --seed 1 (never in the repo). Prints Markdown rows for bench/RESULTS.md.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
volume=$(realpath "$1")
ranks=${2:-2}
vots=$(realpath "${VOTS_BUILD:-build/release}/cli/vots")
source bench/serve_bench.bash
frame="render?dataset=$name&cam=az=30,el=20&size=512x512&eps=2%25"

# KiB of "VmRSS VmHWM" of a process.
memory_of() { awk '/^VmRSS|^VmHWM/ { v[$1] = $2 } END { print v["VmRSS:"], v["VmHWM:"] }' "/proc/$1/status"; }
serve_and_measure() { # LABEL COMMAND...: starts the server, draws one frame, prints one row per process
    local label=$1
    shift
    local launched
    launched=$(date +%s.%N)
    "$@" serve --port 0 --data "$work/data" --cache-dir "$work/cache-$label" --prepare "$name" --no-warm-up \
        >"$work/$label.log" 2>&1 &
    job=$!
    local url
    url=$(url_of "$work/$label.log")
    local code seconds
    code=$(curl -s --max-time 900 -o "$work/$label.png" -w '%{http_code}' "$url$frame")
    [[ $code == 200 ]] || { echo "$label: /render answered $code: $(head -c 300 "$work/$label.png")" >&2; exit 1; }
    seconds=$(/usr/bin/python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" \
        "$launched" "$(date +%s.%N)")
    local pids=$job
    [[ $label == ranks ]] && pids=$(for p in $(pgrep -P "$job"); do
        r=$(tr '\0' '\n' <"/proc/$p/environ" | sed -n 's/^OMPI_COMM_WORLD_RANK=//p')
        echo "$r $p"
    done | sort -n | cut -d' ' -f2)
    local r=0
    for p in $pids; do
        read -r rss hwm < <(memory_of "$p")
        echo "| $label | $r | $seconds | $((rss / 1024)) | $((hwm / 1024)) |"
        r=$((r + 1))
    done
    kill -TERM "$job"
    wait "$job" || true
    job=
}
echo "| serve | rank | launch to first 2 % frame s (512^2) | VmRSS MiB | VmHWM MiB |"
echo "|---|---|---|---|---|"
serve_and_measure one "$vots"
serve_and_measure ranks mpirun --oversubscribe --enable-recovery -np "$ranks" "$vots"
cmp -s "$work/one.png" "$work/ranks.png" && echo "(the two PNGs are the same bytes)" ||
    echo "(the PNGs differ: $ranks ranks' cells fit apart, as mpirun vots render draws them)"
