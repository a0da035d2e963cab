#!/usr/bin/env bash
# `mpirun -np 2 vots serve` of a .vots dataset: each rank reads the file and draws its cells' Vots; the
# served mip is the one-process `vots render FILE.vots` byte for byte, minip (with a slab) and the
# density are `mpirun -np 2 vots render`'s bytes, the aip within one grey level; the frame counts every
# Vot of the file once; another eps and the grid are refused with 409; SIGTERM to rank 0 ends the job
# cleanly.
# Usage: tests/mpi/mpi_serve_vots.sh VOTS_BINARY VOLUME
set -euo pipefail
vots=$1 volume=$2
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
file="$work/data/head.vots"
"$vots" fit "$volume" -o "$file" --eps 2% >/dev/null 2>"$work/fit.err" || fail "vots fit failed: $(cat "$work/fit.err")"
start_job "$work/data" head

view="cam=az=30,el=20&size=96x80"
render_args=(--cam az=30,el=20 --size 96x80)
served() { # MODE [MORE QUERY]: the served frame of that mode into $work/served-MODE.png
    local code
    code=$(curl -s --max-time 60 -D "$work/served-$1.headers" -o "$work/served-$1.png" -w '%{http_code}' \
        "${url}render?dataset=head&$view&mode=$1${2:-}")
    [[ $code == 200 ]] || fail "/render mode=$1 answered $code: $(cat "$work/served-$1.png")"
}
on_ranks() { # MODE [MORE RENDER ARGUMENTS]: mpirun -np 2 vots render of the file into $work/ranks-MODE.png
    local mode=$1
    shift
    mpirun --oversubscribe -np 2 "$vots" render "$file" -o "$work/ranks-$mode.png" --mode "$mode" \
        "${render_args[@]}" "$@" 2>/dev/null
}

served mip
"$vots" render "$file" -o "$work/one-mip.png" "${render_args[@]}" 2>/dev/null
cmp -s "$work/served-mip.png" "$work/one-mip.png" || fail "the served mip differs from one process's"
vot_count() { sed -nE 's/^X-Vots-Vot-Count: ([0-9]+)\r?$/\1/p' "$work/served-$1.headers"; }
mipCount=$(vot_count mip)
get "$work/stats.json" "api/stats" >/dev/null
/usr/bin/python3 - "$work/stats.json" "$mipCount" <<'PY' || fail "/api/stats: $(cat "$work/stats.json")"
import json, sys
stats, count = json.load(open(sys.argv[1])), int(sys.argv[2])
times = stats["rankTimes"]
assert stats["ranks"] == 2 and [t["rank"] for t in times] == [0, 1], times
# For the mip each Vot is drawn by the one rank whose cells its box starts in.
assert count > 0 and sum(t["votCount"] for t in times) == count and all(t["votCount"] > 0 for t in times), times
PY

served minip "&slab=-10,30"
on_ranks minip --slab -10,30
cmp -s "$work/served-minip.png" "$work/ranks-minip.png" || fail "the served minip differs from mpirun vots render's"
[[ $(vot_count minip) == "$mipCount" ]] || fail "the minip counts $(vot_count minip) Vots, the file has $mipCount"
served density
on_ranks density
cmp -s "$work/served-density.png" "$work/ranks-density.png" ||
    fail "the served density differs from mpirun vots render's"
served aip
on_ranks aip
read -r worst differing < <(png_diff "$work/served-aip.png" "$work/ranks-aip.png")
((worst <= 1)) || fail "the served aip differs from mpirun vots render's by $worst grey levels ($differing pixels)"

for refused in "eps=3%25" "renderer=grid"; do
    code=$(get "$work/refused.json" "render?dataset=head&$view&$refused")
    [[ $code == 409 ]] && grep -q '"error"' "$work/refused.json" || fail "$refused answered $code, not 409 JSON"
done
stop_job
echo "mpi_serve_vots: OK"
