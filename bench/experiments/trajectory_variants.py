#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): parts of today's
trajectory files coded again other ways, at the KG errors the issue names. Every shared
sequence is encoded with `animc encode --codec trajectory --target-kg X` (one group each), then
  trajectory_contexts.cpp   codes the file's quantised coefficients, unchanged (so at the file's
                            own error), with other contexts and predictions;
  trajectory_basis_dct.cpp  computes the group's basis again and quantises it at the encoder's
                            steps in the time domain (today) and in a DCT domain along time;
  trajectory_rdoq.cpp       computes the group's coefficients again and quantises them by
                            plain rounding, today's rule and a rate-distortion choice.
All are built here against build/'s libanimc.a. Prints three Markdown tables: each coefficient
variant's bytes over today's, the basis bytes and added error of both domains, and each
quantisation's coefficient bytes and error over today's, and its bytes at today's error.

  usage: bench/experiments/trajectory_variants.py [--animc PATH] [--data DIR] [--kg 0.1,0.3,0.45,1]"""
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench_common import table  # noqa: E402
from trajectory_bits import build_tool, parse_arguments, run_json, trajectory_files  # noqa: E402

VARIANTS = ('previous', 'activity', 'both', 'components', 'shrunk', 'hierarchy', 'one level', 'unpredicted')


def main():
    args = parse_arguments(__doc__)
    coefficient_rows, basis_rows, rdoq_rows = [], [], []
    with tempfile.TemporaryDirectory() as work:
        contexts = build_tool(work, 'trajectory_contexts')
        basis = build_tool(work, 'trajectory_basis_dct')
        rdoq = build_tool(work, 'trajectory_rdoq')
        for name, pc2, ply, kg, ams, _ in trajectory_files(args, work):
            coded = run_json([contexts, ams])
            today = coded['today']
            coefficient_rows.append([name, f'{kg:g}', f'{today:.0f}'] + [f'{coded[v] / today:.3f}' for v in VARIANTS])
            b = run_json([basis, ams, pc2, ply])
            basis_rows.append([name, f'{kg:g}', str(b['components']), f'{b["time_bytes"]:.0f}',
                               f'{b["dct_bytes"]:.0f}', f'{b["dct_bytes"] / b["time_bytes"]:.3f}',
                               f'{b["dct_error"] / b["time_error"]:.3f}'])
            r = run_json([rdoq, ams, pc2, ply])
            rdoq_rows.append([name, f'{kg:g}', f'{r["today_bytes"]:.0f}'] +
                             [f'{r[f"{v}_{part}"] / r[f"today_{part}"]:.3f}' for v in ('nearest', 'rdoq')
                              for part in ('bytes', 'error', 'at_today')])
    print('\n'.join(table(['sequence', 'KG %', 'today (bytes)'] + list(VARIANTS), coefficient_rows)))
    print()
    print('\n'.join(table(['sequence', 'KG %', 'components', 'time (bytes)', 'DCT (bytes)', 'bytes DCT / time',
                           'error DCT / time'], basis_rows)))
    print()
    print('\n'.join(table(['sequence', 'KG %', 'today (bytes)', 'nearest: bytes', 'error', 'bytes at equal error',
                           'rdoq: bytes', 'error', 'bytes at equal error'], rdoq_rows)))


if __name__ == '__main__':
    main()
