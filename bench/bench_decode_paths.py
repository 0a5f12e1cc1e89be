#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Decoding through the public Decoder from a file and from memory: `animc bench FILE.ams`
times both in alternating runs of one command, so the two medians share the machine's state.
bench.py puts the returned Markdown lines into docs/benchmarks.md; run alone, this script
replaces that section of docs/benchmarks.md (or another report) in place.

usage: bench/bench_decode_paths.py [--animc PATH] [--data DIR] [--runs R] [--out FILE]"""
import os
import tempfile

from bench_common import animc_json, log, num, section_main, table

HEADING = '## Decoding from a file and from memory'

SETTINGS = ['--profile', 'predictive', '--max-error', '0.01']


def decode_paths_section(animc, sequences, runs):
    """(Markdown lines, failures) for every sequence, encoded with SETTINGS."""
    rows, failures = [], 0
    # At least 9 runs: a decode of these files takes milliseconds, so a median of few is noisy.
    decode_runs = max(runs, 9)
    with tempfile.TemporaryDirectory(prefix='animc_bench_paths_') as work:
        for seq in sequences:
            ams = os.path.join(work, seq['name'] + '.ams')
            log(f'{seq["name"]}: decode from file and from memory, {decode_runs} runs')
            encoded = animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--json'] + SETTINGS)
            r = encoded and animc_json([animc, 'bench', ams, '--threads', '1', '--runs', str(decode_runs), '--json'])
            if not r:
                failures += 1
                rows.append([seq['name'], 'failed', 'failed', ''])
                continue
            rows.append([seq['name'], num(r['decode_mvps']), num(r['decode_memory_mvps']),
                         num(r['decode_memory_mvps'] / r['decode_mvps'])])
    lines = [HEADING, '',
             f'`animc encode IN --mesh M -o X.ams {" ".join(SETTINGS)}`, then `animc bench X.ams --runs '
             f'{decode_runs} --json`: `Decoder::openFile` and `Decoder::openMemory` (the bytes read into '
             'memory first, untimed) each decode every frame in order, in alternating runs; medians in '
             'million vertices (× frames) per second, opening included.', '']
    lines += table(['sequence', 'from the file', 'from memory', 'memory / file'], rows) + ['']
    return lines, failures


def main():
    section_main(__doc__, HEADING, lambda args, sequences: decode_paths_section(args.animc, sequences, args.runs),
                 lambda p: p.add_argument('--runs', type=int, default=15))


if __name__ == '__main__':
    main()
