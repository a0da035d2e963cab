"""Hostile connections for hostile_load.py, in a process of their own: idle connections (reopened as the
server closes them), event-stream watchers of the running fit, silent viewer sockets and, over TLS,
unfinished handshakes."""
import multiprocessing, selectors, socket, ssl, time

from tls_handshakes import UnfinishedHandshakes


class Hostiles:
    """Idle sockets and event-stream watchers, in a process of their own (one selector loop), so that
    the measuring clients share no interpreter lock with them; counts come back through shared values."""

    def __init__(self, job, port, connect, counts, tls, report):
        """job: the shared value naming the fit to watch; connect(source, timeout): a connection to the
        server (through TLS when tls); counts: idle, watchers, idle_sockets, slow_handshakes, half_handshakes;
        report(text): the parent's failure list."""
        self.job = job
        self.port = port
        self.connect = connect
        self.counts = counts
        self.tls = tls
        self.report = report
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
            self.report("the hostile connections were not all opened within 120 s (or their process died)")

    def run(self):
        self.sel = selectors.DefaultSelector()
        self.open_idle(self.counts["idle"])
        if self.tls:
            self.handshakes = UnfinishedHandshakes(self.port, self.counts["slow_handshakes"], self.counts["half_handshakes"],
                                                   self.fail, self.reopen_count)
            self.handshake_count.value = len(self.handshakes.open)
        for _ in range(self.counts["watchers"]):
            try:
                self.open_watcher()
            except OSError as e:
                self.fail(f"watcher: {e}")
        for i in range(self.counts["idle_sockets"]):
            try:
                self.open_viewer_socket()
            except OSError as e:
                self.fail(f"viewer socket {i}: {e}")
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
                s = socket.create_connection(("127.0.0.1", self.port), source_address=(f"127.0.1.{i % 250 + 1}", 0))
                self.idle.append((s, time.monotonic()))
            except OSError as e:
                self.fail(f"idle connection {i}: {e}")
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
                    s = socket.create_connection(("127.0.0.1", self.port))
                    opened = now
                    self.reopen_count.value += 1
                except OSError as e:
                    self.fail(f"reopening an idle connection: {e}")
                    continue
            kept.append((s, opened))
        self.idle = kept
        self.open_idle_count.value = len(kept)

    def open_watcher(self):
        job = self.job.value  # the fit the load runs (both phases start the same fits)
        s = self.connect("127.0.2.1")
        s.sendall(f"GET /api/jobs/{job}/events HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\n\r\n".encode())
        s.setblocking(False)
        self.sel.register(s, selectors.EVENT_READ, bytearray())
        self.watcher_count.value += 1

    def open_viewer_socket(self):
        """A viewer's WebSocket that is upgraded and then left silent (32 at most per address: spread)."""
        self.sockets_opened += 1
        source = f"127.0.3.{self.sockets_opened % 250 + 1}"
        s = self.connect(source, timeout=30)
        s.sendall((f"GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1:{self.port}\r\nUpgrade: websocket\r\n"
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
            self.fail(f"viewer socket answered {head[:40]!r}")
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
                            self.fail(f"viewer socket: {e}")
                    continue  # a ping: left unanswered, as a frozen page would
                if data:
                    if len(key.data) < 16:
                        key.data.extend(data)
                        if len(key.data) >= 12 and not key.data.startswith(b"HTTP/1.1 200"):
                            self.fail(f"watcher answered {bytes(key.data[:40])!r}")
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
                    self.fail(f"watcher: {e}")
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
            self.report(self.errors.get())

    def fail(self, text):
        """In the child process: the failure goes to the parent, which lists it at close()."""
        self.errors.put(text)
