#!/usr/bin/env bash
# Installs the build into a temporary prefix, moves the build tree aside, and checks the installed
# `vots serve` answers / with its viewer from <prefix>/share/vots/web (and /api/datasets, /render, and
# /turntable through the installed encoder module).
#
# Usage: tests/install/installed_serve.sh BUILD_DIR      (ctest: Install.InstalledServeFindsItsViewer)
# Moves BUILD_DIR to BUILD_DIR.moved-by-install-test while the installed server runs and puts it back on
# every exit the shell sees; ctest runs it RUN_SERIAL, so no other test needs the build tree meanwhile.
# Deletes nothing but its own temporary folder.
set -euo pipefail

build="$(cd "$1" && pwd)"
moved="$build.moved-by-install-test"
work="$(mktemp -d "${TMPDIR:-/tmp}/vots-install-test.XXXXXX")"
server_pid=""

fail() { echo "installed_serve: FAIL: $*" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/wait_for_listening.bash"
cleanup() {
    if [[ -n $server_pid ]]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
    if [[ -d $moved && ! -e $build ]]; then mv "$moved" "$build"; fi
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

[[ ! -e $moved ]] || fail "$moved exists (a killed earlier run?): move it back to $build by hand"

prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log" >&2; fail "cmake --install"; }
prefix="$(cd "$prefix" && pwd -P)" # the server names its folder from /proc/self/exe, links resolved
vots="$prefix/bin/vots"
index="$prefix/share/vots/web/index.html"
[[ -x $vots ]] || fail "no $vots after cmake --install"
[[ -f $index ]] || fail "no $index after cmake --install"
# A marker only the installed copy of the viewer has: the page served must be this file, not web/ of the
# source tree (nor anything the build tree links to).
marker="<!-- installed copy, $(basename "$work") -->"
echo "$marker" >>"$index"

# A tiny volume, so the server has a dataset to list and render.
mkdir -p "$work/data" "$work/cwd"
{
    printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\n'
    for ((i = 0; i < 512; i++)); do printf "\\x$(printf %02x $((i * 7 % 256)))"; done
} >"$work/data/tiny.nrrd"

mv "$build" "$moved"

# From a folder without web/ (the server's first choice), on any free loopback port.
: >"$work/server.log" # exists before the server starts, so the wait below can read it at once
(cd "$work/cwd" && exec "$vots" serve --host 127.0.0.1 --port 0 --data "$work/data" --cache-dir "$work/cache" \
    --no-warm-up --prepare '') >>"$work/server.log" 2>&1 &
server_pid=$!
url="$(wait_for_listening "$server_pid" "$work/server.log" http)"
cat "$work/server.log"
grep -qxF "  web:   $prefix/share/vots/web" "$work/server.log" || fail "the server does not name $prefix/share/vots/web"

curl -sf --max-time 30 -o "$work/index.html" "$url/" || fail "GET / did not answer 200"
cmp -s "$work/index.html" "$index" || fail "GET / is not the installed index.html"
grep -qF "$marker" "$work/index.html" || fail "GET / lacks the installed copy's marker"
grep -qi '<html' "$work/index.html" || fail "GET / is not HTML"
# The module generated from the C++ rules (web/js/contract.js) is installed with the rest of the viewer.
# Into files, not pipes: grep -q stops reading at its match, and under pipefail curl's broken pipe would fail
# the check.
curl -sf --max-time 30 -o "$work/contract.js" "$url/js/contract.js" && grep -q '^export const MODES' "$work/contract.js" ||
    fail "the installed viewer lacks js/contract.js"
curl -sf --max-time 30 -o "$work/datasets.json" "$url/api/datasets" && grep -q '"name":"tiny"' "$work/datasets.json" ||
    fail "/api/datasets does not list tiny"
curl -sf --max-time 120 -o "$work/tiny.png" "$url/render?dataset=tiny&size=32x32" || fail "/render did not answer 200"
[[ "$(head -c 8 "$work/tiny.png" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "/render is not a PNG"
# The turntable's encoder is the installed module, loaded from <prefix>/lib/.../vots with the build tree away.
curl -sf --max-time 120 -o "$work/tiny.webm" "$url/turntable?dataset=tiny&size=32x32&frames=2" ||
    fail "/turntable did not answer 200 (the installed vots_webm module?)"
[[ "$(head -c 4 "$work/tiny.webm" | od -An -tx1 | tr -d ' \n')" == 1a45dfa3 ]] || fail "/turntable is not a WebM"
echo "installed_serve: PASS: $vots serves $prefix/share/vots/web with $build moved aside"
