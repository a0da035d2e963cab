#!/usr/bin/env bash
# Fault injection against a real `vots serve`: kill -9 mid-fit, full disk, unwritable cache, vanishing clients.
#
# Usage: tests/reliability/faults.sh      (builds build/rel unless VOTS_BIN names a binary)
# Prints one "PASS/FAIL <fault>: <outcome>" line per fault; exits 1 if any failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source tests/reliability/common.sh
build_rel

make_work
# A volume whose fit takes seconds (the kill lands mid-fit: the Cranium at 0.1 %, about 4 s on a 2-core
# box; at 2 % it took 0.5 s and a fast machine finished before the kill) and a small one for the rest.
serve_volumes "$work/data"
failures=0
report() { # report PASS|FAIL "fault" "outcome"
    echo "$1 $2: $3"
    [[ $1 == PASS ]] || failures=$((failures + 1))
}
fit() { # fit DATASET EPS -> job JSON
    curl -s -X POST "http://127.0.0.1:$SERVER_PORT/api/fit" -H 'Content-Type: application/json' \
        -d "{\"dataset\":\"$1\",\"eps\":\"$2\"}"
}
job_state() { curl -s "http://127.0.0.1:$SERVER_PORT/api/jobs/$1" | sed -n 's/.*"state":"\([a-z]*\)".*/\1/p'; }
wait_job() { # wait_job ID -> final state
    local state=
    for _ in $(seq 1 600); do
        state=$(job_state "$1")
        [[ $state == done || $state == failed ]] && break
        sleep 0.5
    done
    echo "$state"
}
job_id() { sed -n 's/.*"id":\([0-9]*\).*/\1/p'; }
log_line() { # log_line FILE PATTERN -> the first matching line, waiting up to 30 s for it: the cache
    # write runs deferred, after the fit is answered and its frames drawn, so its warning comes later
    local line=
    for _ in $(seq 1 60); do
        line=$(grep -m1 "$2" "$1" || true)
        [[ -n $line ]] && break
        sleep 0.5
    done
    echo "$line"
}
render_ok() { # render_ok [SOURCE_ADDRESS] -> HTTP status of a small /render
    curl -s -o /dev/null -w '%{http_code}' --interface "${1:-127.0.0.1}" \
        "http://127.0.0.1:$SERVER_PORT/render?dataset=mri-brain_33x41x25_int16&size=64x64&eps=5%25"
}

