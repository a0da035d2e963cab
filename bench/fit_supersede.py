#!/usr/bin/env python3
"""A hand that rests on the eps slider, then moves on: what the first fit costs the second.

Each trial asks for a fit at eps X, waits REST seconds (the viewer's rest fit, web/js/eps-slider.js), then
asks for a fit at eps Y and times Y from its request to its end. "viewer" trials name the same client in
both requests, so the server cancels X (FitJobs::submit); "plain" trials name none, so X runs on beside Y
on the same cores. The two kinds alternate; each trial's eps are new, so no whole Vot-Space is cached.
Needs a running `vots serve` (best with --no-warm-up, whose background fits would blur the times).

    bench/fit_supersede.py --url http://127.0.0.1:8080 --dataset cranium --trials 5 --rest 0.2
"""
import argparse
import json
import statistics
import time
import urllib.request


def post_fit(url, dataset, eps_percent, client):
    body = {"dataset": dataset, "eps": "%.4f%%" % eps_percent}
    if client:
        body["client"] = client
    request = urllib.request.Request(url + "/api/fit", json.dumps(body).encode(),
                                     {"Content-Type": "application/json"})
    with urllib.request.urlopen(request) as answer:
        return json.load(answer)


def wait_for_end(url, job):
    while True:
        with urllib.request.urlopen("%s/api/jobs/%d" % (url, job["job"])) as answer:
            state = json.load(answer)
        if state["state"] in ("done", "failed"):
            return state
        time.sleep(0.01)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--url", required=True)
    parser.add_argument("--dataset", default="cranium")
    parser.add_argument("--trials", type=int, default=5, help="trials of each kind")
    parser.add_argument("--rest", type=float, default=0.2, help="seconds between the two requests")
    args = parser.parse_args()
    times = {"viewer": [], "plain": []}
    for i in range(args.trials):
        for kind in (["viewer", "plain"] if i % 2 == 0 else ["plain", "viewer"]):
            n = len(times["viewer"]) + len(times["plain"])
            x, y = 1.40 + 0.013 * n, 2.60 + 0.017 * n  # percent of the value range, new every trial
            client = "supersede%d" % n if kind == "viewer" else None
            first = post_fit(args.url, args.dataset, x, client)
            time.sleep(args.rest)
            start = time.monotonic()
            second = wait_for_end(args.url, post_fit(args.url, args.dataset, y, client))
            seconds = time.monotonic() - start
            first = wait_for_end(args.url, first)
            times[kind].append(seconds)
            print("%s: X %.3f %% %s, Y %.3f %% %s after %.0f ms" %
                  (kind, x, first["state"], y, second["state"], 1000 * seconds), flush=True)
    for kind, seconds in times.items():
        print("%s: median %.0f ms over %d" % (kind, 1000 * statistics.median(seconds), len(seconds)))


if __name__ == "__main__":
    main()
