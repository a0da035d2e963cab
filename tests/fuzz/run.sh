#!/usr/bin/env bash
# Runs the libFuzzer targets (preset fuzz) on seeded corpora, two at a time, and prints one summary line each.
#
# Usage: tests/fuzz/run.sh [--seconds N] [--runs N] [target...]   (default: all eleven, 600 s or 1,000,000 runs)
# Needs: cmake --preset fuzz && cmake --build --preset fuzz -j2, and a `vots` binary for .vots seeds
# (VOTS_BIN, default build/rel/cli/vots, else build/asan/cli/vots). Logs, corpora and crash artifacts go
# to build/fuzz/{logs,corpus,artifacts}/<target>/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."

seconds=600
runs=1000000
targets=()
while [[ $# -gt 0 ]]; do
    case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    *) targets+=("$1"); shift ;;
    esac
done
[[ ${#targets[@]} -gt 0 ]] ||
    targets=(fuzz_votspace_reader fuzz_nrrd fuzz_nifti fuzz_nifti2 fuzz_mgh fuzz_metaimage fuzz_dicom fuzz_camera fuzz_render_query fuzz_multipart fuzz_stream_message)

fuzz=build/fuzz
volumes=$fuzz/volumes
nibabel=/usr/lib/python3/dist-packages/nibabel/tests/data # python3-nibabel (scripts/setup)
mkdir -p "$fuzz"/{logs,corpus,artifacts}
scripts/make-test-volumes "$volumes"

# Larger seeds than the committed ones: the small test volumes (scripts/make-test-volumes), .vots files
# fitted from the brain MRI, hostile queries.
seed_extra() {
    local target=$1 dir=$fuzz/corpus/$1
    mkdir -p "$dir"
    case "$target" in
    fuzz_nrrd)
        cp -f "$volumes"/{mri-brain_33x41x25_int16,blobs_64x64x64_uint8,orbital_64x64x64_float32}.nrrd "$dir/" ;;
    fuzz_nifti)
        cp -f "$volumes/mri-brain_33x41x25_int16.nii" "$dir/" ;;
    fuzz_nifti2) # byte 0: the frame; nibabel's NIfTI-2 example (4D), inflated
        { printf '\x01'; zcat "$nibabel/example_nifti2.nii.gz"; } >"$dir/example_nifti2.nii" ;;
    fuzz_mgh) # byte 0: the frame; nibabel's 4D .mgz, as it is and inflated
        { printf '\x01'; cat "$nibabel/test.mgz"; } >"$dir/test.mgz"
        { printf '\x01'; zcat "$nibabel/test.mgz"; } >"$dir/test.mgh" ;;
    fuzz_votspace_reader)
        local vots=${VOTS_BIN:-}
        [[ -n $vots ]] || for b in build/rel/cli/vots build/asan/cli/vots; do [[ -x $b ]] && vots=$b && break; done
        if [[ -n $vots ]]; then
            for args in "--eps 10% --degree 3" "--eps 5% --degree 1" "--eps 20% --degree 0"; do
                name=head_$(echo "$args" | tr -cd 'a-z0-9').vots
                [[ -f $dir/$name ]] || ASAN_OPTIONS=detect_leaks=0 $vots fit "$volumes/mri-brain_33x41x25_int16.nrrd" \
                    -o "$dir/$name" $args >/dev/null || true
            done
        fi ;;
    fuzz_render_query)
        # The query string of each hostile request line ("GET /render?QUERY HTTP/1.1"), and its body.
        for f in tests/server/hostile/*.http; do
            grep -m1 -E '^[A-Z]+ /' "$f" | sed -n 's/^[A-Z]* [^?]*?\([^ ]*\) HTTP.*/\1/p' | head -c 20000 \
                >"$dir/$(basename "$f" .http).q"
            awk 'body{print} /^\r?$/{body=1}' "$f" | head -c 20000 >"$dir/$(basename "$f" .http).body"
        done
        find "$dir" -empty -delete ;;
    esac
}

run_one() {
    local target=$1 bin=$fuzz/tests/fuzz/$1
    [[ -x $bin ]] || { echo "$target: not built ($bin)"; return 1; }
    seed_extra "$target"
    mkdir -p "$fuzz/artifacts/$target"
    local maxlen=4096
    [[ $target == fuzz_nrrd || $target == fuzz_votspace_reader ]] && maxlen=131072
    [[ $target == fuzz_multipart ]] && maxlen=65536 # past the 16 KB bound on part headers
    nice -n 10 "$bin" -runs="$runs" -max_total_time="$seconds" -max_len="$maxlen" -rss_limit_mb=2048 \
        -timeout=30 -print_final_stats=1 -artifact_prefix="$fuzz/artifacts/$target/" \
        "$fuzz/corpus/$target" "tests/fuzz/seeds/$target" >"$fuzz/logs/$target.log" 2>&1 || true
    local execs cov crashes
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$fuzz/logs/$target.log" | tail -1)
    cov=$(grep -o 'cov: [0-9]*' "$fuzz/logs/$target.log" | tail -1)
    crashes=$(find "$fuzz/artifacts/$target" -type f | wc -l)
    echo "$target: executions ${execs:-?}, ${cov:-cov: ?}, artifacts $crashes (log $fuzz/logs/$target.log)"
}

# Two at a time: the machine has two cores.
for ((i = 0; i < ${#targets[@]}; i += 2)); do
    run_one "${targets[i]}" &
    [[ $((i + 1)) -lt ${#targets[@]} ]] && run_one "${targets[i + 1]}" &
    wait
done
