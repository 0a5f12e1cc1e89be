#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Rate-distortion plot (KG error against bits per vertex per frame) of several codecs on
several sequences, one panel per sequence, drawn by gnuplot (Debian's gnuplot-nox, installed
by scripts/setup.sh) into a PNG. bench.py calls draw_rd_plot() for docs/img/rate_distortion.png.

usage: bench/rd_plot.py POINTS.json OUT.png
POINTS.json: {"sequence": {"series label": [[bpvf, kg_percent], ...], ...}, ...}; a label
ending in " (points)" is drawn as markers only, the others as lines with markers."""
import json
import math
import os
import subprocess
import sys
import tempfile

COLUMNS = 2


def _usable(points):
    return sorted((x, y) for x, y in points if x and y and x > 0 and y > 0 and math.isfinite(x) and math.isfinite(y))


def _panel(name, series, data_dir, index):
    """gnuplot commands of one panel; writes its data files into data_dir."""
    plots = []
    for k, (label, points) in enumerate(series.items()):
        pts = _usable(points)
        if not pts:
            continue
        path = os.path.join(data_dir, f'p{index}_{k}.dat')
        with open(path, 'w') as f:
            f.writelines(f'{x} {y}\n' for x, y in pts)
        style = 'points pt 7 ps 1.6' if label.endswith(' (points)') else 'linespoints pt 7 ps 0.6 lw 2'
        plots.append(f"'{path}' using 1:2 with {style} lc {k + 1} title \"{label}\"")
    if not plots:
        return [f'set title "{name}: no data"', 'unset key', 'plot [1:2] [1:2] 1.5 notitle lc rgb "white"']
    return [f'set title "{name}"', 'set key top right font ",9"', 'plot ' + ', \\\n     '.join(plots)]


def draw_rd_plot(points_by_sequence, out_png):
    """Writes out_png atomically; raises RuntimeError when gnuplot fails or is missing."""
    names = list(points_by_sequence)
    rows = max(1, math.ceil(len(names) / COLUMNS))
    with tempfile.TemporaryDirectory(prefix='rdplot-') as work:
        tmp_png = os.path.join(work, 'plot.png')
        script = [f"set terminal pngcairo noenhanced size {620 * COLUMNS},{460 * rows} font 'DejaVu Sans,10'",
                  f"set output '{tmp_png}'",
                  'set logscale xy', 'set grid xtics ytics mxtics mytics lc rgb "#dddddd"',
                  'set xlabel "bits per vertex per frame (whole file)"', 'set ylabel "KG error (%)"',
                  f'set multiplot layout {rows},{COLUMNS}']
        for i, name in enumerate(names):
            script += _panel(name, points_by_sequence[name], work, i)
        script += ['unset multiplot', 'set output']
        try:
            p = subprocess.run(['gnuplot'], input='\n'.join(script) + '\n', capture_output=True, text=True)
        except FileNotFoundError:
            raise RuntimeError('gnuplot not found (scripts/setup.sh installs gnuplot-nox)')
        if p.returncode != 0 or not os.path.isfile(tmp_png):
            raise RuntimeError(f'gnuplot failed (exit {p.returncode}): {p.stderr.strip()[:500]}')
        os.makedirs(os.path.dirname(os.path.abspath(out_png)), exist_ok=True)
        staged = out_png + '.tmp'
        with open(tmp_png, 'rb') as src, open(staged, 'wb') as dst:
            dst.write(src.read())
        os.replace(staged, out_png)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        draw_rd_plot(json.load(f), sys.argv[2])


if __name__ == '__main__':
    main()
