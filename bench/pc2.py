#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The one PC2 (Blender Point Cache 2) reader and writer of the Python scripts.

A PC2 file is the 12-byte magic b'POINTCACHE2\\0', int32 version (1), int32 point count,
float32 start frame, float32 sample rate, int32 frame count, then float32 x y z per point,
frame after frame, little-endian. Paths ending in .xz are read through lzma."""
import lzma
import struct
from typing import NamedTuple

MAGIC = b'POINTCACHE2\0'
HEADER = struct.Struct('<12siiffi')


class Header(NamedTuple):
    points: int
    start: float
    rate: float
    frames: int


def open_pc2(path):
    return (lzma.open if path.endswith('.xz') else open)(path, 'rb')


def parse_header(head, path='PC2'):
    """The Header of the first 32 bytes of a PC2 file; ValueError if they are not one."""
    if len(head) < HEADER.size or head[:12] != MAGIC:
        raise ValueError(f'{path}: not a PC2 file')
    _magic, _version, points, start, rate, frames = HEADER.unpack(head[:HEADER.size])
    return Header(points, start, rate, frames)


def pack_header(header):
    return HEADER.pack(MAGIC, 1, header.points, header.start, header.rate, header.frames)


def read_header(path):
    with open_pc2(path) as f:
        return parse_header(f.read(HEADER.size), path)


def read_pc2(path, frames=None):
    """(the first `frames` frames, or all, as a float32 array [F, N, 3]; the file's Header)."""
    import numpy as np  # only the readers of whole sequences need numpy
    with open_pc2(path) as f:
        header = parse_header(f.read(HEADER.size), path)
        count = header.frames if frames is None else min(frames, header.frames)
        data = np.frombuffer(f.read(count * header.points * 12), dtype='<f4')
    if data.size != count * header.points * 3:
        raise ValueError(f'{path}: truncated ({data.size // 3} of {count * header.points} points)')
    return data.reshape(count, header.points, 3), header
