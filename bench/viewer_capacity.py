#!/usr/bin/env python3
"""Benchmark: how many draft frames the server itself gives N viewers dragging at once over the viewer
socket, without browsers on the same cores (bench/stream_drag.mjs measures the pages too).

    python3 bench/viewer_capacity.py --port 8080 --viewers 8 --seconds 10 [--pid SERVER_PID] [--one-address]
        [--pace closed|page]

Each viewer (a thread, from an address of its own unless --one-address) asks for a draft at a new camera as
soon as the last one has come and acknowledges it (one frame in flight), or with --pace page sends a view
every 16 ms and acknowledges each frame as it comes (the page's pacing: the server keeps up to two in
flight); the cameras are distinct per viewer and per run, so the frame cache answers nothing. Prints per
viewer the drafts per second, their median size and the server's median times (waitMs, frameMs, encodeMs,
drawMs), and with --pid the server's CPU use over the run."""
import argparse, json, os, statistics, sys, threading, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "reliability"))
from viewer_drag import TEXT, ViewerDrag  # noqa: E402


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


MOVE_EVERY_S = 0.016  # --pace page: a 60 Hz mouse


def camera(start_az, index, n):
    az = (start_az + 45 * index + 0.5 * n) % 360 - 180
    return f"az={az:.2f},el={10 + index},zoom=1,pan=0:0,proj=ortho,fov=30"


def drag(index, args, start_az, until, out):
    params = {"dataset": args.dataset, "size": args.size}
    source = "127.0.0.1" if args.one_address else f"127.0.5.{index + 1}"
    viewer = ViewerDrag(args.port, source, params)
    headers, n = [], 0
    if args.pace == "closed":
        while time.monotonic() < until:
            n += 1
            headers.append(viewer.frame(camera(start_az, index, n), still=False))
    else:
        drag_as_a_page(viewer, params, start_az, index, until, headers)
    viewer.close()
    out[index] = headers


def drag_as_a_page(viewer, params, start_az, index, until, headers):
    """Views at 60 Hz whatever the frames do (the server draws the latest), each frame acknowledged as it
    comes, as the viewer page does."""
    sending = threading.Lock()  # the views and the acknowledgements share the socket

    def send(message):
        with sending:
            viewer.send(TEXT, json.dumps(message).encode())

    def views():
        n = 0
        while time.monotonic() < until:
            n += 1
            send({"type": "view", "seq": n, "still": False, "params": {**params, "cam": camera(start_az, index, n)}})
            time.sleep(MOVE_EVERY_S)

    sender = threading.Thread(target=views)
    sender.start()
    while time.monotonic() < until:
        headers.append(viewer.next_frame(send))
    sender.join()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--port", type=int, default=8080)
    ap.add_argument("--dataset", default="cranium")
    ap.add_argument("--size", default="1140x900", help="the full frame (the drafts are the server's choice)")
    ap.add_argument("--viewers", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=10)
    ap.add_argument("--pid", type=int, help="the server's process id, for its CPU use")
    ap.add_argument("--one-address", action="store_true", help="every viewer from 127.0.0.1")
    ap.add_argument("--pace", choices=("closed", "page"), default="closed",
                    help="closed: the next view once the last frame came (one in flight); page: views at 60 Hz "
                         "and every frame acknowledged as it comes, as the viewer page does")
    args = ap.parse_args()

    start_az = (time.time() * 7) % 360  # a new camera path per run: nothing from the frame cache
    out = [None] * args.viewers
    cpu0 = cpu_seconds(args.pid) if args.pid else None
    began = time.monotonic()
    until = began + args.seconds
    threads = [threading.Thread(target=drag, args=(i, args, start_az, until, out)) for i in range(args.viewers)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    wall = time.monotonic() - began
    rates = []
    for i, headers in enumerate(out):
        if not headers:
            print(f"viewer {i + 1}: no frames")
            continue
        med = lambda key: statistics.median(h.get(key, float("nan")) for h in headers)  # noqa: E731
        rate = len(headers) / wall
        rates.append(rate)
        print(f"viewer {i + 1}: {rate:.1f} drafts/s at {med('width'):.0f}x{med('height'):.0f}, server ms: "
              f"wait {med('waitMs'):.1f}, render {med('frameMs'):.1f}, encode {med('encodeMs'):.1f}, "
              f"draw {med('drawMs'):.1f}")
    line = f"{args.viewers} viewers: {min(rates):.1f}-{max(rates):.1f} drafts/s each, {sum(rates):.1f} in all"
    if cpu0 is not None:
        line += f"; server CPU {(cpu_seconds(args.pid) - cpu0) / wall:.2f} cores"
    print(line)


if __name__ == "__main__":
    main()
