#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The trajectory codec (codec 3) and `--codec auto` (codec 4) against our two earlier codecs
and FAMC at equal KG error (issue 27's targets). bench.py calls trajectory_section() with the sequences it measured
(their Affine-Octree default-profile sweeps) and puts the returned Markdown lines into
docs/benchmarks.md.

Per sequence and target KG error X:
- trajectory: `animc bench IN --mesh M --codec trajectory --target-kg X`, and the same with
  `--codec auto`;
- wavelet: `animc bench IN --mesh M --codec wavelet --target-kg X --step 1e-5` (a step fine
  enough that the target, not the step, sets the error);
- Affine-Octree (default profile), which has no KG target: its bpvf interpolated log-log on
  the max-error sweep at X, and for the decode speed a file encoded at the max error
  interpolated the same way (its KG is in the table);
- decode speeds: `animc bench FILE.ams` of the trajectory and Affine-Octree files, medians
  of at least 9 runs each, one after the other.
"""
import os
import tempfile

from bench_common import animc_json, failed_cell, log, loglog_interp, num, run_bench, table

TARGETS_KG = [0.3, 1.0]
# Issue 27's targets: at most this fraction of our best earlier codec's bpvf, and on
# chickenCrossing at most half of FAMC's (the MPEG-4 reference software, openFAMC, best of its
# modes and settings, measured for the issue: KG % -> bpvf).
TARGET_FRACTION_OF_BEST = 0.6
FAMC_SEQUENCE = 'chickenCrossing'
FAMC_BPVF = {0.3: 1.65, 1.0: 0.749}
TARGET_FRACTION_OF_FAMC = 0.5


def octree_at(seq, kg):
    """(bpvf, max error) of the Affine-Octree default profile at KG error kg, log-log
    interpolated on its sweep; None where the sweep does not reach kg."""
    points = [(r['kg_error'], r['bpvf'], me) for me, r in seq['sweep'].items() if 'error' not in r]
    bpvf = loglog_interp([(k, b) for k, b, _ in points], kg)
    max_error = loglog_interp([(k, me) for k, _, me in points], kg)
    return bpvf, max_error


def decode_speed(animc, seq, ams, args, runs):
    """(decode M v/s, KG %) of seq encoded with args into ams, or (None, None)."""
    encoded = animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--json'] + args)
    r = encoded and animc_json([animc, 'bench', ams, '--threads', '1', '--runs', str(runs), '--json'])
    return (r['decode_mvps'], encoded['kg_error']) if r else (None, None)


def sequence_rows(animc, seq, runs, work):
    rows, speed_rows, failures = [], [], 0
    decode_runs = max(runs, 9)
    for kg in TARGETS_KG:
        log(f'{seq["name"]}: trajectory and wavelet at KG {kg} %')
        t = run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'trajectory', '--target-kg', repr(kg)], runs)
        a = run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'auto', '--target-kg', repr(kg)], runs)
        w = run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'wavelet', '--target-kg', repr(kg), '--step', '1e-5'],
                      runs)
        o, max_error = octree_at(seq, kg)
        failed = next((r for r in (t, a, w) if 'error' in r), None)
        if failed:
            failures += 1
            rows.append([f'{kg:g}', failed_cell(failed)] + [''] * 8)
            continue
        best = min(b for b in (o, w['bpvf']) if b)
        ratio = a['bpvf'] / best
        famc = FAMC_BPVF.get(kg) if seq['name'] == FAMC_SEQUENCE else None
        rows.append([f'{kg:g}', num(o, 3), num(w['bpvf'], 3), num(t['bpvf'], 3), num(a['bpvf'], 3),
                     num(a['kg_error'], 3), num(ratio, 2) + '×',
                     'yes' if ratio <= TARGET_FRACTION_OF_BEST else '**no**', num(famc, 3) if famc else '–',
                     (num(a['bpvf'] / famc, 2) + '× ' + ('yes' if a['bpvf'] <= TARGET_FRACTION_OF_FAMC * famc
                                                           else '**no**')) if famc else '–'])
        log(f'{seq["name"]}: decode speeds at KG {kg} %')
        t_speed, _ = decode_speed(animc, seq, os.path.join(work, 't.ams'),
                                  ['--codec', 'trajectory', '--target-kg', repr(kg)], decode_runs)
        octree_args = ['--codec', 'affine-octree', '--max-error', repr(max_error)] if max_error else None
        o_speed, o_kg = (decode_speed(animc, seq, os.path.join(work, 'o.ams'), octree_args, decode_runs)
                         if octree_args else (None, None))
        failures += t_speed is None
        speed_rows.append([f'{kg:g}', num(t_speed), f'{max_error:.4g}' if max_error else 'n/a', num(o_kg, 3),
                           num(o_speed), num(t_speed / o_speed, 2) + '×' if t_speed and o_speed else 'n/a'])
    return rows, speed_rows, failures


def trajectory_section(animc, sequences, runs):
    """(Markdown lines, failures)."""
    lines = ['## Trajectory and auto codecs against our earlier codecs and FAMC', '',
             f'Issue 27\'s targets at KG 0.3 % and 1 %: `--codec auto` at most '
             f'{TARGET_FRACTION_OF_BEST:g}× the bpvf of our best earlier codec on every sequence, and on '
             f'{FAMC_SEQUENCE} at most {TARGET_FRACTION_OF_FAMC:g}× FAMC\'s (the MPEG-4 reference software, best of '
             'its modes and settings, as measured for the issue). Trajectory: `animc bench IN --mesh M --codec '
             f'trajectory --target-kg X --runs {runs}`; auto (per group the smaller of trajectory and wavelet): the '
             'same with `--codec auto`; wavelet: with `--codec wavelet --target-kg X --step 1e-5`; Affine-Octree '
             '(default profile, no KG target): bpvf interpolated log-log on its max-error sweep above. bpvf counts the whole file. Decode speeds: `animc bench FILE.ams` (median of '
             f'{max(runs, 9)} runs) of a trajectory file and of an Affine-Octree file encoded at the max error '
             'interpolated from the sweep for the same KG (its measured KG in the table), one after the other.', '']
    failures = 0
    with tempfile.TemporaryDirectory(prefix='animc_bench_trajectory_') as work:
        for seq in sequences:
            rows, speed_rows, f = sequence_rows(animc, seq, runs, work)
            failures += f
            lines += [f'### {seq["name"]}', '']
            lines += table(['KG % target', 'Affine-Octree bpvf', 'wavelet bpvf', 'trajectory bpvf', 'auto bpvf',
                            'auto KG %', 'auto / best earlier', f'≤ {TARGET_FRACTION_OF_BEST:g}×', 'FAMC bpvf',
                            'auto / FAMC, ≤ 0.5×'], rows) + ['']
            lines += table(['KG % target', 'trajectory decode M v/s', 'Affine-Octree max error', 'its KG %',
                            'Affine-Octree decode M v/s', 'trajectory / Affine-Octree'], speed_rows) + ['']
    return lines, failures
