#!/usr/bin/env python3
"""Hostile-connection load against a running `vots serve` on 127.0.0.1 (driven by hostile.sh and soak.sh).

goal: 8 clients rendering (a new camera angle per request), with and without 1,000 idle connections,
200 event-stream watchers and 200 idle viewer sockets (WebSockets on /api/stream that never send); probes /api/* every 100 ms. Both phases keep one fit running (a new eps when one
ends), so the only difference between them is the hostile connections; the watchers watch that fit.
soak: the same parts mixed for --seconds, plus eps changes, clients that disconnect mid-answer and viewers
dragging over the viewer socket (--draggers); samples the server's RSS and open descriptors. Exits 1 on any
failure (see the summary it prints).
With --tls-ca the server speaks HTTPS: every client goes through TLS, the idle connections are idle
handshakes, and --slow-handshakes / --half-handshakes add ClientHellos sent a byte at a time or cut in half.
"""
import argparse, http.client, json, multiprocessing, os, random, resource, socket, ssl, sys, threading, time
import urllib.parse

from hostile_connections import Hostiles
from viewer_drag import ViewerDrag

p = argparse.ArgumentParser()
p.add_argument("mode", choices=["goal", "soak"])
p.add_argument("--port", type=int, required=True)
p.add_argument("--pid", type=int, required=True)
p.add_argument("--dataset", default="mri-brain_33x41x25_int16")
p.add_argument("--eps", default="2%25")
p.add_argument("--size", default="256x256")
p.add_argument("--fit-dataset", default="cranium")
p.add_argument("--fit-eps", type=float, default=0.7, help="percent; long fits keep the watchers open")
p.add_argument("--renderers", type=int, default=8)
p.add_argument("--idle", type=int, default=1000)
p.add_argument("--watchers", type=int, default=200)
p.add_argument("--idle-sockets", type=int, default=200, help="viewer WebSockets that are opened and never used")
p.add_argument("--draggers", type=int, default=0, help="soak: viewers dragging over the viewer socket")
p.add_argument("--seconds", type=float, default=30)
p.add_argument("--sample-seconds", type=float, default=30)
p.add_argument("--errors-only", action="store_true", help="report the latency goals but fail only on errors")
p.add_argument("--tls-ca", help="the server speaks HTTPS with a certificate this CA signed")
p.add_argument("--slow-handshakes", type=int, default=0, help="TLS: ClientHellos sent one byte every 0.5 s")
p.add_argument("--half-handshakes", type=int, default=0, help="TLS: half a ClientHello, then silence")
a = p.parse_args()
tls = ssl.create_default_context(cafile=a.tls_ca) if a.tls_ca else None

soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
resource.setrlimit(resource.RLIMIT_NOFILE, (hard, hard))
errors = []  # every failure, as text
lock = threading.Lock()
stop_all = threading.Event()


def fail(text):
    with lock:
        if len(errors) < 200:
            errors.append(text)


def connect(source, timeout=None):
    """A connection to the server, through TLS when it speaks HTTPS (the handshake done, blocking)."""
    s = socket.create_connection(("127.0.0.1", a.port), source_address=(source, 0), timeout=timeout)
    return tls.wrap_socket(s, server_hostname="127.0.0.1") if tls else s


def request(method, target, body=None, source="127.0.0.1", timeout=120):
    """One exchange; returns (status, headers, body bytes, seconds). A non-JSON error is a failure."""
    if tls:
        c = http.client.HTTPSConnection("127.0.0.1", a.port, timeout=timeout, source_address=(source, 0),
                                        context=tls)
    else:
        c = http.client.HTTPConnection("127.0.0.1", a.port, timeout=timeout, source_address=(source, 0))
    start = time.monotonic()
    try:
        headers = {"Content-Type": "application/json"} if body is not None else {}
        c.request(method, target, body=body, headers=headers)
        r = c.getresponse()
        data = r.read()
        seconds = time.monotonic() - start
        if r.status >= 400:
            try:
                assert "error" in json.loads(data)
            except Exception:
                fail(f"{method} {target}: {r.status} without a JSON error: {data[:100]!r}")
        return r.status, r.getheaders(), data, seconds
    finally:
        c.close()


def percentile(values, q):
    if not values:
        return float("nan")
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q / 100 * (len(values) - 1))))]


