#!/usr/bin/env bash
# Hostile connections: 8 clients rendering with and without 1,000 idle connections, 200 event-stream
# watchers and 200 idle viewer sockets; their /render p99 must stay within 20 % and every /api/* request
# under 100 ms.
#
# With --tls the server speaks HTTPS (a test CA made here): every client goes through TLS, the idle
# connections are idle handshakes, and 200 slow (a byte every 0.5 s) and 200 half-sent ClientHellos join
# them, with the same goals.
#
# Usage: tests/reliability/hostile.sh [--tls] [--idle N] [--watchers N] [--idle-sockets N] [--renderers N]
#        [--slow-handshakes N] [--half-handshakes N] [--seconds S per phase]
# Builds build/rel (Release) unless VOTS_BIN names a binary. Fails on any error answer that is not a JSON
# 4xx/5xx, a missed goal, or a dead server.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source tests/reliability/common.sh
source tests/support/test-certificate.sh
build_rel

make_work
serve_args=()
load_args=()
if [[ ${1:-} == --tls ]]; then
    shift
    make_test_certificate "$work"
    serve_args=(--tls-cert "$work/site.pem" --tls-key "$work/site.key")
    load_args=(--tls-ca "$work/ca.pem" --slow-handshakes 200 --half-handshakes 200)
fi
serve_hostile_load_volumes "$work" "${serve_args[@]}"
status=0
python3 tests/reliability/hostile_load.py goal --port "$SERVER_PORT" --pid "$SERVER_PID" "${load_args[@]}" "$@" ||
    status=$?
kill -0 "$SERVER_PID" 2>/dev/null || { echo "server died"; status=1; }
exit $status
