"""A viewer dragging over the viewer socket (GET /api/stream, docs/API.md "Viewer socket") with the standard
library alone, for the soak: one view at a time at a new camera, every frame acknowledged, each 20th view a
still. Raises on an error answer, a close or a timeout."""
import base64, json, os, socket, struct

TEXT, BINARY, CLOSE, PING, PONG = 0x1, 0x2, 0x8, 0x9, 0xA


class ViewerDrag:
    def __init__(self, port, source, params, timeout=120):
        """params: the /render parameters as strings, without cam."""
        self.sock = socket.create_connection(("127.0.0.1", port), source_address=(source, 0), timeout=timeout)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall((f"GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                           f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise OSError("the server closed the socket during the upgrade")
            head += chunk
        if not head.startswith(b"HTTP/1.1 101"):
            raise OSError(f"the upgrade was answered {head[:40]!r}")
        self.buffer = head.split(b"\r\n\r\n", 1)[1]
        self.params = params
        self.seq = 0

    def send(self, opcode, payload):
        """One masked frame, as a client must send (RFC 6455, 5.3)."""
        mask = os.urandom(4)
        n = len(payload)
        length = bytes([0x80 | n]) if n < 126 else bytes([0x80 | 126]) + struct.pack("!H", n)
        self.sock.sendall(bytes([0x80 | opcode]) + length + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload)))

    def read_exact(self, n):
        while len(self.buffer) < n:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise OSError("the server closed the socket")
            self.buffer += chunk
        out, self.buffer = self.buffer[:n], self.buffer[n:]
        return out

    def read_message(self):
        """(opcode, payload) of the next whole message; pings are answered on the way."""
        opcode, payload = None, b""
        while True:
            b0, b1 = self.read_exact(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack("!H", self.read_exact(2))[0]
            elif n == 127:
                n = struct.unpack("!Q", self.read_exact(8))[0]
            data = self.read_exact(n)
            if b0 & 0x0F == PING:
                self.send(PONG, data)
                continue
            opcode = opcode if b0 & 0x0F == 0 else b0 & 0x0F  # 0: the continuation of a fragmented message
            payload += data
            if b0 & 0x80:
                return opcode, payload

    def frame(self, cam, still=None):
        """Asks for the view at cam (a still if `still`; by default each 20th) and acknowledges its frame;
        returns the frame's header."""
        self.seq += 1
        still = self.seq % 20 == 0 if still is None else still
        view = {"type": "view", "seq": self.seq, "still": still, "params": {**self.params, "cam": cam}}
        self.send(TEXT, json.dumps(view).encode())
        return self.next_frame()

    def next_frame(self, send_json=None):
        """Reads up to the next frame (its header, then its image), acknowledges it and returns the header;
        raises on an error answer or a close. send_json: how the ack goes out (a caller whose other thread
        sends too passes one that locks)."""
        send_json = send_json or (lambda message: self.send(TEXT, json.dumps(message).encode()))
        header = None
        while True:
            opcode, payload = self.read_message()
            if opcode == CLOSE:
                raise OSError(f"closed by the server: {payload[:2].hex()} {payload[2:]!r}")
            if opcode == TEXT:
                message = json.loads(payload)
                if message.get("type") == "error":
                    raise RuntimeError(f"answered {message}")
                header = message
            elif opcode == BINARY and header is not None:
                send_json({"type": "ack", "frame": header["frame"]})
                return header

    def close(self):
        self.sock.close()
