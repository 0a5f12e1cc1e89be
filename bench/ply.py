#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The one PLY triangle reader and writer of the Python scripts: the layout of the shared and
test meshes."""
import numpy as np


def read_ply_faces(path):
    """The triangles (T, 3) uint32 of a binary little-endian PLY with float x y z vertices and
    'list uchar int' faces."""
    with open(path, 'rb') as f:
        raw = f.read()
    end = raw.index(b'end_header\n') + len(b'end_header\n')
    header = raw[:end].decode('ascii').splitlines()
    if 'format binary_little_endian 1.0' not in header:
        raise ValueError(f'{path}: not the expected PLY layout')
    counts = {line.split()[1]: int(line.split()[2]) for line in header if line.startswith('element')}
    body = raw[end + counts['vertex'] * 12:]
    faces = np.frombuffer(body, dtype=[('n', 'u1'), ('v', '<i4', (3,))], count=counts['face'])
    if not (faces['n'] == 3).all():
        raise ValueError(f'{path}: not all faces are triangles')
    return faces['v'].astype(np.uint32)


def write_ply(path, vertices, faces):
    """A binary little-endian PLY of float x y z vertices (N, 3) and 'list uchar int' triangles
    (T, 3), the layout read_ply_faces() reads."""
    header = (f'ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n'
              'property float x\nproperty float y\nproperty float z\n'
              f'element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n')
    records = np.empty(len(faces), dtype=[('n', 'u1'), ('v', '<i4', (3,))])
    records['n'] = 3
    records['v'] = faces
    with open(path, 'wb') as f:
        f.write(header.encode('ascii'))
        f.write(np.asarray(vertices, dtype='<f4').tobytes())
        f.write(records.tobytes())
