#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Checks that a .glb (or .gltf) written by `animc decode --format glb|gltf` plays the frames of
a PC2 of the same decode: the mesh's POSITION is frame 0, POSITION + target k is frame k (to
float rounding), the faces are the PLY's, and the STEP animation gives target k alone the
weight 1 from time k / RATE. Prints one line; exits 1 on the first difference.

usage: check_gltf_frames.py FILE.glb|FILE.gltf FRAMES.pc2 MESH.ply RATE"""
import base64
import json
import os
import struct
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'bench'))
import pc2  # noqa: E402
import ply  # noqa: E402


def load(path):
    """(the JSON document, the BIN buffer's bytes)."""
    data = open(path, 'rb').read()
    if path.endswith('.glb'):
        magic, version, length = struct.unpack_from('<III', data, 0)
        assert (magic, version, length) == (0x46546C67, 2, len(data)), 'bad glb header'
        json_length, json_type = struct.unpack_from('<II', data, 12)
        bin_length, bin_type = struct.unpack_from('<II', data, 20 + json_length)
        assert json_type == 0x4E4F534A and bin_type == 0x004E4942, 'bad chunk types'
        return json.loads(data[20:20 + json_length]), data[28 + json_length:28 + json_length + bin_length]
    doc = json.loads(data)
    prefix = 'data:application/octet-stream;base64,'
    assert doc['buffers'][0]['uri'].startswith(prefix), 'no inlined buffer'
    return doc, base64.b64decode(doc['buffers'][0]['uri'][len(prefix):])


def accessor(doc, buffer, index):
    a = doc['accessors'][index]
    view = doc['bufferViews'][a['bufferView']]
    dtype = {5126: '<f4', 5125: '<u4'}[a['componentType']]
    width = {'SCALAR': 1, 'VEC3': 3}[a['type']]
    start = view.get('byteOffset', 0) + a.get('byteOffset', 0)
    return np.frombuffer(buffer, dtype=dtype, count=a['count'] * width, offset=start).reshape(a['count'], width)


def main():
    path, frames_path, mesh_path, rate = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    doc, buffer = load(path)
    frames, _ = pc2.read_pc2(frames_path)
    primitive = doc['meshes'][0]['primitives'][0]
    faces = accessor(doc, buffer, primitive['indices']).reshape(-1, 3)
    assert np.array_equal(faces, ply.read_ply_faces(mesh_path)), 'faces differ from the mesh'
    base = accessor(doc, buffer, primitive['attributes']['POSITION'])
    assert np.array_equal(base, frames[0]), 'POSITION is not frame 0'
    targets = primitive['targets']
    assert len(targets) == len(frames), f'{len(targets)} targets for {len(frames)} frames'
    scale = float(np.abs(frames).max())
    worst = 0.0
    for k, target in enumerate(targets):
        played = base + accessor(doc, buffer, target['POSITION'])
        worst = max(worst, float(np.abs(played - frames[k]).max()))
    assert worst <= 1e-6 * scale, f'a played frame is {worst} away from the decoded one'
    sampler = doc['animations'][0]['samplers'][0]
    times = accessor(doc, buffer, sampler['input']).ravel()
    weights = accessor(doc, buffer, sampler['output']).reshape(len(frames) + 1, len(frames))
    assert sampler['interpolation'] == 'STEP', 'not a STEP animation'
    exact = np.arange(len(frames) + 1) / rate  # key k at frame k, one more ending the last
    assert np.allclose(times, exact, rtol=1e-6), 'times are not k / rate'
    # A player asked for exactly k / rate must be at or past key k, so each key is rounded down.
    assert (times.astype(np.float64) <= exact).all(), 'a key comes after k / rate'
    one_hot = np.vstack([np.eye(len(frames)), np.eye(len(frames))[-1:]]).astype(np.float32)
    assert np.array_equal(weights, one_hot), 'weights are not one-hot, the last frame repeated'
    print(f'{path}: {len(frames)} frames play within {worst:.3g} of the decoded ones')


if __name__ == '__main__':
    try:
        main()
    except AssertionError as failure:
        sys.exit(f'{sys.argv[1]}: {failure}')
