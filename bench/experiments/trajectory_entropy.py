#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next entropy layer (issue 40): every shared
sequence is encoded with `animc encode --codec trajectory2 --target-kg X`, then
trajectory_entropy (built here from trajectory_entropy.cpp against build/'s libanimc.a) codes
the values of each part again with today's adaptive range coder, with static tables (rANS,
per part or shared by the parts) and with today's adaptive models through rANS, and times
decoding each; `animc bench FILE --runs 9 --threads 1` times decoding the whole file. Prints one
Markdown table: the values a vertex-frame, each variant's bytes over today's, the decoding time
of a value, the whole file's values decoded in vertex-frames/s, and the file decoded from
memory (animc bench) in vertex-frames/s.

  usage: bench/experiments/trajectory_entropy.py [--animc PATH] [--data DIR] [--kg 0.1,0.3,0.45,1]"""
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench_common import table  # noqa: E402
from trajectory_bits import build_tool, parse_arguments, run_json, trajectory_files  # noqa: E402


def row(name, kg, e, bench):
    today = e['adaptive_bytes']
    per_part = (e['static_bytes'] + e['static_table_bytes']) / today
    shared = (e['shared_bytes'] + e['shared_table_bytes']) / today
    ns = {k: 1e9 * e[f'{k}_seconds'] / e['values'] for k in ('adaptive', 'static', 'ans')}
    mvfs = {k: e['vertex_frames'] / e[f'{k}_seconds'] / 1e6 for k in ('adaptive', 'static', 'ans')}
    return [name, f'{kg:g}', f'{e["values"] / e["vertex_frames"]:.2f}', f'{today:.0f}',
            f'{e["static_bytes"] / today:.3f}', f'{per_part:.3f}', f'{shared:.3f}', f'{e["ans_bytes"] / today:.3f}',
            f'{ns["adaptive"]:.1f} / {ns["static"]:.1f} / {ns["ans"]:.1f}',
            f'{mvfs["adaptive"]:.0f} / {mvfs["static"]:.0f} / {mvfs["ans"]:.0f}', f'{bench["decode_memory_mvps"]:.0f}']


def main():
    args = parse_arguments(__doc__)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        tool = build_tool(work, 'trajectory_entropy')
        for name, _, _, kg, ams, _ in trajectory_files(args, work, 'trajectory2'):
            bench = run_json([args.animc, 'bench', ams, '--runs', '9', '--threads', '1', '--json'])
            rows.append(row(name, kg, run_json([tool, ams]), bench))
    print('\n'.join(table(['sequence', 'KG %', 'values / vertex-frame', 'today (bytes)', 'static, no tables',
                           'static + tables per part', 'static + shared tables', 'adaptive rANS',
                           'ns a value: today / static / adaptive rANS',
                           'M vertex-frames/s: today / static / adaptive rANS', 'whole file (M v/s)'], rows)))


if __name__ == '__main__':
    main()
