#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The wavelet codec against the Affine-Octree codec: rate-distortion table and plot, decode
speed, parametric (static) archive size. bench.py calls wavelet_section() with the sequences
it measured (their Affine-Octree sweeps and baseline points) and puts the returned Markdown
lines into docs/benchmarks.md; the plot goes to docs/img/rate_distortion.png."""
import os
import tempfile

from bench_common import (animc_json, encode_wavelet, failed_cell, log, loglog_interp, num, run_bench, step_label,
                          table)
from bench_progressive import progressive_section
from rd_plot import draw_rd_plot

# Quality mode (no rate limit): the finest quantisation step, fraction of the diagonal.
STEPS = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5]
# Rate control by target error: KG error in percent.
TARGETS_KG = [0.1, 0.3, 1, 3]
# The paper's fixed-rate points (Guskov & Khodakovsky 2004, section 5): bits per vertex per frame.
FIXED_RATES = [1, 2, 4, 8]
# Paper, section 5: the Cow's parametric mesh (connectivity and geometry) takes 7 115 bytes for
# 2 904 vertices.
PAPER_COW_BYTES, PAPER_COW_VERTICES = 7115, 2904
PLOT = 'img/rate_distortion.png'


def wavelet_points(animc, seq, runs):
    """[(label, mode, result)] of the wavelet codec on one sequence; mode is 'step',
    'target' or 'fixed'."""
    settings = ([(step_label(v), 'step', ['--step', repr(v)]) for v in STEPS] +
                [(f'target KG {v:g} %', 'target', ['--target-kg', repr(v)]) for v in TARGETS_KG] +
                [(f'{v} bpv', 'fixed', ['--bpv', str(v)]) for v in FIXED_RATES])
    points = []
    for label, mode, args in settings:
        log(f'{seq["name"]}: bench --codec wavelet {" ".join(args)}')
        points.append((label, mode, run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'wavelet'] + args, runs)))
    return points


def octree_curve(seq):
    """(KG, bpvf) of the Affine-Octree default profile's max-error sweep."""
    return [(r['kg_error'], r['bpvf']) for r in seq['sweep'].values() if 'error' not in r]


def rd_table(seq, points):
    octree = octree_curve(seq)
    base = [(p['kg_error'], p['bpvf']) for p in seq['baseline']]
    rows = []
    for label, _mode, r in points:
        if 'error' in r:
            rows.append([label, failed_cell(r)] + [''] * 7)
            continue
        o = loglog_interp(octree, r['kg_error'])
        b = loglog_interp(base, r['kg_error'])
        rows.append([label, num(r['bpvf'], 3), num(r['kg_error'], 3), num(r['psnr'], 1),
                     num(r['encode_mvps']), num(r['decode_mvps']), num(o, 3),
                     num(r['bpvf'] / o, 2) + '×' if o else 'n/a', num(b, 3)])
    return table(['wavelet setting', 'bpvf', 'KG %', 'PSNR dB', 'encode M v/s', 'decode M v/s',
                  'Affine-Octree default bpvf at same KG', 'wavelet / Affine-Octree', 'baseline bpvf at same KG'],
                 rows)


def static_size(animc, seq):
    """{'static_bytes', 'conn_bytes', 'vertices', 'triangles'} of a default wavelet encoding, or None."""
    with tempfile.TemporaryDirectory(prefix='animc-wavelet-') as work:
        ams = os.path.join(work, 'w.ams')
        info = encode_wavelet(animc, seq, ams, []) and animc_json([animc, 'info', ams, '--json'])
        if info is None:
            log(f'{seq["name"]}: wavelet static size FAILED')
            return None
        return {'static_bytes': info['static_bytes'], 'conn_bytes': info['section_CONN_bytes'],
                'vertices': info['vertices'], 'triangles': info['triangles']}


