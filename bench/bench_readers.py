#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Reading speed of every sequence format: each shared sequence is encoded once, decoded into
every format of animc's table (PLY, OFF and OBJ frame folders, PC2, MDD), and each is read with
`animc bench IN [--mesh M] --read-only --runs R --json` (opening and parsing every frame, the
files in the page cache). bench.py puts the returned Markdown lines into docs/benchmarks.md;
run alone, this script replaces that section of docs/benchmarks.md (or another report) in place.

usage: bench/bench_readers.py [--animc PATH] [--data DIR] [--runs R] [--out FILE]"""
import os
import subprocess
import tempfile

from bench_common import animc_json, log, num, section_main, table

HEADING = '## Reading the sequence formats'

# (format, output name, whether it needs --mesh): every format `animc decode --format` writes.
FORMATS = [('ply', 'frames_ply', False), ('off', 'frames_off', False), ('obj', 'frames_obj', False),
           ('pc2', 'frames.pc2', True), ('mdd', 'frames.mdd', True)]
ENCODE = ['--codec', 'affine-octree', '--max-error', '0.001']


def readers_section(animc, sequences, runs):
    """(Markdown lines, failures) for every sequence in every format."""
    rows, failures = [], 0
    with tempfile.TemporaryDirectory(prefix='animc_bench_readers_') as work:
        for seq in sequences:
            ams = os.path.join(work, seq['name'] + '.ams')
            if not animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--json'] + ENCODE):
                failures += 1
                continue
            for fmt, name, needs_mesh in FORMATS:
                log(f'{seq["name"]}: reading {fmt}, {runs} runs')
                out = os.path.join(work, seq['name'] + '_' + name)
                decode = [animc, 'decode', ams, '-o', out, '--format', fmt]
                decoded = subprocess.run(decode, capture_output=True).returncode == 0
                if not decoded:
                    log(f'  FAILED: {" ".join(decode)}')
                mesh = ['--mesh', seq['ply']] if needs_mesh else []
                r = decoded and animc_json([animc, 'bench', out, '--read-only', '--runs', str(runs), '--json'] + mesh)
                if not r:
                    failures += 1
                    rows.append([seq['name'], fmt, 'failed', '', ''])
                    continue
                rows.append([seq['name'], fmt, f'{r["input_bytes"] / 1e6:.1f}', num(r['read_mvps']),
                             num(r['read_mbps'], 0)])
    lines = [HEADING, '',
             f'Each sequence encoded with `animc encode IN --mesh M -o X.ams {" ".join(ENCODE)}`, decoded '
             'with `animc decode X.ams -o OUT --format F` into each format, then read with `animc bench OUT '
             f'[--mesh M] --read-only --runs {runs} --json` (PC2 and MDD with the PLY mesh, which is '
             'read and counted too): opening and parsing every frame, the files in the page cache; '
             'medians in million vertices (× frames) and megabytes of input per second.', '']
    lines += table(['sequence', 'format', 'input MB', 'read M v/s', 'read MB/s'], rows) + ['']
    return lines, failures


def main():
    section_main(__doc__, HEADING, lambda args, sequences: readers_section(args.animc, sequences, args.runs),
                 lambda p: p.add_argument('--runs', type=int, default=5))


if __name__ == '__main__':
    main()
