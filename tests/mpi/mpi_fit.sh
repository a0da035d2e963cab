#!/usr/bin/env bash
# `mpirun -np N vots fit` on loopback, N = 1, 2, 3, 4 (3 and 4 oversubscribed on 2 cores): each rank
# reads only its z cells' planes of a raw NRRD; the one file the ranks write verifies against the volume, records the
# ranks, is reproducible, with one rank holds the single-process Vots, leaves no temporary (the ranks write
# their records into it with MPI-IO, rank 0 renames it), renders alike in one process and
# on N ranks; the gzip input (each rank streams its planes alone) gives the same Vots; a DICOM series of
# the same samples (each rank decodes only its slices) verifies; a focus sphere across the border of two ranks' cells
# verifies; a NaN (no data) on one rank fits as in one process; a failure on one rank ends all (fit and render).
# Usage: tests/mpi/mpi_fit.sh VOTS_BINARY GZIP_NRRD_VOLUME VOTS_WRITE_DICOM_BINARY
set -euo pipefail
vots=$1 gzipped=$2 write_dicom=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# CI runs as root; Open MPI refuses that unless told, and must not look for other hosts.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
mpi() { mpirun --oversubscribe -np "$1" "${@:2}"; }
fail() { echo "mpi_fit: $*" >&2; exit 1; }
# The header and the Vot records of a .vots file (docs/DESIGN.md §8): everything but meta_bytes and the
# meta block, whose fit times differ from run to run.
vots_body() {
    local count
    count=$(od -An -tu8 -j88 -N8 "$1" | tr -d ' ')
    { head -c 96 "$1"; tail -c +105 "$1" | head -c $((24 + 120 * count)); }
}
# A key of `vots info --json` (compact JSON, the meta block in it), without jq: "ranks":2, ...
json_key() { "$vots" info --json "$1" | grep -oE "\"$2\":(\[[^]]*\]|[^,}]*)"; }
fit_args=(--eps 2% --threads 1)
view=(--cam az=30,el=20 --size 96x80)

# The same samples as a detached raw NRRD, which the ranks read by offset.
header_lines=$(sed -n '/^$/=' "$gzipped" | head -1)
tail -n +$((header_lines + 1)) "$gzipped" | gunzip >"$work/head.raw"
head -n "$header_lines" "$gzipped" | grep -aE '^(type|dimension|sizes|spacings|endian):' >"$work/fields"
{ echo NRRD0004; cat "$work/fields"; echo "encoding: raw"; echo "data file: head.raw"; } >"$work/head.nhdr"
volume=$work/head.nhdr

"$vots" fit "$volume" -o "$work/one.vots" "${fit_args[@]}" >/dev/null
for n in 1 2 3 4; do
    out=$work/$n.vots
    mpi "$n" "$vots" fit "$volume" -o "$out" "${fit_args[@]}" >"$work/stdout" 2>"$work/stderr" ||
        fail "$n ranks: fit failed: $(cat "$work/stderr")"
    (($(grep -c '^wrote ' "$work/stdout") == 1)) || fail "$n ranks: not exactly one rank reported: $(cat "$work/stdout")"
    "$vots" verify "$out" "$volume" >"$work/verify" || fail "$n ranks: verify failed: $(cat "$work/verify")"
    [[ $(json_key "$out" ranks) == "\"ranks\":$n" ]] || fail "$n ranks: the meta block does not record ranks $n"
    "$vots" info "$out" | grep -q "^ranks *$n " || fail "$n ranks: vots info does not show the ranks"
    for key in value_range background eps; do
        [[ $(json_key "$out" $key) == "$(json_key "$work/one.vots" $key)" ]] ||
            fail "$n ranks: $key differs from one process's: $(json_key "$out" $key)"
    done
done
cmp -s <(vots_body "$work/one.vots") <(vots_body "$work/1.vots") || fail "one rank's Vots differ from one process's"
leftover=$(find "$work" -name '*.tmp-*')
[[ -z $leftover ]] || fail "temporaries left behind: $leftover"
cmp -s <(vots_body "$work/one.vots") <(vots_body "$work/2.vots") && fail "two ranks gave one process's Vots (no split?)"

