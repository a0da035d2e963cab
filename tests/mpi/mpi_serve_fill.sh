#!/usr/bin/env bash
# The whole volume's background fill in frames served under mpirun: on a generated volume whose air is
# -3000 in the lower half of its z cells and -2980 in the upper (a sphere of 1000 in the middle), the aip
# and the minip that `mpirun -np 2 vots serve` composites are `mpirun -np 2 vots render`'s PNG, byte for
# byte (each rank's own fill would darken one half and lighten the other).
# Usage: tests/mpi/mpi_serve_fill.sh VOTS_BINARY
set -euo pipefail
vots=$1
source "$(dirname "$0")/serve_job.bash"

mkdir "$work/data"
/usr/bin/python3 - "$work/data/air_step.nrrd" <<'PY'
import struct, sys
nx, ny, nz = 64, 64, 40
samples = []
for z in range(nz):
    for y in range(ny):
        for x in range(nx):
            inside = (x - 31.5) ** 2 + (y - 31.5) ** 2 + (z - 19.5) ** 2 <= 144.0
            samples.append(1000 if inside else (-3000 if z < nz // 2 else -2980))
with open(sys.argv[1], "wb") as out:
    out.write(b"NRRD0004\ntype: int16\ndimension: 3\nsizes: 64 64 40\nspacings: 1 1 1\n"
              b"endian: little\nencoding: raw\n\n")
    out.write(struct.pack("<%dh" % len(samples), *samples))
PY

start_job "$work/data" air_step
for mode in aip minip; do
    mpirun --oversubscribe -np 2 "$vots" render "$work/data/air_step.nrrd" -o "$work/render-$mode.png" \
        --cam anterior --size 128x128 --mode "$mode" --window -2990,200 --eps 2% --fit-norm lsq 2>/dev/null ||
        fail "mpirun vots render --mode $mode failed"
    code=$(get "$work/served-$mode.png" \
        "render?dataset=air_step&cam=anterior&size=128x128&mode=$mode&window=-2990,200&eps=2%25")
    [[ $code == 200 ]] || fail "/render --mode $mode answered $code: $(cat "$work/served-$mode.png")"
    cmp -s "$work/render-$mode.png" "$work/served-$mode.png" ||
        fail "the served $mode differs from mpirun vots render's: $(png_diff "$work/render-$mode.png" "$work/served-$mode.png")"
done
stop_job
echo "mpi_serve_fill: the served aip and minip are mpirun vots render's bytes"
