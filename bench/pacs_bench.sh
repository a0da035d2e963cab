#!/usr/bin/env bash
# A large series on a PACS opened in `vots serve`, against the same series from a local folder: time to the
# first (exact-grid) image and to the first Vot frame, the server's peak memory; then a slab sweep of about
# 300 slabs written to a folder and stored back on the PACS with STOW-RS.
#
# Usage: bench/pacs_bench.sh [SLICES [SWEEP_SLABS]]   (defaults 1000 and 300; VOTS_BUILD default build/ci)
# VOTS_BENCH_ROUNDS=N repeats the folder and the PACS opens N times, alternately, and prints the medians and
# their ratio; VOTS_BENCH_FIRST_IMAGE_ONLY=1 leaves out the Vot frame (a fit) and the sweep.
# The series is the Cranium (scripts/fetch-ct) resampled to 512x512xSLICES int16 with noise (make_scaled_volume)
# and written as DICOM by the tests' GDCM writer; Orthanc runs on loopback (tests/pacs/orthanc.sh). Needs the
# tests built (vots_write_dicom) and about 3 x 0.5 GB of disk per 1000 slices under $TMPDIR.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${VOTS_BUILD:-build/ci}
slices=${1:-1000}
sweep_slabs=${2:-300}
vots=$build/cli/vots
size=512x512
work=$(mktemp -d "${TMPDIR:-/tmp}/vots-pacs-bench.XXXXXX")
server=0
cleanup() {
    ((server)) && kill "$server" 2>/dev/null
    wait 2>/dev/null
    tests/pacs/orthanc.sh stop "$work/orthanc" >/dev/null 2>&1 || true
    if [[ -n ${VOTS_BENCH_KEEP:-} ]]; then echo "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
now() { date +%s.%N; }
since() { echo "$(now) - $1" | bc -l; }

# The series: the Cranium resampled, written one file a slice, then uploaded 4 at a time.
series_uid=1.2.826.0.1.3680043.10.1234.700
"$build/bench/make_scaled_volume" data/cranium.nhdr "$work/scaled.nhdr" --size "512x512x$slices" --noise 8 --seed 1 \
    >/dev/null
"$build/tests/vots_write_dicom" "$work/folder/bench" --input "$work/scaled.nhdr" --series-uid "$series_uid" \
    --description "bench $slices" >/dev/null
extent_z=$(awk -v n="$slices" '/^spacings:/ { printf "%.6f", $4 * (n - 1) }' "$work/scaled.nhdr")
rm -f "$work"/scaled.*
tests/pacs/orthanc.sh start "$work/orthanc"
port=$(cat "$work/orthanc/port")
password=$(cat "$work/orthanc/password")
auth=$work/orthanc/auth
start=$(now)
find "$work/folder/bench" -type f -print0 |
    xargs -0 -P 4 -I{} curl -fsS -u "vots:$password" -X POST --data-binary @{} -H 'Content-Type: application/dicom' \
        "http://127.0.0.1:$port/instances" -o /dev/null
printf 'upload of %s instances (%s MB): %.1f s\n' "$slices" "$(du -sm "$work/folder/bench" | cut -f1)" "$(since "$start")"

# One fresh server per run: its peak memory is that run's.
serve() { # serve LOG ARGS... -> sets server, base
    local server_port=$((20000 + RANDOM % 20000))
    "$vots" serve --port "$server_port" --cache-dir "$work/cache-$RANDOM" --no-warm-up "${@:2}" >"$1" 2>&1 &
    server=$!
    base=http://127.0.0.1:$server_port
    # /api/stats, not /api/datasets: listing the datasets loads them, and the folder's clock would then
    # start with its series read already.
    until curl -sf "$base/api/stats" >/dev/null; do
        kill -0 "$server" 2>/dev/null || { cat "$1"; exit 1; }
        sleep 0.1
    done
}
frame() { # frame DATASET QUERY [CAMERA] -> "HTTP_STATUS FRAME_MS" of one /render (FRAME_MS: the render
    # thread's upload and draw, X-Vots-Frame-Ms)
    curl -s -o /dev/null -D "$work/headers" -w '%{http_code}' \
        "$base/render?dataset=$1&size=$size&cam=${3:-az%3D30%2Cel%3D20}&$2"
    printf ' %s' "$(tr -d '\r' <"$work/headers" | awk -F': ' 'tolower($1) == "x-vots-frame-ms" { print $2 }')"
}
peak_mib() { awk '/VmHWM/ { printf "%.0f", $2 / 1024 }' "/proc/$server/status"; }
stop_server() {
    kill "$server"
    wait "$server" 2>/dev/null || true
    server=0
}
first_images=() # "LABEL SECONDS" per open
report() { # report LABEL START DATASET
    local grid vots first asked
    asked=$(now)
    read -r grid frame_ms <<<"$(frame "$3" "renderer=grid")"
    first=$(since "$2")
    first_images+=("$1 $first")
    printf '%-7s first image (grid) %6.2f s (HTTP %s; the request %.2f s, of which upload and draw %.2f s)' \
        "$1" "$first" "$grid" "$(since "$asked")" "$(echo "${frame_ms:-0} / 1000" | bc -l)"
    local again
    again=$(now)
    read -r grid frame_ms <<<"$(frame "$3" "renderer=grid" "az%3D60%2Cel%3D10")"
    printf ', the next %.2f s (HTTP %s, draw %.2f s)' "$(since "$again")" "$grid" "$(echo "${frame_ms:-0} / 1000" | bc -l)"
    if [[ -z ${VOTS_BENCH_FIRST_IMAGE_ONLY:-} ]]; then
        read -r vots _ <<<"$(frame "$3" "eps=2%25")"
        printf '  first Vot frame %6.2f s (HTTP %s)' "$(since "$2")" "$vots"
    fi
    printf '  peak %s MiB\n' "$(peak_mib)"
}
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

mkdir -p "$work/empty"
for ((round = 1; round <= ${VOTS_BENCH_ROUNDS:-1}; ++round)); do
# The folder: the clock starts at the first request, which loads the series.
serve "$work/folder.log" --data "$work/folder"
report folder "$(now)" bench
stop_server

# What Orthanc and loopback alone take to announce the series (QIDO-RS, then its metadata) and to serve it:
# the floor of any open.
start=$(now)
curl -fsS -u "vots:$password" -o /dev/null \
    "http://127.0.0.1:$port/dicom-web/studies/$series_uid.0/series?SeriesInstanceUID=$series_uid&includefield=00201209"
curl -fsS -u "vots:$password" -o /dev/null \
    "http://127.0.0.1:$port/dicom-web/studies/$series_uid.0/series/$series_uid/metadata"
printf 'orthanc series announcement alone (QIDO-RS and metadata, curl): %.2f s\n' "$(since "$start")"
start=$(now)
bytes=$(curl -sS -u "vots:$password" -o /dev/null -w '%{size_download}' \
    -H 'Accept: multipart/related; type="application/dicom"; transfer-syntax=*' \
    "http://127.0.0.1:$port/dicom-web/studies/$series_uid.0/series/$series_uid")
printf 'orthanc series retrieve alone (curl to /dev/null): %.2f s for %s MB\n' "$(since "$start")" "$((bytes >> 20))"

# The PACS: the clock starts at the open (announce, retrieve, load), as the viewer's "Open" does. A fresh
# cache folder each time: the series is retrieved, never read from a kept copy.
serve "$work/pacs.log" --data "$work/empty" --dicomweb "orthanc=dicomweb+http://127.0.0.1:$port/dicom-web" \
    --dicomweb-auth "orthanc=$auth"
start=$(now)
open=$(curl -sf -X POST "$base/api/pacs/orthanc/studies/$series_uid.0/series/$series_uid/open" \
    -H 'Content-Type: application/json' -d '{}')
id=$(echo "$open" | sed -n 's/.*"id":\([0-9]*\).*/\1/p')
# Each state's first sight (polled every 0.05 s) says where the open's time goes.
state=
seen=
until [[ $state == done || $state == failed || $state == cancelled ]]; do
    sleep 0.05
    state=$(curl -sf "$base/api/pacs/opens/$id" | sed -n 's/.*"state":"\([a-z]*\)".*/\1/p')
    if [[ $state != "${seen##* }" ]]; then
        seen="$seen $state"
        printf -v stages '%s %s %.2f s' "${stages:-}" "$state" "$(since "$start")"
    fi
done
[[ $state == done ]] || { curl -s "$base/api/pacs/opens/$id"; exit 1; }
printf 'pacs    opened (retrieved, loaded) %6.2f s; states first seen:%s\n' "$(since "$start")" "$stages"
stages=
report pacs "$start" "orthanc-${series_uid//./_}"
stop_server
done
folder_median=$(printf '%s\n' "${first_images[@]}" | awk '$1 == "folder" { print $2 }' | median)
pacs_median=$(printf '%s\n' "${first_images[@]}" | awk '$1 == "pacs" { print $2 }' | median)
printf 'first image, median of %s: folder %.2f s, pacs %.2f s, ratio %.2f\n' "${VOTS_BENCH_ROUNDS:-1}" \
    "$folder_median" "$pacs_median" "$(echo "$pacs_median / $folder_median" | bc -l)"
[[ -z ${VOTS_BENCH_FIRST_IMAGE_ONLY:-} ]] || exit 0

# The sweep: THICKNESS 10 mm, the step that makes about SWEEP_SLABS slabs along the series' z extent.
step=$(printf '%.4f' "$(echo "($extent_z - 10) / ($sweep_slabs - 1.5)" | bc -l)")
sweep=(--view inferior --slab-sweep "10,$step" --size "$size")
mkdir -p "$work/sweep"
/usr/bin/time -f '%e s %M KB' -o "$work/time-folder" "$vots" render "$work/folder/bench" "${sweep[@]}" \
    -o "$work/sweep/%04d.dcm" 2>"$work/sweep-folder.log" || { cat "$work/sweep-folder.log"; exit 1; }
printf 'sweep of %s slabs to a folder: %s\n' "$(find "$work/sweep" -name '*.dcm' | wc -l)" "$(cat "$work/time-folder")"
/usr/bin/time -f '%e s %M KB' -o "$work/time-pacs" "$vots" render "$work/folder/bench" "${sweep[@]}" \
    -o "dicomweb+http://127.0.0.1:$port/dicom-web" --dicomweb-auth "$auth" 2>"$work/sweep.log" ||
    { cat "$work/sweep.log"; exit 1; }
printf 'sweep stored on the PACS: %s (%s)\n' "$(cat "$work/time-pacs")" "$(grep -o 'stored [0-9]* images' "$work/sweep.log")"
