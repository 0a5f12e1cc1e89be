#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): where the bytes of
today's trajectory files go at the KG errors the issue names. Every shared sequence is encoded
with `animc encode --codec trajectory --target-kg X --json`, then trajectory_bits (built here
from trajectory_bits.cpp against build/'s libanimc.a) splits each file: the connectivity and
the rest outside the groups, each group's head and steps, mean trajectory, basis vectors and
coefficients. Prints a Markdown table (bits per vertex per frame of each part, and its share),
then one of what the mean and the basis would cost with a second-order prediction along time
instead of today's first-order one (the same coder, fed second differences).

  usage: bench/experiments/trajectory_bits.py [--animc PATH] [--data DIR] [--kg 0.1,0.3,0.45,1]"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from bench_common import find_sequences, log, table  # noqa: E402


def build_tool(work, name='trajectory_bits'):
    """Builds bench/experiments/NAME.cpp against build/'s libanimc.a into work/NAME."""
    tool = os.path.join(work, name)
    build = os.path.join(REPO, 'build')
    subprocess.run(['g++', '-O2', '-std=c++17', '-I', os.path.join(REPO, 'shared_codec'), '-I',
                    os.path.join(REPO, 'include'), '-I', os.path.join(build, 'generated'), '-I', '/usr/include/eigen3',
                    os.path.join(HERE, name + '.cpp'), os.path.join(build, 'shared_codec', 'libanimc.a'),
                    '-llzma', '-lpthread', '-o', tool], check=True)
    return tool


def run_json(command):
    """The JSON a command prints; its failure stops the measurement."""
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def parse_arguments(doc):
    """The options of the measurements of this folder: animc, the sequences, the KG targets."""
    p = argparse.ArgumentParser(description=doc.split('\n')[0])
    p.add_argument('--animc', default=os.path.join(REPO, 'build', 'animc', 'animc'))
    p.add_argument('--data', default=os.path.normpath(os.path.join(REPO, '..', 'shared', 'data')))
    p.add_argument('--kg', default='0.1,0.3,0.45,1')
    return p.parse_args()


def trajectory_files(args, work, codec='trajectory'):
    """Every shared sequence encoded by a trajectory codec at every KG target, one after the
    other into work/NAME.ams: yields (name, pc2, ply, kg, ams, animc's JSON report)."""
    for name, pc2, ply in find_sequences(args.data):
        for kg in (float(x) for x in args.kg.split(',')):
            log(f'{name}: KG {kg:g} %')
            ams = os.path.join(work, f'{name}.ams')
            encoded = run_json([args.animc, 'encode', pc2, '--mesh', ply, '-o', ams, '--codec', codec,
                                '--target-kg', str(kg), '--json'])
            yield name, pc2, ply, kg, ams, encoded


def row(name, kg, split, encoded):
    vf = split['vertices'] * split['frames'] / 8  # bytes to bits per vertex per frame
    groups = split['head'] + split['mean'] + split['basis'] + split['coefficients']
    parts = [split['file_bytes'] - groups, split['head'] + split['mean'], split['basis'], split['coefficients']]
    total = split['file_bytes']
    cells = [f'{p / vf:.3f} ({100 * p / total:.0f} %)' for p in parts]
    k = split['components']
    components = str(k[0]) if len(set(k)) == 1 else f'{min(k)}–{max(k)}'
    return [name, f'{kg:g}', f'{encoded["kg_error"]:.3f}', f'{total / vf:.3f}'] + cells + [components]


def prediction_row(name, kg, split):
    mean, basis = split['mean'], split['basis']
    return [name, f'{kg:g}', f'{mean:.0f}', f'{split["mean_second_order"]:.0f}',
            f'{split["mean_second_order"] / mean:.3f}' if mean else '–', f'{basis:.0f}',
            f'{split["basis_second_order"]:.0f}', f'{split["basis_second_order"] / basis:.3f}' if basis else '–']


def main():
    args = parse_arguments(__doc__)
    rows, prediction_rows = [], []
    with tempfile.TemporaryDirectory() as work:
        tool = build_tool(work)
        for name, _, _, kg, ams, encoded in trajectory_files(args, work):
            split = run_json([tool, ams])
            rows.append(row(name, kg, split, encoded))
            prediction_rows.append(prediction_row(name, kg, split))
    print('\n'.join(table(['sequence', 'target KG %', 'KG %', 'bpvf', 'outside groups', 'head + mean', 'basis',
                           'coefficients', 'components'], rows)))
    print()
    print('\n'.join(table(['sequence', 'target KG %', 'mean bytes', 'second order', 'ratio', 'basis bytes',
                           'second order', 'ratio'], prediction_rows)))


if __name__ == '__main__':
    main()
