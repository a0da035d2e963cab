#!/usr/bin/env bash
# Runs the browser specs against a freshly started `vots serve`; builds nothing, installs only npm test deps.
#
# Usage: tests/web/run.sh [--bin PATH] [--data DIR] [--port N] [spec.mjs ...]
# Env:   VOTS_BIN (default build/release/cli/vots, else the first build/*/cli/vots),
#        VOTS_TEST_DATA (default: a temporary folder with the index-space volumes of
#        scripts/make-test-volumes: the brain MRI as NRRD, the blobs and the orbital, and nibabel's 4D
#        functional.nii), VOTS_WEB_PORT,
#        CHROMIUM (default /usr/bin/chromium), VOTS_TEST_DATASET, VOTS_URL (a server to test instead of
#        starting one; token.spec.mjs then fails, as it needs run.sh to start its own).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"

bin="${VOTS_BIN:-}"
data="${VOTS_TEST_DATA:-}"
port="${VOTS_WEB_PORT:-}"
specs=()
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --data) data="$2"; shift 2 ;;
    --port) port="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) specs+=("$1"); shift ;;
  esac
done

chromium_bin="${CHROMIUM:-/usr/bin/chromium}"
if [ ! -x "$chromium_bin" ]; then
  echo "run.sh: no chromium at $chromium_bin (apt-get install -y chromium)" >&2
  exit 2
fi

# npm deps only; nothing here downloads a browser (playwright-core has no install hook).
if [ ! -d "$here/node_modules/playwright-core" ]; then
  (cd "$here" && { npm ci --no-audit --no-fund || npm install --no-audit --no-fund; })
fi

artifacts="$here/artifacts"
rm -rf "$artifacts"
mkdir -p "$artifacts"

server_pid=""
stop_server() {
  if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then
    kill "$server_pid" 2>/dev/null || true
    # Give it a moment to exit cleanly, then insist.
    for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.2; done
    kill -9 "$server_pid" 2>/dev/null || true
  fi
}
cache_dir=""
volumes_dir=""
cleanup() {
  stop_server
  if [ -n "$cache_dir" ]; then rm -rf "$cache_dir"; fi
  if [ -n "$volumes_dir" ]; then rm -rf "$volumes_dir"; fi
}
trap cleanup EXIT INT TERM

if [ -z "${VOTS_URL:-}" ]; then
  if [ -z "$bin" ]; then
    if [ -x "$repo/build/release/cli/vots" ]; then
      bin="$repo/build/release/cli/vots"
    else
      for candidate in "$repo"/build/*/cli/vots; do
        if [ -x "$candidate" ]; then bin="$candidate"; break; fi
      done
    fi
  fi
  if [ -z "$bin" ] || [ ! -x "$bin" ]; then
    echo "run.sh: no vots binary (set VOTS_BIN or build build/release/cli/vots)" >&2
    exit 2
  fi
  if [ -z "$data" ]; then
    # The specs open the small brain MRI (support/browser.mjs) and need it in index space: the NRRD form.
    volumes_dir="$(mktemp -d "${TMPDIR:-/tmp}/vots-web-data.XXXXXX")"
    "$repo/scripts/make-test-volumes" "$volumes_dir/all"
    data="$volumes_dir/data"
    mkdir "$data"
    for name in mri-brain_33x41x25_int16.nrrd blobs_64x64x64_uint8.nrrd orbital_64x64x64_float32.nrrd; do
      ln -s "$volumes_dir/all/$name" "$data/$name"
    done
    # A 4D file for time.spec.mjs: nibabel's fMRI (17x21x3, 20 frames), installed by scripts/setup.
    ln -s /usr/lib/python3/dist-packages/nibabel/tests/data/functional.nii "$data/functional.nii"
  fi
  if [ ! -d "$data" ]; then
    echo "run.sh: no data folder at $data (set VOTS_TEST_DATA or pass --data)" >&2
    exit 2
  fi

  # A port per checkout (stable, so parallel checkouts do not collide); a free one if that is taken.
  port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
  if [ -z "$port" ]; then
    port=$((20000 + $(printf '%s' "$repo" | cksum | cut -d' ' -f1) % 20000))
    if ! port_free "$port"; then
      port="$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')"
    fi
  fi

  serve_args=(serve --port "$port" --data "$data")
  serve_help="$("$bin" serve --help 2>&1 || true)"
  # Point the server at this checkout's web/ when it takes such an option; otherwise it finds web/ itself.
  if grep -q -- '--web' <<<"$serve_help"; then serve_args+=(--web "$repo/web"); fi
  # A fresh fit cache per run, so the eps spec really fits and no run depends on an earlier one.
  if grep -q -- '--cache-dir' <<<"$serve_help"; then
    cache_dir="$(mktemp -d "${TMPDIR:-/tmp}/vots-web-cache.XXXXXX")"
    serve_args+=(--cache-dir "$cache_dir")
  fi
  echo "run.sh: $bin ${serve_args[*]}"
  (cd "$repo" && exec "$bin" "${serve_args[@]}") >"$artifacts/server.log" 2>&1 &
  server_pid=$!

  export VOTS_URL="http://127.0.0.1:$port"
  # Specs that need a server of their own (token.spec.mjs) start this binary over this data.
  export VOTS_BIN="$bin" VOTS_DATA="$data"
  ready=""
  for _ in $(seq 1 600); do
    if ! kill -0 "$server_pid" 2>/dev/null; then
      echo "run.sh: vots serve exited early; its log:" >&2
      cat "$artifacts/server.log" >&2
      exit 1
    fi
    if curl -sf -o /dev/null "$VOTS_URL/api/datasets"; then ready=1; break; fi
    sleep 0.2
  done
  if [ -z "$ready" ]; then
    echo "run.sh: $VOTS_URL/api/datasets did not answer within 120 s; server log:" >&2
    cat "$artifacts/server.log" >&2
    exit 1
  fi
fi

echo "run.sh: testing $VOTS_URL (artifacts in $artifacts)"
if [ ${#specs[@]} -eq 0 ]; then specs=("$here"/*.spec.mjs); fi
# One spec at a time: the server renders on one thread and the cores are shared.
status=0
CHROMIUM="$chromium_bin" node --test --test-concurrency=1 "${specs[@]}" || status=$?
if [ "$status" -ne 0 ]; then
  echo "run.sh: failures; screenshots, page HTML and logs kept in $artifacts" >&2
fi
exit "$status"
