#!/usr/bin/env bash
# Soak: mixed load for a while (renders at new angles, eps changes, event-stream watchers, idle
# connections, clients that disconnect mid-answer, viewers dragging over the viewer socket), sampling the
# server's RSS and open descriptors.
#
# Usage: tests/reliability/soak.sh [--seconds S (default 1800)] [--idle N] [--watchers N] [--renderers N]
#        [--draggers N]
# Builds build/rel (Release) unless VOTS_BIN names a binary. Fails on a crash or any error answer that
# is not a JSON 4xx/5xx; judge the RSS and descriptor columns for flatness after warm-up.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source tests/reliability/common.sh
build_rel

make_work
serve_hostile_load_volumes "$work"
status=0
python3 tests/reliability/hostile_load.py soak --port "$SERVER_PORT" --pid "$SERVER_PID" --seconds 1800 \
    --idle 200 --watchers 50 --renderers 4 --draggers 4 "$@" || status=$?
kill -0 "$SERVER_PID" 2>/dev/null || { echo "server died"; status=1; }
exit $status
