#!/usr/bin/env python3
"""Writes small seed inputs for the fuzz targets (the committed tests/fuzz/seeds/* come from here)."""
import gzip
import os
import struct
import sys
import zlib

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "seeds")


def put(target, name, data):
    os.makedirs(os.path.join(out, target), exist_ok=True)
    with open(os.path.join(out, target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


ramp = bytes((i * 37) % 256 for i in range(4 * 3 * 2))

# NRRD: attached raw and gzip, big-endian int16, space directions, detached names (which cannot exist).
put("fuzz_nrrd", "raw_uint8.nrrd",
    b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: 1 1.5 nan\nencoding: raw\n\n" + ramp)
put("fuzz_nrrd", "gzip_int16_big.nrrd",
    b"NRRD0005\n# comment\ntype: short\ndimension: 3\nsizes: 4 3 2\nendian: big\n"
    b"space: left-posterior-superior\nspace directions: (1,0,0) (0,2,0) (0,0,0.5)\n"
    b"space origin: (-1,2.5,3)\nkinds: domain domain domain\nencoding: gzip\n\n"
    + gzip.compress(struct.pack(">24h", *range(-12, 12))))
put("fuzz_nrrd", "float_byteskip.nrrd",
    b"NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nendian: little\nbyte skip: -1\nline skip: 0\n"
    b"encoding: raw\nkey:=value\n\n" + struct.pack("<8f", *[0.5 * i for i in range(8)]))
put("fuzz_nrrd", "detached_pattern.nhdr",
    "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nencoding: raw\ndata file: slice%03d.raw 1 2 1 2\n")
put("fuzz_nrrd", "detached_list.nhdr",
    "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nencoding: raw\ndata file: LIST\na.raw\nb.raw\n")

# NIfTI-1: 348-byte header, 4 extension bytes, samples at vox_offset 352; little and big endian, gzip.


def nifti(endian, datatype, bitpix, fmt, values, slope=0.0):
    h = bytearray(348)
    struct.pack_into(endian + "i", h, 0, 348)
    struct.pack_into(endian + "8h", h, 40, 3, 4, 3, 2, 1, 1, 1, 1)
    struct.pack_into(endian + "hh", h, 70, datatype, bitpix)
    struct.pack_into(endian + "8f", h, 76, 1, 1.0, 1.5, 2.0, 1, 1, 1, 1)
    struct.pack_into(endian + "fff", h, 108, 352.0, slope, 0.5)
    struct.pack_into(endian + "hh", h, 252, 1, 1)
    struct.pack_into(endian + "12f", h, 280, 1, 0, 0, -5, 0, 1, 0, 6, 0, 0, 1, 7)
    h[344:348] = b"n+1\0"
    return bytes(h) + b"\0\0\0\0" + struct.pack(endian + str(len(values)) + fmt, *values)


put("fuzz_nifti", "uint8_le.nii", nifti("<", 2, 8, "B", list(ramp)))
put("fuzz_nifti", "int16_be_scaled.nii", nifti(">", 4, 16, "h", list(range(-12, 12)), slope=2.0))
put("fuzz_nifti", "float_gz.nii", gzip.compress(nifti("<", 16, 32, "f", [0.25 * i for i in range(24)])))

# NIfTI-2: 540-byte header, int64 dims and float64 fields; 4D (two frames), little and big endian, gzip,
# a NaN. The first input byte is the frame fuzz_nifti2 reads.


def nifti2(endian, datatype, bitpix, fmt, values, frames=2):
    h = bytearray(540)
    struct.pack_into(endian + "i", h, 0, 540)
    h[4:12] = b"n+2\0\r\n\x1a\n"
    struct.pack_into(endian + "hh", h, 12, datatype, bitpix)
    struct.pack_into(endian + "8q", h, 16, 4, 4, 3, 2, frames, 1, 1, 1)
    struct.pack_into(endian + "8d", h, 104, -1, 1.0, 1.5, 2.0, 1, 1, 1, 1)
    struct.pack_into(endian + "qdd", h, 168, 544, 0.0, 0.0)
    struct.pack_into(endian + "ii", h, 344, 1, 1)
    struct.pack_into(endian + "3d3d", h, 352, 0.1, 0.2, 0.3, 4, 5, 6)
    struct.pack_into(endian + "12d", h, 400, 1, 0, 0, -5, 0, 1, 0, 6, 0, 0, 1, 7)
    return bytes(h) + b"\0\0\0\0" + struct.pack(endian + str(len(values)) + fmt, *values)


put("fuzz_nifti2", "int16_le_4d.nii", b"\x01" + nifti2("<", 4, 16, "h", list(range(-24, 24))))
put("fuzz_nifti2", "float_be_nan.nii",
    b"\x00" + nifti2(">", 16, 32, "f", [float("nan")] + [0.5 * i for i in range(47)]))
put("fuzz_nifti2", "uint8_gz.nii", b"\x01" + gzip.compress(nifti2("<", 2, 8, "B", list(ramp) * 2)))

# FreeSurfer MGH: big-endian 284-byte header (version, dims, frames, type, dof, goodRASflag, voxel sizes,
# Mdc, c_ras), samples, then optional scan parameters; plain and gzip (.mgz). First byte: the frame.


def mgh(type_code, fmt, values, frames=2, good_ras=1):
    h = bytearray(284)
    struct.pack_into(">7i", h, 0, 1, 4, 3, 2, frames, type_code, 0)
    struct.pack_into(">h", h, 28, good_ras)
    struct.pack_into(">3f9f3f", h, 30, 1.0, 1.5, 2.0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 10, 20, 30)
    return bytes(h) + struct.pack(">" + str(len(values)) + fmt, *values) + struct.pack(">4f", 2.0, 0.1, 3.0, 0.0)


put("fuzz_mgh", "uchar.mgh", b"\x01" + mgh(0, "B", list(ramp) * 2))
put("fuzz_mgh", "float_nan.mgh", b"\x00" + mgh(3, "f", [float("nan")] + [0.25 * i for i in range(47)]))
put("fuzz_mgh", "short_gz.mgz", b"\x01" + gzip.compress(mgh(4, "h", list(range(-24, 24)), good_ras=0)))
put("fuzz_mgh", "int_1frame.mgh", b"\x00" + mgh(1, "i", list(range(24)), frames=1))

# MetaImage: LOCAL raw, zlib-compressed, big-endian short, and a detached file name.
put("fuzz_metaimage", "local_raw.mha",
    b"ObjectType = Image\nNDims = 3\nDimSize = 4 3 2\nElementSpacing = 1 1 2\nOffset = 0 1 2\n"
    b"ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + ramp)
packed = zlib.compress(struct.pack("<24f", *[0.5 * i for i in range(24)]))
put("fuzz_metaimage", "local_zlib.mha",
    ("ObjectType = Image\nNDims = 3\nDimSize = 4 3 2\nCompressedData = True\nCompressedDataSize = %d\n"
     "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n" % len(packed)).encode() + packed)
put("fuzz_metaimage", "big_short.mha",
    b"NDims = 3\nDimSize = 4 3 2\nBinaryDataByteOrderMSB = True\nHeaderSize = -1\nElementType = MET_SHORT\n"
    b"ElementDataFile = LOCAL\n" + struct.pack(">24h", *range(24)))
put("fuzz_metaimage", "detached.mhd", "NDims = 3\nDimSize = 4 3 2\nElementType = MET_UCHAR\nElementDataFile = x.raw\n")

# Camera text.
for i, cam in enumerate(["anterior", "az=30,el=20", "az=-45.5,el=89,zoom=2.5,pan=0.1:-0.2,proj=persp,fov=45",
                         "view=left,zoom=1e0,proj=ortho", "pan=+1:-1,fov=10"]):
    put("fuzz_camera", "cam%d.txt" % i, cam)

# /render queries and /api/fit bodies (the hostile .http requests of tests/server are added by make-corpus).
for i, query in enumerate([
        "dataset=blobs_64x64x64_uint8&cam=az=30,el=20&size=256x256&eps=2%25&mode=mip&window=120,200&colormap=hot&client=tab1",
        "dataset=cranium&cam=az%3D30%2Cel%3D20&size=512x512&eps=2%&window=300,1500&_=169",
        "dataset=x&eps=20&degree=0&mode=density&colormap=viridis",
        "dataset=x&mode=reference&size=1x4096&window=-1e3,2.5e3&colormap=bone",
        '{"dataset":"blobs_64x64x64_uint8","eps":"3%","degree":3,"focus":{"x":32,"y":32,"z":32,"r":8,"eps":1}}',
        '{"dataset":"x","eps":7.5}',
        '{"dataset":"x","eps":"2%","client":"0123456789abcdef"}']):
    put("fuzz_render_query", "query%d.txt" % i, query)

# The viewer socket's messages (docs/API.md, "Viewer socket").
for i, message in enumerate([
        '{"type":"view","seq":1,"still":false,"params":{"dataset":"cranium","cam":"az=30,el=20","size":"1140x900",'
        '"eps":"2%","mode":"mip","window":"300,1500","colormap":"grey"}}',
        '{"type":"view","seq":18446744073709551615,"still":true,"params":{"dataset":"x","slab":"0.1:0.5"}}',
        '{"type":"ack","frame":3}',
        '{"type":"view","seq":2,"params":{"dataset":"x","size":"0x0"}}',
        '[{"type":"ack"}]']):
    put("fuzz_stream_message", "message%d.txt" % i, message)

# multipart/related bodies: byte 0 picks the chunk size, byte 1 the boundary "012345" (5 -> 6 characters).
def multipart(parts, close=True, preamble=b""):
    body = preamble
    for headers, data in parts:
        body += b"--012345\r\n" + headers + b"\r\n" + data + b"\r\n"
    return bytes([7, 5]) + body + (b"--012345--\r\n" if close else b"")


put("fuzz_multipart", "two_parts", multipart([(b"Content-Type: application/dicom\r\n", b"DICM" + ramp),
                                              (b"Content-Type: application/dicom\r\nX-A: b\r\n", ramp)]))
put("fuzz_multipart", "preamble_padding", bytes([0, 5]) + b"preamble\r\n--012345 \t\r\n\r\nx\r\n--012345--")
put("fuzz_multipart", "cut", multipart([(b"Content-Type: application/dicom\r\n", ramp)], close=False))
put("fuzz_multipart", "delimiter_like_data", multipart([(b"", b"\r\n--01234\r\n--0123456")]))
