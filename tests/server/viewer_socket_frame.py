#!/usr/bin/env python3
"""The viewer socket's first frame, for the shell tests: opens ws:// or wss:// (RFC 6455 by hand, the
standard library only), asks for one view and prints the frame's header JSON and the image's size."""
import argparse
import base64
import json
import os
import socket
import ssl
import struct
import sys
import urllib.parse


def read_exactly(sock, n):
    data = b''
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise EOFError('the server closed the socket')
        data += chunk
    return data


def send_text(sock, text):
    payload = text.encode()
    mask = os.urandom(4)
    header = bytes([0x81])
    if len(payload) < 126:
        header += bytes([0x80 | len(payload)])
    else:
        header += bytes([0x80 | 126]) + struct.pack('!H', len(payload))
    sock.sendall(header + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload)))


def read_message(sock):
    """(opcode, payload) of the next data message; pings are skipped (the server's keep-alive)."""
    while True:
        first, second = read_exactly(sock, 2)
        length = second & 0x7F
        if length == 126:
            length = struct.unpack('!H', read_exactly(sock, 2))[0]
        elif length == 127:
            length = struct.unpack('!Q', read_exactly(sock, 8))[0]
        payload = read_exactly(sock, length)
        opcode = first & 0x0F
        if opcode == 0x8:
            code = struct.unpack('!H', payload[:2])[0] if len(payload) >= 2 else 0
            raise EOFError(f'the server closed the socket with {code}: {payload[2:].decode(errors="replace")}')
        if opcode in (0x1, 0x2):
            return opcode, payload


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('url', help='ws://HOST:PORT/api/stream or wss://...')
    parser.add_argument('--dataset', required=True)
    parser.add_argument('--cacert', help='the CA to trust for wss://')
    parser.add_argument('--source', help='local address to connect from')
    parser.add_argument('--origin', help='Origin header (default: the URL\'s own origin)')
    args = parser.parse_args()

    url = urllib.parse.urlsplit(args.url)
    secure = url.scheme == 'wss'
    port = url.port or (443 if secure else 80)
    sock = socket.create_connection((url.hostname, port), timeout=60,
                                    source_address=(args.source, 0) if args.source else None)
    if secure:
        context = ssl.create_default_context(cafile=args.cacert)
        sock = context.wrap_socket(sock, server_hostname=url.hostname)
    key = base64.b64encode(os.urandom(16)).decode()
    origin = args.origin or f'{"https" if secure else "http"}://{url.netloc}'
    sock.sendall((f'GET {url.path or "/"}{"?" + url.query if url.query else ""} HTTP/1.1\r\n'
                  f'Host: {url.netloc}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n'
                  f'Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\nOrigin: {origin}\r\n\r\n').encode())
    head = b''
    while b'\r\n\r\n' not in head:
        head += read_exactly(sock, 1)
    status = head.split(b'\r\n', 1)[0].decode()
    if ' 101 ' not in status + ' ':
        print(f'upgrade refused: {head.decode(errors="replace")}', file=sys.stderr)
        return 1
    send_text(sock, json.dumps({'type': 'view', 'seq': 1, 'still': False,
                                'params': {'dataset': args.dataset, 'cam': 'az=30,el=20', 'size': '96x64',
                                           'mode': 'mip'}}))
    opcode, header = read_message(sock)
    if opcode != 0x1:
        print('the first message is not a frame header', file=sys.stderr)
        return 1
    opcode, image = read_message(sock)
    if opcode != 0x2:
        print('no image after the frame header', file=sys.stderr)
        return 1
    print(json.dumps({'header': json.loads(header), 'imageBytes': len(image)}))
    return 0


if __name__ == '__main__':
    sys.exit(main())
