#!/usr/bin/env bash
# Checks bench/vot_crossings.py on a known answer: a ramp that one Vot fits exactly, whose box of 4 x 8 x 12 mm
# casts 48 mm^2 seen from the front, 32 from above and 95.1 from az 30, el 20.
#
# Usage: vot_crossings.sh VOTS
set -euo pipefail

vots="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
script="$here/../../bench/vot_crossings.py"
work="$(mktemp -d "${TMPDIR:-/tmp}/vots-crossings-test.XXXXXX")"
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# 5 x 5 x 5 float samples of x + 2y + 3z, spacing 1, 2, 3 mm.
python3 - "$work" <<'PY'
import struct, sys
work = sys.argv[1]
values = [x + 2 * y + 3 * z for z in range(5) for y in range(5) for x in range(5)]
open(f"{work}/ramp.raw", "wb").write(struct.pack(f"<{len(values)}f", *values))
open(f"{work}/ramp.nhdr", "w").write(
    "NRRD0004\ntype: float\ndimension: 3\nsizes: 5 5 5\nspacings: 1 2 3\nencoding: raw\n"
    "endian: little\ndata file: ramp.raw\n")
PY
"$vots" fit "$work/ramp.nhdr" -o "$work/ramp.vots" --eps 0.5 --degree 1 --background none >"$work/fit.log" 2>&1 ||
  fail "fit: $(cat "$work/fit.log")"
grep -q " 1 Vots" "$work/fit.log" || fail "expected one Vot: $(cat "$work/fit.log")"

python3 "$script" "$work/ramp.vots" "$work/ramp.vots" --view anterior --view axial --view 30,20 >"$work/out.md" ||
  fail "vot_crossings.py failed"
crossings() { awk -F'|' -v view="$1" '$2 ~ " "view" " { gsub(/[ ,]/, "", $5); print $5; exit }' "$work/out.md"; }
[ "$(crossings anterior)" = 48 ] || fail "anterior: $(crossings anterior), want 48"$'\n'"$(cat "$work/out.md")"
[ "$(crossings axial)" = 32 ] || fail "axial: $(crossings axial), want 32"
[ "$(crossings 30,20)" = 95 ] || fail "az 30, el 20: $(crossings 30,20), want 95"
# The second file of a pair is compared with the first: the same file gives 1 for both ratios.
grep -q "| 1.000 | 1.000 |" "$work/out.md" || fail "pair ratio: $(cat "$work/out.md")"

# Not a .vots file: a clear message and a non-zero exit.
if python3 "$script" "$work/ramp.nhdr" "$work/ramp.vots" >"$work/bad.log" 2>&1; then fail "a NRRD header was read as .vots"; fi
grep -q "not a .vots file" "$work/bad.log" || fail "bad input: $(cat "$work/bad.log")"
echo "vot_crossings.sh: ok"
