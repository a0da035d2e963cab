#!/usr/bin/env bash
# `mpirun -np N vots render` on loopback: the ranks' slabs composited by MAX give the single-process
# bytes of the same Vot-Space for N = 1, 2, 3 (3 oversubscribed on 2 cores); fitting per slab is
# reproducible and with one rank is the single-process fit; what is not composited yet exits 2.
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
    for n in 1 2 3; do
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

status=0
mpi 2 "$vots" render "$work/v.vots" -o "$work/no.png" --mode aip "${view[@]}" 2>"$work/err" || status=$?
((status != 0)) || fail "aip on two ranks was not refused"
grep -q "under mpirun" "$work/err" || fail "aip on two ranks: no clear message: $(cat "$work/err")"
[[ ! -e $work/no.png ]] || fail "a refused render wrote its output"
echo "mpi_render: OK"
