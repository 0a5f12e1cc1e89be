#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Random access backwards into trajectory files: `animc bench X.ams --backwards` decodes every
frame from the last to the first, each one a `Decoder::frame(k)` that goes back into its group,
from the file and from memory in alternating runs. With --reference ANIMC (an earlier build)
both builds decode the same files, in turns, so that the two share the machine's state.
bench.py puts the returned Markdown lines into docs/benchmarks.md; run alone, this script
replaces that section of docs/benchmarks.md (or another report) in place.

usage: bench/bench_random_access.py [--animc PATH] [--reference PATH [--reference-name TEXT]]
                                    [--data DIR] [--runs R] [--out FILE]"""
import os
import statistics
import tempfile

from bench_common import animc_json, log, num, section_main, table

HEADING = '## Random access backwards (trajectory)'

SETTINGS = ['--codec', 'trajectory', '--target-kg', '0.3']


def backwards(animc, ams, runs):
    """(from the file, from memory) median seconds of a backwards pass, or None."""
    r = animc_json([animc, 'bench', ams, '--threads', '1', '--runs', str(runs), '--backwards', '--json'])
    return (r['decode_seconds_median'], r['decode_memory_seconds_median']) if r else None


def timed_row(animc, reference, ams, runs):
    """Median seconds (file, memory) of this build and of the reference (or None), from
    `runs` rounds that each run both builds once."""
    mine, theirs = [], []
    for _ in range(runs):
        mine.append(backwards(animc, ams, 1))
        if reference:
            theirs.append(backwards(reference, ams, 1))
    if None in mine or None in theirs:
        return None

    def medians(results):
        return tuple(statistics.median(r[i] for r in results) for i in (0, 1)) if results else None

    return medians(mine), medians(theirs)


def random_access_section(animc, reference, sequences, runs, reference_name=None):
    """(Markdown lines, failures) for every sequence, encoded with SETTINGS by this build."""
    rows, failures = [], 0
    with tempfile.TemporaryDirectory(prefix='animc_bench_random_') as work:
        for seq in sequences:
            ams = os.path.join(work, seq['name'] + '.ams')
            log(f'{seq["name"]}: backwards, {runs} rounds')
            encoded = animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--json'] + SETTINGS)
            timed = encoded and timed_row(animc, reference, ams, runs)
            if not timed:
                failures += 1
                rows.append([seq['name'], 'failed'] + [''] * (5 if reference else 2))
                continue
            (file_s, memory_s), old = timed
            frames = encoded['frames']
            row = [seq['name'], frames, num(1e3 * file_s / frames, 3), num(1e3 * memory_s / frames, 3)]
            if old:
                row += [num(1e3 * old[0] / frames, 3), num(1e3 * old[1] / frames, 3),
                        num(old[0] / file_s, 1) + '× / ' + num(old[1] / memory_s, 1) + '×']
            rows.append(row)
    header = ['sequence', 'frames', 'ms a frame, file', 'ms a frame, memory']
    if reference:
        header += ['reference: file', 'reference: memory', 'speed-up file / memory']
    lines = [HEADING, '',
             f'`animc encode IN --mesh M -o X.ams {" ".join(SETTINGS)}` (one group: every sequence is '
             f'under 512 frames), then `animc bench X.ams --threads 1 --runs 1 --backwards --json`, '
             f'{runs} rounds: every frame decoded from the last to the first through `Decoder::openFile` '
             'and `Decoder::openMemory`, each a random access into the group; the median of the rounds, '
             'in milliseconds a frame, opening included.'
             + (f' The reference is `{reference}` ({reference_name or "an earlier build"}), run in the same '
                'rounds on the same files.' if reference else ''),
             '']
    lines += table(header, rows) + ['']
    return lines, failures


def main():
    def arguments(p):
        p.add_argument('--runs', type=int, default=5)
        p.add_argument('--reference', help='an earlier animc build to compare with')
        p.add_argument('--reference-name', help='what the reference is, for the report')

    section_main(__doc__, HEADING,
                 lambda args, sequences: random_access_section(args.animc, args.reference, sequences, args.runs,
                                                               args.reference_name),
                 arguments)


if __name__ == '__main__':
    main()
