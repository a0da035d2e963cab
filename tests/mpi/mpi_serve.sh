#!/usr/bin/env bash
# `mpirun -np 2 vots serve` on loopback: rank 0 answers /render with the frame the two ranks composite,
# the bytes of `mpirun -np 2 vots render` of the same camera and eps (mip, minip with a slab; the aip
# within one grey level), and the exact grid's frames from the ranks' planes; POST /api/fit has the ranks
# refit from their box caches (the next frame at that eps refits nothing and is a fresh fit's bytes);
# --prepare has the ranks fit the default eps before the
# first frame; the density is mpirun vots render's; /api/stats says "ranks": 2
# with both ranks' times; a second dataset is refused with 409; a rank killed
# mid-session makes the next /render (one that refits: its deadline is 10 min, the rank's silent heartbeat
# ends the wait after 15 s) a 503 JSON within 30 s, and every later one; SIGTERM to rank 0 then ends the
# job cleanly, all of it bounded by timeouts; a rank's planes over its --memory-budget are a 507.
# Usage: tests/mpi/mpi_serve.sh VOTS_BINARY VOLUME [OTHER_VOLUME]
set -euo pipefail
vots=$1 volume=$2 other=${3:-}
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
ln -s "$(realpath "$volume")" "$work/data/$(basename "$volume")"
[[ -n $other ]] && ln -s "$(realpath "$other")" "$work/data/$(basename "$other")"
name=$(basename "$volume" | sed -E 's/\.(nrrd|nhdr|nii\.gz|nii|mhd|mha)$//')

# Minimax fits on the ranks (`vots serve` fits least squares unless told): the frames, refits from the
# ranks' box caches included, are `mpirun vots render`'s, whose default is minimax.
start_job "$work/data" "$name" --fit-norm minimax
view="cam=az=30,el=20&size=96x80&eps=2%25"
render_args=(--cam az=30,el=20 --size 96x80 --eps 2%)

# --prepare: the ranks fit the default eps (2 %) as the server starts, so the first frame fits nothing.
/usr/bin/python3 - "$url" <<'PY' || fail "--prepare did not have the ranks fit"
import json, sys, time, urllib.request
for _ in range(600):
    fits = json.load(urllib.request.urlopen(sys.argv[1] + "api/stats", timeout=60))["fits"]
    if fits:
        break
    time.sleep(0.1)
assert [f["source"] for f in fits] == ["ranks"], fits
PY
code=$(get "$work/served-mip.png" "render?dataset=$name&$view")
[[ $code == 200 ]] || fail "/render answered $code: $(cat "$work/served-mip.png")"
get "$work/stats-first.json" "api/stats" >/dev/null
/usr/bin/python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["rankTimes"]; assert all(r["fitMs"] == 0 and r["votCount"] > 0 for r in t), t' \
    "$work/stats-first.json" || fail "the first frame refitted after --prepare: $(cat "$work/stats-first.json")"
mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-mip.png" "${render_args[@]}" 2>/dev/null
cmp -s "$work/served-mip.png" "$work/ranks-mip.png" || fail "the served mip differs from mpirun vots render's"

code=$(get "$work/served-minip.png" "render?dataset=$name&$view&mode=minip&slab=-10,30")
[[ $code == 200 ]] || fail "/render mode=minip answered $code"
mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-minip.png" --mode minip --slab -10,30 \
    "${render_args[@]}" 2>/dev/null
cmp -s "$work/served-minip.png" "$work/ranks-minip.png" || fail "the served minip differs from mpirun vots render's"

code=$(get "$work/served-aip.png" "render?dataset=$name&$view&mode=aip")
[[ $code == 200 ]] || fail "/render mode=aip answered $code"
mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-aip.png" --mode aip "${render_args[@]}" \
    2>/dev/null
read -r worst differing < <(png_diff "$work/served-aip.png" "$work/ranks-aip.png")
((worst <= 1)) || fail "the served aip differs from mpirun vots render's by $worst grey levels ($differing pixels)"

get "$work/stats.json" "api/stats" >/dev/null
/usr/bin/python3 - "$work/stats.json" <<'PY' || fail "/api/stats: $(cat "$work/stats.json")"
import json, sys
stats = json.load(open(sys.argv[1]))
assert stats["ranks"] == 2, stats["ranks"]
times = stats["rankTimes"]
assert [t["rank"] for t in times] == [0, 1], times
assert all(t["frameMs"] > 0 for t in times), times
PY

# POST /api/fit (the viewer's eps slider): the ranks fit their z cells, rank 0 nothing whole; the next
# frame at that eps finds every rank's fit held.
/usr/bin/python3 - "$url" "$name" <<'PY' || fail "POST /api/fit under mpirun failed"
import json, sys, time, urllib.request
url, name = sys.argv[1], sys.argv[2]
body = json.dumps({"dataset": name, "eps": "3%"}).encode()
post = urllib.request.Request(url + "api/fit", data=body, headers={"Content-Type": "application/json"})
job_id = json.load(urllib.request.urlopen(post, timeout=60))["job"]
for _ in range(600):
    job = json.load(urllib.request.urlopen(url + "api/jobs/%d" % job_id, timeout=60))
    if job["state"] in ("done", "failed"):
        break
    time.sleep(0.1)
assert job["state"] == "done" and job["votCount"] > 0 and job["fitSeconds"] > 0, job
stats = json.load(urllib.request.urlopen(url + "api/stats", timeout=60))
assert [f["source"] for f in stats["fits"]] == ["ranks", "ranks"], stats["fits"]  # --prepare's and this
PY
code=$(get "$work/served-3.png" "render?dataset=$name&cam=az=30,el=20&size=96x80&eps=3%25")
[[ $code == 200 ]] || fail "/render at the fitted eps answered $code"
get "$work/stats3.json" "api/stats" >/dev/null
/usr/bin/python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["rankTimes"]; assert all(r["fitMs"] == 0 and r["votCount"] > 0 for r in t), t' \
    "$work/stats3.json" || fail "the frame after POST /api/fit refitted: $(cat "$work/stats3.json")"
