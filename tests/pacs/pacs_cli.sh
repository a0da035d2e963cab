#!/usr/bin/env bash
# `vots fit|render|verify` with a series on a real Orthanc (started by tests/pacs/pacs_setup.sh) as input:
# the results equal a folder's, and every failure is one line, exit 2, no output file and no spool left.
#
# Usage: tests/pacs/pacs_cli.sh STATE_DIR VOTS_BINARY CASE   (ctest runs each CASE as Pacs.Cli.CASE)
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
state=${1:?usage: pacs_cli.sh STATE_DIR VOTS CASE}
vots=${2:?usage: pacs_cli.sh STATE_DIR VOTS CASE}
case_name=${3:?usage: pacs_cli.sh STATE_DIR VOTS CASE}

[[ -f $state/port ]] || { echo "pacs_cli: no Orthanc state in $state (the Orthanc fixture did not run)" >&2; exit 1; }
port=$(cat "$state/port")
password=$(cat "$state/password")
auth=$state/auth
ramp_series=1.2.826.0.1.3680043.10.1234.201
cranium_series=1.2.826.0.1.3680043.10.1234.202
mixed_series=1.2.826.0.1.3680043.10.1234.203
sweep_series=1.2.826.0.1.3680043.10.1234.206 # its study gets the derived series of SweepStoredOnThePacs
url() { echo "dicomweb+http://127.0.0.1:$1/dicom-web/studies/$2.0/series/$2"; }

work=$(mktemp -d)
spool=$work/spool # every vots here spools into it: it must be empty when vots has ended
mkdir -p "$spool"
export TMPDIR=$spool
proxy_pid=
cleanup() {
    [[ -n $proxy_pid ]] && kill "$proxy_pid" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT

fail() { echo "pacs_cli $case_name: FAILED: $*" >&2; exit 1; }
no_spool_left() { [[ -z $(ls -A "$spool") ]] || fail "spool left behind: $(ls -A "$spool")"; }

# Runs vots expecting exit 2 with one line on stderr containing $1, no file $2, no spool and no password.
expect_refused() {
    local expected=$1 output=$2
    shift 2
    "$vots" "$@" >"$work/out" 2>"$work/err"
    local rc=$?
    [[ $rc == 2 ]] || fail "exit $rc (expected 2): $(cat "$work/err")"
    [[ $(wc -l <"$work/err") == 1 ]] || fail "not one line: $(cat "$work/err")"
    grep -q -- "$expected" "$work/err" || fail "no '$expected' in: $(cat "$work/err")"
    grep -q -- "$password" "$work/err" "$work/out" && fail "the password is in the output"
    [[ -e $output ]] && fail "$output was written"
    no_spool_left
    echo "refused as expected: $(cat "$work/err")"
}

# Starts tests/pacs/fault_proxy.py in front of Orthanc with the given fault; sets proxy_port.
start_proxy() {
    python3 "$here/fault_proxy.py" --target "$port" --port-file "$work/proxy_port" --log "$work/proxy.log" "$@" &
    proxy_pid=$!
    for _ in $(seq 100); do [[ -s $work/proxy_port ]] && break; sleep 0.05; done
    proxy_port=$(cat "$work/proxy_port")
}

case "$case_name" in
RenderMatchesFolder)
    # The same files read from the PACS and from a folder render byte for byte the same.
    for view in anterior left; do
        "$vots" render "$(url "$port" $cranium_series)" --dicomweb-auth "$auth" -o "$work/pacs-$view.png" \
            --view "$view" --size 128x128 || fail "render from the PACS"
        "$vots" render "$state/series/cranium" -o "$work/folder-$view.png" --view "$view" --size 128x128 ||
            fail "render from the folder"
        cmp "$work/pacs-$view.png" "$work/folder-$view.png" || fail "the $view PNGs differ"
    done
    # The volume of a .vots input (--volume) from the PACS too.
    "$vots" fit "$state/series/ramp" -o "$work/ramp.vots" --eps 2% >/dev/null || fail "fit of the ramp folder"
    "$vots" render "$work/ramp.vots" --volume "$(url "$port" $ramp_series)" --dicomweb-auth "$auth" --renderer grid \
        -o "$work/pacs-grid.png" --size 64x64 || fail "render --volume from the PACS"
    "$vots" render "$work/ramp.vots" --volume "$state/series/ramp" --renderer grid -o "$work/folder-grid.png" \
        --size 64x64 || fail "render --volume from the folder"
    cmp "$work/pacs-grid.png" "$work/folder-grid.png" || fail "the --volume PNGs differ"
    no_spool_left
    ;;
