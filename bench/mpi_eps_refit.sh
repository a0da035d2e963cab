#!/usr/bin/env bash
# The viewer's eps slider under `mpirun -np N vots serve`: after --prepare's 2 % fit, POST /api/fit at each
# eps in turn and time the job (its fitSeconds: the slowest rank's fit of its cells) and the request to its end.
#
# Usage: bench/mpi_eps_refit.sh VOLUME [RANKS] [EPS...]    VOTS_BUILD=build/release (default)
# Default eps: 3% 1.5% 2.5% 1.3% 2%. Prints Markdown rows for bench/RESULTS.md.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
volume=$(realpath "$1")
ranks=${2:-2}
shift $(($# < 2 ? $# : 2))
epsList=("$@")
((${#epsList[@]})) || epsList=(3% 1.5% 2.5% 1.3% 2%)
vots=$(realpath "${VOTS_BUILD:-build/release}/cli/vots")
source bench/serve_bench.bash
mpirun --oversubscribe --enable-recovery -np "$ranks" "$vots" serve --port 0 --data "$work/data" \
    --cache-dir "$work/cache" --prepare "$name" >"$work/serve.log" 2>&1 &
job=$!
url=$(url_of "$work/serve.log")
/usr/bin/python3 - "$url" "$name" "$ranks" "${epsList[@]}" <<'PY'
import json, sys, time, urllib.request
url, name, ranks, eps_list = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
def get(path):
    return json.load(urllib.request.urlopen(url + path, timeout=900))
for _ in range(6000):  # --prepare's fit
    if get("api/stats")["fits"]:
        break
    time.sleep(0.1)
print("| ranks | eps | job s (request to done) | fitSeconds (slowest rank) | Vots |")
print("|---|---|---|---|---|")
for eps in eps_list:
    body = json.dumps({"dataset": name, "eps": eps}).encode()
    start = time.monotonic()
    post = urllib.request.Request(url + "api/fit", data=body, headers={"Content-Type": "application/json"})
    job_id = json.load(urllib.request.urlopen(post, timeout=900))["job"]
    while True:
        job = get("api/jobs/%d" % job_id)
        if job["state"] in ("done", "failed"):
            break
        time.sleep(0.02)
    assert job["state"] == "done", job
    print("| %s | %s | %.2f | %.2f | %d |" % (ranks, eps, time.monotonic() - start, job["fitSeconds"], job["votCount"]))
PY
