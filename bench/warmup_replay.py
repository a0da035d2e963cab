#!/usr/bin/env python3
"""Warm-up replay: the new box fits of each eps slider move, with the server's warm-ups before it.

For each move of bench/eps_change.mjs in turn, fit_refit fills a box cache with every earlier move's fit and
the warm-ups that followed it (the move's own eps times each factor, not below 1 % of the range, as
server/src/fits/WarmUpFits.h runs them when the user pauses), then refits at the move's eps and reports
the boxes it had to fit for the first time. Box counts are exact, so this runs on a busy machine too.

    bench/warmup_replay.py build/ci/bench/fit_refit data/cranium.nhdr 0.5 0.8,1.25,0.5
"""
import argparse
import re
import subprocess

# bench/eps_change.mjs's moves (percent of the value range), from the server's default 2 %.
MOVES = [2, 2.222, 1.723, 2.424, 1.579, 2.643, 1.446, 2.893, 1.327, 3.1]
FLOOR_PERCENT = 1.0  # WarmUpFits::FLOOR


def replay(fit_refit, volume, factors):
    for k in range(1, len(MOVES)):
        bases = []
        for eps in MOVES[:k]:
            bases.append(eps)
            bases += [round(eps * f, 4) for f in factors if eps * f >= FLOOR_PERCENT]
        run = subprocess.run([fit_refit, "--cells", "--lsq", "--no-fresh", volume, ",".join(map(str, bases)),
                              str(MOVES[k])], capture_output=True, text=True, check=True)
        counts = re.search(r"refit [\d.]+ %: (\d+) box fits, (\d+) scans", run.stderr)
        yield MOVES[k], int(counts.group(1)), int(counts.group(2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fit_refit")
    parser.add_argument("volume")
    parser.add_argument("factors", nargs="+", help="comma-separated warm-up factors, one column per list")
    args = parser.parse_args()
    columns = [[float(f) for f in factors.split(",")] for factors in args.factors]
    results = [list(replay(args.fit_refit, args.volume, factors)) for factors in columns]
    print("| move to | " + " | ".join(f"first fits, warm-ups x{f}" for f in args.factors) + " | " +
          " | ".join(f"scans, x{f}" for f in args.factors) + " |")
    print("|---" * (1 + 2 * len(columns)) + "|")
    for i, (eps, _, _) in enumerate(results[0]):
        fits = " | ".join(f"{r[i][1]:,}" for r in results)
        scans = " | ".join(f"{r[i][2]:,}" for r in results)
        print(f"| {eps} % | {fits} | {scans} |")


if __name__ == "__main__":
    main()
