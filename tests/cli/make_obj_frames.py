#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Writes OBJ frame sequences the way exporters do, for tests/cli/obj_sequences_test.sh.

  make_obj_frames.py exported PC2 PLY OUT_DIR   the PC2's frames on the PLY's triangles, each
      frame with a normal and a texture coordinate per vertex, faces as v/vt/vn (and v//vn, v/vt,
      negative indices in some frames), o/g/s/usemtl/mtllib lines, CRLF in odd frames, no
      newline at the end of the last line
  make_obj_frames.py quads N F OUT_DIR          an N x N grid of quads (and one pentagon) waving
      over F frames, written as polygons

Coordinates are written with 9 significant digits, which read back as the same float32."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'bench'))
import pc2  # noqa: E402
import ply  # noqa: E402


def number(value):
    return '%.9g' % value


def write_frame(path, lines, crlf):
    text = ('\r\n' if crlf else '\n').join(lines)  # no newline after the last line
    with open(path, 'w', newline='') as f:
        f.write(text)


def exported(pc2_path, ply_path, out):
    frames, _ = pc2.read_pc2(pc2_path)
    triangles = ply.read_ply_faces(ply_path)
    os.makedirs(out, exist_ok=True)
    for k, frame in enumerate(frames):
        lines = ['# exported for a test', 'mtllib walk.mtl', 'o Walker']
        lines += ['v ' + ' '.join(number(c) for c in p) for p in frame]
        lines += ['vt %s %s' % (number(i / len(frame)), number(1 - i / len(frame))) for i in range(len(frame))]
        lines += ['vn 0 0 1'] * len(frame)
        lines += ['g body', 's 1', 'usemtl skin']
        n = len(frame)
        for t, (a, b, c) in enumerate(triangles):
            form = (k + t) % 4
            if form == 0:
                corners = ['%d/%d/%d' % (i + 1, i + 1, i + 1) for i in (a, b, c)]
            elif form == 1:
                corners = ['%d//%d' % (i + 1, i + 1) for i in (a, b, c)]
            elif form == 2:
                corners = ['%d/%d' % (i - n, i - n) for i in (a, b, c)]  # negative: from the end
            else:
                corners = ['%d' % (i + 1) for i in (a, b, c)]
            lines.append('f ' + ' '.join(corners))
        write_frame(os.path.join(out, 'walk_%04d.obj' % (k + 1)), lines, crlf=k % 2 == 1)


def quads(n, frame_count, out):
    os.makedirs(out, exist_ok=True)
    index = lambda i, j: i * (n + 1) + j + 1  # noqa: E731
    faces = ['f %d %d %d %d' % (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1))
             for i in range(n) for j in range(n)]
    apex = (n + 1) * (n + 1) + 1
    faces.append('f %d %d %d %d %d' % (index(0, 0), index(0, 1), index(0, 2), index(0, 3), apex))
    for k in range(frame_count):
        phase = 2 * math.pi * k / frame_count
        lines = ['v %s %s %s' % (number(i / n), number(j / n),
                                 number(0.1 * math.sin(3 * i / n + phase) * math.cos(2 * j / n)))
                 for i in range(n + 1) for j in range(n + 1)]
        lines.append('v -0.1 0.05 %s' % number(0.05 * math.sin(phase)))
        write_frame(os.path.join(out, 'grid%d.obj' % k), lines + faces, crlf=False)


if __name__ == '__main__':
    if sys.argv[1:2] == ['exported'] and len(sys.argv) == 5:
        exported(*sys.argv[2:])
    elif sys.argv[1:2] == ['quads'] and len(sys.argv) == 5:
        quads(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])
    else:
        sys.exit(__doc__)
