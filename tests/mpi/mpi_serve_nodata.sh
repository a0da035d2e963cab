#!/usr/bin/env bash
# No data in frames served under mpirun: on a volume whose NaN lies in rank 1's planes and whose lowest
# finite sample (-50) lies in rank 0's, the grid MinIP that `mpirun -np 2 vots serve` composites is the
# one-process `vots render` PNG byte for byte (rank 1's own lowest sample would draw the NaN cells lighter);
# a frame other than 0 is refused with 409 under mpirun.
# Usage: tests/mpi/mpi_serve_nodata.sh VOTS_BINARY
set -euo pipefail
vots=$1
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
/usr/bin/python3 "$(dirname "$0")/write_nodata_4d.py" "$work/data/nodata.nii"

"$vots" render "$work/data/nodata.nii" --frame 0 -o "$work/one.png" --renderer grid --mode minip \
    --cam az=30,el=20 --size 96x80 --window -50,200 2>/dev/null
start_job "$work/data" nodata
code=$(get "$work/served.png" "render?dataset=nodata&renderer=grid&mode=minip&cam=az=30,el=20&size=96x80&window=-50,200")
[[ $code == 200 ]] || fail "/render answered $code: $(cat "$work/served.png")"
cmp -s "$work/one.png" "$work/served.png" ||
    fail "the served grid minip with no data differs from one process: $(png_diff "$work/one.png" "$work/served.png")"
code=$(get "$work/frame1.json" "render?dataset=nodata&frame=1&renderer=grid&size=32x32")
[[ $code == 409 ]] || fail "frame=1 under mpirun answered $code, not 409: $(cat "$work/frame1.json")"
stop_job
echo "mpi_serve_nodata: the served grid minip with no data is one process's bytes; frame 1 is a 409"
