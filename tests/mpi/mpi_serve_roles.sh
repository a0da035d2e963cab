#!/usr/bin/env bash
# `mpirun -np 2 vots serve --token-file` with a viewer's and an operator's token: the viewer's /render and
# /turntable at an eps the ranks have not fitted get 403 and leave the ranks' fits as they were; the
# default eps (fitted by --prepare) is drawn for it; once the operator's POST /api/fit has the ranks fit
# that eps, the viewer draws it; the viewer's own POST /api/fit is 403.
# Usage: tests/mpi/mpi_serve_roles.sh VOTS_BINARY VOLUME
set -euo pipefail
vots=$1 volume=$2
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
ln -s "$(realpath "$volume")" "$work/data/$(basename "$volume")"
name=$(basename "$volume" | sed -E 's/\.(nrrd|nhdr|nii\.gz|nii|mhd|mha)$//')
viewer=mpi-viewer-token-0123456789 operator=mpi-operator-token-0123456789
printf 'alice viewer %s\nbob operator %s\n' "$viewer" "$operator" >"$work/tokens"
start_job "$work/data" "$name" --token-file "$work/tokens"
as() { # TOKEN FILE PATH_AND_QUERY [CURL ARGUMENTS]: the status
    local token=$1 file=$2 target=$3
    shift 3
    curl -s --max-time 120 -H "Authorization: Bearer $token" -o "$file" -w '%{http_code}' "$@" "${url}$target"
}
fits() { as "$operator" "$work/stats.json" api/stats >/dev/null && python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["fits"]))' "$work/stats.json"; }
for _ in $(seq 600); do [[ $(fits) -ge 1 ]] && break; sleep 0.1; done # --prepare's fit on the ranks
[[ $(fits) == 1 ]] || fail "--prepare did not have the ranks fit: $(cat "$work/stats.json")"

view="dataset=$name&cam=az=30,el=20&size=64x48"
for target in "render?$view&eps=3%25" "turntable?$view&eps=3%25&frames=2"; do
    code=$(as "$viewer" "$work/refused.json" "$target")
    [[ $code == 403 ]] || fail "the viewer's $target answered $code: $(head -c 300 "$work/refused.json")"
    grep -q "viewer's" "$work/refused.json" || fail "the 403 does not say why: $(cat "$work/refused.json")"
done
[[ $(fits) == 1 ]] || fail "a viewer's frame had the ranks fit: $(cat "$work/stats.json")"
code=$(as "$viewer" "$work/default.png" "render?$view")
[[ $code == 200 ]] || fail "the viewer's frame at the default eps answered $code"
code=$(as "$viewer" "$work/fit.json" api/fit -H 'Content-Type: application/json' --data "{\"dataset\":\"$name\",\"eps\":\"3%\"}")
[[ $code == 403 ]] || fail "the viewer's POST /api/fit answered $code"

code=$(as "$operator" "$work/job.json" api/fit -H 'Content-Type: application/json' --data "{\"dataset\":\"$name\",\"eps\":\"3%\"}")
[[ $code == 202 ]] || fail "the operator's POST /api/fit answered $code: $(cat "$work/job.json")"
job_id=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["job"])' "$work/job.json")
for _ in $(seq 600); do
    as "$operator" "$work/state.json" "api/jobs/$job_id" >/dev/null
    grep -q '"state":"done"' "$work/state.json" && break
    grep -q '"state":"failed"' "$work/state.json" && fail "the ranks' fit failed: $(cat "$work/state.json")"
    sleep 0.2
done
grep -q '"state":"done"' "$work/state.json" || fail "the ranks' fit did not end: $(cat "$work/state.json")"
code=$(as "$viewer" "$work/fitted.png" "render?$view&eps=3%25")
[[ $code == 200 ]] || fail "the viewer's frame at the operator's eps answered $code: $(head -c 300 "$work/fitted.png")"
stop_job
echo "mpi_serve_roles: PASS"
