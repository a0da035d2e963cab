#!/usr/bin/env bash
# `mpirun -np N vots render` on loopback: the ranks' slabs composited by MAX give the single-process
# bytes of the same Vot-Space for N = 1, 2, 3, 4 (3 and 4 oversubscribed on 2 cores); MinIP and the
# average, each rank's rays cut to its slab of cells, give the same bytes twice and the single-process
# image within one grey level; fitting per slab is reproducible and with one rank is the single-process
# fit; what is not composited yet exits 2.
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

# MinIP and the average: the composite rounds differently from one process (a Vot cut by a slab face is
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
# A file fitted on the same 3 slabs has no box across their faces: every Vot is drawn on one rank, whole,
# and the MinIP is the single-process one byte for byte.
mpi 3 "$vots" fit "$volume" -o "$work/v3.vots" --eps 2% --certify cells >/dev/null 2>&1
"$vots" render "$work/v3.vots" -o "$work/one-v3-minip.png" --mode minip "${view[@]}" 2>/dev/null
mpi 3 "$vots" render "$work/v3.vots" -o "$work/3-v3-minip.png" --mode minip "${view[@]}" 2>/dev/null
cmp -s "$work/one-v3-minip.png" "$work/3-v3-minip.png" || fail "minip of a 3-slab fit on 3 ranks differs from one process"
for run in a b; do
    mpi 3 "$vots" render "$volume" -o "$work/fit-minip-3$run.png" --mode minip --eps 2% "${view[@]}" 2>/dev/null
done
cmp -s "$work/fit-minip-3a.png" "$work/fit-minip-3b.png" || fail "three ranks' fits differ between runs in minip"

status=0
mpi 2 "$vots" render "$work/v.vots" -o "$work/no.png" --renderer grid --volume "$volume" "${view[@]}" \
    2>"$work/err" || status=$?
((status == 2)) || fail "--renderer grid on two ranks was not refused with exit 2 ($status)"
grep -q "under mpirun" "$work/err" || fail "--renderer grid on two ranks: no clear message: $(cat "$work/err")"
[[ ! -e $work/no.png ]] || fail "a refused render wrote its output"
echo "mpi_render: OK"
