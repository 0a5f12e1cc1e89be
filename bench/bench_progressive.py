#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Progressive decoding of wavelet files with P-frames (`--progressive-p-frames`): what the
option costs in rate, and what a decoder that keeps only the first N bytes of every frame
gets, against I-frames only and against the encoder's own fixed rate. bench_wavelet.py puts
the returned Markdown lines into docs/benchmarks.md."""
import os
import subprocess
import tempfile

from bench_common import animc_json, encode_wavelet, log, num, step_label, table

COST_STEPS = [1e-2, 1e-3, 1e-4]
CUT_STEP = 1e-4
CUT_BYTES = [300, 1000, 3000]   # bytes kept of every detail frame
CUT_SEQUENCE = 'chickenCrossing'
GROUP = 25                      # --iframe-interval of the grouped file


def cut_kg(animc, seq, ams, cut_bytes, work):
    """KG error of the file decoded from the first cut_bytes of every frame."""
    out = os.path.join(work, 'cut.pc2')
    p = subprocess.run([animc, 'decode', ams, '-o', out, '--max-bytes', str(cut_bytes)],
                       capture_output=True, text=True)
    if p.returncode != 0:
        log(f'  FAILED: decode --max-bytes {cut_bytes}: {p.stderr.strip()}')
        return None
    r = animc_json([animc, 'compare', seq['pc2'], out, '--mesh', seq['ply'], '--json'])
    return r and r['kg_error']


def cost_rows(animc, seq, plain_points, work):
    """plain_points: {label: animc bench result} of the same steps without the option."""
    rows, failures = [], 0
    ams = os.path.join(work, 'cost.ams')
    for step in COST_STEPS:
        log(f'{seq["name"]}: wavelet step {step:g} with --progressive-p-frames')
        plain = plain_points.get(step_label(step), {'error': 'not measured'})
        progressive = encode_wavelet(animc, seq, ams, ['--step', repr(step), '--progressive-p-frames'])
        if 'error' in plain or progressive is None:
            rows.append([seq['name'], f'{step:g}', 'failed', '', '', ''])
            failures += progressive is None
            continue
        rows.append([seq['name'], f'{step:g}', num(plain['bpvf'], 3), num(progressive['bpvf'], 3),
                     f'{100 * (progressive["bpvf"] / plain["bpvf"] - 1):+.1f} %', num(progressive['kg_error'], 4)])
    return rows, failures


def cut_rows(animc, seq, work):
    """KG at each byte cut for: progressive P-frames (one group, groups of GROUP frames),
    I-frames only, and the encoder's own --bpv at the same rate (closed loop)."""
    files = [('P, one group', ['--progressive-p-frames']),
             (f'P, groups of {GROUP}', ['--progressive-p-frames', '--iframe-interval', str(GROUP)]),
             ('I-frames only', ['--i-frames-only'])]
    paths, failures = [], 0
    for i, (label, args) in enumerate(files):
        path = os.path.join(work, f'cut{i}.ams')
        log(f'{seq["name"]}: wavelet step {CUT_STEP:g} {label}')
        ok = encode_wavelet(animc, seq, path, ['--step', repr(CUT_STEP)] + args) is not None
        failures += not ok
        paths.append(path if ok else None)
    rows = []
    for cut in CUT_BYTES:
        kgs = [cut_kg(animc, seq, p, cut, work) if p else None for p in paths]
        bpv = 8.0 * cut / seq['vertices']
        closed = encode_wavelet(animc, seq, os.path.join(work, 'bpv.ams'), ['--step', repr(CUT_STEP), '--bpv', f'{bpv:.4f}'])
        failures += sum(k is None for k in kgs) + (closed is None)
        rows.append([str(cut), num(bpv, 2)] + [num(k, 3) for k in kgs] + [num(closed and closed['kg_error'], 3)])
    return rows, [label for label, _a in files], failures


def progressive_section(animc, sequences, step_points):
    """Markdown lines; the number of failed measurements. step_points: {sequence name:
    {label: animc bench result}} of the quality-mode points without the option."""
    lines = ['### Progressive P-frames', '',
             '`animc encode --codec wavelet --progressive-p-frames` codes P-frames without the previous '
             'frame\'s bitplane history as context, so that `animc decode --bitplanes K` / `--max-bytes N` '
             'may cut them; a cut frame\'s error then drifts through the later P-frames of its group '
             '(docs/wavelet.md, "Progressive decoding"). Cost in rate: the bpvf of the quality-mode points above '
             '(`animc bench --step S`) against `animc encode --json --step S --progressive-p-frames` (KG is the '
             'same: whole frames decode identically).', '']
    rows, failures = [], 0
    with tempfile.TemporaryDirectory(prefix='animc-progressive-') as work:
        for seq in sequences:
            r, f = cost_rows(animc, seq, step_points.get(seq['name'], {}), work)
            rows += r
            failures += f
        lines += table(['sequence', 'step', 'bpvf', 'bpvf, progressive P-frames', 'cost', 'KG %'], rows) + ['']
        cut_seq = next((s for s in sequences if s['name'] == CUT_SEQUENCE), None)
        if cut_seq is not None:
            rows, labels, f = cut_rows(animc, cut_seq, work)
            failures += f
            lines += [f'{CUT_SEQUENCE}, files at step {CUT_STEP:g} decoded from the first N bytes of every '
                      f'detail frame (`animc decode --max-bytes N`, then `animc compare`): KG error in %. The last '
                      f'column is the encoder\'s own fixed rate at the same bits per vertex (`--bpv`, closed loop, '
                      f'no drift), what a sender that knows the rate in advance gets.', '']
            lines += table(['N bytes', 'bpv'] + [f'KG, {label}' for label in labels] + ['KG, encoder --bpv (P-frames)'],
                           rows) + ['']
    return lines, failures
