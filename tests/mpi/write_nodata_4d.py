#!/usr/bin/env python3
"""Writes a float32 NIfTI-1 of 2 frames, 24x20x16, for the mpi tests of frames and no data: values 10..110
in a ball (brighter and larger in frame 1), a NaN block in the upper z planes (rank 1's of 2), the lowest
finite sample (-50) at one corner of plane 0 (rank 0's). Usage: write_nodata_4d.py OUT.nii"""
import math
import struct
import sys

NX, NY, NZ, FRAMES = 24, 20, 16, 2


def main():
    header = bytearray(352)
    struct.pack_into("<i", header, 0, 348)
    struct.pack_into("<8h", header, 40, 4, NX, NY, NZ, FRAMES, 1, 1, 1)
    struct.pack_into("<hh", header, 70, 16, 32)  # float32
    struct.pack_into("<8f", header, 76, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<f", header, 108, 352.0)
    header[344:348] = b"n+1\0"
    samples = []
    for t in range(FRAMES):
        for z in range(NZ):
            for y in range(NY):
                for x in range(NX):
                    r = math.sqrt((x - 11.5) ** 2 + (y - 9.5) ** 2 + (z - 7.5) ** 2)
                    value = 10.0 + (60.0 + 40.0 * t) * max(0.0, 1.0 - r / (6.0 + 2.0 * t))
                    if 11 <= z <= 13 and 5 <= x <= 17 and 4 <= y <= 15:
                        value = float("nan")
                    if (x, y, z) == (0, 0, 0):
                        value = -50.0
                    samples.append(value)
    with open(sys.argv[1], "wb") as out:
        out.write(header)
        out.write(struct.pack("<%df" % len(samples), *samples))


main()
