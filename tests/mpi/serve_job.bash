# Sourced by the `mpirun vots serve` tests: a work folder removed on exit, the job started and watched,
# its ranks' processes found. Needs $vots; sets $work, $job and $url.
work=$(mktemp -d)
job=
cleanup() {
    [[ -n $job ]] && kill -KILL "$job" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
# CI runs as root; Open MPI refuses that unless told, and must not look for other hosts.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
fail() {
    echo "$(basename "$0" .sh): $*" >&2
    sed 's/^/  serve: /' "$work/serve.log" >&2 || true
    exit 1
}
png_diff() { /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/png_diff.py" "$@"; } # Debian's python3-pil

# --enable-recovery: without it Open MPI ends the whole job, rank 0 too, when one rank dies.
start_job() { # DATA_FOLDER DATASET [MORE SERVE ARGUMENTS]
    local data=$1 dataset=$2
    shift 2
    mpirun --oversubscribe --enable-recovery -np 2 "$vots" serve --port 0 --data "$data" \
        --cache-dir "$work/cache" --prepare "$dataset" "$@" >"$work/serve.log" 2>&1 &
    job=$!
    url=
    for _ in $(seq 240); do
        # Not anchored at the line's start: mpirun forwards the ranks' output in pieces, so another
        # rank's words can stand before it on the same line.
        url=$(sed -nE 's|^.*vots serve: listening on (http://[^ ]+/)$|\1|p' "$work/serve.log")
        [[ -n $url ]] && return
        kill -0 "$job" 2>/dev/null || fail "mpirun ended before listening"
        sleep 0.5
    done
    fail "no 'listening on' line within 120 s"
}
get() { curl -s --max-time 60 -o "$1" -w '%{http_code}' "${url}$2"; } # FILE PATH_AND_QUERY
job_ends_within() { # SECONDS WHAT: fails unless mpirun has ended within that time
    for _ in $(seq $(($1 * 2))); do
        kill -0 "$job" 2>/dev/null || return 0
        sleep 0.5
    done
    fail "mpirun still runs $1 s $2"
}
rank_pid() { # RANK: its process, a child of mpirun
    local pid
    for pid in $(pgrep -P "$job"); do
        tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$1" && echo "$pid"
    done
    return 0
}
stop_job() { # SIGTERM to rank 0 with every rank alive: the whole job ends at once with status 0
    kill -TERM "$(rank_pid 0)"
    job_ends_within 10 "after SIGTERM to rank 0 with every rank alive"
    wait "$job" || fail "mpirun ended with status $? after SIGTERM to rank 0"
    job=
    grep -q "leaving\|did not take the quit" "$work/serve.log" && fail "a rank was not let go"
    return 0
}