def static_table(rows):
    out = [['Cow (paper)', f'{PAPER_COW_VERTICES:,}', 'n/a', f'{PAPER_COW_BYTES:,}', 'n/a', 'n/a',
            num(8 * PAPER_COW_BYTES / PAPER_COW_VERTICES, 1)]]
    for name, s in rows:
        if s is None:
            out.append([name, 'failed', '', '', '', '', ''])
            continue
        first = s['static_bytes'] - s['conn_bytes']
        out.append([name, f'{s["vertices"]:,}', f'{s["triangles"]:,}', f'{s["static_bytes"]:,}',
                    f'{s["conn_bytes"]:,} ({num(8 * s["conn_bytes"] / max(1, s["triangles"]), 1)} bits/triangle)',
                    f'{first:,} ({num(8 * first / s["vertices"], 1)} bits/vertex)',
                    num(8 * s['static_bytes'] / s['vertices'], 1)])
    return table(['sequence', 'vertices', 'triangles', 'static bytes', 'connectivity (CONN)',
                  'parametric frame + headers', 'bits per vertex'], out)


def mode_points(points, mode):
    return [(r['bpvf'], r['kg_error']) for _l, m, r in points if m == mode and 'error' not in r]


def plot_series(seq, points):
    """The rate-distortion plot's series for one sequence: {label: [(bpvf, KG)]}."""
    paper_profile = [(r['bpvf'], r['kg_error']) for (profile, _me), r in seq['results'].items()
                     if profile == 'paper' and 'error' not in r]
    return {
        'Affine-Octree default': [(r['bpvf'], r['kg_error']) for r in seq['sweep'].values() if 'error' not in r],
        'Affine-Octree paper': paper_profile,
        'wavelet (step)': mode_points(points, 'step'),
        'wavelet (target KG)': mode_points(points, 'target'),
        'wavelet at 1/2/4/8 bpv (points)': mode_points(points, 'fixed'),
        'baseline (quantise, delta, xz)': [(p['bpvf'], p['kg_error']) for p in seq['baseline']],
    }


def wavelet_section(animc, sequences, runs, docs_dir):
    """Markdown lines of the wavelet section; the number of failed measurements."""
    lines = ['## Wavelet codec against the Affine-Octree codec', '',
             f'Every wavelet point is `animc bench IN --mesh M --codec wavelet --step S` (quality mode: no '
             f'rate limit, S = finest quantisation step as a fraction of the first frame\'s bounding-box '
             f'diagonal, default 1e-4), `--target-kg X` (rate control: the fewest bits per frame that keep '
             f'the KG error at or below X %) or `--bpv B` (fixed rate: each frame cut at B bits per vertex; '
             f'the paper\'s 1/2/4/8 bpv points), `--runs {runs}`, medians. "Affine-Octree default bpvf at same KG" is '
             'interpolated log-log on the default profile\'s max-error sweep of the same sequence (above); '
             '"wavelet / Affine-Octree" below 1.00× means the wavelet codec needs fewer bits at that KG '
             'error. The baseline is bench/baseline.py as above.', '',
             f'![KG error against bpvf, both codecs, every sequence]({PLOT})', '']
    failures = 0
    series = {}
    static_rows = []
    step_points = {}  # sequence name -> {label: result} of the quality-mode points
    for seq in sequences:
        points = wavelet_points(animc, seq, runs)
        step_points[seq['name']] = {label: r for label, mode, r in points if mode == 'step'}
        failures += sum('error' in r for _l, _m, r in points)
        lines += [f'### {seq["name"]}', ''] + rd_table(seq, points) + ['']
        series[seq['name']] = plot_series(seq, points)
        static_rows.append((seq['name'], static_size(animc, seq)))
    try:
        draw_rd_plot(series, os.path.join(docs_dir, PLOT))
    except RuntimeError as e:
        log(f'rate-distortion plot FAILED: {e}')
        lines += [f'(The plot could not be drawn: {e})', '']
        failures += 1
    lines += ['### Parametric archive', '',
              'What a wavelet file spends before the first detail frame: header, connectivity (CONN, '
              'triangle order preserved) and the parametric frame (frame 0, 14-bit grid), from '
              '`animc encode --codec wavelet` + `animc info --json`. The paper reports 7 115 bytes for the '
              'Cow\'s parametric mesh (2 904 vertices; coder of [KADS02]).', '']
    lines += static_table(static_rows) + ['']
    failures += sum(s is None for _n, s in static_rows)
    progressive_lines, progressive_failures = progressive_section(animc, sequences, step_points)
    return lines + progressive_lines, failures + progressive_failures
