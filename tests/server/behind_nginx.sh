#!/usr/bin/env bash
# Debian's nginx in front of `vots serve --behind-proxy 127.0.0.1`, run by the test user on loopback with
# a test CA made here: /render, the viewer socket and a fit's event stream through nginx over HTTPS; the
# audit log and the per-client render quota see the forwarded client; a forged X-Forwarded-For sent
# straight to vots from another address is ignored.
#
# Usage: tests/server/behind_nginx.sh VOTS DATASET_FILE CRANIUM_NHDR
#        (a small volume to draw, and the Cranium CT's header for a fit that lasts: scripts/fetch-ct)
set -euo pipefail

vots=$1
dataset_file=$2
cranium=$3
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../support/test-certificate.sh"
nginx_bin=${NGINX:-/usr/sbin/nginx}
[[ -x $nginx_bin ]] || { echo "behind_nginx.sh: no nginx at $nginx_bin (apt-get install nginx)"; exit 1; }

work=$(mktemp -d)
vots_pid=""
cleanup() {
    [[ -f $work/nginx.pid ]] && kill "$(cat "$work/nginx.pid")" 2>/dev/null
    [[ -n $vots_pid ]] && kill "$vots_pid" 2>/dev/null && wait "$vots_pid" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
failures=0
check() { # check WHAT COMMAND...: runs it, says PASS or FAIL
    local what=$1
    shift
    if "$@"; then echo "PASS: $what"; else echo "FAIL: $what"; failures=$((failures + 1)); fi
}

make_test_certificate "$work"
data=$work/data
mkdir "$data"
ln -s "$(realpath "$dataset_file")" "$data/"
dataset=$(basename "${dataset_file%.*}")
# The Cranium's header beside it, naming its samples by their absolute path.
samples=$(realpath "$(dirname "$cranium")/$(sed -n 's/^data file: //p' "$cranium")")
sed "s|^data file: .*|data file: $samples|" "$cranium" >"$data/cranium.nhdr"
# nginx's port, one the kernel just gave; vots answers to that name (Host) as --allow-host says.
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')

# The log exists before the server starts: the background job opens it only when the kernel runs it, which
# on a busy machine can be after the first look for its "listening on" line.
: >"$work/vots.log"
"$vots" serve --host 127.0.0.1 --port 0 --behind-proxy 127.0.0.1 --data "$data" --cache-dir "$work/cache" \
    --prepare '' --no-warm-up --audit-log "$work/audit.log" --renders-per-client 1 --allow-host "127.0.0.1:$port" >"$work/vots.log" 2>&1 &
vots_pid=$!
vots_port=""
for _ in $(seq 1 600); do
    vots_port=$(sed -n 's|.*listening on http://[^:]*:\([0-9]*\)/.*|\1|p' "$work/vots.log" | head -1)
    [[ -n $vots_port ]] && break
    kill -0 "$vots_pid" 2>/dev/null || { cat "$work/vots.log"; exit 1; }
    sleep 0.1
done
[[ -n $vots_port ]] || { echo "vots did not start"; cat "$work/vots.log"; exit 1; }

# nginx as this user: every path it writes is in the work folder.
mkdir -p "$work/temp"
sed -e "s|@LISTEN@|127.0.0.1:$port|" -e "s|@SERVER_NAME@|127.0.0.1|" -e "s|@CERT@|$work/site.pem|" \
    -e "s|@KEY@|$work/site.key|" -e "s|@UPSTREAM@|127.0.0.1:$vots_port|" \
    "$here/nginx/vots-site.conf.in" >"$work/vots-site.conf"
user_line=""
[[ $(id -u) == 0 ]] && user_line="user $(id -un) $(id -gn);" # else the workers would drop to nobody
cat >"$work/nginx.conf" <<EOF
$user_line
worker_processes 1;
pid $work/nginx.pid;
error_log $work/nginx-error.log warn;
events { worker_connections 256; }
http {
    access_log $work/nginx-access.log;
    client_body_temp_path $work/temp/body;
    proxy_temp_path $work/temp/proxy;
    fastcgi_temp_path $work/temp/fastcgi;
    uwsgi_temp_path $work/temp/uwsgi;
    scgi_temp_path $work/temp/scgi;
    include $work/vots-site.conf;
}
EOF
"$nginx_bin" -p "$work" -e "$work/nginx-error.log" -c "$work/nginx.conf" ||
    { cat "$work/nginx-error.log"; exit 1; }
for _ in $(seq 1 100); do
    curl -s -o /dev/null --cacert "$work/ca.pem" "https://127.0.0.1:$port/api/datasets" && break
    sleep 0.1
done

site="https://127.0.0.1:$port"
# curl through nginx from client address $1 (nginx connects to vots from 127.0.0.1 whoever the client is).
through() {
    local from=$1
    shift
    curl -s --cacert "$work/ca.pem" --interface "$from" --max-time 120 "$@"
}
audit_clients() { # the audit lines' clients for action $1, in order
    python3 -c 'import json, sys
for line in open(sys.argv[1]):
    entry = json.loads(line)
    if entry.get("action") == sys.argv[2]: print(entry.get("client"))' "$work/audit.log" "$1"
}
render_query="dataset=$dataset&cam=az=30,el=20&size=96x64&mode=mip"

# /render over HTTPS through nginx, audited under the client's own address.
code=$(through 127.0.0.3 -o "$work/render.png" -w '%{http_code}' "$site/render?$render_query")
check "/render through nginx over https answers 200 ($code)" test "$code" = 200
check "the answer is a PNG" test "$(head -c 4 "$work/render.png" | tail -c 3)" = PNG
check "the audit log names the forwarded client 127.0.0.3" \
    test "$(audit_clients render | tail -1)" = 127.0.0.3

# Through nginx a forged X-Forwarded-For stays in front of the address nginx saw; straight to vots from
# 127.0.0.2 (not the proxy's address) it is not read at all.
through 127.0.0.3 -o /dev/null -H 'X-Forwarded-For: 10.9.8.7' "$site/render?$render_query"
check "through nginx, a forged X-Forwarded-For is not the client" \
    test "$(audit_clients render | tail -1)" = 127.0.0.3
code=$(curl -s --interface 127.0.0.2 -o /dev/null -w '%{http_code}' -H 'X-Forwarded-For: 10.9.8.7' \
    "http://127.0.0.1:$vots_port/render?$render_query")
check "straight to vots from 127.0.0.2 with a forged X-Forwarded-For: answered ($code)" test "$code" = 200
check "and audited as 127.0.0.2, not the forged 10.9.8.7" test "$(audit_clients render | tail -1)" = 127.0.0.2

# The per-client quota (--renders-per-client 1, and as many waiting) counts forwarded clients, not nginx:
# while a turntable of 127.0.0.3's holds its place and a render of its waits, its next /render is
# refused, 127.0.0.4's is drawn.
# The turntable must hold the place before the render that waits is sent: were that render first, the
# turntable would be the one waiting and the next render would wait behind it, not be refused. Its
# frames being drawn (the server's frame count rising) says it holds the place.
frames_drawn() { curl -s "http://127.0.0.1:$vots_port/api/stats" | python3 -c 'import json, sys; print(json.load(sys.stdin)["frames"]["count"])'; }
drawn_before=$(frames_drawn)
through 127.0.0.3 -o /dev/null "$site/turntable?dataset=$dataset&cam=az=30&size=512x512&frames=360" &
turn=$!
for _ in $(seq 1 500); do
    (($(frames_drawn) > drawn_before + 1)) && break
    sleep 0.02
done
through 127.0.0.3 -o /dev/null --max-time 20 "$site/render?dataset=$dataset&cam=az=-1&size=96x64" &
waiting=$!
sleep 0.2
refused=$(through 127.0.0.3 "$site/render?dataset=$dataset&cam=az=1&size=96x64" | tr -d '\0')
other=$(through 127.0.0.4 -o /dev/null -w '%{http_code}' "$site/render?dataset=$dataset&cam=az=-1&size=96x64")
still_turning=no
kill -0 "$turn" 2>/dev/null && still_turning=yes
kill "$turn" 2>/dev/null || true # a client gone mid-answer: the server carries on
wait "$turn" 2>/dev/null || true
[[ -n $waiting ]] && { kill "$waiting" 2>/dev/null || true; wait "$waiting" 2>/dev/null || true; }
check "127.0.0.3's render beyond its place and its waiting one is refused, naming it: $refused" \
    grep -q 'too many renders in progress from 127.0.0.3' <<<"$refused"
check "127.0.0.4's render through the same nginx is drawn meanwhile ($other)" test "$other" = 200
check "(the turntable was still running then)" test "$still_turning" = yes

# The viewer socket through nginx (wss:// to nginx, ws:// on to vots).
frame=$(python3 "$here/viewer_socket_frame.py" "wss://127.0.0.1:$port/api/stream" --dataset "$dataset" \
    --cacert "$work/ca.pem" --source 127.0.0.3 2>&1) || true
check "a frame arrives over the socket through nginx: $frame" grep -q '"type": "frame"' <<<"$frame"

# A fit's event stream through nginx, to its end.
job=$(through 127.0.0.3 -X POST -H 'Content-Type: application/json' \
    -d "{\"dataset\": \"$dataset\", \"eps\": 0.02}" "$site/api/fit" |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["job"])') || true
events=$(through 127.0.0.3 -N "$site/api/jobs/$job/events")
check "the fit's events come through nginx to 'done'" grep -q '^event: done' <<<"$events"
check "the fit is audited under 127.0.0.3" test "$(audit_clients fit | tail -1)" = 127.0.0.3

# Unbuffered: a long fit's progress events arrive through nginx as they come, well before its end (a
# buffering proxy passes them on together when the stream ends), on a fast machine as on a slow one. The
# stream is read until its end or for a second past the first progress, whichever comes first: either
# shows the progress went through while the fit ran (under ThreadSanitizer this fit outlasts curl's
# --max-time, so waiting for its end would fail a proxy that streams).
job=$(through 127.0.0.3 -X POST -H 'Content-Type: application/json' \
    -d '{"dataset": "cranium", "eps": "0.5%"}' "$site/api/fit" |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["job"])') || true
arrivals=$(through 127.0.0.3 -N "$site/api/jobs/$job/events" | python3 -c '
import sys, time
start = time.monotonic()
first = end = None
for line in sys.stdin:
    t = time.monotonic() - start
    if line.startswith("event: progress") and first is None: first = t
    if line.startswith("event: done"): end = t
    if end is not None or (first is not None and t - first >= 1.0): break
seen = end if end is not None else time.monotonic() - start
print(f"first progress {first}, done {end}, read until {seen:.2f} s")
# Said here, not by the exit status: leaving early ends curl with a write error, which pipefail reports.
if first is not None and seen - first >= 0.2: print("streamed")' || true)
check "a running fit's progress comes through nginx before its end ($arrivals)" grep -q streamed <<<"$arrivals"

if ((failures > 0)); then
    echo "--- vots"; tail -20 "$work/vots.log"; echo "--- nginx"; tail -20 "$work/nginx-error.log"
    echo "behind_nginx.sh: $failures check(s) failed"
    exit 1
fi
echo "behind_nginx.sh: all checks passed"