FitAndVerify)
    # The Cranium fitted from the PACS holds the Vots of the same files fitted from a folder.
    "$vots" fit "$(url "$port" $cranium_series)" --dicomweb-auth "$auth" -o "$work/pacs.vots" --eps 2% --progress ||
        fail "fit from the PACS"
    "$vots" fit "$state/series/cranium" -o "$work/folder.vots" --eps 2% || fail "fit from the folder"
    "$vots" verify "$work/pacs.vots" "$(url "$port" $cranium_series)" --dicomweb-auth "$auth" || fail "verify from the PACS"
    "$vots" verify "$work/pacs.vots" "$state/series/cranium" || fail "verify against the folder"
    "$vots" info "$work/pacs.vots" --json >"$work/info.json" || fail "info"
    "$vots" info "$work/folder.vots" --json >"$work/folder-info.json" || fail "info"
    python3 - "$work/info.json" "$work/folder-info.json" <<'PY' || fail "the PACS and folder fits differ"
import json, sys
pacs, folder = (json.load(open(path)) for path in sys.argv[1:])
for info in (pacs, folder):
    for key in ("meta", "fit_seconds", "file"):
        info.pop(key)
assert pacs == folder and pacs["vot_count"] > 1000, (pacs, folder)
PY
    python3 - "$work/info.json" "$(url "$port" $cranium_series)" <<'PY' || fail "the meta block does not name the series"
import json, sys
source = json.load(open(sys.argv[1]))["meta"]["source"]
assert source["path"] == sys.argv[2] and source["name"] == sys.argv[2].rsplit("/", 1)[1], source
PY
    grep -q -- "$password" "$work/pacs.vots" "$work/info.json" && fail "the password is in the .vots file"
    no_spool_left
    ;;
WrongCredentials)
    echo "basic vots:not-$password" >"$work/wrong"
    expect_refused "refused the credentials" "$work/o.vots" fit "$(url "$port" $ramp_series)" --dicomweb-auth "$work/wrong" \
        -o "$work/o.vots" --eps 1%
    expect_refused "refused the credentials" "$work/o.vots" fit "$(url "$port" $ramp_series)" -o "$work/o.vots" --eps 1%
    echo "bearer $password" >"$work/bearer" # Orthanc does Basic only
    expect_refused "refused the credentials" "$work/o.png" render "$(url "$port" $ramp_series)" --dicomweb-auth "$work/bearer" \
        -o "$work/o.png"
    ;;
UnreachablePort)
    closed=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
    expect_refused "cannot connect" "$work/o.vots" fit "$(url "$closed" $ramp_series)" --dicomweb-auth "$auth" \
        -o "$work/o.vots" --eps 1%
    ;;
UnknownSeries)
    expect_refused "no such series" "$work/o.vots" fit "$(url "$port" 1.2.3.999)" --dicomweb-auth "$auth" -o "$work/o.vots" --eps 1%
    expect_refused "no such series" "$work/o.png" render "$(url "$port" 1.2.3.999)" --dicomweb-auth "$auth" -o "$work/o.png"
    ;;
MixedSizes)
    expect_refused "mixed image sizes" "$work/o.vots" fit "$(url "$port" $mixed_series)" --dicomweb-auth "$auth" \
        -o "$work/o.vots" --eps 1%
    ;;
NotImages)
    # A series of one report, then a report among the images of a series.
    expect_refused "is not an image" "$work/o.vots" fit "$(url "$port" 1.2.826.0.1.3680043.10.1234.204)" \
        --dicomweb-auth "$auth" -o "$work/o.vots" --eps 1%
    expect_refused "not an image" "$work/o.vots" fit "$(url "$port" 1.2.826.0.1.3680043.10.1234.205)" \
        --dicomweb-auth "$auth" -o "$work/o.vots" --eps 1%
    ;;
