# Sourced by the benchmarks that start `vots serve` on a volume (mpi_serve_memory.sh, mpi_eps_refit.sh):
# $volume and $vots set, a work folder removed on exit (the server stopped first), the volume linked into
# $work/data as dataset $name, and url_of LOG waiting for the server's address.
work=$(mktemp -d)
job=
cleanup() {
    if [[ -n $job ]]; then # a server's status after SIGTERM is not a failure of the benchmark
        kill -TERM "$job" 2>/dev/null
        wait "$job" 2>/dev/null || true
    fi
    rm -rf "$work"
}
trap cleanup EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
mkdir "$work/data"
ln -s "$volume" "$work/data/"
if [[ $volume == *.nhdr ]]; then # its data file (or the folder holding it) beside it
    data_file=$(sed -nE 's/^data file: *//p' "$volume")
    [[ $data_file == /* ]] || ln -s "$(dirname "$volume")/${data_file%%/*}" "$work/data/"
fi
name=$(basename "$volume" | sed -E 's/\.(nrrd|nhdr|nii\.gz|nii|mhd|mha)$//')

url_of() { # LOG: the URL the server listening into LOG prints (up to 5 min); exits when there is none
    local url=
    for _ in $(seq 600); do
        url=$(sed -nE 's|^.*vots serve: listening on (http://[^ ]+/)$|\1|p' "$1")
        [[ -n $url ]] && break
        sleep 0.5
    done
    [[ -n $url ]] || { cat "$1" >&2; exit 1; }
    echo "$url"
}
