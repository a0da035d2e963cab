#!/usr/bin/env bash
# Starts and stops a real Orthanc (with its DICOMweb plugin) on loopback for the pacs tests: a temporary
# config, Basic auth, no DICOM port, storage and index in the state folder, a free HTTP port.
#
# Usage: tests/pacs/orthanc.sh start STATE_DIR   (writes STATE_DIR/{port,user,password,auth}; waits until it answers)
#        tests/pacs/orthanc.sh stop STATE_DIR    (stops it and removes STATE_DIR)
# Fails (never skips) when Orthanc or its DICOMweb plugin is missing: scripts/setup installs both.
set -euo pipefail

action=${1:?usage: orthanc.sh start|stop STATE_DIR}
state=${2:?usage: orthanc.sh start|stop STATE_DIR}

die() { echo "orthanc.sh: $*" >&2; exit 1; }

stop() {
    if [[ -f $state/orthanc.pid ]]; then
        local pid
        pid=$(cat "$state/orthanc.pid")
        if kill -0 "$pid" 2>/dev/null; then
            kill "$pid"
            for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
            kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
        fi
    fi
    rm -rf "$state"
}

plugin() {
    local candidate
    for candidate in /usr/share/orthanc/plugins/libOrthancDicomWeb.so /usr/lib/orthanc/libOrthancDicomWeb.so*; do
        [[ -f $candidate ]] && { echo "$candidate"; return; }
    done
    candidate=$(dpkg -L orthanc-dicomweb 2>/dev/null | grep -m1 'libOrthancDicomWeb\.so' || true)
    [[ -n $candidate ]] && echo "$candidate"
}

free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

start() {
    command -v Orthanc >/dev/null || die "Orthanc is not installed (scripts/setup installs orthanc and orthanc-dicomweb)"
    local dicomweb
    dicomweb=$(plugin)
    [[ -n $dicomweb ]] || die "the Orthanc DICOMweb plugin is not installed (apt-get install orthanc-dicomweb)"
    stop
    mkdir -p "$state/storage"
    chmod 700 "$state"
    local port password
    port=$(free_port)
    password=$(python3 -c 'import secrets; print(secrets.token_hex(12))')
    echo "$port" >"$state/port"
    echo vots >"$state/user"
    echo "$password" >"$state/password"
    echo "basic vots:$password" >"$state/auth"
    chmod 600 "$state/password" "$state/auth"
    cat >"$state/orthanc.json" <<JSON
{
  "Name": "vots-tests",
  "StorageDirectory": "$state/storage",
  "IndexDirectory": "$state/storage",
  "HttpPort": $port,
  "DicomServerEnabled": false,
  "RemoteAccessAllowed": false,
  "AuthenticationEnabled": true,
  "RegisteredUsers": { "vots": "$password" },
  "HttpCompressionEnabled": false,
  "Plugins": [ "$dicomweb" ],
  "DicomWeb": { "Enable": true, "Root": "/dicom-web/", "SeriesMetadata": "Extrapolate" }
}
JSON
    Orthanc "$state/orthanc.json" >"$state/orthanc.log" 2>&1 &
    echo $! >"$state/orthanc.pid"
    for _ in $(seq 300); do
        if curl -fsS -u "vots:$password" "http://127.0.0.1:$port/dicom-web/studies" -o /dev/null 2>/dev/null; then
            return 0
        fi
        kill -0 "$(cat "$state/orthanc.pid")" 2>/dev/null || { tail -20 "$state/orthanc.log" >&2; die "Orthanc exited at start"; }
        sleep 0.1
    done
    tail -20 "$state/orthanc.log" >&2
    die "Orthanc did not answer on port $port within 30 s"
}

case "$action" in
start) start ;;
stop) stop ;;
*) die "unknown action '$action' (start or stop)" ;;
esac
