#!/usr/bin/env python3
"""How two PNGs of one size differ: prints "MAX COUNT", the largest difference of any channel and the
number of pixels that differ at all. Exit 2 when they cannot be compared (size, channels)."""
import sys

from PIL import Image, ImageChops


def main():
    a, b = (Image.open(path) for path in sys.argv[1:3])
    if (a.size, a.mode) != (b.size, b.mode):
        print(f"{sys.argv[1]} is {a.size} {a.mode}, {sys.argv[2]} {b.size} {b.mode}", file=sys.stderr)
        sys.exit(2)
    diff = ImageChops.difference(a, b)
    bands = diff.split()
    worst = max(band.getextrema()[1] for band in bands)
    # A pixel differs when any of its channels does: the largest channel difference per pixel, nonzero.
    per_pixel = bands[0]
    for band in bands[1:]:
        per_pixel = ImageChops.lighter(per_pixel, band)
    differing = sum(per_pixel.point(lambda v: 1 if v else 0).histogram()[1:])
    print(worst, differing)


main()
