#!/usr/bin/env bash
# Strong scaling under mpirun (issue 23): fit time and each rank's peak memory, and the frame's time
# for N = 1, 2, 4 ranks on this machine (4 on 2 cores is oversubscribed, and reported as such).
#
# Usage: bench/mpi_scaling.sh [VOLUME...]   (default data/cranium.nhdr; raw NRRDs are read by slab)
#        VOTS_BUILD=build/release   VOTS_MPI_RANKS="1 2 4"   VOTS_SCALE_DIR=/tmp/vots-mpi-scale
# A 512x512x1000 volume: build/release/bench/make_scaled_volume data/cranium.nhdr /tmp/s1000.nhdr \
#   --size 512x512x1000 --noise 8 --seed 1 (never in the repo). Prints Markdown rows for
# bench/RESULTS.md. The frame split comes from `vots render --times` (render, composite, display).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

build=${VOTS_BUILD:-build/release}
vots=$(realpath "$build/cli/vots")
dir=${VOTS_SCALE_DIR:-/tmp/vots-mpi-scale}
mkdir -p "$dir"
[[ $# -gt 0 ]] || set -- data/cranium.nhdr
read -r -a rank_counts <<<"${VOTS_MPI_RANKS:-1 2 4}"
cores=$(nproc)
# Root in CI containers; never look for other hosts.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader

# Runs `vots ARGS` on N ranks, each under GNU time writing "SECONDS PEAK_KIB" to $dir/time.RANK.
timed_ranks() {
    local n=$1
    shift
    rm -f "$dir"/time.*
    mpirun --oversubscribe -np "$n" sh -c \
        'exec /usr/bin/time -f "%e %M" -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' "$dir/time" "$vots" "$@"
}
# "WALL_S PEAK_MIB_PER_RANK..." from the time files: the slowest rank's seconds, every rank's peak.
rank_figures() {
    local wall=0 peaks=() f s k
    for f in $(ls "$dir"/time.* | sort -t. -k2 -n); do
        read -r s k <"$f"
        wall=$(awk -v a="$wall" -v b="$s" 'BEGIN { print (b > a ? b : a) }')
        peaks+=("$((k / 1024))")
    done
    echo "$wall ${peaks[*]}"
}

echo "cores $cores, load $(cut -d' ' -f1 /proc/loadavg); ranks beyond $cores are oversubscribed"
echo
echo "| volume | ranks | threads/rank | fit s | fit peak MiB per rank | Vots | render s (whole process) | render peak MiB per rank | frame ms: render / composite (slowest rank) |"
echo "|---|---|---|---|---|---|---|---|---|"
for volume in "$@"; do
    name=$(basename "$volume" .nhdr)
    for n in "${rank_counts[@]}"; do
        threads=$((cores / n > 0 ? cores / n : 1))
        fitted=$dir/$name.$n.vots
        timed_ranks "$n" fit "$volume" -o "$fitted" --eps 2% --certify cells --threads "$threads" >/dev/null
        read -r fit_s fit_peaks < <(rank_figures)
        vot_count=$("$vots" info "$fitted" 2>/dev/null | awk '$1 == "Vots" { print $2; exit }')
        timed_ranks "$n" render "$fitted" --cam az=30,el=20 --size 512x512 -o "$dir/$name.$n.png" \
            --times 2>"$dir/render.err" >/dev/null
        read -r render_s render_peaks < <(rank_figures)
        split=$(grep -oE 'render [0-9.]+ ms, composite [0-9.]+ ms' "$dir/render.err" | tail -1 || true)
        over=$([[ $n -gt $cores ]] && echo " (oversubscribed)" || true)
        echo "| $name | $n$over | $threads | $fit_s | ${fit_peaks// / \/ } | $vot_count | $render_s |" \
            "${render_peaks// / \/ } | ${split:-n/a} |"
    done
done
