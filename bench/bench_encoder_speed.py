#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The default encoder's time against the affine-octree codec's, on one thread:
`animc bench IN --mesh M --threads 1 --runs R --json` at animc's default settings (auto, max
error 1 %), with `--codec affine-octree` and with `--codec trajectory --max-error 0.01`, every
time from the same run of this script; then the trajectory codec's files at KG 0.1, 0.3 and
1 %. With --reference ANIMC (a build of an earlier release) each file's size and error are
compared with that release's for the same settings. bench.py puts the returned Markdown lines
into docs/benchmarks.md; run alone, this script replaces that section in place.

usage: bench/bench_encoder_speed.py [--animc PATH] [--reference PATH] [--data DIR] [--runs R]
                                    [--out FILE]"""
import subprocess

from bench_common import failed_cell, log, num, run_bench, section_main, table

HEADING = '## Encoder speed'
DEFAULT = []
OCTREE = ['--codec', 'affine-octree']
TRAJECTORY = ['--codec', 'trajectory', '--max-error', '0.01']
TARGETS = (0.1, 0.3, 1.0)


def version(animc):
    p = subprocess.run([animc, '--version'], capture_output=True, text=True)
    return p.stdout.strip() or 'unknown'


def against(result, reference):
    """'bpvf (KG %)' of a result, and its size as a share of the reference's."""
    if 'error' in result:
        return failed_cell(result), 'n/a'
    cell = f'{num(result["bpvf"], 3)} ({num(result["kg_error"], 3)} %)'
    if reference is None or 'error' in reference:
        return cell, 'n/a'
    return cell, num(result['file_bytes'] / reference['file_bytes'], 3)


def speed_rows(animc, reference, sequences, runs):
    rows, failures = [], 0
    for s in sequences:
        log(f'{s["name"]}: default, affine-octree and trajectory encodes, {runs} runs')
        default, octree, trajectory = (run_bench(animc, s['pc2'], s['ply'], settings, runs)
                                       for settings in (DEFAULT, OCTREE, TRAJECTORY))
        old = run_bench(reference, s['pc2'], s['ply'], DEFAULT, 1, one_thread=False) if reference else None
        if any('error' in r for r in (default, octree, trajectory)):
            failures += 1
            rows.append([s['name']] + ['failed'] * 7)
            continue
        size, share = against(default, old)
        seconds = default['encode_seconds_median'], octree['encode_seconds_median']
        rows.append([s['name'], num(seconds[0], 3), num(seconds[1], 3),
                     num(trajectory['encode_seconds_median'], 3), num(seconds[0] / seconds[1]) + '×', size,
                     'n/a' if old is None or 'error' in old else f'{num(old["bpvf"], 3)} ({num(old["kg_error"], 3)} %)',
                     share])
    return rows, failures


def size_rows(animc, reference, sequences):
    rows, failures = [], 0
    for s in sequences:
        row = [s['name']]
        for target in TARGETS:
            settings = ['--codec', 'trajectory', '--target-kg', str(target)]
            log(f'{s["name"]}: trajectory at KG {target} %')
            new = run_bench(animc, s['pc2'], s['ply'], settings, 1)
            old = run_bench(reference, s['pc2'], s['ply'], settings, 1, one_thread=False) if reference else None
            failures += 'error' in new
            cell, share = against(new, old)
            row += [cell, share]
        rows.append(row)
    return rows, failures


def encoder_speed_section(animc, reference, sequences, runs):
    speed, failures = speed_rows(animc, reference, sequences, runs)
    sizes, size_failures = size_rows(animc, reference, sequences)
    old = f'{version(reference)} (`{reference}`)' if reference else 'none given'
    lines = [HEADING, '',
             f'Encoding on one thread: `animc bench IN --mesh M --threads 1 --runs {runs} --json`, medians in '
             'seconds (the encode only: the input is read before the runs), all from one run of '
             'bench/bench_encoder_speed.py. "Default" is animc\'s default (auto, max error 1 %); the ratio is '
             'its time over `--codec affine-octree`\'s (default profile, max error 1 %). Sizes in bits per '
             f'vertex per frame with the KG error reached; the reference is the release {old}, with the same '
             'settings, and the share is this release\'s file size over the reference\'s.', '']
    lines += table(['sequence', 'default (s)', 'affine-octree (s)', 'trajectory (s)', 'default / affine-octree',
                    'default bpvf (KG)', 'reference bpvf (KG)', 'size share'], speed) + ['']
    lines += ['The trajectory codec at a KG target (`--codec trajectory --target-kg X`), the same comparison:', '']
    header = ['sequence']
    for target in TARGETS:
        header += [f'KG {target:g} %: bpvf (KG)', 'size share']
    lines += table(header, sizes) + ['']
    return lines, failures + size_failures


def main():
    def arguments(p):
        p.add_argument('--runs', type=int, default=5)
        p.add_argument('--reference', help='animc of an earlier release, to compare sizes with')
    section_main(__doc__, HEADING,
                 lambda args, sequences: encoder_speed_section(args.animc, args.reference, sequences, args.runs),
                 arguments)


if __name__ == '__main__':
    main()
