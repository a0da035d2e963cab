#!/usr/bin/env python3
"""An independent reading of a volume file with nibabel, for tests/fit/test_OtherToolsVolumes.cpp.

Usage: nibabel_reference.py PATH FRAME
Prints one JSON object: dims (of one frame), frames, zooms, the affine in LPS (3 rows of 4), the count
of NaN/Inf samples, the sum of the finite ones, and (i, j, k, value) at a spread of grid points (value
null where it is NaN or Inf).
"""
import json
import sys

import nibabel
import numpy


def main():
    path, frame = sys.argv[1], int(sys.argv[2])
    image = nibabel.load(path)
    data = numpy.asarray(image.dataobj, dtype=numpy.float64)
    frames = 1
    if data.ndim > 3:
        frames = int(numpy.prod(data.shape[3:]))
        data = data.reshape(data.shape[:3] + (frames,), order="F")[..., frame]
    affine = numpy.array(image.affine, dtype=numpy.float64)
    affine[:2, :] *= -1.0  # RAS to LPS
    finite = numpy.isfinite(data)
    samples = []
    dims = data.shape
    for n in range(24):
        i, j, k = (n * 7) % dims[0], (n * 11) % dims[1], (n * 5) % dims[2]
        value = data[i, j, k]
        samples.append([i, j, k, float(value) if numpy.isfinite(value) else None])
    print(json.dumps({
        "dims": list(dims),
        "frames": frames,
        "zooms": [float(z) for z in image.header.get_zooms()[:3]],
        "affine": affine[:3, :].tolist(),
        "non_finite": int((~finite).sum()),
        "finite_sum": float(data[finite].sum()),
        "samples": samples,
    }))


if __name__ == "__main__":
    main()