class Fits:
    """Keeps one fit of --fit-dataset running: a new eps each time the last one has ended."""

    def __init__(self):
        self.job = None
        self.started = 0
        self.shared_job = multiprocessing.Value("q", 0)  # read by the hostiles' process

    def current(self):
        if self.job is not None:
            status, _, data, _ = request("GET", f"/api/jobs/{self.job}")
            if status == 200 and json.loads(data)["state"] in ("queued", "running"):
                return self.job
        # A new key each time (a repeated one would come from the cache), all of about the same cost.
        eps = a.fit_eps * (1 + 1e-4 * self.started + 1e-3 * random.random())
        body = json.dumps({"dataset": a.fit_dataset, "eps": f"{eps:.7f}%"})
        status, _, data, _ = request("POST", "/api/fit", body, source="127.0.0.250")
        if status != 202:
            fail(f"POST /api/fit: {status} {data[:100]!r}")
            return self.job
        self.job = json.loads(data)["job"]
        self.shared_job.value = self.job
        self.started += 1
        return self.job


def renderer(index, latencies, until, disconnect_every=0):
    source = f"127.0.0.{10 + index}"
    n = 0
    while time.monotonic() < until and not stop_all.is_set():
        n += 1
        az = (index * 100000 + n + random.random()) * 0.0137 % 360 - 180
        target = f"/render?dataset={a.dataset}&size={a.size}&eps={a.eps}&cam=az%3D{az:.5f}%2Cel%3D{20 + index}"
        if disconnect_every and n % disconnect_every == 0:  # a client that goes away mid-answer
            try:
                s = connect(source)
                s.sendall(f"GET {target} HTTP/1.1\r\nHost: 127.0.0.1:{a.port}\r\n\r\n".encode())
                s.close()
            except OSError as e:
                fail(f"disconnecting client: {e}")
            continue
        try:
            status, _, _, seconds = request("GET", target, source=source)
            if status == 200:
                latencies.append(seconds)
            else:
                fail(f"/render: {status}")
        except Exception as e:
            fail(f"/render: {e!r}")


def dragger(index, frames, until):
    """A viewer dragging over its socket from an address of its own: a frame at a new camera after each."""
    params = {"dataset": a.dataset, "size": a.size, "eps": urllib.parse.unquote(a.eps)}
    try:
        viewer = ViewerDrag(a.port, f"127.0.4.{index + 1}", params)
    except Exception as e:
        fail(f"viewer socket: {e!r}")
        return
    n = 0
    while time.monotonic() < until and not stop_all.is_set():
        n += 1
        try:
            viewer.frame(f"az={(index * 1000 + n) * 0.37 % 360 - 180:.3f},el={10 + index}")
            frames.append(1)
        except Exception as e:
            fail(f"viewer socket: {e!r}")
            break
    viewer.close()


def prober(latencies, until):
    while time.monotonic() < until and not stop_all.is_set():
        for target in ("/api/datasets", "/api/stats"):
            try:
                status, _, _, seconds = request("GET", target, source="127.0.0.251", timeout=30)
                latencies.append(seconds)
                if status != 200:
                    fail(f"{target}: {status}")
            except Exception as e:
                fail(f"{target}: {e!r}")
        time.sleep(0.1)


def hostiles_of(fits):
    counts = {"idle": a.idle, "watchers": a.watchers, "idle_sockets": a.idle_sockets,
              "slow_handshakes": a.slow_handshakes, "half_handshakes": a.half_handshakes}
    return Hostiles(fits.shared_job, a.port, connect, counts, tls, fail)


def server_sample():
    status = open(f"/proc/{a.pid}/status").read()
    rss = int(status.split("VmRSS:")[1].split()[0])
    fds = len(os.listdir(f"/proc/{a.pid}/fd"))
    threads = int(status.split("Threads:")[1].split()[0])
    return rss, fds, threads