# That fit was a refit from each rank's box cache (filled by the 2 % fit): the same Vots as a fresh fit.
mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-3.png" --cam az=30,el=20 --size 96x80 \
    --eps 3% 2>/dev/null
cmp -s "$work/served-3.png" "$work/ranks-3.png" || fail "the frame of the cached refit differs from a fresh fit's"

# The exact grid: each rank reads its cells' planes; the reference (the grid's mip) is the one-process
# image bit for bit, the grid's minip and aip are mpirun vots render's.
code=$(get "$work/served-ref.png" "render?dataset=$name&$view&mode=reference")
[[ $code == 200 ]] || fail "/render mode=reference answered $code: $(cat "$work/served-ref.png")"
"$vots" render "$volume" -o "$work/one-ref.png" --mode reference "${render_args[@]}" 2>/dev/null
cmp -s "$work/served-ref.png" "$work/one-ref.png" || fail "the served reference differs from one process's"
for mode in minip aip; do
    code=$(get "$work/served-grid-$mode.png" "render?dataset=$name&$view&mode=$mode&renderer=grid")
    [[ $code == 200 ]] || fail "/render mode=$mode renderer=grid answered $code"
    mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-grid-$mode.png" --mode "$mode" \
        --renderer grid "${render_args[@]}" 2>/dev/null
    cmp -s "$work/served-grid-$mode.png" "$work/ranks-grid-$mode.png" ||
        fail "the served grid $mode differs from mpirun vots render's"
done

# The density: the smallest box along each ray, the min over the ranks, shown over their sizes' union.
code=$(get "$work/served-density.png" "render?dataset=$name&$view&mode=density")
[[ $code == 200 ]] || fail "/render mode=density answered $code: $(cat "$work/served-density.png")"
mpirun --oversubscribe -np 2 "$vots" render "$volume" -o "$work/ranks-density.png" --mode density \
    "${render_args[@]}" 2>/dev/null
cmp -s "$work/served-density.png" "$work/ranks-density.png" ||
    fail "the served density differs from mpirun vots render's"
if [[ -n $other ]]; then
    otherName=$(basename "$other" | sed -E 's/\.(nrrd|nhdr|nii\.gz|nii|mhd|mha)$//')
    code=$(get "$work/refused.json" "render?dataset=$otherName&$view")
    [[ $code == 409 ]] || fail "a second dataset answered $code, not 409"
fi

rank0=$(rank_pid 0) rank1=$(rank_pid 1)
[[ -n $rank0 && -n $rank1 ]] || fail "cannot find the ranks' processes"
kill -KILL "$rank1"
start=$(date +%s)
# eps 2 % while the ranks hold the fit of 3 %: rank 0 waits under the fit's deadline until rank 1's
# heartbeat has been silent for 15 s.
code=$(get "$work/lost.json" "render?dataset=$name&cam=az=60,el=20&size=96x80&eps=2%25")
seconds=$(($(date +%s) - start))
[[ $code == 503 ]] && grep -q '"error":"rank 1' "$work/lost.json" ||
    fail "with rank 1 killed /render answered $code: $(cat "$work/lost.json")"
((seconds <= 30)) || fail "the 503 took $seconds s"
code=$(get "$work/lost.json" "render?dataset=$name&cam=az=90,el=20&size=96x80&eps=2%25")
[[ $code == 503 ]] || fail "a later /render answered $code, not 503"
(($(grep -c "rank 1 of 2" "$work/serve.log") == 1)) || fail "the lost rank is not logged once"

kill -TERM "$rank0"
job_ends_within 30 "after SIGTERM to rank 0"
wait "$job" || true
job=
grep -q "vots serve: stopping" "$work/serve.log" || fail "rank 0 did not stop cleanly"

# Rank 0 killed: rank 1 misses its heartbeat and leaves within the 30 s silence, so mpirun ends.
start_job "$work/data" "$name"
code=$(get "$work/before.png" "render?dataset=$name&$view")
[[ $code == 200 ]] || fail "/render of the second job answered $code"
rank0=$(rank_pid 0)
[[ -n $rank0 ]] || fail "cannot find rank 0's process"
kill -KILL "$rank0"
start=$(date +%s)
job_ends_within 60 "after rank 0 was killed"
wait "$job" || true
job=
left=$(($(date +%s) - start))
grep -q "rank 1 of 2: rank 0 has sent nothing" "$work/serve.log" || fail "rank 1 did not say why it left"
# A memory budget too small for a rank's planes: every rank checks its planes' size against it before
# reading, and rank 0 answers 507 JSON (as one process does for a study over its budget), no OOM.
start_job "$work/data" "$name" --memory-budget 64M
code=$(get "$work/budget.json" "render?dataset=$name&$view")
[[ $code == 507 ]] && grep -q 'memory budget' "$work/budget.json" ||
    fail "a rank's planes over its memory budget answered $code: $(cat "$work/budget.json")"
code=$(get "$work/budget.json" "render?dataset=$name&$view")
[[ $code == 507 ]] || fail "the second request over the budget answered $code"
# SIGTERM to rank 0 with every rank alive: it lets them go (each says it has taken the quit) and the
# whole job ends at once with status 0, not after the other ranks' 30 s of silence.
stop_job

echo "mpi_serve: OK (503 after $seconds s; with rank 0 killed the job ended after $left s)"
