#!/usr/bin/env bash
# `mpirun -np N vots render` on loopback: the ranks' z cells composited by MAX give the single-process
# bytes of the same Vot-Space for N = 1, 2, 3, 4 (3 and 4 oversubscribed on 2 cores); MinIP and the
# average, each rank's rays cut to its z cells, give the same bytes twice and the single-process
# image within one grey level; fitting per rank's cells is reproducible and with one rank is the single-process
# fit; turntables of N ranks are the single-process frames; the exact grid renderer draws each rank's
# planes; a failing rank ends every rank with exit 2.
# Usage: tests/mpi/mpi_render.sh VOTS_BINARY VOLUME
set -euo pipefail
vots=$1 volume=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# CI runs as root; Open MPI refuses that unless told, and must not look for other hosts.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
mpi() { mpirun --oversubscribe -np "$1" "${@:2}"; }
fail() { echo "mpi_render: $*" >&2; exit 1; }
view=(--cam az=30,el=20 --size 96x80)

"$vots" fit "$volume" -o "$work/v.vots" --eps 2% --certify cells >/dev/null 2>&1
for mode in mip density; do
    "$vots" render "$work/v.vots" -o "$work/one-$mode.png" --mode "$mode" "${view[@]}" 2>/dev/null
    for n in 1 2 3 4; do
        mpi "$n" "$vots" render "$work/v.vots" -o "$work/$n-$mode.png" --mode "$mode" "${view[@]}" 2>/dev/null
        cmp -s "$work/one-$mode.png" "$work/$n-$mode.png" || fail "$mode of the .vots on $n ranks differs from one process"
    done
done

"$vots" render "$volume" -o "$work/fit-one.png" --eps 2% "${view[@]}" 2>/dev/null
mpi 1 "$vots" render "$volume" -o "$work/fit-1.png" --eps 2% "${view[@]}" 2>/dev/null
cmp -s "$work/fit-one.png" "$work/fit-1.png" || fail "one rank's fit differs from the single-process fit"
for run in a b; do
    mpi 2 "$vots" render "$volume" -o "$work/fit-2$run.png" --eps 2% "${view[@]}" 2>/dev/null
done
cmp -s "$work/fit-2a.png" "$work/fit-2b.png" || fail "two ranks' fits differ between runs"

# MinIP and the average: the composite rounds differently from one process (a Vot cut by a face between ranks' cells is
# expanded from the face; the mean's integrals are summed per rank), by far less than a grey level in the
# float frame, so a PNG pixel may differ by one level where the float lies on a rounding edge.
png_diff() { /usr/bin/python3 "$(dirname "$0")/png_diff.py" "$@"; } # Debian's python3-pil
tolerance=1
for projection in "--mode minip" "--mode aip" "--mode aip --slab 5,20" "--mode minip --slab -10,30"; do
    read -ra how <<<"$projection"
    tag=$(tr -c 'a-z0-9' _ <<<"$projection")
    "$vots" render "$work/v.vots" -o "$work/one-$tag.png" "${how[@]}" "${view[@]}" 2>/dev/null
    for n in 1 2 3 4; do
        for run in a b; do
            mpi "$n" "$vots" render "$work/v.vots" -o "$work/$n$run-$tag.png" "${how[@]}" "${view[@]}" 2>/dev/null
        done
        cmp -s "$work/${n}a-$tag.png" "$work/${n}b-$tag.png" || fail "$projection on $n ranks differs between runs"
        read -r worst differing < <(png_diff "$work/one-$tag.png" "$work/${n}a-$tag.png")
        echo "mpi_render: $projection on $n ranks: $differing pixels differ from one process, by at most $worst"
        ((worst <= tolerance)) || fail "$projection on $n ranks differs from one process by $worst grey levels"
    done
done
# A file fitted on the same 3 ranks' cells has no box across their faces: every Vot is drawn on one rank, whole,
# and the MinIP is the single-process one byte for byte.
mpi 3 "$vots" fit "$volume" -o "$work/v3.vots" --eps 2% --certify cells >/dev/null 2>&1
"$vots" render "$work/v3.vots" -o "$work/one-v3-minip.png" --mode minip "${view[@]}" 2>/dev/null
mpi 3 "$vots" render "$work/v3.vots" -o "$work/3-v3-minip.png" --mode minip "${view[@]}" 2>/dev/null
cmp -s "$work/one-v3-minip.png" "$work/3-v3-minip.png" || fail "minip of a 3-rank fit on 3 ranks differs from one process"
for run in a b; do
    mpi 3 "$vots" render "$volume" -o "$work/fit-minip-3$run.png" --mode minip --eps 2% "${view[@]}" 2>/dev/null
