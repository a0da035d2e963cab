#!/usr/bin/env python3
"""/render latency of a running `vots serve`: p50/p99 and throughput with 1 and N concurrent clients.

Usage: bench/server_latency.py [--url http://127.0.0.1:8080] [--dataset NAME] [--size 512x512]
                               [--eps 2%] [--requests 20] [--clients 1,8] [--same-view]
Without --dataset it takes "cranium" when the server lists it, else the first dataset.
The first request fits the Vot-Space (timed separately). Every later frame uses a camera angle no
other request of the run uses, so the server's frame cache cannot answer any of them; with
--same-view every client asks for the same frames instead (the same angle for every client's i-th frame), the case the
frame cache and shared renders are for. Standard library only.
"""
import argparse
import http.client
import json
import statistics
import threading
import time
import urllib.parse


def get(conn, path):
    conn.request("GET", path)
    res = conn.getresponse()
    body = res.read()
    return res.status, dict(res.getheaders()), body


def percentile(values, p):
    ordered = sorted(values)
    k = min(len(ordered) - 1, max(0, round(p / 100.0 * (len(ordered) - 1))))
    return ordered[k]


def render_path(args, az, client):
    query = {"dataset": args.dataset, "size": args.size, "eps": args.eps,
             "cam": f"az={az},el=15", "client": client}
    return "/render?" + urllib.parse.urlencode(query)


def azimuth(args, clients, index, i, run):
    """A distinct angle per (run, client, frame), or with --same-view one per frame for all clients."""
    if args.same_view:
        return -180 + 7 * i + 0.5 * run
    return round(-180 + 360.0 * (index * args.requests + i) / (clients * args.requests) + 0.001 * run, 4)


def run_clients(args, host, port, clients, run):
    latencies, frame_ms, errors = [], [], []
    sources = {"miss": 0, "shared": 0, "hit": 0}
    lock = threading.Lock()

    def worker(index):
        conn = http.client.HTTPConnection(host, port, timeout=600)
        for i in range(args.requests):
            az = azimuth(args, clients, index, i, run)
            start = time.perf_counter()
            status, headers, _ = get(conn, render_path(args, az, f"bench{index}"))
            elapsed = (time.perf_counter() - start) * 1000.0
            with lock:
                if status == 200:
                    latencies.append(elapsed)
                    frame_ms.append(float(headers.get("X-Vots-Frame-Ms", "nan")))
                    sources[headers.get("X-Vots-Frame-Cache", "miss")] += 1
                else:
                    errors.append(status)
        conn.close()

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(clients)]
    wall = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    wall = time.perf_counter() - wall
    return latencies, frame_ms, errors, wall, sources


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--url", default="http://127.0.0.1:8080")
    parser.add_argument("--dataset")
    parser.add_argument("--size", default="512x512")
    parser.add_argument("--eps", default="2%")
    parser.add_argument("--requests", type=int, default=20, help="frames per client")
    parser.add_argument("--clients", default="1,8", help="comma-separated concurrency levels")
    parser.add_argument("--same-view", action="store_true",
                        help="all clients request the same frames (frame cache and shared renders)")
    args = parser.parse_args()
    url = urllib.parse.urlparse(args.url)
    host, port = url.hostname, url.port or 80

    conn = http.client.HTTPConnection(host, port, timeout=600)
    status, _, body = get(conn, "/api/datasets")
    names = [d["name"] for d in json.loads(body)["datasets"]] if status == 200 else []
    if not args.dataset:
        args.dataset = "cranium" if "cranium" in names else (names[0] if names else "")
    start = time.perf_counter()
    status, headers, body = get(conn, render_path(args, 0.123, "bench-warmup"))  # an angle no run uses
    if status != 200:
        raise SystemExit(f"warm-up /render failed: {status} {body[:200]!r}")
    print(f"dataset {args.dataset}, size {args.size}, eps {args.eps}: "
          f"{headers.get('X-Vots-Vot-Count')} Vots, fit {headers.get('X-Vots-Fit-Seconds')} s, "
          f"first request {time.perf_counter() - start:.2f} s")
    conn.close()

    for run, clients in enumerate(int(c) for c in args.clients.split(",")):
        latencies, frame_ms, errors, wall, sources = run_clients(args, host, port, clients, run)
        if not latencies:
            print(f"{clients} client(s): no successful frames, errors {errors}")
            continue
        print(f"{clients} client(s) x {args.requests} frames: p50 {percentile(latencies, 50):.1f} ms, "
              f"p99 {percentile(latencies, 99):.1f} ms, render-thread frame median "
              f"{statistics.median(frame_ms):.1f} ms, {len(latencies) / wall:.2f} frames/s, "
              f"answers rendered/shared/cached {sources['miss']}/{sources['shared']}/{sources['hit']}"
              + (f", {len(errors)} errors {sorted(set(errors))}" if errors else ""))


if __name__ == "__main__":
    main()
