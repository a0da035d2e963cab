#!/usr/bin/env bash
# No data in frames served under mpirun: on a volume whose NaN lies in rank 1's planes and whose lowest
# finite sample (-50) lies in rank 0's, the grid MinIP that `mpirun -np 2 vots serve` composites is the
# one-process `vots render` PNG byte for byte (rank 1's own lowest sample would draw the NaN cells lighter);
# frame 1 of the 4D file is drawn by the ranks from their planes of frame 1 (the grid's MIP is one process's
# `--frame 1` bytes, and not frame 0's), fitted on them too, and frame 0 again after it is frame 0's.
# Usage: tests/mpi/mpi_serve_nodata.sh VOTS_BINARY
set -euo pipefail
vots=$1
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
/usr/bin/python3 "$(dirname "$0")/write_nodata_4d.py" "$work/data/nodata.nii"

view="cam=az=30,el=20&size=96x80&window=-50,200"
"$vots" render "$work/data/nodata.nii" --frame 0 -o "$work/one.png" --renderer grid --mode minip \
    --cam az=30,el=20 --size 96x80 --window -50,200 2>/dev/null
for frame in 0 1; do
    "$vots" render "$work/data/nodata.nii" --frame "$frame" -o "$work/mip-one-$frame.png" --renderer grid \
        --cam az=30,el=20 --size 96x80 --window -50,200 2>/dev/null
done
cmp -s "$work/mip-one-0.png" "$work/mip-one-1.png" && fail "frames 0 and 1 draw alike: the test sees no frame"
start_job "$work/data" nodata
code=$(get "$work/served.png" "render?dataset=nodata&renderer=grid&mode=minip&cam=az=30,el=20&size=96x80&window=-50,200")
[[ $code == 200 ]] || fail "/render answered $code: $(cat "$work/served.png")"
cmp -s "$work/one.png" "$work/served.png" ||
    fail "the served grid minip with no data differs from one process: $(png_diff "$work/one.png" "$work/served.png")"
for frame in 1 0; do
    code=$(get "$work/mip-served-$frame.png" "render?dataset=nodata&frame=$frame&renderer=grid&$view")
    [[ $code == 200 ]] || fail "frame=$frame under mpirun answered $code: $(cat "$work/mip-served-$frame.png")"
    cmp -s "$work/mip-one-$frame.png" "$work/mip-served-$frame.png" ||
        fail "the served grid mip of frame $frame differs from one process's: $(png_diff "$work/mip-one-$frame.png" "$work/mip-served-$frame.png")"
done
# Fitted on the ranks: frame 1's Vots are not frame 0's.
for frame in 0 1; do
    code=$(get "$work/fit-$frame.png" "render?dataset=nodata&frame=$frame&eps=2%25&$view")
    [[ $code == 200 ]] || fail "a fitted frame=$frame under mpirun answered $code: $(cat "$work/fit-$frame.png")"
done
cmp -s "$work/fit-0.png" "$work/fit-1.png" && fail "the fitted frames 0 and 1 draw alike under mpirun"
code=$(get "$work/frame9.json" "render?dataset=nodata&frame=9&renderer=grid&size=32x32")
[[ $code == 400 ]] || fail "frame=9 of 2 under mpirun answered $code, not 400: $(cat "$work/frame9.json")"
stop_job
echo "mpi_serve_nodata: the served grid minip with no data is one process's bytes; frame 1 is drawn and fitted on the ranks"
