#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Encoding through the MeshLab filter against `animc encode` on the same frames.

usage: bench/bench_plugin.py [--animc PATH] [--data DIR] [--runs R]   (prints a Markdown section)

For each sequence NAME/ of --data: every frame is written as a binary PLY (what MeshLab loads
as layers) and as an uncompressed PC2. Then, R times each, in turns:
- meshlabserver (staged in build/stage, headless through scripts/meshlabserver.sh) runs Compress
  Animation Layers (default profile, max error 1 %) on the layers, without and with the
  reconstructed layers and error colours; the filter logs its own wall time ("whole filter":
  reading the layers, checking them, encoding, writing the file, measuring the error);
- `animc encode NAME.pc2 --mesh NAME.ply` with the same settings, timed as a whole process
  (start-up, reading the PC2, encoding, writing, measuring).
Medians are compared; both .ams files must be byte-identical. bench.py includes this section in
docs/benchmarks.md."""
import argparse
import filecmp
import lzma
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, 'scripts'))
import pc2 as pc2_format  # noqa: E402
from bench_common import find_sequences, table  # noqa: E402
from make_samples import write_ply_frames  # noqa: E402
from mlx_script import with_values  # noqa: E402

MAX_ERROR_PERCENT = 1
SAMPLE_SCRIPT = os.path.join(REPO, 'samples', 'compress.mlx')


def filter_script(output, layers):
    """samples/compress.mlx with this benchmark's codec (Affine-Octree, enum value 0), max error,
    output and layer options."""
    return with_values(SAMPLE_SCRIPT, {'Codec': '0', 'MaxErrorPercent': str(MAX_ERROR_PERCENT), 'OutputFile': output,
                                       'AddReconstructed': layers, 'ColourByError': layers})


FILTER_TIME = re.compile(r'encode time: ([0-9.]+) s .*; whole filter ([0-9.]+) s')


def log(message):
    print(f'[bench_plugin] {message}', file=sys.stderr, flush=True)


def prepare(name, pc2_xz, ply, tmp):
    """Writes tmp/NAME/frames/*.ply and tmp/NAME/NAME.pc2; returns (frame paths, pc2, mesh,
    vertices, frames)."""
    with lzma.open(pc2_xz, 'rb') as f:
        pc2 = f.read()
    points, frames = pc2_format.parse_header(pc2, pc2_xz)[::3]
    work = os.path.join(tmp, name)
    os.makedirs(work)
    write_ply_frames(ply, points, pc2[32:], os.path.join(work, 'frames'), frames)
    with open(os.path.join(work, name + '.pc2'), 'wb') as f:
        f.write(pc2)
    paths = [os.path.join(work, 'frames', 'frame_%05d.ply' % i) for i in range(frames)]
    return paths, os.path.join(work, name + '.pc2'), ply, points, frames


def run_filter(frames, work, layers):
    """One meshlabserver run; returns (encode seconds, whole-filter seconds, .ams path)."""
    output = os.path.join(work, 'filter.ams')
    script = os.path.join(work, 'compress.mlx')
    with open(script, 'w') as f:
        f.write(filter_script(output, 'true' if layers else 'false'))
    env = dict(os.environ, ANIMC_MESHLAB_HOME=os.path.join(work, 'home'))
    done = subprocess.run([os.path.join(REPO, 'scripts', 'meshlabserver.sh'), '-i', *frames, '-s', script],
                          capture_output=True, text=True, env=env, cwd=work)
    match = FILTER_TIME.search(done.stdout + done.stderr)
    if done.returncode != 0 or not match:
        raise RuntimeError(f'meshlabserver failed ({done.returncode}):\n{(done.stdout + done.stderr)[-2000:]}')
    return float(match.group(1)), float(match.group(2)), output


def run_cli(animc, pc2, mesh, work):
    """One `animc encode` process; returns (encode seconds, wall seconds, .ams path)."""
    output = os.path.join(work, 'cli.ams')
    start = time.perf_counter()
    done = subprocess.run([animc, 'encode', pc2, '--mesh', mesh, '-o', output, '--codec', 'affine-octree',
                           '--max-error', str(MAX_ERROR_PERCENT / 100), '--json'], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f'animc encode failed: {done.stderr}')
    return float(re.search(r'"encode_seconds":([0-9.eE+-]+)', done.stdout).group(1)), wall, output


def bench_sequence(animc, name, pc2_xz, ply, runs, tmp):
    frames, pc2, mesh, points, count = prepare(name, pc2_xz, ply, tmp)
    work = os.path.dirname(pc2)
    cli, bare, full = [], [], []
    for run in range(runs):
        log(f'{name}: run {run + 1}/{runs}')
        cli.append(run_cli(animc, pc2, mesh, work))
        bare.append(run_filter(frames, work, layers=False))
        if not filecmp.cmp(cli[-1][2], bare[-1][2], shallow=False):
            raise RuntimeError(f'{name}: the filter and animc wrote different files')
        full.append(run_filter(frames, work, layers=True))
    med = lambda rows, k: statistics.median(r[k] for r in rows)  # noqa: E731
    return {'name': name, 'points': points, 'frames': count, 'cli_encode': med(cli, 0), 'cli_wall': med(cli, 1),
            'filter_encode': med(bare, 0), 'filter_wall': med(bare, 1), 'full_wall': med(full, 1)}


def section(rows, runs, command):
    lines = ['## Encoding through the MeshLab filter', '',
             f'Generated by `{command}` (`bench/bench_plugin.py` alone prints only this section). Compress Animation Layers (default profile, '
             f'max error {MAX_ERROR_PERCENT} %) in the staged meshlabserver on every frame loaded as a layer, '
             f'against `animc encode NAME.pc2 --mesh NAME.ply --codec affine-octree --max-error {MAX_ERROR_PERCENT / 100}` on the '
             f'same frames; medians of {runs} runs. "filter" is the wall time the filter logs for itself '
             '(read the layers, check them, encode, write, measure); "animc" is the whole process (start, '
             'read the PC2, encode, write, measure). "coding" is the time inside the encoder alone, which '
             'both report. The two .ams files were byte-identical in every run.', '']
    header = ['sequence', 'vertices × frames', 'animc (s)', 'filter (s)', 'filter / animc',
              'coding: animc / filter (s)', 'filter + reconstructed layers and colours (s)']
    cells = [[r['name'], f'{r["points"]} × {r["frames"]}', f'{r["cli_wall"]:.3f}', f'{r["filter_wall"]:.3f}',
              f'{r["filter_wall"] / r["cli_wall"]:.2f}', f'{r["cli_encode"]:.3f} / {r["filter_encode"]:.3f}',
              f'{r["full_wall"]:.3f}'] for r in rows]
    return lines + table(header, cells) + ['']


def plugin_section(animc, data, runs, command):
    rows = []
    with tempfile.TemporaryDirectory(prefix='animc_bench_plugin.') as tmp:
        for name, pc2_xz, ply in find_sequences(data):
            rows.append(bench_sequence(animc, name, pc2_xz, ply, runs, tmp))
    return section(rows, runs, command)


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--animc', default=os.path.join(REPO, 'build', 'animc', 'animc'))
    p.add_argument('--data', default=os.path.normpath(os.path.join(REPO, '..', 'shared', 'data')))
    p.add_argument('--runs', type=int, default=5)
    args = p.parse_args()
    print('\n'.join(plugin_section(os.path.abspath(args.animc), args.data, args.runs, ' '.join(sys.argv))))


if __name__ == '__main__':
    main()