def phase(name, seconds, fits, hostiles=None):
    until = time.monotonic() + seconds
    renders, probes = [], []
    threads = [threading.Thread(target=renderer, args=(i, renders, until)) for i in range(a.renderers)]
    threads.append(threading.Thread(target=prober, args=(probes, until)))
    for t in threads:
        t.start()
    while time.monotonic() < until:
        fits.current()
        time.sleep(1)
    for t in threads:
        t.join()
    extra = ""
    if hostiles:
        extra = (f", idle {hostiles.idle_open} (reopened {hostiles.reopened}), watchers {hostiles.watchers}, "
                 f"viewer sockets {hostiles.viewer_sockets}, unfinished TLS handshakes {hostiles.handshakes_open}")
    print(f"{name}: renders {len(renders)}, p50 {percentile(renders, 50) * 1000:.0f} ms, "
          f"p99 {percentile(renders, 99) * 1000:.0f} ms; /api/* {len(probes)}, p50 {percentile(probes, 50) * 1000:.1f} ms, "
          f"p99 {percentile(probes, 99) * 1000:.1f} ms, max {max(probes or [0]) * 1000:.1f} ms; fits started {fits.started}{extra}", flush=True)
    return renders, probes


def goal():
    request("GET", f"/render?dataset={a.dataset}&size={a.size}&eps={a.eps}")  # fit once
    fits = Fits()
    fits.current()  # the fit dataset loads before the first phase measures anything
    time.sleep(3)
    base_renders, base_probes = phase("without hostile connections", a.seconds, fits)
    fits.current()
    hostiles = hostiles_of(fits)
    hostiles.start()
    time.sleep(1)
    stats = json.loads(request("GET", "/api/stats")[2])
    print(f"server: {stats.get('connections')}, rss/fds/threads {server_sample()}", flush=True)
    renders, probes = phase("with hostile connections", a.seconds, fits, hostiles)
    rss, fds, threads = server_sample()
    print(f"server after: rss {rss} KiB, fds {fds}, threads {threads}", flush=True)
    hostiles.close()
    ratio = percentile(renders, 99) / percentile(base_renders, 99)
    print(f"/render p99 with / without: {ratio:.2f} (goal <= 1.20); /api/* max {max(probes) * 1000:.1f} ms (goal < 100)")
    return not errors and (a.errors_only or (ratio <= 1.2 and max(probes) < 0.1))


def soak():
    request("GET", f"/render?dataset={a.dataset}&size={a.size}&eps={a.eps}")
    fits = Fits()
    fits.current()
    hostiles = hostiles_of(fits)
    hostiles.start()
    until = time.monotonic() + a.seconds
    renders, probes = [], []
    threads = [threading.Thread(target=renderer, args=(i, renders, until, 7)) for i in range(a.renderers)]
    threads.append(threading.Thread(target=prober, args=(probes, until)))
    dragged = []
    threads += [threading.Thread(target=dragger, args=(i, dragged, until)) for i in range(a.draggers)]
    for t in threads:
        t.start()
    start = time.monotonic()
    next_sample = start
    print("minute  rss_kib  fds  threads  renders  watchers  idle  fits", flush=True)
    samples = []
    while time.monotonic() < until:
        fits.current()  # eps changes: a new fit whenever the last one ended
        if time.monotonic() >= next_sample:
            try:
                rss, fds, nthreads = server_sample()
            except FileNotFoundError:
                fail("the server died")
                break
            samples.append((rss, fds))
            print(f"{(time.monotonic() - start) / 60:6.1f}  {rss:7d}  {fds:4d}  {nthreads:7d}  {len(renders):7d}  "
                  f"{hostiles.watchers:8d}  {hostiles.idle_open:4d}  {fits.started:4d}", flush=True)
            next_sample += a.sample_seconds
        time.sleep(1)
    for t in threads:
        t.join()
    hostiles.close()
    time.sleep(6)  # the server closes what the hostiles left
    rss, fds, nthreads = server_sample()
    print(f"end: rss {rss} KiB, fds {fds}, threads {nthreads}; renders {len(renders)}, "
          f"p50 {percentile(renders, 50) * 1000:.0f} ms, p99 {percentile(renders, 99) * 1000:.0f} ms; "
          f"/api/* max {max(probes or [0]) * 1000:.1f} ms; socket frames {len(dragged)} by {a.draggers} dragging viewers")
    return not errors


ok = goal() if a.mode == "goal" else soak()
for e in errors[:20]:
    print("error:", e)
print(f"{a.mode}: {'OK' if ok else 'FAILED'} ({len(errors)} errors)")
sys.exit(0 if ok else 1)
