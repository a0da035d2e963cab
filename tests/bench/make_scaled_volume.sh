#!/usr/bin/env bash
# Checks make_scaled_volume: header dims and spacing, vots fits what it writes, same seed same bytes, bad args exit 2.
#
# Usage: make_scaled_volume.sh MAKE_SCALED_VOLUME VOTS INPUT.nhdr
set -euo pipefail

tool="$1"
vots="$2"
input="$3"
[ -f "$input" ] || { echo "make_scaled_volume.sh: no input $input (scripts/fetch-ct writes it)" >&2; exit 1; }
work="$(mktemp -d "${TMPDIR:-/tmp}/vots-scaled-test.XXXXXX")"
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
field() { sed -n "s/^$1: //p" "$2"; }

"$tool" "$input" "$work/a.nhdr" --size 64x64x20 --noise 8 --seed 7 2>"$work/a.log" || fail "tool: $(cat "$work/a.log")"
[ "$(field sizes "$work/a.nhdr")" = "64 64 20" ] || fail "sizes: $(field sizes "$work/a.nhdr")"
[ "$(field type "$work/a.nhdr")" = "int16" ] || fail "type: $(field type "$work/a.nhdr")"
[ "$(field 'data file' "$work/a.nhdr")" = "a.raw" ] || fail "data file: $(field 'data file' "$work/a.nhdr")"
[ "$(stat -c %s "$work/a.raw")" = $((64 * 64 * 20 * 2)) ] || fail "raw size $(stat -c %s "$work/a.raw")"

# Same physical extent: (points - 1) * spacing of the input, read from its own header.
read -r -a in_sizes <<<"$(field sizes "$input")"
# The input's spacings, or the lengths of its space directions (the Cranium's header states its axes).
in_spacing_text="$(field spacings "$input")"
if [ -z "$in_spacing_text" ]; then
  in_spacing_text="$(field 'space directions' "$input" | python3 -c 'import math, re, sys
print(" ".join(repr(math.hypot(*map(float, v.split(",")))) for v in re.findall(r"\(([^)]*)\)", sys.stdin.read())))')"
fi
read -r -a in_spacings <<<"$in_spacing_text"
read -r -a out_spacings <<<"$(field spacings "$work/a.nhdr")"
out_sizes=(64 64 20)
for a in 0 1 2; do
  awk -v ni="${in_sizes[$a]}" -v si="${in_spacings[$a]}" -v no="${out_sizes[$a]}" -v so="${out_spacings[$a]}" \
    'BEGIN { want = (ni - 1) * si / (no - 1); d = so - want; if (d < 0) d = -d; exit !(d <= 1e-6 * want) }' ||
    fail "axis $a spacing ${out_spacings[$a]}, want (${in_sizes[$a]}-1)*${in_spacings[$a]}/(${out_sizes[$a]}-1)"
done

# vots reads it: a fit at 2 % succeeds, and the Vot-Space file has the generated grid.
"$vots" fit "$work/a.nhdr" -o "$work/a.vots" --eps 2% >"$work/fit.log" 2>&1 || fail "vots fit: $(cat "$work/fit.log")"
"$vots" info --json "$work/a.vots" >"$work/info.json" || fail "vots info"
info_grid() {
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(" ".join(str(x) for x in d["dims"]), " ".join("%.6f" % x for x in d["spacing"]))' "$1"
}
info="$(info_grid "$work/info.json")"
want="64 64 20 $(printf '%.6f %.6f %.6f' "${out_spacings[@]}")"
[ "$info" = "$want" ] || fail "vots info says '$info', the header '$want'"

# Reproducible: the same seed gives the same bytes; another seed other noise; no noise, no randomness.
"$tool" "$input" "$work/b.nhdr" --size 64x64x20 --noise 8 --seed 7 2>/dev/null
cmp -s "$work/a.raw" "$work/b.raw" || fail "two runs with seed 7 differ"
"$tool" "$input" "$work/c.nhdr" --size 64x64x20 --noise 8 --seed 8 2>/dev/null
! cmp -s "$work/a.raw" "$work/c.raw" || fail "seeds 7 and 8 gave the same bytes"

# Bad arguments: one line naming the problem (then the usage), exit 2.
expect_bad() {
  local rc=0
  "$tool" "$@" >/dev/null 2>"$work/bad.log" || rc=$?
  [ "$rc" = 2 ] || fail "'$*' exited $rc, want 2"
  head -1 "$work/bad.log" | grep -q '^make_scaled_volume: ' || fail "'$*' said: $(head -1 "$work/bad.log")"
}
expect_bad "$input" "$work/d.nhdr"
expect_bad "$input" "$work/d.nhdr" --size 64x64
expect_bad "$input" "$work/d.nhdr" --size 64x1x20
expect_bad "$input" "$work/d.nhdr" --size 64x64x20x
expect_bad "$input" "$work/d.nhdr" --size 64x64x20 --noise -1
expect_bad "$input" "$work/d.nhdr" --size 64x64x20 --seed x
expect_bad "$input" "$work/d.nrrd" --size 64x64x20
expect_bad "$work/missing.nhdr" "$work/d.nhdr" --size 64x64x20
[ ! -e "$work/d.nhdr" ] || fail "a refused run left $work/d.nhdr"
echo "make_scaled_volume.sh: all checks passed"
