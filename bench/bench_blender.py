#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""How an .ams plays in Blender, the measurement behind the add-on's choice (docs/blender.md):
a 316 × 316 grid (99 856 vertices, 198 450 triangles) waving over 400 frames, encoded with
`animc encode` at its defaults, played in headless Blender by each way of bench/blender_playback.py
(the add-on's Mesh Cache import, shape keys, a frame-change handler). Run alone, it replaces
its section of docs/benchmarks.md (or another report) in place.

usage: bench/bench_blender.py [--animc PATH] [--blender PATH] [--python-module DIR] [--out FILE]
                             [-- animc encode flags]"""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import numpy as np

from bench_common import log, num, section_main, table

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADING = '## Playing an .ams in Blender'
SIDE, FRAMES = 316, 400
METHODS = ['cache', 'keys', 'handler']


def write_grid(pc2_path, ply_path):
    i, j = np.meshgrid(np.arange(SIDE), np.arange(SIDE), indexing='ij')
    x, y = (i / (SIDE - 1)).astype(np.float32), (j / (SIDE - 1)).astype(np.float32)
    corner = (i[:-1, :-1] * SIDE + j[:-1, :-1]).ravel()
    faces = np.concatenate([np.stack([corner, corner + SIDE, corner + SIDE + 1], 1),
                            np.stack([corner, corner + SIDE + 1, corner + 1], 1)])
    with open(pc2_path, 'wb') as f:
        f.write(struct.pack('<12siiffi', b'POINTCACHE2\0', 1, SIDE * SIDE, 0, 1, FRAMES))
        for k in range(FRAMES):
            t = k / 25
            z = 0.05 * np.sin(6 * x + 2 * t) * np.cos(4 * y - t) + 0.02 * np.sin(10 * (x + y) + 3 * t)
            f.write(np.stack([x + 0.01 * np.sin(t), y, z], -1).astype('<f4').tobytes())
    with open(ply_path, 'wb') as f:
        f.write((f'ply\nformat binary_little_endian 1.0\nelement vertex {SIDE * SIDE}\nproperty float x\n'
                 f'property float y\nproperty float z\nelement face {len(faces)}\n'
                 'property list uchar int vertex_indices\nend_header\n').encode())
        f.write(np.stack([x, y, np.zeros_like(x)], -1).astype('<f4').tobytes())
        records = np.zeros(len(faces), dtype=[('n', 'u1'), ('v', '<i4', (3,))])
        records['n'], records['v'] = 3, faces
        f.write(records.tobytes())


def blender_section(animc, blender, python_module, encode_flags):
    if not blender:
        sys.exit('no blender (scripts/setup.sh installs it)')
    rows, failures = [], 0
    with tempfile.TemporaryDirectory(prefix='animc_bench_blender_') as work:
        pc2, ply, ams = (os.path.join(work, n) for n in ('grid.pc2', 'grid.ply', 'grid.ams'))
        log('writing the 99 856-vertex grid over 400 frames')
        write_grid(pc2, ply)
        log('encoding it with animc encode ' + ' '.join(encode_flags))
        subprocess.run([animc, 'encode', pc2, '--mesh', ply, '-o', ams] + encode_flags, check=True,
                       capture_output=True)
        os.makedirs(os.path.join(work, 'scripts', 'addons'))
        os.symlink(os.path.join(REPO, 'blender', 'io_anim_ams'), os.path.join(work, 'scripts', 'addons', 'io_anim_ams'))
        env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(work, 'scripts'),
                   BLENDER_USER_CONFIG=os.path.join(work, 'config'), PYTHONPATH=python_module)
        for method in METHODS:
            log(f'playing it in Blender: {method}')
            p = subprocess.run([blender, '-b', '--factory-startup', '--python-exit-code', '1', '--python',
                                os.path.join(REPO, 'bench', 'blender_playback.py'), '--', ams, method],
                               capture_output=True, text=True, env=env)
            lines = [line for line in p.stdout.splitlines() if line.startswith('RESULT ')]
            if p.returncode != 0 or not lines:
                failures += 1
                rows.append([method, 'failed', '', '', '', ''])
                log(p.stdout[-2000:] + p.stderr[-2000:])
                continue
            r = json.loads(lines[0][len('RESULT '):])
            rows.append([method, num(r['setup_s']), num(r['forwards_ms'], 1), num(r['backwards_ms'], 1),
                         f"{r['error']:.2g}", num(r['peak_rss_mb'], 0)])
        ams_bytes = os.path.getsize(ams)
    lines = [HEADING, '',
             f'bench/bench_blender.py: a {SIDE} × {SIDE} grid ({SIDE * SIDE} vertices) waving over {FRAMES} frames, '
             f'`animc encode IN.pc2 --mesh M.ply -o X.ams{"".join(" " + f for f in encode_flags)}` ({ams_bytes} bytes), played in '
             'headless Blender (Debian\'s 3.4) by bench/blender_playback.py: `cache` is the add-on\'s import '
             '(a Mesh Cache modifier over a PC2 decoded once beside the file, 12 bytes a vertex a frame on '
             'disk), `keys` one shape key per frame, `handler` a frame-change handler decoding each frame. '
             'Setup is the import; a frame is `scene.frame_set(k)` and reading the evaluated positions, '
             'forwards over every frame and backwards over every 7th; the error is against the decoded '
             'frame 123; peak RSS of the Blender process. One run.', '']
    lines += table(['way', 'setup s', 'ms per frame, forwards', 'ms per frame, backwards', 'error',
                    'peak RSS MB'], rows) + ['']
    return lines, failures


def add_arguments(p):
    p.add_argument('--blender', default=shutil.which('blender'))
    p.add_argument('--python-module', default=os.path.join(REPO, 'build', 'python'),
                   help='folder of the animcompress Python module (default: build/python)')
    p.add_argument('encode_flags', nargs='*', help='animc encode flags (default: none, its defaults)')


def main():
    section_main(__doc__, HEADING, lambda args, sequences: blender_section(
        args.animc, args.blender, os.path.abspath(args.python_module), args.encode_flags), add_arguments)


if __name__ == '__main__':
    main()
