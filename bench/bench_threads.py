#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Encoding and decoding on one thread and on two: `animc bench --threads N` (encoding) and
`animc bench X.ams --threads N` (decoding) at animc's default settings (auto, max error 1 %), on
every sequence as one group and cut into groups of 64 frames, and on a large single group made
here: the first sequence with every triangle cut into four (edge midpoints) until it has at
least 500 000 vertices, as many of its first frames as one group holds (2^25 / (3 × vertices)).
Both thread counts must write the same bytes (the script checks) and the peak memory of the
large case is measured. bench.py puts the returned Markdown lines into
docs/benchmarks.md; run alone, this script replaces that section in place.

usage: bench/bench_threads.py [--animc PATH] [--data DIR] [--runs R] [--out FILE]"""
import filecmp
import json
import os
import statistics
import subprocess
import tempfile

import numpy as np

import pc2
from bench_common import animc_json, log, num, run_bench, run_measured, section_main, table
from ply import read_ply_faces, write_ply

HEADING = '## Threads'
THREADS = (1, 2)
GROUP_FRAMES = 64
# animc's default codec, and the codec whose memory docs/trajectory.md bounds.
MEMORY_CODECS = ('auto', 'trajectory')
LARGE_VERTICES = 500_000
GROUP_VALUES = 2**25  # a trajectory group holds at most this many trajectory values (3 x frames x vertices)
LARGE_RUNS = 5  # encoding the large sequence takes seconds: one run a round
ROUNDS = 7  # the thread counts take turns this many times (measure())


def subdivide(frames, faces):
    """Every triangle cut into four at its edge midpoints: (frames [F, N', 3], faces [4T, 3])."""
    corners = [(0, 1), (1, 2), (2, 0)]
    edges = np.sort(np.concatenate([faces[:, c] for c in corners]), axis=1)
    unique, inverse = np.unique(edges, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    n = frames.shape[1]
    mid = (frames[:, unique[:, 0]] + frames[:, unique[:, 1]]) * np.float32(0.5)
    m = (n + inverse).reshape(3, -1).T  # midpoint of edge 01, 12, 20 of each face
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    new_faces = np.concatenate([np.stack(f, axis=1) for f in
                                ((a, m[:, 0], m[:, 2]), (m[:, 0], b, m[:, 1]), (m[:, 2], m[:, 1], c),
                                 (m[:, 0], m[:, 1], m[:, 2]))])
    return np.concatenate([frames, mid], axis=1), new_faces.astype(np.uint32)


def make_large(seq, work):
    """seq subdivided to LARGE_VERTICES vertices or more, its first frames that fit one group, as
    work/large.pc2 and work/large.ply; returns (pc2, ply, vertices, frames)."""
    frames, header = pc2.read_pc2(seq['pc2'], 64)
    faces = read_ply_faces(seq['ply'])
    while frames.shape[1] < LARGE_VERTICES:
        frames, faces = subdivide(frames, faces)
    frames = frames[:GROUP_VALUES // (3 * frames.shape[1])]
    out_pc2, out_ply = os.path.join(work, 'large.pc2'), os.path.join(work, 'large.ply')
    with open(out_pc2, 'wb') as f:
        f.write(pc2.pack_header(header._replace(points=frames.shape[1], frames=frames.shape[0])))
        f.write(np.ascontiguousarray(frames, dtype='<f4').tobytes())
    write_ply(out_ply, frames[0], faces)
    return out_pc2, out_ply, frames.shape[1], frames.shape[0]


def measure(animc, name, pc2_path, ply, extra, runs, work):
    """(a table row of both thread counts, encode speed-up, decode speed-up), or None when a
    run failed or the bytes differ. The thread counts take turns, ROUNDS rounds of runs / ROUNDS
    runs each (one for the large sequence), so that a slow spell of this shared machine falls on
    both; each speed figure is the median over the rounds of a round's median, and each speed-up
    the median over the rounds of the round's own ratio (its two thread counts ran one after
    the other, under the same load)."""
    rounds = ROUNDS
    per_round = max(1, round(runs / ROUNDS))
    encode_s = {t: [] for t in THREADS}
    decode_s = {t: [] for t in THREADS}
    files, first = {}, None
    for r in range(rounds):
        for threads in THREADS:
            files[threads] = os.path.join(work, f'{name}.t{threads}.ams')
            log(f'{name} {" ".join(extra)}: {threads} thread(s), round {r + 1} of {rounds}, {per_round} run(s)')
            result = run_bench(animc, pc2_path, ply, extra + ['--threads', str(threads), '-o', files[threads]],
                               per_round)
            if 'error' in result:
                return None
            first = first or result
            encode_s[threads].append(result['encode_seconds_median'])
        if not filecmp.cmp(files[1], files[2], shallow=False):
            log(f'  {name}: the two thread counts wrote different bytes')
            return None
    for r in range(rounds):  # decoding alone, of the same file, more runs: it takes milliseconds
        for threads in THREADS:
            decoded = animc_json([animc, 'bench', files[1], '--threads', str(threads), '--runs',
                                  str(max(per_round, 3)), '--json'])
            if not decoded:
                return None
            decode_s[threads].append(decoded['decode_seconds_median'])
    vertex_frames = first['vertices'] * first['frames']
    enc_s = {t: statistics.median(encode_s[t]) for t in THREADS}
    dec_s = {t: statistics.median(decode_s[t]) for t in THREADS}
    enc = statistics.median(one / two for one, two in zip(encode_s[1], encode_s[2]))
    dec = statistics.median(one / two for one, two in zip(decode_s[1], decode_s[2]))
    mvps = lambda seconds: num(vertex_frames / seconds / 1e6)
    return [name, first['vertices'], first['frames'], num(first['bpvf'], 3),
            mvps(enc_s[1]), mvps(enc_s[2]), num(enc) + '×',
            mvps(dec_s[1]), mvps(dec_s[2]), num(dec) + '×'], enc, dec


def machine_scaling(work):
    """bench/memory_scaling.cpp's speed-ups of this machine on two threads, or None without g++."""
    source = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'memory_scaling.cpp')
    probe = os.path.join(work, 'memory_scaling')
    try:
        subprocess.run(['g++', '-O2', '-std=c++17', '-pthread', source, '-o', probe], check=True,
                       capture_output=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    log('two threads against one on plain work (bench/memory_scaling.cpp)')
    return json.loads(subprocess.run([probe], check=True, capture_output=True, text=True).stdout)


def amdahl(speedup, threads):
    """(parallel fraction p from a speedup on 2 threads, projected speedup on `threads`)."""
    p = min(1.0, max(0.0, 2 * (1 - 1 / speedup)))
    return p, 1 / ((1 - p) + p / threads)


def threads_section(animc, sequences, runs):
    rows, failures, speedups = [], 0, []
    with tempfile.TemporaryDirectory(prefix='animc_bench_threads_') as work:
        cases = [(s['name'], s['pc2'], s['ply'], []) for s in sequences]
        cases += [(s['name'] + f', groups of {GROUP_FRAMES}', s['pc2'], s['ply'],
                   ['--iframe-interval', str(GROUP_FRAMES)]) for s in sequences]
        machine = [machine_scaling(work)]
        large = None
        if sequences:
            log(f'making the large sequence from {sequences[0]["name"]}')
            large = make_large(sequences[0], work)
            cases.append((f'{sequences[0]["name"]} subdivided, one group', large[0], large[1], []))
        for name, pc2_path, ply, extra in cases:
            is_large = pc2_path == (large or [None])[0]
            row = measure(animc, name, pc2_path, ply, extra, min(runs, LARGE_RUNS) if is_large else runs, work)
            if row is None:
                failures += 1
                rows.append([name] + ['failed'] * 9)
                continue
            rows.append(row[0])
            speedups.append((name, row[1], row[2]))
        machine.append(machine_scaling(work))
        memory = []
        if large:
            for codec, threads in [(c, t) for c in MEMORY_CODECS for t in THREADS]:
                out = os.path.join(work, f'memory.{codec}.t{threads}.ams')
                log(f'peak memory of the large case, {codec}, {threads} thread(s)')
                # Measured from a process of its own (GNU time, or a small Python): this script's
                # own memory, which holds the large sequence, would otherwise count.
                _, kib, _ = run_measured([animc, 'encode', large[0], '--mesh', large[1], '-o', out,
                                          '--codec', codec, '--threads', str(threads)])
                mib = kib / 1024
                memory.append([f'`{codec}`', threads, f'{mib:.0f} MiB',
                               num(mib / (large[2] * large[3] * 12 / 2**20)) + '×'])
    lines = [HEADING, '',
             f'Encoding: `animc bench IN --mesh M --threads N --runs {max(1, round(runs / ROUNDS))} --json` '
             f'(`--runs {max(1, round(min(runs, LARGE_RUNS) / ROUNDS))}` for the large sequence) at animc\'s default '
             'settings (auto, max error 1 %), which includes the rate search; decoding: '
             f'`animc bench X.ams --threads N --runs {max(3, round(runs / ROUNDS))} --json` of the file written, which '
             'decodes in the runs of groups a reader takes (`decodeChunkEnd`). The two thread counts take turns, '
             f'{ROUNDS} rounds each, so that a slow spell of the machine falls on both; each figure is the median of '
             'the rounds\' medians, in million vertices '
             '(× frames) per second, and each speed-up the median of the rounds\' own ratios (a round\'s two '
             'thread counts ran one after the other, under the same load of the machine); both thread counts '
             'wrote identical bytes (checked). Without an I-frame '
             'interval each of these sequences is one group: its work is split inside the group (the '
             'trajectory Gram matrix and products; the rate search in blocks of 2048 vertices; decoding\'s frame reconstruction over ranges of 4096 '
             'vertices, so not below that; the coding order\'s walk beside the reading of the group), the '
             'eigensolver stays on one thread. With '
             f'`--iframe-interval {GROUP_FRAMES}` the groups are coded and decoded one a thread. The large '
             'sequence is one group of as many frames as the trajectory codec puts in one '
             '(2^25 / (3 × vertices)); with more than 65 536 triangles it is written as .ams format 2, whose '
             'connectivity is coded and decoded in pieces on every thread (docs/format.md, section 6.2.2).', '']
    lines += table(['sequence', 'vertices', 'frames', 'bpvf', 'encode 1 thread', 'encode 2 threads', 'speed-up',
                    'decode 1 thread', 'decode 2 threads', 'speed-up'], rows) + ['']
    if memory:
        raw = large[2] * large[3] * 12 / 2**20
        lines += [f'Peak memory of `animc encode` on the large sequence ({large[2]} vertices × {large[3]} '
                  f'frames, one group; raw floats {raw:.0f} MiB) at its default settings, from the kernel\'s '
                  'count for the process. With `auto`, the candidates run one after the other on a group this '
                  'large, so its peak is the larger of theirs beside the group\'s frames (docs/auto.md):', '']
        lines += table(['codec', 'threads', 'peak RSS', 'of the raw floats'], memory) + ['']
    if speedups:
        projected = []
        for name, enc, dec in speedups:
            pe, e4 = amdahl(enc, 4)
            pd, d4 = amdahl(dec, 4)
            projected.append([name, f'{100 * pe:.0f} %', num(e4) + '×', num(amdahl(enc, 8)[1]) + '×',
                              f'{100 * pd:.0f} %', num(d4) + '×', num(amdahl(dec, 8)[1]) + '×'])
        lines += ['More cores, estimated on paper: the parallel fraction p of each run follows from its '
                  'speed-up S on two threads (Amdahl: S = 1 / ((1 − p) + p/2), so p = 2 (1 − 1/S)); the '
                  'speed-up on n cores is then 1 / ((1 − p) + p/n). This assumes the serial part stays '
                  'serial and memory bandwidth keeps up; it is an estimate, not a measurement.', '']
        lines += table(['sequence', 'encode p', 'encode 4 cores', 'encode 8 cores', 'decode p', 'decode 4 cores',
                        'decode 8 cores'], projected) + ['']
    if all(machine):
        probe = lambda m: (f'arithmetic in registers {num(m["arithmetic"])}×, reads streaming through 256 MiB a '
                           f'thread {num(m["streaming_reads"])}×, writes at random places in 32 MiB a thread '
                           f'{num(m["random_writes"])}×')
        lines += ['What two threads can give on this machine: the same work on two threads against one '
                  '(`bench/memory_scaling.cpp`, compiled and run by this script, median of 5 rounds), before '
                  f'the runs above: {probe(machine[0])}; after them: {probe(machine[1])}. On a shared virtual '
                  'machine the second core\'s share of memory varies with the neighbours\' load, and work '
                  'bound by memory (a large group\'s frames, adjacency and coefficients) gains what it gives.', '']
    return lines, failures


def main():
    section_main(__doc__, HEADING, lambda args, sequences: threads_section(args.animc, sequences, args.runs),
                 lambda p: p.add_argument('--runs', type=int, default=5))


if __name__ == '__main__':
    main()