MemoryBudget)
    expect_refused "memory budget" "$work/o.vots" fit "$(url "$port" $cranium_series)" --dicomweb-auth "$auth" \
        -o "$work/o.vots" --eps 1% --memory-budget 1M
    ;;
CutStream)
    # Every answer is cut after 64 KB, less than one Cranium instance: the series and the fallback fail.
    start_proxy --cut 65536
    expect_refused "one by one" "$work/o.vots" fit "$(url "$proxy_port" $cranium_series)" --dicomweb-auth "$auth" \
        -o "$work/o.vots" --eps 1%
    ;;
CutSeriesFallsBack)
    # Cut after 20 KB: the ramp's series answer breaks, its small instances come one by one.
    start_proxy --cut 20000
    "$vots" render "$(url "$proxy_port" $ramp_series)" --dicomweb-auth "$auth" -o "$work/pacs.png" --size 64x64 ||
        fail "render through the cutting proxy"
    grep -q "/series/$ramp_series HTTP/1.1 CUT" "$work/proxy.log" || fail "the proxy did not cut the series answer"
    # Only the instances the cut answer lacked come one by one: some, not all 20.
    one_by_one=$(grep -cE "/instances/[0-9.]+ HTTP/1.1 PASSED" "$work/proxy.log")
    ((one_by_one > 0 && one_by_one < 20)) || fail "$one_by_one instances one by one (expected the missing ones only)"
    "$vots" render "$state/series/ramp" -o "$work/folder.png" --size 64x64 || fail "render from the folder"
    cmp "$work/pacs.png" "$work/folder.png" || fail "the PNGs differ"
    no_spool_left
    ;;
RefusedSeriesFallsBack)
    start_proxy --refuse-series
    "$vots" render "$(url "$proxy_port" $cranium_series)" --dicomweb-auth "$auth" -o "$work/pacs.png" --size 96x96 ||
        fail "render with the series request refused"
    grep -q "/series/$cranium_series HTTP/1.1 REFUSED" "$work/proxy.log" || fail "the proxy did not refuse the series"
    [[ $(grep -cE "/instances/[0-9.]+ HTTP/1.1 PASSED" "$work/proxy.log") == 108 ]] || fail "not 108 instances one by one"
    "$vots" render "$state/series/cranium" -o "$work/folder.png" --size 96x96 || fail "render from the folder"
    cmp "$work/pacs.png" "$work/folder.png" || fail "the PNGs differ"
    no_spool_left
    ;;
MalformedBody)
    start_proxy --garble
    expect_refused "malformed multipart body" "$work/o.vots" fit "$(url "$proxy_port" $ramp_series)" \
        --dicomweb-auth "$auth" -o "$work/o.vots" --eps 1%
    ;;
InterruptRemovesTheSpool)
    # The answer stalls after 1 MB; once instances are in the spool, SIGINT ends vots with one line, exit 2
    # and no spool folder.
    start_proxy --stall 1000000
    "$vots" fit "$(url "$proxy_port" $cranium_series)" --dicomweb-auth "$auth" -o "$work/o.vots" --eps 1% \
        >"$work/out" 2>"$work/err" &
    vots_pid=$!
    for _ in $(seq 600); do
        [[ -n $(find "$spool" -name 'instance-*' 2>/dev/null) ]] && break
        sleep 0.1
    done
    [[ -n $(find "$spool" -name 'instance-*') ]] || fail "no instance reached the spool"
    kill -INT "$vots_pid"
    wait "$vots_pid"
    rc=$?
    [[ $rc == 2 ]] || fail "exit $rc after SIGINT (expected 2): $(cat "$work/err")"
    grep -q "cancelled" "$work/err" || fail "no 'cancelled' in: $(cat "$work/err")"
    [[ $(wc -l <"$work/err") == 1 ]] || fail "not one line: $(cat "$work/err")"
    [[ -e $work/o.vots ]] && fail "o.vots was written"
    no_spool_left
    echo "interrupted as expected: $(cat "$work/err")"
    ;;
