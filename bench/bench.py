#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Benchmark animc on every sequence of the data folder and write docs/benchmarks.md.

usage: bench/bench.py [--animc PATH] [--data DIR] [--runs R] [--out FILE] [--quick] [--no-plugin]

For each sequence folder NAME/ (NAME.ply + NAME.pc2.xz) of --data (default
../shared/data from the repository root):
1. `animc bench` at max error 1 %, 5 %, 10 % of the root cube (and 15 %, 25 % on
   chickenCrossing, to meet every row of the Affine-Octree paper's Table II) with both
   profiles, R runs each (medians, as animc bench reports them);
2. an equal-KG comparison with the simple baseline (bench/baseline.py, B = 6..14 bits;
   its results are cached next to --out in baseline_cache.json, keyed by the sha256 of the
   uncompressed sequence and B) over a max-error sweep of the default profile;
3. unless --quick: peak memory of `animc encode` / `animc decode` on a 100 000-frame
   sequence made by bench/long_sequence.py from sydney_md2, and on a 1 000-frame one;
4. the wavelet codec (bench/bench_wavelet.py): quality steps and the paper's 1/2/4/8 bpv
   fixed rates on every sequence, against the Affine-Octree sweep at equal KG error, with the
   rate-distortion plot docs/img/rate_distortion.png (bench/rd_plot.py, gnuplot), and the
   parametric archive size against the paper's Cow, and the cost and cuts of progressive
   P-frames (bench/bench_progressive.py);
5. decoding through the public Decoder from a file and from memory (bench/bench_decode_paths.py),
   and backwards, a random access a frame, into trajectory files (bench/bench_random_access.py);
   reading every sequence format (bench/bench_readers.py); the glb of `animc decode` beside
   the .ams and gltfpack -cc (bench/bench_gltf.py); the trajectory codec against the other two and FAMC at KG 0.3 % and 1 %, and its decode
   speed against the Affine-Octree codec's (bench/bench_trajectory.py);
6. unless --no-plugin: encoding through the MeshLab filter against animc encode
   (bench/bench_plugin.py; needs the staged MeshLab of `cmake --install build --prefix build/stage`).
Progress goes to stderr; the Markdown report to --out (default docs/benchmarks.md)."""
import argparse
import datetime
import hashlib
import json
import lzma
import os
import platform
import shlex
import shutil
import subprocess
import sys
import tempfile
import time


REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, 'scripts'))
import pc2 as pc2_format  # noqa: E402
from long_sequence import write_long_sequence  # noqa: E402
from bench_plugin import plugin_section  # noqa: E402
from bench_wavelet import wavelet_section  # noqa: E402
from bench_decode_paths import decode_paths_section  # noqa: E402
from bench_random_access import random_access_section  # noqa: E402
from bench_readers import readers_section  # noqa: E402
from bench_gltf import gltf_section  # noqa: E402
from bench_trajectory import trajectory_section  # noqa: E402
from bench_trajectory2 import trajectory2_section  # noqa: E402
from bench_threads import threads_section  # noqa: E402
from bench_encoder_speed import encoder_speed_section  # noqa: E402
from bench_web import web_section  # noqa: E402
from bench_common import (log, run_bench, run_measured, loglog_interp, num, pct, mib, table,  # noqa: E402
                          failed_cell, find_sequences, START)

PROFILES = ['paper', 'predictive']
MAX_ERRORS = [0.01, 0.05, 0.10]
SWEEP_MAX_ERRORS = [0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.10, 0.15, 0.25]  # default profile, runs=1
BASELINE_BITS = list(range(4, 15))

# Affine-Octree paper, Table II, "Ours" on Chicken: ME, Size (bytes), ratio, PSNR (dB).
PAPER_SEQUENCE = 'chickenCrossing'
PAPER_CHICKEN = [(0.01, 709139, 20.51, 39.43), (0.05, 242625, 59.94, 32.0),
                 (0.10, 119231, 121.98, 29.0), (0.15, 79548, 182.83, 27.74),
                 (0.25, 44023, 330.37, 26.0)]
# DESIGN.md, "Measured on chickenCrossing": the simple baseline at B = 12 / 10 / 8.
DESIGN_REFERENCE = [(12, 0.20, 7.2), (10, 0.81, 4.8), (8, 3.3, 3.4)]

# Long-sequence memory test (skipped with --quick).
LONG_SOURCE = 'sydney_md2'
LONG_FRAMES = [1000, 100000]
LONG_SETTINGS = ['--profile', 'predictive', '--max-error', '0.01']

# ---------------------------------------------------------------- running things

def octree_settings(profile, max_error):
    return ['--profile', profile, '--max-error', repr(max_error)]


def bench_sequence(animc, name, pc2, ply, runs):
    """{(profile, max_error): result} for the main table (and the paper comparison)."""
    max_errors = list(MAX_ERRORS)
    if name == PAPER_SEQUENCE:
        max_errors += [me for me, *_ in PAPER_CHICKEN if me not in max_errors]
    results = {}
    for profile in PROFILES:
        for me in max_errors:
            log(f'{name}: bench --profile {profile} --max-error {me} --runs {runs}')
            results[(profile, me)] = run_bench(animc, pc2, ply, octree_settings(profile, me), runs)
    return results


def sweep_sequence(animc, name, pc2, ply, main_results):
    """{max_error: result} of the default profile over SWEEP_MAX_ERRORS (runs=1), reusing
    the points already measured for the main table (the metrics do not depend on R)."""
    sweep = {}
    for me in SWEEP_MAX_ERRORS:
        if ('predictive', me) in main_results:
            sweep[me] = main_results[('predictive', me)]
            continue
        log(f'{name}: sweep --profile default --max-error {me}')
        sweep[me] = run_bench(animc, pc2, ply, octree_settings('predictive', me), 1)
    return sweep


def sequence_info(pc2_xz):
    """(sha256 of the uncompressed PC2, the one SOURCE.md quotes; vertices; frames)."""
    h = hashlib.sha256()
    with lzma.open(pc2_xz, 'rb') as f:
        head = f.read(32)
        h.update(head)
        for block in iter(lambda: f.read(1 << 20), b''):
            h.update(block)
    header = pc2_format.parse_header(head, pc2_xz)
    return h.hexdigest(), header.points, header.frames


def file_sha256(path):
    with open(path, 'rb') as f:
        return hashlib.sha256(f.read()).hexdigest()


def load_baseline_cache(path, baseline_hash):
    """The cache's entries, or {} if missing or made by another version of baseline.py."""
    try:
        with open(path) as f:
            cache = json.load(f)
    except (OSError, json.JSONDecodeError):
        return {}
    if cache.get('baseline_py_sha256') != baseline_hash:
        log(f'{path}: made by another baseline.py, measuring again')
        return {}
    return cache.get('entries', {})


def save_baseline_cache(path, baseline_hash, entries):
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump({'baseline_py_sha256': baseline_hash, 'entries': entries}, f, indent=1,
                  sort_keys=True)
        f.write('\n')
    os.replace(tmp, path)


def baseline_points(name, pc2, sha, entries, cache_path, baseline_hash):
    """[baseline.py result for B in BASELINE_BITS], measuring only what the cache lacks."""
    missing = [b for b in BASELINE_BITS if f'{sha}:{b}' not in entries]
    if missing:
        log(f'{name}: baseline.py for B = {missing} (slow, cached afterwards)')
        cmd = [sys.executable, os.path.join(REPO, 'bench', 'baseline.py'), pc2] + [str(b) for b in missing]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            log(f'  baseline.py FAILED (exit {p.returncode}): {p.stderr.strip()}')
            return []
        for line in p.stdout.splitlines():
            point = json.loads(line)
            entries[f'{sha}:{point["bits"]}'] = point
        save_baseline_cache(cache_path, baseline_hash, entries)
    return [entries[f'{sha}:{b}'] for b in BASELINE_BITS if f'{sha}:{b}' in entries]


# ---------------------------------------------------------------- peak memory

def memory_test(animc, data_dir, tmp_root, frame_counts):
    """[{frames, pc2_bytes, ams_bytes, encode_s, encode_rss_kib, decode_s, decode_rss_kib}]
    for long versions of LONG_SOURCE; files live in a temporary folder deleted afterwards."""
    src = os.path.join(data_dir, LONG_SOURCE, LONG_SOURCE + '.pc2.xz')
    ply = os.path.join(data_dir, LONG_SOURCE, LONG_SOURCE + '.ply')
    if not (os.path.isfile(src) and os.path.isfile(ply)):
        log(f'memory test skipped: no {LONG_SOURCE} in {data_dir}')
        return []
    rows = []
    work = tempfile.mkdtemp(prefix='animc-bench-', dir=tmp_root)
    try:
        for frames in frame_counts:
            pc2 = os.path.join(work, f'long{frames}.pc2')
            ams = os.path.join(work, f'long{frames}.ams')
            out = os.path.join(work, f'long{frames}.decoded.pc2')
            log(f'memory: writing {frames} frames of {LONG_SOURCE} to {pc2}')
            pc2_bytes = write_long_sequence(src, pc2, frames)
            row = {'frames': frames, 'pc2_bytes': pc2_bytes, 'vertices': (pc2_bytes - 32) // (12 * frames)}
            try:
                log(f'memory: encode {frames} frames')
                row['encode_s'], row['encode_rss_kib'], _ = run_measured(
                    [animc, 'encode', pc2, '--mesh', ply, '-o', ams] + LONG_SETTINGS)
                row['ams_bytes'] = os.path.getsize(ams)
                os.remove(pc2)
                log(f'memory: decode {frames} frames')
                row['decode_s'], row['decode_rss_kib'], _ = run_measured(
                    [animc, 'decode', ams, '-o', out])
            except RuntimeError as e:
                log(f'  FAILED: {e}')
                row['error'] = str(e).splitlines()[0]
            for path in (pc2, ams, out):
                if os.path.exists(path):
                    os.remove(path)
            rows.append(row)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return rows


# ---------------------------------------------------------------- Markdown

def main_table(results):
    rows = []
    for (profile, me), r in results.items():
        if 'error' in r:
            rows.append([profile, pct(me), failed_cell(r)] + [''] * 6)
            continue
        rows.append([profile, pct(me), num(r['ratio']) + ':1', num(r['bpvf'], 3), num(r['kg_error'], 3),
                     num(r['psnr'], 1), num(100 * r['max_error_rel_cube'], 2) + ' %',
                     num(r['encode_mvps']), num(r['decode_mvps'])])
    return table(['profile', 'ME', 'ratio', 'bpvf', 'KG %', 'PSNR dB', 'max error (rel. cube)',
                  'encode M v/s', 'decode M v/s'], rows)


def paper_table(results, vertex_frames):
    def ours(profile, me, key, digits):
        r = results.get((profile, me), {})
        return num(r[key], digits) if key in r else 'n/a'
    rows = []
    for me, size, ratio, psnr in PAPER_CHICKEN:
        rows.append([pct(me), f'{ratio:g}:1', num(8.0 * size / vertex_frames, 3), f'{psnr:g}',
                     ours('paper', me, 'ratio', 2) + ':1', ours('paper', me, 'bpvf', 3),
                     ours('paper', me, 'psnr', 1),
                     ours('predictive', me, 'ratio', 2) + ':1', ours('predictive', me, 'bpvf', 3),
                     ours('predictive', me, 'psnr', 1)])
    lines = table(['ME', 'paper ratio', 'paper bpvf', 'paper PSNR dB', 'ours (paper) ratio',
                   'ours (paper) bpvf', 'ours (paper) PSNR dB', 'ours (default) ratio',
                   'ours (default) bpvf', 'ours (default) PSNR dB'], rows)
    lines += ['',
              "Paper rows: Table II (\"Ours\") of the Affine-Octree paper; its bpvf is computed here from "
              "its Size column (bytes) and this sequence's vertex and frame counts (its raw size, Size × "
              "ratio, matches ours: 3030 vertices × 400 frames × 12 bytes). The paper's PSNR is "
              "10·log10(dmax²/MSE) with dmax \"the size of the largest bounding box\", not defined "
              "precisely; ours is 10·log10(diag²/MSE) with diag the bounding-box diagonal of the whole "
              "sequence and MSE the mean squared per-vertex distance. The dB values are therefore not "
              "directly comparable: compare ratios at equal max error (ME = fraction of the root cube's "
              "side)."]
    return lines


def equal_psnr_table(results, sweep):
    """The default profile's ratio at the PSNR our paper profile reaches at each paper ME,
    interpolated (log ratio over log PSNR) from the default profile's sweep."""
    ours = [(r['psnr'], r['ratio']) for r in sweep.values() if 'error' not in r]
    rows = []
    for me, _size, paper_ratio, _psnr in PAPER_CHICKEN:
        r = results.get(('paper', me), {})
        if 'psnr' not in r:
            continue
        d = loglog_interp(ours, r['psnr'])
        rows.append([pct(me), num(r['psnr'], 1), num(r['ratio'], 2) + ':1', f'{paper_ratio:g}:1',
                     num(d, 1) + ':1' if d else 'n/a',
                     num(d / r['ratio'], 2) + '×' if d else 'n/a',
                     num(d / paper_ratio, 2) + '×' if d else 'n/a'])
    return table(['paper ME', 'PSNR of our paper profile dB', 'our paper profile ratio',
                  'paper\'s published ratio', 'default profile ratio at that PSNR',
                  'default / our paper profile', 'default / published'], rows)


def baseline_tables(sweep, points):
    """Equal-KG table of the sweep against the baseline, and the baseline's points."""
    base = [(p['kg_error'], p['bpvf']) for p in points]
    rows = []
    for me, r in sweep.items():
        if 'error' in r:
            rows.append([pct(me), failed_cell(r), '', '', ''])
            continue
        b = loglog_interp(base, r['kg_error'])
        rows.append([pct(me), num(r['bpvf'], 3), num(r['kg_error'], 3), num(b, 3),
                     num(b / r['bpvf'], 2) + '×' if b is not None and r['bpvf'] > 0 else 'n/a'])
    lines = table(['ME', 'our bpvf', 'KG %', 'baseline bpvf at same KG', 'baseline / ours'], rows)
    lines += ['', 'Baseline (bench/baseline.py) points: ' +
              '; '.join(f'B={p["bits"]}: {p["bpvf"]:.3f} bpvf, KG {p["kg_error"]:.3f} %' for p in points)
              if points else 'Baseline: not available (baseline.py failed).']
    return lines


def reference_table(sweep, points):
    """Our bpvf at DESIGN.md's three baseline KG values, interpolated from the sweep."""
    ours = [(r['kg_error'], r['bpvf']) for r in sweep.values() if 'error' not in r]
    base = [(p['kg_error'], p['bpvf']) for p in points]
    rows = []
    for bits, kg, design_bpvf in DESIGN_REFERENCE:
        b = loglog_interp(base, kg)
        o = loglog_interp(ours, kg)
        rows.append([num(kg, 2), f'B = {bits}', num(design_bpvf, 1), num(b, 3), num(o, 3),
                     num(b / o, 2) + '×' if b is not None and o else 'n/a'])
    return table(['KG %', 'baseline setting', 'baseline bpvf (DESIGN.md)', 'baseline bpvf (measured here)',
                  'our bpvf (default profile)', 'baseline / ours'], rows)


def memory_table(rows):
    out = []
    for r in rows:
        if 'error' in r:
            out.append([r['frames'], mib(r['pc2_bytes']), failed_cell(r), '', '', '', ''])
            continue
        out.append([f'{r["frames"]:,}', mib(r['pc2_bytes']), mib(r['ams_bytes']),
                    num(r['encode_s'], 1), num(r['encode_rss_kib'] / 1024, 1) if r['encode_rss_kib'] else 'n/a',
                    num(r['decode_s'], 1), num(r['decode_rss_kib'] / 1024, 1) if r['decode_rss_kib'] else 'n/a'])
    return table(['frames', 'input PC2', '.ams', 'encode s', 'encode peak RSS MiB', 'decode s',
                  'decode peak RSS MiB'], out)


def memory_growth(rows):
    """A sentence on how much the peak RSS grows per extra frame, from the first to the
    last row, next to the size of one raw frame (what O(N·F) memory would add)."""
    ok = [r for r in rows if 'error' not in r and r.get('encode_rss_kib') and r.get('decode_rss_kib')]
    if len(ok) < 2 or ok[-1]['frames'] == ok[0]['frames']:
        return []
    extra = ok[-1]['frames'] - ok[0]['frames']
    growth = {k: 1024.0 * (ok[-1][k] - ok[0][k]) / extra for k in ('encode_rss_kib', 'decode_rss_kib')}
    return [f'Peak RSS growth from {ok[0]["frames"]:,} to {ok[-1]["frames"]:,} frames: '
            f'{growth["encode_rss_kib"]:.1f} bytes per extra frame when encoding, '
            f'{growth["decode_rss_kib"]:.1f} when decoding; one raw frame is {12 * ok[-1]["vertices"]:,} bytes.', '']


def git_head():
    try:
        return subprocess.run(['git', '-C', REPO, 'rev-parse', '--short', 'HEAD'], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return 'unknown'


def cpu_model():
    try:
        with open('/proc/cpuinfo') as f:
            for line in f:
                if line.startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or 'unknown'


def command_line():
    """The command line as typed, and where it was run."""
    where = 'from the repository root' if os.getcwd() == REPO else f'in `{os.getcwd()}`'
    return shlex.join(sys.argv), where


def write_report(path, args, sequences, wavelet_lines, memory_rows, plugin_lines, elapsed_s):
    command, where = command_line()
    lines = ['# animcompress benchmarks', '',
             f'Generated by `{command}` ({where})  ',
             f'Date: {datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")}, '
             f'commit `{git_head()}` of the repository (uncommitted changes, if any, are included)  ',
             f'Machine: {len(os.sched_getaffinity(0))} CPUs (nproc), {cpu_model()}, '
             f'{platform.system()} {platform.release()}  ',
             f'animc: `{args.animc}`; data: `{args.data}`; runtime of this script: {elapsed_s / 60:.1f} min',
             '',
             f'Every number comes from `animc bench IN --mesh M --profile P --max-error ME --runs {args.runs} '
             f'--json`: the sequence is read into memory first, then encoded and decoded {args.runs} '
             'time(s) on one core; speeds are the median over the runs, in million vertices (× frames) '
             'per second. ME is the codec\'s max-error setting as a fraction of the root cube\'s side; '
             '"max error (rel. cube)" is the measured maximum per-vertex error relative to the same '
             'cube side. bpvf counts the whole file (connectivity and first frame included); KG is the '
             'Karni–Gotsman error; PSNR is 10·log10(diag²/MSE), diag = bounding-box diagonal of the whole '
             'sequence. Definitions: DESIGN.md, "Metrics".', '']
    for s in sequences:
        lines += [f'## {s["name"]}', '', f'{s["vertices"]} vertices × {s["frames"]} frames, sha256 of the '
                  f'uncompressed PC2 `{s["sha256"][:16]}…`', '']
        lines += main_table(s['results']) + ['']
        if s['name'] == PAPER_SEQUENCE:
            lines += ['### Against the Affine-Octree paper (Table II, Chicken)', '']
            lines += paper_table(s['results'], s['vertices'] * s['frames']) + ['']
            lines += ['### Default profile against the paper at equal PSNR', '',
                      'Same PSNR definition on both sides: the default profile\'s ratio at the PSNR that '
                      'our paper profile reaches at each paper ME (interpolated from the sweep below).', '']
            lines += equal_psnr_table(s['results'], s['sweep']) + ['']
        lines += ['### Equal KG error against the simple baseline', '',
                  'Default profile, max-error sweep (runs = 1 where not in the table above). The baseline '
                  '(bench/baseline.py: B-bit quantisation on the sequence box, minus the previous frame, '
                  'xz -9) is measured for B = 4..14; its bpvf at our KG error is interpolated log-log '
                  'between its two neighbouring points ("n/a" outside its measured range).', '']
        lines += baseline_tables(s['sweep'], s['baseline']) + ['']
        if s['name'] == PAPER_SEQUENCE:
            lines += ['### DESIGN.md reference points', '',
                      'Our bpvf interpolated log-log from the sweep above at the KG errors of the baseline '
                      'points DESIGN.md quotes ("Measured on chickenCrossing").', '']
            lines += reference_table(s['sweep'], s['baseline']) + ['']
    lines += wavelet_lines
    lines += ['## Peak memory on a long sequence', '']
    if args.quick:
        lines += ['Skipped (--quick).', '']
    elif memory_rows:
        lines += [f'{LONG_SOURCE} ({memory_rows[0]["vertices"]} vertices) played back and forth '
                  '(bench/long_sequence.py) to the frame counts below, written as an uncompressed PC2 '
                  f'and encoded with `animc encode IN.pc2 --mesh {LONG_SOURCE}.ply -o OUT.ams '
                  f'{" ".join(LONG_SETTINGS)}`, then decoded with `animc decode OUT.ams -o DEC.pc2`. '
                  'Times are wall-clock seconds including file reading and writing; peak RSS is the '
                  'maximum resident set size (`/usr/bin/time -v`, else getrusage of a wrapper process). '
                  'Equal peaks for 1 000 and 100 000 frames mean memory grows with the vertex count '
                  'only, not with the frame count: the whole 100 000-frame sequence in memory would be '
                  f'{mib(memory_rows[-1]["pc2_bytes"])}.', '']
        lines += memory_table(memory_rows) + ['']
        lines += memory_growth(memory_rows)
    else:
        lines += [f'Not measured (no {LONG_SOURCE} in the data folder).', '']
    lines += plugin_lines or ['## Encoding through the MeshLab filter', '', 'Skipped (--no-plugin).', '']
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w') as f:
        f.write('\n'.join(lines))


# ---------------------------------------------------------------- main

def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    default_animc = os.path.join(REPO, 'build', 'animc', 'animc')
    p.add_argument('--animc', default=default_animc if os.path.exists(default_animc) else 'animc',
                   help='animc binary (default: build/animc/animc of the repository)')
    p.add_argument('--data', default=os.path.normpath(os.path.join(REPO, '..', 'shared', 'data')),
                   help='folder of sequence folders (default: ../shared/data from the repository root)')
    p.add_argument('--runs', type=int, default=5, help='animc bench runs per point (median; default 5)')
    p.add_argument('--out', default=os.path.join(REPO, 'docs', 'benchmarks.md'), help='Markdown report')
    p.add_argument('--baseline-cache', help='baseline results cache (default: baseline_cache.json next to --out)')
    p.add_argument('--tmp', default=None, help='folder for the long sequence files (default: system temp)')
    p.add_argument('--long-frames', type=int, default=LONG_FRAMES[-1],
                   help=f'frames of the long sequence (default {LONG_FRAMES[-1]})')
    p.add_argument('--quick', action='store_true', help='skip the long-sequence memory test')
    p.add_argument('--no-plugin', action='store_true', help='skip the MeshLab filter benchmark')
    args = p.parse_args()
    if args.runs < 1:
        p.error('--runs must be >= 1')
    resolved = shutil.which(args.animc)
    if not resolved:
        p.error(f'animc not found: {args.animc} (build it or pass --animc)')
    args.animc = os.path.abspath(resolved)
    if not os.path.isdir(args.data):
        p.error(f'no data folder {args.data}')
    if args.baseline_cache is None:
        args.baseline_cache = os.path.join(os.path.dirname(os.path.abspath(args.out)), 'baseline_cache.json')
    return args


# The report's sections after its own tables, in their order: each gives its Markdown lines
# and its failures from (args, sequences).
SECTIONS = (
    lambda a, s: trajectory_section(a.animc, s, a.runs),
    lambda a, s: trajectory2_section(a.animc, s, a.runs),
    lambda a, s: encoder_speed_section(a.animc, None, s, a.runs),
    lambda a, s: threads_section(a.animc, s, a.runs),
    lambda a, s: wavelet_section(a.animc, s, a.runs, os.path.dirname(os.path.abspath(a.out))),
    lambda a, s: decode_paths_section(a.animc, s, a.runs),
    lambda a, s: random_access_section(a.animc, None, s, a.runs),
    lambda a, s: readers_section(a.animc, s, a.runs),
    lambda a, s: gltf_section(a.animc, shutil.which('gltfpack'), s),
    lambda a, s: web_section(a.animc, s, a.runs),
)


def main():
    args = parse_args()
    baseline_hash = file_sha256(os.path.join(REPO, 'bench', 'baseline.py'))
    os.makedirs(os.path.dirname(args.baseline_cache), exist_ok=True)
    entries = load_baseline_cache(args.baseline_cache, baseline_hash)
    sequences = []
    failures = 0
    for name, pc2, ply in find_sequences(args.data):
        log(f'{name}: hashing')
        sha, vertices, frames = sequence_info(pc2)
        results = bench_sequence(args.animc, name, pc2, ply, args.runs)
        sweep = sweep_sequence(args.animc, name, pc2, ply, results)
        points = baseline_points(name, pc2, sha, entries, args.baseline_cache, baseline_hash)
        failures += sum('error' in r for r in list(results.values()) + list(sweep.values())) + (not points)
        sequences.append({'name': name, 'sha256': sha, 'results': results, 'sweep': sweep, 'baseline': points,
                          'vertices': vertices, 'frames': frames, 'pc2': pc2, 'ply': ply})
    if not sequences:
        sys.exit(f'no sequence folders (NAME/NAME.pc2.xz + NAME/NAME.ply) in {args.data}')
    section_lines = []
    for section in SECTIONS:
        lines, section_failures = section(args, sequences)
        section_lines += lines
        failures += section_failures
    memory_rows = []
    if not args.quick:
        counts = sorted({min(LONG_FRAMES[0], args.long_frames), args.long_frames})
        memory_rows = memory_test(args.animc, args.data, args.tmp, counts)
        failures += sum('error' in r for r in memory_rows)
    plugin_lines = None
    if not args.no_plugin:
        log('MeshLab filter against animc encode')
        plugin_lines = plugin_section(args.animc, args.data, args.runs, command_line()[0])
    elapsed = time.monotonic() - START
    write_report(args.out, args, sequences,
                 section_lines,
                 memory_rows, plugin_lines, elapsed)
    log(f'wrote {args.out} ({failures} failure(s)) in {elapsed / 60:.1f} min')
    sys.exit(1 if failures else 0)


if __name__ == '__main__':
    main()
