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
import argparse, http.client, json, multiprocessing, os, random, resource, selectors, socket, ssl, sys, threading, time
import urllib.parse

from tls_handshakes import UnfinishedHandshakes
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


class Hostiles:
    """Idle sockets and event-stream watchers, in a process of their own (one selector loop), so that
    the measuring clients share no interpreter lock with them; counts come back through shared values."""

    def __init__(self, fits):
        self.job = fits.shared_job
        self.idle = []
        self.handshakes = None  # UnfinishedHandshakes, in the child process
        self.handshake_count = multiprocessing.Value("q", 0)
        self.due = []  # when closed watchers come back: a browser's EventSource retries after 3 s
        self.open_idle_count = multiprocessing.Value("q", 0)
        self.watcher_count = multiprocessing.Value("q", 0)
        self.socket_count = multiprocessing.Value("q", 0)
        self.sockets_opened = 0  # spreads the viewer sockets over source addresses
        self.reopen_count = multiprocessing.Value("q", 0)
        self.stop = multiprocessing.Event()
        self.ready = multiprocessing.Event()
        self.errors = multiprocessing.Queue()
        self.process = multiprocessing.Process(target=self.run, daemon=True)

    def start(self):
        self.process.start()
        if not self.ready.wait(120):
            fail("the hostile connections were not all opened within 120 s (or their process died)")

    def run(self):
        global fail
        fail = lambda text: self.errors.put(text)  # noqa: E731 (the child's failures go to the parent)
        self.sel = selectors.DefaultSelector()
        self.open_idle(a.idle)
        if tls:
            self.handshakes = UnfinishedHandshakes(a.port, a.slow_handshakes, a.half_handshakes,
                                                   lambda text: fail(text), self.reopen_count)
            self.handshake_count.value = len(self.handshakes.open)
        for _ in range(a.watchers):
            try:
                self.open_watcher()
            except OSError as e:
                fail(f"watcher: {e}")
        for i in range(a.idle_sockets):
            try:
                self.open_viewer_socket()
            except OSError as e:
                fail(f"viewer socket {i}: {e}")
        self.ready.set()
        self.loop()
        for key in list(self.sel.get_map().values()):
            key.fileobj.close()
        for s, _ in self.idle:
            s.close()
        if self.handshakes:
            self.handshakes.close()

    @property
    def watchers(self):
        return self.watcher_count.value

    @property
    def viewer_sockets(self):
        return self.socket_count.value

    @property
    def reopened(self):
        return self.reopen_count.value

    @property
    def idle_open(self):
        return self.open_idle_count.value

    @property
    def handshakes_open(self):
        return self.handshake_count.value

    def open_idle(self, count):
        for i in range(count):
            try:
                s = socket.create_connection(("127.0.0.1", a.port), source_address=(f"127.0.1.{i % 250 + 1}", 0))
                self.idle.append((s, time.monotonic()))
            except OSError as e:
                fail(f"idle connection {i}: {e}")
                break
        self.open_idle_count.value = len(self.idle)

    def refresh_idle(self):
        """The server closes a connection that sent nothing for 5 s: an attacker simply opens another."""
        now = time.monotonic()
        kept = []
        for s, opened in self.idle:
            if now - opened > 4.5:
                s.close()
                try:
                    s = socket.create_connection(("127.0.0.1", a.port))
                    opened = now
                    self.reopen_count.value += 1
                except OSError as e:
                    fail(f"reopening an idle connection: {e}")
                    continue
            kept.append((s, opened))
        self.idle = kept
        self.open_idle_count.value = len(kept)

    def open_watcher(self):
        job = self.job.value  # the fit the load runs (both phases start the same fits)
        s = connect("127.0.2.1")
        s.sendall(f"GET /api/jobs/{job}/events HTTP/1.1\r\nHost: 127.0.0.1:{a.port}\r\n\r\n".encode())
        s.setblocking(False)
        self.sel.register(s, selectors.EVENT_READ, bytearray())
        self.watcher_count.value += 1

    def open_viewer_socket(self):
        """A viewer's WebSocket that is upgraded and then left silent (32 at most per address: spread)."""
        self.sockets_opened += 1
        source = f"127.0.3.{self.sockets_opened % 250 + 1}"
        s = connect(source, timeout=30)
        s.sendall((f"GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1:{a.port}\r\nUpgrade: websocket\r\n"
                   "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                   "Sec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head and len(head) < 4096:
            chunk = s.recv(4096)
            if not chunk:
                break
            head += chunk
        if not head.startswith(b"HTTP/1.1 101"):
            s.close()
            fail(f"viewer socket answered {head[:40]!r}")
            return
        s.setblocking(False)
        self.sel.register(s, selectors.EVENT_READ, "socket")
        self.socket_count.value += 1

    def loop(self):
        last_refresh = time.monotonic()
        while not self.stop.is_set():
            for key, _ in self.sel.select(timeout=0.2):
                s = key.fileobj
                try:
                    data = s.recv(65536)
                except (BlockingIOError, ssl.SSLWantReadError, ssl.SSLWantWriteError):
                    continue
                except OSError:
                    data = b""
                if key.data == "socket":
                    if not data:  # closed by the server (idle for a minute): open another
                        self.sel.unregister(s)
                        s.close()
                        self.socket_count.value -= 1
                        try:
                            self.open_viewer_socket()
                        except OSError as e:
                            fail(f"viewer socket: {e}")
                    continue  # a ping: left unanswered, as a frozen page would
                if data:
                    if len(key.data) < 16:
                        key.data.extend(data)
                        if len(key.data) >= 12 and not key.data.startswith(b"HTTP/1.1 200"):
                            fail(f"watcher answered {bytes(key.data[:40])!r}")
                    continue
                self.sel.unregister(s)  # the fit ended: watch the next one, as a browser would
                s.close()
                self.watcher_count.value -= 1
                self.due.append(time.monotonic() + 3)
            now = time.monotonic()
            while self.due and self.due[0] <= now:
                self.due.pop(0)
                try:
                    self.open_watcher()
                except OSError as e:
                    fail(f"watcher: {e}")
            if time.monotonic() - last_refresh > 0.5:
                self.refresh_idle()
                if self.handshakes:
                    self.handshakes.advance()
                    self.handshake_count.value = len(self.handshakes.open)
                last_refresh = time.monotonic()

    def close(self):
        self.stop.set()
        self.process.join(30)
        while not self.errors.empty():
            fail(self.errors.get())


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
    hostiles = Hostiles(fits)
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
    hostiles = Hostiles(fits)
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