HttpsVerifiesTheCertificate)
    # HTTPS with a self-signed certificate for 127.0.0.1 (the proxy terminates TLS in front of Orthanc):
    # refused unless --dicomweb-ca trusts it.
    openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=127.0.0.1 -addext subjectAltName=IP:127.0.0.1 \
        -keyout "$work/key.pem" -out "$work/cert.pem" 2>/dev/null || fail "openssl could not make a certificate"
    start_proxy --tls "$work/cert.pem" "$work/key.pem"
    tls_url=dicomweb+https://127.0.0.1:$proxy_port/dicom-web/studies/$ramp_series.0/series/$ramp_series
    expect_refused "TLS" "$work/o.png" render "$tls_url" --dicomweb-auth "$auth" -o "$work/o.png"
    "$vots" render "$tls_url" --dicomweb-auth "$auth" --dicomweb-ca "$work/cert.pem" -o "$work/pacs.png" --size 64x64 ||
        fail "render over HTTPS with --dicomweb-ca"
    "$vots" render "$state/series/ramp" -o "$work/folder.png" --size 64x64 || fail "render from the folder"
    cmp "$work/pacs.png" "$work/folder.png" || fail "the PNGs differ"
    no_spool_left
    ;;
SweepStoredOnThePacs)
    # A slab sweep stored with STOW-RS joins its source's study as a new series whose images read back as
    # the same volume as the sweep written to a folder; a refused store leaves nothing behind.
    mkdir -p "$work/local"
    sweep=(--view inferior --slab-sweep 6,3 --size 48x48)
    "$vots" render "$state/series/sweep-source" "${sweep[@]}" -o "$work/local/%03d.dcm" || fail "sweep to a folder"
    count=$(find "$work/local" -name '*.dcm' | wc -l)
    ((count > 1)) || fail "the sweep wrote $count images"
    echo "basic vots:not-$password" >"$work/wrong"
    expect_refused "refused the credentials" "$work/none" render "$state/series/sweep-source" "${sweep[@]}" \
        -o "dicomweb+http://127.0.0.1:$port/dicom-web" --dicomweb-auth "$work/wrong"
    "$vots" render "$state/series/sweep-source" "${sweep[@]}" -o "dicomweb+http://127.0.0.1:$port/dicom-web" \
        --dicomweb-auth "$auth" 2>"$work/err" || fail "sweep to the PACS: $(cat "$work/err")"
    grep -q "stored $count images" "$work/err" || fail "no 'stored $count images' in: $(cat "$work/err")"
    curl -fsS -u "vots:$password" "http://127.0.0.1:$port/dicom-web/studies/$sweep_series.0/series" >"$work/series.json" ||
        fail "QIDO of the source's study"
    derived=$(python3 - "$work/series.json" "$sweep_series" <<'PY'
import json, sys
series = [s for s in json.load(open(sys.argv[1])) if s["0020000E"]["Value"][0] != sys.argv[2]]
assert len(series) == 1, f"{len(series)} new series in the source's study"
s = series[0]
print(s["0020000E"]["Value"][0], s["00201209"]["Value"][0], s["0008103E"]["Value"][0])
PY
) || fail "the source's study: $(cat "$work/series.json")"
    read -r derived_uid derived_count derived_description <<<"$derived"
    [[ $derived_count == "$count" ]] || fail "the PACS holds $derived_count images of the sweep's $count"
    echo "derived series $derived_uid: $derived_count images, '$derived_description'"
    derived_url=dicomweb+http://127.0.0.1:$port/dicom-web/studies/$sweep_series.0/series/$derived_uid
    "$vots" render "$derived_url" --dicomweb-auth "$auth" --renderer grid --view anterior --size 64x64 \
        -o "$work/pacs.png" || fail "render of the stored series"
    "$vots" render "$work/local" --renderer grid --view anterior --size 64x64 -o "$work/folder.png" ||
        fail "render of the folder's series"
    cmp "$work/pacs.png" "$work/folder.png" || fail "the stored series renders differently from the folder's"
    no_spool_left
    ;;
*)
    fail "unknown case"
    ;;
esac
echo "pacs_cli $case_name: OK"
