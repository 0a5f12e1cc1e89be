#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The WebAssembly decoder (web/): the npm package's size, and its decoding speed against the
native decoder's on one core. Each shared sequence is encoded with each codec at its default
settings; the native decoder is timed by `animc bench F.ams --threads 1 --runs R --json` (from
memory: open and every frame in order), the WebAssembly one by `node
bench/web_decode_speed.mjs F.ams R` (the same work in Node, after a second of it untimed, while
V8 swaps optimised code in), in the same run; each file's frames
from both decoders must be the same bytes (SHA-256 against `animc decode --format pc2`), else
its row says so and the script fails. bench.py puts
the returned Markdown lines into docs/benchmarks.md; run alone, this script replaces that
section in place. Needs web/dist/animc.wasm (scripts/build_web.sh).

usage: bench/bench_web.py [--animc PATH] [--data DIR] [--runs R] [--out FILE]"""
import gzip
import hashlib
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


def native_frames_sha256(animc, ams, work):
    pc2 = os.path.join(work, 'native.pc2')
    subprocess.run([animc, 'decode', ams, '-o', pc2, '--format', 'pc2', '--replace'], check=True, capture_output=True)
    with open(pc2, 'rb') as f:
        return hashlib.sha256(f.read()[32:]).hexdigest()


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
            if not web or web['frames_sha256'] != native_frames_sha256(animc, ams, work):
                failures += 1
                rows.append([seq['name'], codec, 'failed' if not web else 'frames differ', '', '', ''])
                continue
            rows.append([seq['name'], codec, num(encoded['bpvf'], 3), num(native['decode_memory_mvps'], 1),
                         num(web['decode_mvps'], 1), num(native['decode_memory_mvps'] / web['decode_mvps'], 2)])
    return rows, failures


def web_section(animc, sequences, runs):
    if not os.path.isfile(os.path.join(REPO, 'web', PACKAGE_FILES[0])):
        log('no web/dist/animc.wasm: the WebAssembly decoder is not measured (scripts/build_web.sh builds it)')
        return [HEADING, '', 'Not measured: no `web/dist/animc.wasm` (`bash scripts/build_web.sh` builds it).', ''], 0
    with tempfile.TemporaryDirectory() as work:
        rows, failures = speed_rows(animc, sequences, runs, work)
    node = subprocess.run(['node', '--version'], capture_output=True, text=True).stdout.strip()
    lines = [HEADING, '', *size_lines(), '',
             f'Decoding on one core, median of {runs} runs, in millions of vertices a second (M v/s): the '
             f'native decoder (`animc bench --threads 1`, from memory) and the WebAssembly one in Node {node}, '
             'after a second of untimed decoding (until then V8 runs code from its baseline compiler: a '
             'page\'s first second of decoding is slower); '
             'the last column is how many times slower the WebAssembly decoder is. Every file\'s frames are the '
             'same bytes from both.', '',
             *table(['sequence', 'codec', 'bpvf', 'native M v/s', 'WASM M v/s', 'native / WASM'], rows)]
    return lines, failures


def main():
    def arguments(p):
        p.add_argument('--runs', type=int, default=5)
    section_main(__doc__, HEADING, lambda args, sequences: web_section(args.animc, sequences, args.runs), arguments)


if __name__ == '__main__':
    main()
