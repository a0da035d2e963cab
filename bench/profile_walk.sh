#!/usr/bin/env bash
# Where a walk frame's time goes inside llvmpipe's JIT code: perf samples a running render_bench, gdb
# disassembles the JIT code around the sampled addresses, and the samples are summed per JIT function
# (llvmpipe compiles each texel fetch as its own small function; the largest one is the shader body).
# Needs perf and gdb (not part of scripts/setup) and a build with render_bench.
#
# Usage: bench/profile_walk.sh VOTS_FILE [VIEW] [BUILD_DIR]     VIEW: anterior, oblique (default), persp
# Example: bench/profile_walk.sh /tmp/ct1.vots oblique build/lead
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
vots=${1:?usage: bench/profile_walk.sh VOTS_FILE [VIEW] [BUILD_DIR]}
view=${2:-oblique}
build=${3:-build/lead}
work=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null || true; rm -rf "$work"' EXIT

"$build/bench/render_bench" data/cranium.nhdr --vots "$vots" --no-reference --view "$view" --frames 400 \
    --warmup 1 --strategy walk >/dev/null 2>&1 &
pid=$!
sleep 6 # loading and upload; then steady frames
perf record -q -o "$work/perf.data" -p "$pid" -- sleep 4 >/dev/null 2>&1
perf report -i "$work/perf.data" --no-children --sort sym 2>/dev/null | grep -E '^\s+[0-9]' >"$work/samples.txt"
# JIT code lives in anonymous mappings high in the address space; the hottest 100 addresses there.
first=$(python3 -c "
a = [int(l.split()[2], 16) for l in open('$work/samples.txt') if l.split()[2].startswith('0x')]
a = [x for x in a if x >= 0x7f0000000000]
print(hex(min(a[:100]) - 0x400))")
gdb -p "$pid" -batch -ex "x/8000i $first" 2>/dev/null | grep -E '^ *0x' >"$work/code.txt" || true
kill "$pid" 2>/dev/null || true
python3 - "$work" <<'PY'
import re, sys
work = sys.argv[1]
samples = {}
for line in open(f"{work}/samples.txt"):
    p = line.split()
    if len(p) >= 3 and p[2].startswith("0x"):
        samples[int(p[2], 16)] = float(p[0].rstrip("%"))
functions, current = [], []
for line in open(f"{work}/code.txt"):
    m = re.match(r"\s*(0x[0-9a-f]+):\s*(.*)", line)
    if not m:
        continue
    current.append((int(m.group(1), 16), m.group(2)))
    if m.group(2).startswith("ret"):
        functions.append(current)
        current = []
inside = 0.0
print("| JIT function | instructions | calls in it | gathers | share of samples |")
print("|---|---|---|---|---|")
for f in functions:
    share = sum(samples.get(a, 0.0) for a, _ in f)
    inside += share
    if share >= 0.3:
        calls = sum(1 for _, t in f if t.startswith("call"))
        gathers = sum(1 for _, t in f if "gather" in t)
        print(f"| {hex(f[0][0])} | {len(f)} | {calls} | {gathers} | {share:.1f} % |")
print(f"\noutside these functions: {sum(samples.values()) - inside:.1f} %")
PY
