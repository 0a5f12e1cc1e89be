#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Rebuilds samples/ from ../shared/data: the first FRAMES frames of sydney_md2 as a PC2 point
cache (xz-compressed) beside its PLY mesh, and the first PLY_FRAMES frames as PLY files (what
MeshLab loads as layers). Run from the repository root."""
import lzma, os, shutil, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'bench'))
import pc2  # noqa: E402

FRAMES = 50
PLY_FRAMES = 24
SRC = os.path.join('..', 'shared', 'data', 'sydney_md2')
DST = os.path.join('samples', 'sydney')

def main():
    frames, header = pc2.read_pc2(os.path.join(SRC, 'sydney_md2.pc2.xz'), FRAMES)
    points, body = header.points, frames.tobytes()
    os.makedirs(DST, exist_ok=True)
    out = pc2.pack_header(header._replace(frames=FRAMES)) + body
    with lzma.open(os.path.join(DST, 'sydney_50.pc2.xz'), 'wb', preset=9) as f:
        f.write(out)
    shutil.copyfile(os.path.join(SRC, 'sydney_md2.ply'), os.path.join(DST, 'sydney_md2.ply'))
    write_ply_frames(os.path.join(SRC, 'sydney_md2.ply'), points, body, os.path.join(DST, 'frames'), PLY_FRAMES)

def write_ply_frames(mesh_path, points, body, folder, count):
    """Writes frames 0..count-1 of body (count * points * 12 bytes of little-endian x y z floats)
    to folder/frame_NNNNN.ply: each the mesh's own binary PLY with its vertex block replaced."""
    with open(mesh_path, 'rb') as f:
        mesh = f.read()
    end = mesh.index(b'end_header\n') + len(b'end_header\n')
    header = mesh[:end]
    if b'binary_little_endian' not in header or b'element vertex %d\n' % points not in header:
        sys.exit('unexpected PLY header in ' + mesh_path)
    faces = mesh[end + points * 12:]
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    for i in range(count):
        vertices = body[i * points * 12:(i + 1) * points * 12]
        with open(os.path.join(folder, 'frame_%05d.ply' % i), 'wb') as f:
            f.write(header + vertices + faces)

if __name__ == '__main__':
    main()
