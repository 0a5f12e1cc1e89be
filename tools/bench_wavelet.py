#!/usr/bin/python3
"""The wavelet codec against the Affine-Octree codec: rate-distortion table and plot, decode
speed, parametric (static) archive size. bench.py calls wavelet_section() with the sequences
it measured (their Affine-Octree sweeps and baseline points) and puts the returned Markdown
lines into docs/benchmarks.md; the plot goes to docs/img/rate_distortion.png."""
import json
import os
import subprocess
import tempfile

from bench_common import failed_cell, log, loglog_interp, num, run_bench, table
from rd_plot import draw_rd_plot

# Quality mode (no rate limit): the finest quantisation step, fraction of the diagonal.
STEPS = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5]
# The paper's fixed-rate points (Guskov & Khodakovsky 2004, section 5): bits per vertex per frame.
FIXED_RATES = [1, 2, 4, 8]
# Paper, section 5: the Cow's parametric mesh (connectivity and geometry) takes 7 115 bytes for
# 2 904 vertices.
PAPER_COW_BYTES, PAPER_COW_VERTICES = 7115, 2904
PLOT = 'img/rate_distortion.png'


def wavelet_points(animc, seq, runs):
    """[(label, is_fixed_rate, result)] of the wavelet codec on one sequence."""
    points = []
    for step in STEPS:
        log(f'{seq["name"]}: bench --codec wavelet --step {step}')
        points.append((f'step {step:g}', False,
                       run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'wavelet', '--step', repr(step)], runs)))
    for bpv in FIXED_RATES:
        log(f'{seq["name"]}: bench --codec wavelet --bpv {bpv}')
        points.append((f'{bpv} bpv', True,
                       run_bench(animc, seq['pc2'], seq['ply'], ['--codec', 'wavelet', '--bpv', str(bpv)], runs)))
    return points


def octree_curve(seq):
    """(KG, bpvf) of the Affine-Octree default profile's max-error sweep."""
    return [(r['kg_error'], r['bpvf']) for r in seq['sweep'].values() if 'error' not in r]


def rd_table(seq, points):
    octree = octree_curve(seq)
    base = [(p['kg_error'], p['bpvf']) for p in seq['baseline']]
    rows = []
    for label, _fixed, r in points:
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
    """{'static_bytes', 'conn_bytes', 'vertices'} of a default wavelet encoding, or None."""
    with tempfile.TemporaryDirectory(prefix='animc-wavelet-') as work:
        ams = os.path.join(work, 'w.ams')
        enc = subprocess.run([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--codec', 'wavelet',
                              '--json'], capture_output=True, text=True)
        info = subprocess.run([animc, 'info', ams, '--json'], capture_output=True, text=True)
        if enc.returncode != 0 or info.returncode != 0:
            log(f'{seq["name"]}: wavelet static size FAILED: {enc.stderr.strip()} {info.stderr.strip()}')
            return None
        i = json.loads(info.stdout)
        return {'static_bytes': i['static_bytes'], 'conn_bytes': i['section_CONN_bytes'], 'vertices': i['vertices'],
                'triangles': i['triangles']}


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


def plot_series(seq, points):
    """The rate-distortion plot's series for one sequence: {label: [(bpvf, KG)]}."""
    paper_profile = [(r['bpvf'], r['kg_error']) for (profile, _me), r in seq['results'].items()
                     if profile == 'paper' and 'error' not in r]
    return {
        'Affine-Octree default': [(r['bpvf'], r['kg_error']) for r in seq['sweep'].values() if 'error' not in r],
        'Affine-Octree paper': paper_profile,
        'wavelet (step)': [(r['bpvf'], r['kg_error']) for _l, fixed, r in points if not fixed and 'error' not in r],
        'wavelet at 1/2/4/8 bpv (points)': [(r['bpvf'], r['kg_error']) for _l, fixed, r in points
                                             if fixed and 'error' not in r],
        'baseline (quantise, delta, xz)': [(p['bpvf'], p['kg_error']) for p in seq['baseline']],
    }


def wavelet_section(animc, sequences, runs, docs_dir):
    """Markdown lines of the wavelet section; the number of failed measurements."""
    lines = ['## Wavelet codec against the Affine-Octree codec', '',
             f'Every wavelet point is `animc bench IN --mesh M --codec wavelet --step S` (quality mode: no '
             f'rate limit, S = finest quantisation step as a fraction of the first frame\'s bounding-box '
             f'diagonal) or `--bpv B` (fixed rate: each frame cut at B bits per vertex; the paper\'s '
             f'1/2/4/8 bpv points), `--runs {runs}`, medians. "Affine-Octree default bpvf at same KG" is '
             'interpolated log-log on the default profile\'s max-error sweep of the same sequence (above); '
             '"wavelet / Affine-Octree" below 1.00× means the wavelet codec needs fewer bits at that KG '
             'error. The baseline is tools/baseline.py as above.', '',
             f'![KG error against bpvf, both codecs, every sequence]({PLOT})', '']
    failures = 0
    series = {}
    static_rows = []
    for seq in sequences:
        points = wavelet_points(animc, seq, runs)
        failures += sum('error' in r for _l, _f, r in points)
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
    return lines, failures
