#!/usr/bin/env bash
# 4D files and no data under mpirun on loopback: `--frame 1` on 2 ranks fits a file that verifies against
# frame 1 and renders frame 1 (the exact grid's MIP is the one-process PNG byte for byte); and on a volume
# whose NaN (no data) lies in rank 1's planes while the lowest finite sample lies in rank 0's, the grid's
# MinIP on 2 ranks is the one-process PNG byte for byte and its average within a grey level (each rank's own
# lowest sample would draw the no-data cells 60 levels lighter), and a fit on 2 ranks is reproducible.
# Usage: tests/mpi/mpi_frames.sh VOTS_BINARY
set -euo pipefail
vots=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# CI runs as root; Open MPI refuses that unless told, and must not look for other hosts.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
mpi() { timeout 120 mpirun --oversubscribe -np "$1" "${@:2}"; }
fail() { echo "mpi_frames: $*" >&2; exit 1; }
png_diff() { /usr/bin/python3 "$(dirname "$0")/png_diff.py" "$@"; } # Debian's python3-pil
view=(--cam az=30,el=20 --size 96x80 --window -50,200)

# A float32 NIfTI-1 of 2 frames, 24x20x16: values 10..110 in a ball (brighter and larger in frame 1), a NaN
# block in the upper z planes (rank 1's), the lowest finite sample (-50) at one corner of plane 0 (rank 0's).
/usr/bin/python3 "$(dirname "$0")/write_nodata_4d.py" "$work/four.nii"

# --frame 1 on 2 ranks: the fit verifies against frame 1 (not frame 0) and says so; the grid draws frame 1.
mpi 2 "$vots" fit "$work/four.nii" --frame 1 -o "$work/f1.vots" --eps 2% >/dev/null 2>"$work/err" ||
    fail "fit --frame 1 on 2 ranks: $(cat "$work/err")"
"$vots" verify "$work/f1.vots" "$work/four.nii" --frame 1 >/dev/null 2>&1 ||
    fail "the 2-rank fit of frame 1 does not verify against frame 1"
if "$vots" verify "$work/f1.vots" "$work/four.nii" --frame 0 >/dev/null 2>&1; then
    fail "the 2-rank fit of frame 1 verifies against frame 0 too: it was not frame 1"
fi
"$vots" info "$work/f1.vots" | grep -q "frame *1 (of a 4D file)" || fail "vots info does not name frame 1"
for frame in 0 1; do
    "$vots" render "$work/four.nii" --frame "$frame" -o "$work/mip-one-$frame.png" --renderer grid "${view[@]}" 2>/dev/null
    mpi 2 "$vots" render "$work/four.nii" --frame "$frame" -o "$work/mip-2-$frame.png" --renderer grid \
        "${view[@]}" 2>"$work/err" || fail "render --frame $frame on 2 ranks: $(cat "$work/err")"
    cmp -s "$work/mip-one-$frame.png" "$work/mip-2-$frame.png" ||
        fail "grid mip of frame $frame on 2 ranks differs from one process: $(png_diff "$work/mip-one-$frame.png" "$work/mip-2-$frame.png")"
done
cmp -s "$work/mip-one-0.png" "$work/mip-one-1.png" && fail "frames 0 and 1 draw alike: the test sees no frame"

# No data: each rank counts a NaN's cell as the whole volume's lowest finite sample (-50), as one process does.
"$vots" render "$work/four.nii" --frame 1 -o "$work/minip-one.png" --renderer grid --mode minip "${view[@]}" 2>/dev/null
mpi 2 "$vots" render "$work/four.nii" --frame 1 -o "$work/minip-2.png" --renderer grid --mode minip "${view[@]}" \
    2>"$work/err" || fail "grid minip on 2 ranks: $(cat "$work/err")"
cmp -s "$work/minip-one.png" "$work/minip-2.png" ||
    fail "grid minip with no data on 2 ranks differs from one process: $(png_diff "$work/minip-one.png" "$work/minip-2.png")"
"$vots" render "$work/four.nii" --frame 1 -o "$work/aip-one.png" --renderer grid --mode aip "${view[@]}" 2>/dev/null
mpi 2 "$vots" render "$work/four.nii" --frame 1 -o "$work/aip-2.png" --renderer grid --mode aip "${view[@]}" \
    2>"$work/err" || fail "grid aip on 2 ranks: $(cat "$work/err")"
read -r worst differing < <(png_diff "$work/aip-one.png" "$work/aip-2.png")
echo "mpi_frames: grid aip with no data on 2 ranks: $differing pixels differ from one process, by at most $worst"
((worst <= 1)) || fail "grid aip with no data on 2 ranks differs from one process by $worst grey levels"

# Fitted on the ranks (each its cells, with the whole volume's fill and no-data value): the same frame twice.
for run in a b; do
    mpi 2 "$vots" render "$work/four.nii" --frame 1 -o "$work/fit-aip-$run.png" --mode aip --eps 2% "${view[@]}" \
        2>"$work/err" || fail "fit and aip on 2 ranks: $(cat "$work/err")"
done
cmp -s "$work/fit-aip-a.png" "$work/fit-aip-b.png" || fail "the 2-rank fit's aip differs between runs"
echo "mpi_frames: --frame 1 fits, verifies and draws on 2 ranks; no data draws as in one process"
