#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The WebAssembly decoder (web/): the npm package's size, and its decoding speed against the
native decoder's on one core. Each shared sequence is encoded with each codec at its default
settings; the native decoder is timed by `animc bench F.ams --threads 1 --runs R --json` (from
memory: open and every frame in order), the WebAssembly one by `node
bench/web_decode_speed.mjs F.ams R` (the same work in Node), in the same run. bench.py puts
the returned Markdown lines into docs/benchmarks.md; run alone, this script replaces that
section in place. Needs web/dist/animc.wasm (scripts/build_web.sh).

usage: bench/bench_web.py [--animc PATH] [--data DIR] [--runs R] [--out FILE]"""
import gzip
import json
import os
import subprocess
import tempfile

from bench_common import animc_json, log, num, section_main, table

HEADING = '## WebAssembly decoder'
CODECS = ('affine-octree', 'wavelet', 'trajectory', 'auto')
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE_FILES = ('dist/animc.wasm', 'animcompress.mjs', 'worker_stream.mjs', 'decode_worker.mjs')


def gzip_bytes(path):
    with open(path, 'rb') as f:
        return len(gzip.compress(f.read(), 9))


def size_lines():
    rows = []
    for name in PACKAGE_FILES:
        path = os.path.join(REPO, 'web', name)
        rows.append([f'`{name}`', str(os.path.getsize(path)), str(gzip_bytes(path))])
    return ['What a page loads (bytes; gzip -9 as a server would send them):', ''] + \
        table(['file', 'bytes', 'gzip'], rows)


def web_speed(ams, runs):
    p = subprocess.run(['node', os.path.join(REPO, 'bench', 'web_decode_speed.mjs'), ams, str(runs)],
                       capture_output=True, text=True)
    if p.returncode != 0:
        log(f'  FAILED: web_decode_speed.mjs {ams}\n    {p.stderr.strip()}')
        return None
    return json.loads(p.stdout)


def speed_rows(animc, sequences, runs, work):
    rows, failures = [], 0
    for seq in sequences:
        for codec in CODECS:
            ams = os.path.join(work, f'{seq["name"]}.{codec}.ams')
            log(f'{seq["name"]}: {codec}')
            encoded = animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--codec', codec,
                                  '--json'])
            native = encoded and animc_json([animc, 'bench', ams, '--threads', '1', '--runs', str(runs), '--json'])
            web = native and web_speed(ams, runs)
            if not web:
                failures += 1
                rows.append([seq['name'], codec, 'failed', '', '', ''])
                continue
            rows.append([seq['name'], codec, num(encoded['bpvf'], 3), num(native['decode_memory_mvps'], 1),
                         num(web['decode_mvps'], 1), num(native['decode_memory_mvps'] / web['decode_mvps'], 2)])
    return rows, failures


def web_section(animc, sequences, runs):
    with tempfile.TemporaryDirectory() as work:
        rows, failures = speed_rows(animc, sequences, runs, work)
    node = subprocess.run(['node', '--version'], capture_output=True, text=True).stdout.strip()
    lines = [HEADING, '', *size_lines(), '',
             f'Decoding on one core, median of {runs} runs, in millions of vertices a second (M v/s): the '
             f'native decoder (`animc bench --threads 1`, from memory) and the WebAssembly one in Node {node}; '
             'the last column is how many times slower the WebAssembly decoder is.', '',
             *table(['sequence', 'codec', 'bpvf', 'native M v/s', 'WASM M v/s', 'native / WASM'], rows)]
    return lines, failures


def main():
    def arguments(p):
        p.add_argument('--runs', type=int, default=5)
    section_main(__doc__, HEADING, lambda args, sequences: web_section(args.animc, sequences, args.runs), arguments)


if __name__ == '__main__':
    main()
