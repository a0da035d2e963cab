# Shared by the reliability scripts: build build/rel (Release `vots`), start/stop `vots serve`, read its RSS.
# Sourced, not run. Sets VOTS (the binary) and uses SERVER_PID / SERVER_PORT for the server it started.

VOTS=${VOTS_BIN:-build/rel/cli/vots}
CRANIUM=${VOTS_CRANIUM:-data/cranium.nhdr} # scripts/fetch-ct writes it

build_rel() {
    [[ -n ${VOTS_BIN:-} ]] && return 0
    cmake -S . -B build/rel -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOTS_BUILD_TESTS=OFF >/dev/null
    nice cmake --build build/rel -j2 --target vots >/dev/null
}

# make_work: sets $work to a new temporary folder, removed (after stopping the server) when the script exits.
make_work() {
    work=$(mktemp -d)
    trap 'stop_server; rm -rf "$work"' EXIT
}

# start_server LOG ARGS...: starts `vots serve --port 0 ARGS` and waits for its "listening on" line.
start_server() {
    local log=$1
    shift
    : >"$log" # before the server: its background job may open the log only after the first look below
    "$VOTS" serve --port 0 "$@" >"$log" 2>&1 &
    SERVER_PID=$!
    for _ in $(seq 1 600); do
        SERVER_PORT=$(sed -n 's|.*listening on https\?://[^:]*:\([0-9]*\)/.*|\1|p' "$log" | head -1)
        [[ -n $SERVER_PORT ]] && return 0
        kill -0 "$SERVER_PID" 2>/dev/null || { cat "$log"; return 1; }
        sleep 0.1
    done
    echo "server did not start"; cat "$log"; return 1
}

stop_server() {
    [[ -n ${SERVER_PID:-} ]] || return 0
    kill "$SERVER_PID" 2>/dev/null || true
    wait "$SERVER_PID" 2>/dev/null || true
    SERVER_PID=
}

rss_kib() {
    sed -n 's/^VmRSS:[[:space:]]*\([0-9]*\) kB/\1/p' "/proc/$1/status"
}

# serve_volumes DATA: DATA gets the small real brain MRI (dataset mri-brain_33x41x25_int16, written by
# scripts/make-test-volumes beside DATA) and the Cranium CT (dataset cranium, a header whose data file is
# $CRANIUM's, whose fit takes seconds).
serve_volumes() {
    local data=$1
    mkdir -p "$data" "$data.volumes"
    scripts/make-test-volumes "$data.volumes"
    ln -s "$(realpath "$data.volumes/mri-brain_33x41x25_int16.nii")" "$data/"
    [[ -f $CRANIUM ]] || { echo "no $CRANIUM: run scripts/fetch-ct"; return 1; }
    local samples
    samples=$(realpath "$(dirname "$CRANIUM")/$(sed -n 's/^data file: //p' "$CRANIUM")")
    sed "s|^data file: .*|data file: $samples|" "$CRANIUM" >"$data/cranium.nhdr"
}

# serve_hostile_load_volumes WORK [ARGS...]: starts `vots serve` on the brain MRI and the Cranium
# (serve_volumes WORK/data, cache in WORK/cache, no warm-up, then ARGS), as the hostile and soak runs load it.
serve_hostile_load_volumes() {
    local work=$1
    shift
    serve_volumes "$work/data"
    start_server "$work/server.log" --data "$work/data" --cache-dir "$work/cache" --no-warm-up "$@"
    echo "server pid $SERVER_PID, $(grep -m1 renderer "$work/server.log" | sed 's/^ *//')"
}
