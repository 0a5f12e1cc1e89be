#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Writes two_motions.ply and two_motions.pc2.xz, the input of the codec-5 golden files
(manifest.txt): two 10 x 8 grids side by side, not joined, over 48 frames; one waves, the other
turns and drifts, as tests/unit/trajectory_parts_test.cpp's twoMotions(). Coordinates are
rounded to 1/4096 so that the file stays small. The committed files are the golden input: this
script says how they were made, and is not run by the tests.

usage: make_two_motions.py OUT_DIR"""
import lzma
import math
import os
import struct
import sys

NX, NY, FRAMES = 10, 8, 48


def grid_frame(f, deform, rigid):
    angle = rigid * 0.05 * f
    ca, sa = math.cos(angle), math.sin(angle)
    out = []
    for y in range(NY):
        for x in range(NX):
            px, py = x / (NX - 1), y / (NY - 1)
            pz = 0.2 * math.sin(7 * px + 3 * py) + deform * 0.1 * math.sin(6 * px - 0.3 * f)
            out.append((ca * px - sa * pz + rigid * 0.02 * f, py + rigid * 0.01 * f, sa * px + ca * pz))
    return out


def frame(f):
    waving = grid_frame(f, 1.0, 0.0)
    turning = [(x + 2.0, y, z) for x, y, z in grid_frame(2 * f + 7, 0.5, 1.5)]
    return [round(c * 4096) / 4096 for p in waving + turning for c in p]


def faces():
    one = []
    for y in range(NY - 1):
        for x in range(NX - 1):
            a = y * NX + x
            one += [(a, a + 1, a + NX + 1), (a, a + NX + 1, a + NX)]
    return one + [tuple(v + NX * NY for v in t) for t in one]


def main():
    out = sys.argv[1]
    vertices = 2 * NX * NY
    tris = faces()
    header = ('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
              'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'
              % (vertices, len(tris))).encode()
    with open(os.path.join(out, 'two_motions.ply'), 'wb') as f:
        f.write(header + struct.pack('<%df' % (3 * vertices), *frame(0)))
        for t in tris:
            f.write(struct.pack('<B3i', 3, *t))
    with lzma.open(os.path.join(out, 'two_motions.pc2.xz'), 'wb') as f:
        f.write(struct.pack('<12siiffi', b'POINTCACHE2\0', 1, vertices, 0.0, 1.0, FRAMES))
        for i in range(FRAMES):
            f.write(struct.pack('<%df' % (3 * vertices), *frame(i)))


if __name__ == '__main__':
    main()