# 1. kill -9 in the middle of a fit, then restart on the same cache folder.
cache=$work/cache
start_server "$work/s1.log" --data "$work/data" --cache-dir "$cache"
job=$(fit cranium 0.1%)
id=$(echo "$job" | job_id)
key=$(echo "$job" | sed -n 's/.*"key":"\([^"]*\)".*/\1/p')
for _ in $(seq 1 100); do [[ $(job_state "$id") == running ]] && break; sleep 0.1; done
sleep 0.3
state_at_kill=$(job_state "$id")
kill -9 "$SERVER_PID"
wait "$SERVER_PID" 2>/dev/null || true
SERVER_PID=
# What a kill between open and rename leaves (a temporary of a dead writer), and a corrupt file under
# the key's own name (a disk that lost the tail), which must be refitted, not served.
dead=$(sh -c 'echo $$')
echo half >"$cache/$key.vots.tmp-$dead-0"
printf 'VOTS\x01' >"$cache/$key.vots"
start_server "$work/s2.log" --data "$work/data" --cache-dir "$cache"
id=$(fit cranium 0.1% | job_id)
state=$(wait_job "$id")
# A fit is announced before its disk write, so give the write (tens of MB) up to 60 s to replace the
# corrupt file under the key's name.
for _ in $(seq 1 120); do
    temps=$(find "$cache" -name '*.tmp-*' | wc -l)
    bad=0
    for f in "$cache"/*.vots; do
        "$VOTS" info "$f" >/dev/null 2>&1 || bad=$((bad + 1))
    done
    [[ $temps -eq 0 && $bad -eq 0 ]] && break
    sleep 0.5
done
if [[ $state_at_kill != running ]]; then
    report FAIL "kill -9 mid-fit" "the kill did not land mid-fit (job was '$state_at_kill'); use a slower fit"
elif [[ $state == done && $temps -eq 0 && $bad -eq 0 ]]; then
    report PASS "kill -9 mid-fit" "job was '$state_at_kill' at the kill; after restart the fit is done, 0 temporaries left, every fitted .vots reads back with vots info"
else
    report FAIL "kill -9 mid-fit" "state=$state temporaries=$temps unreadable=$bad"
fi
stop_server

# 2. A full disk: a tiny tmpfs when mounting is allowed, else a 1 KiB file-size limit on the server.
full=$work/full
mkdir -p "$full"
if mount -t tmpfs -o size=16k tmpfs "$full" 2>/dev/null; then
    how="16 KiB tmpfs"
    start_server "$work/s3.log" --data "$work/data" --cache-dir "$full"
else
    how="RLIMIT_FSIZE 1 KiB"
    ulimit -f 1
    start_server "$work/s3.log" --data "$work/data" --cache-dir "$full"
    ulimit -f unlimited 2>/dev/null || true
fi
id=$(fit mri-brain_33x41x25_int16 1% | job_id)
state=$(wait_job "$id")
status=$(render_ok)
warning=$(log_line "$work/s3.log" 'warning: cache folder')
alive=$(kill -0 "$SERVER_PID" 2>/dev/null && echo yes || echo no)
if [[ $state == done && $status == 200 && $alive == yes && -n $warning && -z $(find "$full" -name '*.tmp-*') ]]; then
    report PASS "full disk ($how)" "fit done from memory, /render 200, log: $warning"
else
    report FAIL "full disk ($how)" "state=$state render=$status alive=$alive warning='$warning'"
fi
stop_server
umount "$full" 2>/dev/null || true

# 3. An unusable cache folder (a path below a regular file: root ignores permission bits).
touch "$work/afile"
start_server "$work/s4.log" --data "$work/data" --cache-dir "$work/afile/cache"
id=$(fit mri-brain_33x41x25_int16 1% | job_id)
state=$(wait_job "$id")
status=$(render_ok)
warning=$(log_line "$work/s4.log" 'warning: cache folder')
if [[ $state == done && $status == 200 && -n $warning ]]; then
    report PASS "unwritable cache folder" "fit done, /render 200, log: $warning"
else
    report FAIL "unwritable cache folder" "state=$state render=$status warning='$warning'"
fi

# 4. Clients that send a /render request and close at once, while another client keeps rendering. The
# other client has an address of its own (127.0.0.2): the closers' 127.0.0.1 may have only 4 renders in
# progress, the rest of its requests are refused (429) before any work, which is the fairness rule.
q="/render?dataset=mri-brain_33x41x25_int16&size=256x256&eps=5%25&cam=az%3D"
(for i in $(seq 1 100); do
    exec 3<>/dev/tcp/127.0.0.1/"$SERVER_PORT"
    # Its own name: any other Host is refused (421) before a frame would be rendered.
    printf 'GET %s%d HTTP/1.1\r\nHost: 127.0.0.1:%s\r\n\r\n' "$q" "$i" "$SERVER_PORT" >&3
    exec 3>&-
done) &
closer=$!
statuses=$(for _ in $(seq 1 20); do render_ok 127.0.0.2; echo; done | sort | uniq -c | tr -s ' \n' ' ')
wait "$closer"
after=$(render_ok 127.0.0.2)
alive=$(kill -0 "$SERVER_PID" 2>/dev/null && echo yes || echo no)
if [[ $statuses == " 20 200 " && $after == 200 && $alive == yes ]]; then
    report PASS "100 clients closing mid-request" "20/20 concurrent renders of another client 200, server alive"
else
    report FAIL "100 clients closing mid-request" "statuses:$statuses after=$after alive=$alive"
fi
stop_server
[[ $failures -eq 0 ]] && echo "faults: all passed" || echo "faults: $failures failed"
exit $((failures > 0))
