#!/usr/bin/env bash
# Hostile connections: 8 clients rendering with and without 1,000 idle connections, 200 event-stream
# watchers and 200 idle viewer sockets; their /render p99 must stay within 20 % and every /api/* request
# under 100 ms.
#
# Usage: tests/reliability/hostile.sh [--idle N] [--watchers N] [--idle-sockets N] [--renderers N]
#        [--seconds S per phase]
# Builds build/rel (Release) unless VOTS_BIN names a binary. Fails on any error answer that is not a JSON
# 4xx/5xx, a missed goal, or a dead server.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source tests/reliability/common.sh
build_rel

work=$(mktemp -d)
trap 'stop_server; rm -rf "$work"' EXIT
serve_hostile_load_volumes "$work"
status=0
python3 tests/reliability/hostile_load.py goal --port "$SERVER_PORT" --pid "$SERVER_PID" "$@" || status=$?
kill -0 "$SERVER_PID" 2>/dev/null || { echo "server died"; status=1; }
exit $status
