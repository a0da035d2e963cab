#!/usr/bin/env python3
"""A loopback HTTP proxy in front of Orthanc that breaks answers on purpose, for the pacs tests.

One request per connection (it asks Orthanc to close), then one of these faults:
  --cut N            drop the connection after N bytes of a multipart answer (a retrieve)
  --refuse-series    answer 503 to a series-level retrieve (GET .../series/UID), pass everything else
  --refuse-store     answer 503 to a store (STOW-RS: POST .../studies) without reading its body
  --stall N          send N bytes of a multipart answer, then nothing more until the client hangs up
  --garble           break the part headers of multipart answers ("Content-Type application/dicom")
  (none)             pass everything unchanged
  --tls CERT KEY     serve HTTPS with this certificate (Debian's Orthanc 1.10 crashes on its own TLS)
Usage: fault_proxy.py --target PORT --port-file FILE [--log FILE] [fault]   (writes its port to FILE once
listening; --log gets each request line, with REFUSED or CUT when the fault struck it)
"""
import argparse
import os
import re
import socket
import socketserver
import ssl
import threading

SERIES_RETRIEVE = re.compile(rb"^GET [^ ]*/studies/[0-9.]+/series/[0-9.]+ HTTP/1\.[01]$")
STORE = re.compile(rb"^POST [^ ]*/studies HTTP/1\.[01]$")


def read_head(sock):
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        if not chunk:
            return None, b""
        data += chunk
    head, rest = data.split(b"\r\n\r\n", 1)
    return head, rest


class Handler(socketserver.BaseRequestHandler):
    def handle(self):
        options = self.server.options
        head, rest = read_head(self.request)
        if head is None:
            return
        lines = head.split(b"\r\n")
        if (options.refuse_series and SERIES_RETRIEVE.match(lines[0])) or (
            options.refuse_store and STORE.match(lines[0])
        ):
            self.server.log(lines[0], "REFUSED")
            self.request.sendall(b"HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")
            return
        lines = [l for l in lines if not l.lower().startswith(b"connection:")] + [b"Connection: close"]
        upstream = socket.create_connection(("127.0.0.1", options.target))
        upstream.sendall(b"\r\n".join(lines) + b"\r\n\r\n" + rest)
        sent = 0
        multipart = None
        try:
            while True:
                chunk = upstream.recv(65536)
                if not chunk:
                    break
                if multipart is None:
                    head = chunk.split(b"\r\n\r\n", 1)[0]
                    multipart = b"multipart/" in head.lower()
                    # This connection ends with the answer, whatever Orthanc offers.
                    chunk = re.sub(rb"(?im)^connection: *keep-alive", b"Connection: close", head) + chunk[len(head):]
                if options.stall is not None and multipart and sent + len(chunk) >= options.stall:
                    self.request.sendall(chunk[: options.stall - sent])
                    self.server.log(lines[0], "STALLED")
                    self.request.recv(1)  # returns when the client hangs up
                    return
                if options.garble and multipart:
                    chunk = chunk.replace(b"Content-Type: application/dicom", b"Content-Type application/dicom")
                if options.cut is not None and multipart and sent + len(chunk) >= options.cut:
                    self.request.sendall(chunk[: options.cut - sent])
                    self.server.log(lines[0], "CUT")
                    return
                self.request.sendall(chunk)
                sent += len(chunk)
            self.server.log(lines[0], "PASSED")
        finally:
            upstream.close()


class Server(socketserver.ThreadingTCPServer):
    daemon_threads = True
    allow_reuse_address = True
    log_file = None
    lock = threading.Lock()

    def log(self, request_line, outcome):
        if self.log_file:
            with self.lock, open(self.log_file, "a") as f:
                f.write(request_line.decode("latin-1") + " " + outcome + "\n")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--target", type=int, required=True)
    parser.add_argument("--port-file", required=True)
    parser.add_argument("--cut", type=int)
    parser.add_argument("--refuse-series", action="store_true")
    parser.add_argument("--refuse-store", action="store_true")
    parser.add_argument("--garble", action="store_true")
    parser.add_argument("--stall", type=int)
    parser.add_argument("--log")
    parser.add_argument("--tls", nargs=2, metavar=("CERT", "KEY"))
    options = parser.parse_args()
    server = Server(("127.0.0.1", 0), Handler)
    if options.tls:
        context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
        context.load_cert_chain(*options.tls)
        server.socket = context.wrap_socket(server.socket, server_side=True)
    server.options = options
    server.log_file = options.log
    with open(options.port_file + ".tmp", "w") as f:
        f.write(str(server.server_address[1]))
    os.replace(options.port_file + ".tmp", options.port_file)
    server.serve_forever()


if __name__ == "__main__":
    main()