# Reproducible: the same arguments and N give the same bytes, meta block apart from its fit times.
mpi 2 "$vots" fit "$volume" -o "$work/2b.vots" "${fit_args[@]}" >/dev/null
cmp -s <(vots_body "$work/2.vots") <(vots_body "$work/2b.vots") || fail "two runs on 2 ranks differ"
no_times() { "$vots" info --json "$1" | sed -E 's/"(fit_)?seconds":[^,}]*//g; s/"file":"[^"]*"//'; }
[[ $(no_times "$work/2.vots") == "$(no_times "$work/2b.vots")" ]] || fail "two runs on 2 ranks: meta blocks differ"

# Either norm on the ranks (docs/DESIGN.md §3): least squares verifies as well, with more Vots than minimax
# (the default), and only a minimax file names its norm.
mpi 2 "$vots" fit "$volume" -o "$work/2lsq.vots" "${fit_args[@]}" --fit-norm lsq >/dev/null ||
    fail "2 ranks, --fit-norm lsq: fit failed"
"$vots" verify "$work/2lsq.vots" "$volume" >"$work/verify" || fail "2 ranks, lsq: verify failed: $(cat "$work/verify")"
vot_count() { od -An -tu8 -j88 -N8 "$1" | tr -d ' '; }
(($(vot_count "$work/2.vots") < $(vot_count "$work/2lsq.vots"))) ||
    fail "2 ranks: minimax gave $(vot_count "$work/2.vots") Vots, least squares $(vot_count "$work/2lsq.vots")"
[[ $(json_key "$work/2.vots" norm) == '"norm":"minimax"' ]] || fail "2 ranks: the minimax file does not name its norm"
[[ -z $(json_key "$work/2lsq.vots" norm) ]] || fail "2 ranks: the least-squares file names a norm"

# A focus sphere across the border of two ranks' cells, named in the whole volume's index space: every rank holds its
# samples to the focus's eps (vots verify rebuilds the field from the meta block), and the file records
# the focus as one process's does.
focus_args=(--eps 4% --focus 24,31,20,8 --eps-focus 1 --threads 1)
"$vots" fit "$volume" -o "$work/focus1.vots" "${focus_args[@]}" >/dev/null
mpi 2 "$vots" fit "$volume" -o "$work/focus2.vots" "${focus_args[@]}" >/dev/null 2>"$work/stderr" ||
    fail "2 ranks with --focus: $(cat "$work/stderr")"
"$vots" verify "$work/focus2.vots" "$volume" >"$work/verify" || fail "2 ranks with --focus: $(cat "$work/verify")"
[[ $(json_key "$work/focus2.vots" focus) == "$(json_key "$work/focus1.vots" focus)" ]] ||
    fail "2 ranks with --focus: the meta's focus differs: $(json_key "$work/focus2.vots" focus)"
mpi 2 "$vots" fit "$volume" -o "$work/nofocus2.vots" --eps 4% --threads 1 >/dev/null
votsOf() { "$vots" info "$1" | awk '$1 == "Vots" { gsub(",", "", $2); print $2; exit }'; }
(($(votsOf "$work/focus2.vots") > $(votsOf "$work/nofocus2.vots"))) ||
    fail "2 ranks: the focus gave no more Vots than none ($(votsOf "$work/focus2.vots"))"
mpi 2 "$vots" fit "$volume" -o "$work/outside.vots" --eps 4% --focus 24,31,60,8 --eps-focus 1 >/dev/null 2>&1 &&
    fail "2 ranks: a focus centre outside the volume was accepted"

# Each rank inflates the gzip file up to its last plane and keeps its planes: the same cells, so the same Vots.
mpi 2 "$vots" fit "$gzipped" -o "$work/gz.vots" "${fit_args[@]}" >/dev/null
cmp -s <(vots_body "$work/2.vots") <(vots_body "$work/gz.vots") || fail "gzip and raw input differ on 2 ranks"

