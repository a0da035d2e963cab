#!/usr/bin/env python3
"""Fit benchmark: every volume x eps (1, 2, 5 % of range) x method x norm; medians of repeated runs, peak memory.

Runs the real `vots fit` / `vots info --json` / `vots verify`, so it measures what users run. The norms
(`--fit-norm`, docs/DESIGN.md §3) of one volume and eps run interleaved, lsq then minimax in each round, so
that both see the same load; each minimax row gives its Vots against least squares'. "fit s" is the fit
alone (the file's meta), "user s" the process's CPU time, which a loaded machine disturbs less than wall
time. Writes a markdown table to stdout and, with --write, replaces the fit section of bench/RESULTS.md.

    bench/fit_bench.py --vots build/release/cli/vots --write
    bench/fit_bench.py --only cranium --no-paper --certify cells --eps 2 --runs 5
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
    """Runs cmd; returns (wall seconds, peak RSS MiB, returncode, user CPU seconds) or None on timeout."""
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
    return wall, usage.ru_maxrss / 1024.0, os.waitstatus_to_exitcode(status), usage.ru_utime


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
    parser.add_argument("--eps", default="1,2,5",
                        help="percent of the value range; a value ending in u is in data units (20u: 20 HU)")
    parser.add_argument("--norms", default="lsq,minimax", help="--fit-norm values, run interleaved")
    parser.add_argument("--certify", default="samples", choices=("samples", "cells"))
    parser.add_argument("--background", help="--background for every fit (default: auto)")
    parser.add_argument("--threads", type=int, default=0, help="--threads (0: all cores)")
    parser.add_argument("--only", help="substring filter on volume file names")
    parser.add_argument("--no-paper", action="store_true")
    parser.add_argument("--paper-minimax", action="store_true", help="also the paper method with minimax")
    parser.add_argument("--no-ct", action="store_true")
    parser.add_argument("--write", action="store_true", help="update bench/RESULTS.md")
    args = parser.parse_args()
    norms = args.norms.split(",")

    rows = []
    header = ("| volume | eps % | eps | method | norm | Vots | vs lsq | Vots/sample | fit s (median) | user s "
              "| wall s | peak MiB | file MiB | max err | verify |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
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
                run_norms = [n for n in norms if method == "fast" or n == "lsq" or args.paper_minimax]
                runs = args.runs if method == "fast" else 1
                timeout = args.paper_timeout if method == "paper" else 3600
                measured = {n: {"walls": [], "peaks": [], "fit": [], "user": []} for n in run_norms}
                infos, outs = {}, {}
                timed_out = False
                # Interleaved: every round runs each norm once, so a change of load touches them alike.
                for _ in range(runs):
                    for norm in run_norms:
                        out = tmp / f"{vol.stem}-{pct}-{method}-{norm}.vots"
                        eps_arg = pct[:-1] if pct.endswith("u") else f"{pct}%"
                        cmd = [args.vots, "fit", str(vol), "-o", str(out), "--eps", eps_arg, "--method", method,
                               "--fit-norm", norm, "--certify", args.certify, "--threads", str(args.threads)]
                        if args.background:
                            cmd += ["--background", args.background]
                        res = run_measured(cmd, timeout)
                        if res is None:
                            timed_out = True
                            break
                        wall, peak, rc, user = res
                        if rc != 0:
                            sys.exit(f"fit failed: {' '.join(cmd)}")
                        info = json.loads(subprocess.check_output([args.vots, "info", str(out), "--json"]))
                        m = measured[norm]
                        m["walls"].append(wall)
                        m["peaks"].append(peak)
                        m["fit"].append(info["fit_seconds"])
                        m["user"].append(user)
                        infos[norm], outs[norm] = info, out
                    if timed_out:
                        break
                if timed_out:
                    row = f"| {vol.stem} | {pct} | | {method} | | | | | > {timeout:.0f} (not finished) | | | | | | |"
                    skipped_paper.add(vol)  # a smaller eps only takes longer here
                    rows.append(row)
                    print(row, flush=True)
                    continue
                for norm in run_norms:
                    info, out, m = infos[norm], outs[norm], measured[norm]
                    verify = subprocess.run([args.vots, "verify", str(out), str(vol)], capture_output=True)
                    versus = ""
                    if norm != "lsq" and "lsq" in infos:
                        versus = f"{100.0 * (info['vot_count'] / infos['lsq']['vot_count'] - 1.0):+.1f} %"
                    row = (f"| {vol.stem} | {pct} | {info['eps']:.4g} | {method} | {norm} | {info['vot_count']:,} "
                           f"| {versus} | {info['vots_per_sample']:.4f} | {statistics.median(m['fit']):.3f} "
                           f"| {statistics.median(m['user']):.2f} | {statistics.median(m['walls']):.2f} "
                           f"| {max(m['peaks']):.0f} | {out.stat().st_size / 2**20:.2f} | {info['max_error']:.4g} "
                           f"| {'ok' if verify.returncode == 0 else 'FAILED'} |")
                    rows.append(row)
                    print(row, flush=True)
                for out in outs.values():
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
