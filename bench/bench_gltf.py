#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Sizes of the glTF that `animc decode --format glb` writes, beside the .ams it came from and
beside `gltfpack -cc` of that glb (what a web user would pick otherwise: meshopt-compressed morph
targets, 14-bit positions by default). Each shared sequence is encoded with ENCODE. bench.py
puts the returned Markdown lines into docs/benchmarks.md; run alone, this script replaces that
section of docs/benchmarks.md (or another report) in place.

usage: bench/bench_gltf.py [--animc PATH] [--gltfpack PATH] [--data DIR] [--out FILE]"""
import os
import shutil
import subprocess
import tempfile

from bench_common import animc_json, log, num, section_main, table

HEADING = '## glTF output'
ENCODE = ['--target-kg', '0.5']


def bpvf(size, vertices, frames):
    return num(8 * size / (vertices * frames), 3)


def gltf_section(animc, gltfpack, sequences):
    """(Markdown lines, failures) for every sequence."""
    rows, failures = [], 0
    with tempfile.TemporaryDirectory(prefix='animc_bench_gltf_') as work:
        for seq in sequences:
            log(f'{seq["name"]}: .ams, glb and gltfpack -cc sizes')
            ams, glb, packed = (os.path.join(work, seq['name'] + ext) for ext in ('.ams', '.glb', '.packed.glb'))
            r = animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--json'] + ENCODE)
            ok = r and subprocess.run([animc, 'decode', ams, '-o', glb], capture_output=True).returncode == 0
            ok = ok and gltfpack and subprocess.run([gltfpack, '-i', glb, '-o', packed, '-cc'],
                                                    capture_output=True).returncode == 0
            if not ok:
                failures += 1
                rows.append([seq['name'], 'failed', '', '', '', ''])
                continue
            v, f = r['vertices'], r['frames']
            sizes = [os.path.getsize(p) for p in (ams, glb, packed)]
            rows.append([seq['name'], f'{v} × {f}', num(r['kg_error'], 3)] +
                        [f'{s:,} ({bpvf(s, v, f)})'.replace(',', ' ') for s in sizes] +
                        [num(sizes[2] / sizes[0], 1) + '×'])
    lines = [HEADING, '',
             f'`animc encode IN --mesh M -o X.ams {" ".join(ENCODE)}`, then `animc decode X.ams -o X.glb` '
             '(frame 0 as the mesh, every frame a float morph target, one STEP animation; '
             'docs/sequence_formats.md) and `gltfpack -i X.glb -o P.glb -cc` (Debian\'s gltfpack '
             '0.18). Bytes, with bits per vertex per frame in parentheses; the glb and gltfpack\'s file '
             'hold the decoded frames, so their error is at least the .ams\'s KG (gltfpack adds its own '
             'quantisation of positions and resamples the animation at 30 Hz).', '']
    lines += table(['sequence', 'vertices × frames', '.ams KG %', '.ams', '.glb', 'gltfpack -cc',
                    'gltfpack / .ams'], rows) + ['']
    return lines, failures


def main():
    section_main(__doc__, HEADING, lambda args, sequences: gltf_section(args.animc, args.gltfpack, sequences),
                 lambda p: p.add_argument('--gltfpack', default=shutil.which('gltfpack')))


if __name__ == '__main__':
    main()