# A DICOM series written by GDCM from the same volume: one rank holds the single-process Vots, two
# ranks (each decoding only its own slices' files) give a file that verifies against the series.
"$write_dicom" "$work/series" --input "$volume" >/dev/null
"$vots" fit "$work/series" -o "$work/dcm-one.vots" "${fit_args[@]}" >/dev/null
mpi 1 "$vots" fit "$work/series" -o "$work/dcm-1.vots" "${fit_args[@]}" >/dev/null
cmp -s <(vots_body "$work/dcm-one.vots") <(vots_body "$work/dcm-1.vots") ||
    fail "DICOM: one rank's Vots differ from one process's"
mpi 2 "$vots" fit "$work/series" -o "$work/dcm-2.vots" "${fit_args[@]}" >/dev/null 2>"$work/stderr" ||
    fail "DICOM on 2 ranks: fit failed: $(cat "$work/stderr")"
"$vots" verify "$work/dcm-2.vots" "$work/series" >"$work/verify" ||
    fail "DICOM on 2 ranks: verify failed: $(cat "$work/verify")"
[[ $(json_key "$work/dcm-2.vots" value_range) == "$(json_key "$work/dcm-one.vots" value_range)" ]] ||
    fail "DICOM on 2 ranks: the value range is not the whole series'"

# The N-rank file in one process and on N ranks (each rank its Vots, frames composited) draws alike.
for n in 2 3; do
    "$vots" render "$work/$n.vots" -o "$work/$n-one.png" "${view[@]}" 2>/dev/null
    mpi "$n" "$vots" render "$work/$n.vots" -o "$work/$n-ranks.png" "${view[@]}" 2>/dev/null
    cmp -s "$work/$n-one.png" "$work/$n-ranks.png" || fail "the $n-rank file renders differently on $n ranks"
done

# A NaN in the last plane is no data (a fit leaves its cells out): 2 ranks fit it as one process does.
{
    printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 8 8 10\nencoding: raw\nendian: little\n\n'
    head -c 1280 /dev/zero
    for _ in $(seq 319); do printf '\x00\x00\x80\x3f'; done
    printf '\x00\x00\xc0\x7f'
} >"$work/nan.nrrd"
"$vots" fit "$work/nan.nrrd" -o "$work/nan-one.vots" --eps 0.1 >"$work/nan-one.txt"
timeout 120 mpirun --oversubscribe -np 2 "$vots" fit "$work/nan.nrrd" -o "$work/nan.vots" --eps 0.1 \
    >/dev/null 2>"$work/err" || fail "a NaN on rank 1: $(cat "$work/err")"
"$vots" verify "$work/nan.vots" "$work/nan.nrrd" >/dev/null || fail "the 2-rank fit of a NaN volume does not verify"

# A gzip payload longer than the header says: only the last rank reads the stream's end; every rank
# exits 2, rank 0 names it, no file.
{
    printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 8 8 10\nencoding: gzip\nendian: little\n\n'
    { head -c 1280 /dev/zero; for _ in $(seq 321); do printf '\x00\x00\x80\x3f'; done; } | gzip -c
} >"$work/long.nrrd"
status=0
timeout 120 mpirun --oversubscribe -np 2 "$vots" fit "$work/long.nrrd" -o "$work/long.vots" --eps 0.1 \
    >/dev/null 2>"$work/err" || status=$?
((status == 2)) || fail "a long stream on rank 1: exit $status, not 2: $(cat "$work/err")"
grep -q "vots: error: rank 1: .*longer than the header says" "$work/err" ||
    fail "a long stream on rank 1: no clear message: $(cat "$work/err")"
[[ ! -e $work/long.vots ]] || fail "a failed fit wrote its output"
status=0 # `vots render VOLUME` reads its ranks' planes alike
timeout 120 mpirun --oversubscribe -np 2 "$vots" render "$work/long.nrrd" -o "$work/long.png" --eps 0.1 \
    --size 32x32 >/dev/null 2>"$work/err" || status=$?
((status == 2)) || fail "render, a long stream on rank 1: exit $status, not 2: $(cat "$work/err")"
grep -q "vots: error: rank 1: .*longer than the header says" "$work/err" ||
    fail "render, a long stream on rank 1: $(cat "$work/err")"
[[ ! -e $work/long.png ]] || fail "a failed render wrote its output"
echo "mpi_fit: OK"
