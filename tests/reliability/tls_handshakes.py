"""Unfinished TLS handshakes for hostile_load.py: ClientHellos sent one byte every 0.5 s, or cut in half
and left there. Each is opened again when the server closes it (5 s without a request), or after 4.5 s,
as an attacker would keep them up."""
import socket
import ssl
import time


def client_hello():
    """The bytes a TLS client opens with, made without a socket."""
    context = ssl.create_default_context()
    context.check_hostname = False
    context.verify_mode = ssl.CERT_NONE
    outgoing = ssl.MemoryBIO()
    try:
        context.wrap_bio(ssl.MemoryBIO(), outgoing).do_handshake()
    except ssl.SSLWantReadError:
        pass
    return outgoing.read()


class UnfinishedHandshakes:
    """slow + half connections to 127.0.0.1:port from 127.0.4.x; fail(text) reports a failure, reopened
    (a shared counter) counts the connections opened again. Not thread-safe: one selector loop's."""

    def __init__(self, port, slow, half, fail, reopened):
        self.port = port
        self.fail = fail
        self.reopened = reopened
        self.hello = client_hello()
        self.open = []  # [socket, bytes still to send (None: half sent, then silent), opened at]
        for i in range(slow + half):
            self.begin(slow=i < slow)

    def begin(self, slow):
        try:
            source = f"127.0.4.{len(self.open) % 250 + 1}"
            s = socket.create_connection(("127.0.0.1", self.port), source_address=(source, 0))
            s.setblocking(False)
            if not slow:
                s.send(self.hello[:len(self.hello) // 2])
            self.open.append([s, self.hello if slow else None, time.monotonic()])
        except OSError as e:
            self.fail(f"TLS handshake connection: {e}")

    def advance(self):
        """Slow ones send their next byte; those the server closed, or older than 4.5 s, begin again."""
        now = time.monotonic()
        ended = []
        for entry in self.open:
            s, rest, opened = entry
            try:
                if rest:
                    s.send(rest[:1])
                    entry[1] = rest[1:]
                closed = s.recv(1, socket.MSG_PEEK) == b""
            except BlockingIOError:
                closed = False
            except OSError:
                closed = True
            if closed or now - opened > 4.5:
                ended.append(entry)
        for entry in ended:
            self.open.remove(entry)
            entry[0].close()
            self.reopened.value += 1
            self.begin(slow=entry[1] is not None)

    def close(self):
        for s, _, _ in self.open:
            s.close()
        self.open = []