done
cmp -s "$work/fit-minip-3a.png" "$work/fit-minip-3b.png" || fail "three ranks' fits differ between runs in minip"

# Turntables: every frame of the .vots on N ranks is the single-process frame byte for byte; a volume
# fitted on 2 ranks gives the same frames twice, PNG or WebM.
"$vots" render "$work/v.vots" -o "$work/turn-one-%02d.png" --turntable 3 "${view[@]}" 2>/dev/null
for n in 1 2 3; do
    mpi "$n" "$vots" render "$work/v.vots" -o "$work/turn-$n-%02d.png" --turntable 3 "${view[@]}" 2>/dev/null
    for k in 00 01 02; do
        cmp -s "$work/turn-one-$k.png" "$work/turn-$n-$k.png" || fail "turntable frame $k on $n ranks differs from one process"
    done
done
for run in a b; do
    mpi 2 "$vots" render "$volume" -o "$work/turn-fit-$run.webm" --turntable 3 --eps 2% --cam az=30,el=20 \
        --size 128x128 2>/dev/null
done
cmp -s "$work/turn-fit-a.webm" "$work/turn-fit-b.webm" || fail "a turntable WebM fitted on 2 ranks differs between runs"

# The exact grid: each rank draws its cells' planes with cut rays; max, min or sum over the ranks. One rank
# is the single-process image byte for byte; more ranks cut the rays at the faces between their cells (a few ulps).
for mode in mip minip aip; do
    "$vots" render "$volume" -o "$work/grid-one-$mode.png" --renderer grid --mode "$mode" "${view[@]}" 2>/dev/null
    for n in 1 2 3 4; do
        for run in a b; do
            mpi "$n" "$vots" render "$volume" -o "$work/grid-$n$run-$mode.png" --renderer grid --mode "$mode" \
                "${view[@]}" 2>/dev/null
        done
        cmp -s "$work/grid-${n}a-$mode.png" "$work/grid-${n}b-$mode.png" || fail "grid $mode on $n ranks differs between runs"
        if ((n == 1)); then
            cmp -s "$work/grid-one-$mode.png" "$work/grid-1a-$mode.png" || fail "grid $mode on one rank differs from one process"
        fi
        read -r worst differing < <(png_diff "$work/grid-one-$mode.png" "$work/grid-${n}a-$mode.png")
        echo "mpi_render: grid $mode on $n ranks: $differing pixels differ from one process, by at most $worst"
        ((worst <= tolerance)) || fail "grid $mode on $n ranks differs from one process by $worst grey levels"
    done
done
"$vots" render "$work/v.vots" --mode reference --volume "$volume" --turntable 2 \
    --cam az=30,el=20 --size 96x80 -o "$work/ref-one-%d.png" 2>/dev/null
mpi 2 "$vots" render "$work/v.vots" --mode reference --volume "$volume" --turntable 2 --cam az=30,el=20 \
    --size 96x80 -o "$work/ref-2-%d.png" 2>/dev/null
for k in 0 1; do
    read -r worst differing < <(png_diff "$work/ref-one-$k.png" "$work/ref-2-$k.png")
    ((worst <= tolerance)) || fail "reference turntable frame $k on 2 ranks differs by $worst grey levels"
done

# Failures end every rank with the exit code and a one-line message on rank 0, never a hang.
status=0
mpi 2 "$vots" render "$work/v.vots" -o "$work/no.png" --renderer grid "${view[@]}" 2>"$work/err" || status=$?
((status == 2)) || fail "--renderer grid on a .vots without --volume on two ranks did not exit 2 ($status)"
grep -q "needs the volume" "$work/err" || fail "--renderer grid without --volume: no clear message: $(cat "$work/err")"
[[ ! -e $work/no.png ]] || fail "a refused render wrote its output"
# A frame that cannot be written (a file-size limit on the ranks; TCP, since the shared-memory transport
# needs files of its own) ends the turn on every rank and leaves no frame behind.
mkdir "$work/quota"
status=0
OMPI_MCA_btl=self,tcp mpi 2 bash -c 'ulimit -f 4; exec "$0" "$@"' "$vots" render "$volume" --turntable 4 \
    --size 200x200 -o "$work/quota/%d.png" 2>"$work/err" || status=$?
((status == 2)) || fail "a turntable that cannot be written did not exit 2 on two ranks ($status)"
grep -q "cannot write" "$work/err" || fail "an unwritable turntable: no clear message: $(cat "$work/err")"
[[ -z $(ls -A "$work/quota") ]] || fail "an unwritable turntable left files behind: $(ls "$work/quota")"
echo "mpi_render: OK"
