#!/usr/bin/env python3
"""How many Vot boxes the rays of a view cross, summed over the image, for .vots files side by side.

    python3 bench/vot_crossings.py A.vots B.vots [C.vots D.vots ...] [--view az,el ...]

The walk takes one step per Vot box a ray crosses (stepped over by its bound or evaluated), so its Vot
steps follow the boxes' summed projected area along the view, not their count: a box of extents
(x, y, z) seen along the unit direction d casts |d_x| y z + |d_y| x z + |d_z| x y of image area, and
the rays that cross it are those that land in that area. The sum over a file's boxes is the total number
of box crossings for rays spaced one mm apart; the ratio of two files' sums, for the same volume and
view, is the ratio of their walks' Vot steps. Files are compared in pairs (B against A, D against C).
The direction follows the camera's az/el (render/src/Camera.cpp); the sum depends only on the sizes of
its components, so the index axes' signs do not matter.
"""
import argparse
import math
import struct

HEADER_BYTES = 128
RECORD_BYTES = 120
VIEWS = {"anterior": (0.0, 0.0), "oblique": (30.0, 20.0), "lateral": (90.0, 0.0), "axial": (0.0, 90.0)}


def box_extents(path):
    """The world extents (mm) of every Vot box in a .vots file (docs/DESIGN.md, section 8)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"VOTS":
        raise SystemExit(f"{path}: not a .vots file")
    spacing = struct.unpack_from("<3d", data, 48)
    count = struct.unpack_from("<Q", data, 88)[0]
    if len(data) < HEADER_BYTES + count * RECORD_BYTES:
        raise SystemExit(f"{path}: shorter than its {count} records")
    extents = []
    for lo_x, lo_y, lo_z, hi_x, hi_y, hi_z in struct.iter_unpack(
        "<6i" + "x" * (RECORD_BYTES - 24), data[HEADER_BYTES : HEADER_BYTES + count * RECORD_BYTES]
    ):
        extents.append(((hi_x - lo_x) * spacing[0], (hi_y - lo_y) * spacing[1], (hi_z - lo_z) * spacing[2]))
    return extents


def crossings(extents, az_deg, el_deg):
    """The boxes' summed projected area along the view (mm^2): box crossings of rays 1 mm apart."""
    az, el = math.radians(az_deg), math.radians(el_deg)
    d = (abs(math.sin(az) * math.cos(el)), abs(math.cos(az) * math.cos(el)), abs(math.sin(el)))
    return sum(d[0] * y * z + d[1] * x * z + d[2] * x * y for x, y, z in extents)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", help=".vots files, compared in pairs (B against A)")
    parser.add_argument("--view", action="append", help="az,el in degrees, or a name: " + ", ".join(VIEWS))
    args = parser.parse_args()
    views = {}
    for v in args.view or ["anterior", "oblique"]:
        views[v] = VIEWS[v] if v in VIEWS else tuple(float(x) for x in v.split(","))
    boxes = [box_extents(path) for path in args.files]
    print("| view | file | Vots | crossings (rays 1 mm apart) | against the pair's first: Vots | crossings |")
    print("|---|---|---|---|---|---|")
    for name, (az, el) in views.items():
        sums = [crossings(extents, az, el) for extents in boxes]
        for k, path in enumerate(args.files):
            first = k - k % 2
            ratio = " | "
            if k != first:
                ratio = f"{len(boxes[k]) / len(boxes[first]):.3f} | {sums[k] / sums[first]:.3f}"
            print(f"| {name} | {path} | {len(boxes[k]):,} | {sums[k]:,.0f} | {ratio} |")


if __name__ == "__main__":
    main()
