#!/usr/bin/env python3
"""Fit benchmark: every volume x eps (1, 2, 5 % of range) x method; medians of repeated runs, peak memory.

Runs the real `vots fit` / `vots info --json` / `vots verify`, so it measures what users run.
Writes a markdown table to stdout and, with --write, replaces the fit section of bench/RESULTS.md.

    bench/fit_bench.py --vots build/release/cli/vots --write
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "data"
BEGIN, END = "<!-- fit-bench:begin -->", "<!-- fit-bench:end -->"


def run_measured(cmd, timeout):
    """Runs cmd; returns (wall seconds, peak RSS MiB, returncode) or None on timeout."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = start + timeout
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        if time.monotonic() > deadline:
            proc.kill()
            proc.wait()
            return None
        time.sleep(0.05)
    wall = time.monotonic() - start
    return wall, usage.ru_maxrss / 1024.0, os.waitstatus_to_exitcode(status)


def volumes(include_ct):
    found = sorted(SHARED.glob("*.nrrd"))
    ct = ROOT / "data" / "cranium.nhdr"
    if include_ct and ct.exists():
        found.append(ct)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--vots", default=str(ROOT / "build" / "release" / "cli" / "vots"))
    parser.add_argument("--runs", type=int, default=3, help="fast-method runs per cell (median)")
    parser.add_argument("--paper-timeout", type=float, default=600.0)
    parser.add_argument("--eps", default="1,2,5", help="percent of the value range")
    parser.add_argument("--only", help="substring filter on volume file names")
    parser.add_argument("--no-paper", action="store_true")
    parser.add_argument("--no-ct", action="store_true")
    parser.add_argument("--write", action="store_true", help="update bench/RESULTS.md")
    args = parser.parse_args()

    rows = []
    header = ("| volume | eps % | eps | method | Vots | Vots/sample | fit s (median) | wall s | peak MiB "
              "| max err | verify |\n|---|---|---|---|---|---|---|---|---|---|---|")
    print(header, flush=True)
    tmp = Path(tempfile.mkdtemp(prefix="vots-bench-"))
    skipped_paper = set()
    for vol in volumes(not args.no_ct):
        if args.only and args.only not in vol.name:
            continue
        for pct in args.eps.split(","):
            for method in ("fast", "paper"):
                if method == "paper" and (args.no_paper or vol in skipped_paper):
                    continue
                out = tmp / f"{vol.stem}-{pct}-{method}.vots"
                cmd = [args.vots, "fit", str(vol), "-o", str(out), "--eps", f"{pct}%", "--method", method]
                runs = args.runs if method == "fast" else 1
                timeout = args.paper_timeout if method == "paper" else 3600
                walls, peaks, fit_secs = [], [], []
                timed_out = False
                for _ in range(runs):
                    res = run_measured(cmd, timeout)
                    if res is None:
                        timed_out = True
                        break
                    wall, peak, rc = res
                    if rc != 0:
                        sys.exit(f"fit failed: {' '.join(cmd)}")
                    info = json.loads(subprocess.check_output([args.vots, "info", str(out), "--json"]))
                    walls.append(wall)
                    peaks.append(peak)
                    fit_secs.append(info["fit_seconds"])
                if timed_out:
                    row = f"| {vol.stem} | {pct} | | {method} | | | > {timeout:.0f} (not finished) | | | | |"
                    skipped_paper.add(vol)  # a smaller eps only takes longer here
                else:
                    verify = subprocess.run([args.vots, "verify", str(out), str(vol)], capture_output=True)
                    row = (f"| {vol.stem} | {pct} | {info['eps']:.4g} | {method} | {info['vot_count']:,} "
                           f"| {info['vots_per_sample']:.4f} | {statistics.median(fit_secs):.3f} "
                           f"| {statistics.median(walls):.2f} | {max(peaks):.0f} | {info['max_error']:.4g} "
                           f"| {'ok' if verify.returncode == 0 else 'FAILED'} |")
                rows.append(row)
                print(row, flush=True)
                out.unlink(missing_ok=True)
    table = header + "\n" + "\n".join(rows)
    if args.write:
        results = ROOT / "bench" / "RESULTS.md"
        text = results.read_text() if results.exists() else "# Benchmark results\n"
        section = (f"{BEGIN}\n## Fit (`bench/fit_bench.py`, {os.cpu_count()} cores, {time.strftime('%Y-%m-%d')})\n\n"
                   f"{table}\n{END}")
        if BEGIN in text:
            text = text[: text.index(BEGIN)] + section + text[text.index(END) + len(END):]
        else:
            text = text.rstrip() + "\n\n" + section + "\n"
        results.write_text(text)


if __name__ == "__main__":
    main()
