#!/usr/bin/env python3
"""/render latency of a running `vots serve`: p50/p99 and throughput with 1 and N concurrent clients.

Usage: bench/server_latency.py [--url http://127.0.0.1:8080] [--dataset NAME] [--size 512x512]
                               [--eps 2%] [--requests 20] [--clients 1,8]
Without --dataset it takes "cranium" when the server lists it, else the first dataset.
The first request fits the Vot-Space (timed separately); every later frame uses a new camera angle
so no layer can answer from a cache of images. Standard library only.
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


def run_clients(args, host, port, clients):
    latencies, frame_ms, errors = [], [], []
    lock = threading.Lock()

    def worker(index):
        conn = http.client.HTTPConnection(host, port, timeout=600)
        for i in range(args.requests):
            az = (index * 37 + i * 11) % 360 - 180
            start = time.perf_counter()
            status, headers, _ = get(conn, render_path(args, az, f"bench{index}"))
            elapsed = (time.perf_counter() - start) * 1000.0
            with lock:
                if status == 200:
                    latencies.append(elapsed)
                    frame_ms.append(float(headers.get("X-Vots-Frame-Ms", "nan")))
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
    return latencies, frame_ms, errors, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--url", default="http://127.0.0.1:8080")
    parser.add_argument("--dataset")
    parser.add_argument("--size", default="512x512")
    parser.add_argument("--eps", default="2%")
    parser.add_argument("--requests", type=int, default=20, help="frames per client")
    parser.add_argument("--clients", default="1,8", help="comma-separated concurrency levels")
    args = parser.parse_args()
    url = urllib.parse.urlparse(args.url)
    host, port = url.hostname, url.port or 80

    conn = http.client.HTTPConnection(host, port, timeout=600)
    status, _, body = get(conn, "/api/datasets")
    names = [d["name"] for d in json.loads(body)["datasets"]] if status == 200 else []
    if not args.dataset:
        args.dataset = "cranium" if "cranium" in names else (names[0] if names else "")
    start = time.perf_counter()
    status, headers, body = get(conn, render_path(args, 0, "bench-warmup"))
    if status != 200:
        raise SystemExit(f"warm-up /render failed: {status} {body[:200]!r}")
    print(f"dataset {args.dataset}, size {args.size}, eps {args.eps}: "
          f"{headers.get('X-Vots-Vot-Count')} Vots, fit {headers.get('X-Vots-Fit-Seconds')} s, "
          f"first request {time.perf_counter() - start:.2f} s")
    conn.close()

    for clients in (int(c) for c in args.clients.split(",")):
        latencies, frame_ms, errors, wall = run_clients(args, host, port, clients)
        if not latencies:
            print(f"{clients} client(s): no successful frames, errors {errors}")
            continue
        print(f"{clients} client(s) x {args.requests} frames: p50 {percentile(latencies, 50):.1f} ms, "
              f"p99 {percentile(latencies, 99):.1f} ms, render-thread frame median "
              f"{statistics.median(frame_ms):.1f} ms, {len(latencies) / wall:.2f} frames/s"
              + (f", {len(errors)} errors {sorted(set(errors))}" if errors else ""))


if __name__ == "__main__":
    main()
