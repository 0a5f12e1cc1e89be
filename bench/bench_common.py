#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Helpers shared by the benchmark scripts (bench.py, bench_wavelet.py, bench_progressive.py,
bench_plugin.py, bench_decode_paths.py, bench_readers.py): finding the sequences, running
`animc bench --json` and other animc commands that print JSON, log-log interpolation, Markdown
cells and tables, progress lines, and replacing one section of a report."""
import argparse
import datetime
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time

import numpy as np

ANIMC_TIMEOUT_S = 3600
START = time.monotonic()


def log(message):
    """Progress line on stderr, with the time since start."""
    print(f'[{time.monotonic() - START:7.1f} s] {message}', file=sys.stderr, flush=True)


def find_sequences(data_dir):
    """Sorted [(name, pc2_xz_path, ply_path)] of the folders that hold both files."""
    found = []
    for name in sorted(os.listdir(data_dir)):
        folder = os.path.join(data_dir, name)
        pc2 = os.path.join(folder, name + '.pc2.xz')
        ply = os.path.join(folder, name + '.ply')
        if os.path.isfile(pc2) and os.path.isfile(ply):
            found.append((name, pc2, ply))
    return found


def animc_json(cmd):
    """JSON of an animc command that prints one, or None (logged) when it fails."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        log(f'  FAILED: {" ".join(cmd)}\n    {p.stderr.strip()}')
        return None
    return json.loads(p.stdout)


def encode_wavelet(animc, seq, ams, args):
    """JSON of `animc encode --codec wavelet --json` of seq into ams with more arguments args,
    or None (logged) when it fails."""
    return animc_json([animc, 'encode', seq['pc2'], '--mesh', seq['ply'], '-o', ams, '--codec', 'wavelet',
                       '--json'] + args)


def run_bench(animc, pc2, ply, settings, runs, one_thread=True):
    """One `animc bench --json` with the encoder settings (a list of animc arguments, e.g.
    ['--profile', 'predictive', '--max-error', '0.01']), on one thread unless they say
    `--threads` or one_thread is False (for an animc older than --threads, when only its
    sizes count: they never depend on the thread count); its JSON object, or {'error': text}."""
    threads = [] if '--threads' in settings or not one_thread else ['--threads', '1']
    cmd = [animc, 'bench', pc2, '--mesh', ply] + settings + threads + ['--runs', str(runs), '--json']
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=ANIMC_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return {'error': f'timed out after {ANIMC_TIMEOUT_S} s'}
    if p.returncode != 0:
        message = (p.stderr.strip().splitlines() or [''])[-1]
        log(f'  FAILED (exit {p.returncode}): {shlex.join(cmd)}\n    {p.stderr.strip()}')
        return {'error': f'exit {p.returncode}' + (f': {message}' if message else '')}
    try:
        return json.loads(p.stdout)
    except json.JSONDecodeError:
        return {'error': 'output is not JSON'}


def loglog_interp(points, x):
    """y at x by linear interpolation of log y over log x between the (x, y) points;
    None outside the range of the points' x (no extrapolation)."""
    pts = sorted((px, py) for px, py in points
                 if px is not None and py is not None and px > 0 and py > 0
                 and math.isfinite(px) and math.isfinite(py))
    if not pts or x < pts[0][0] or x > pts[-1][0]:
        return None
    xs = np.log([p[0] for p in pts])
    ys = np.log([p[1] for p in pts])
    return float(np.exp(np.interp(math.log(x), xs, ys)))


def num(x, digits=2):
    """A number for a table cell; 'n/a' for None, '∞' for +inf."""
    if x is None:
        return 'n/a'
    if isinstance(x, float) and math.isinf(x):
        return '∞' if x > 0 else '−∞'
    if isinstance(x, float) and math.isnan(x):
        return 'NaN'
    return f'{x:.{digits}f}'


def pct(fraction):
    return f'{100 * fraction:g} %'


def mib(n_bytes):
    return f'{n_bytes / 2**20:.1f} MiB'


def step_label(step):
    """The row label of a wavelet quality-mode point (--step)."""
    return f'step {step:g}'


def table(header, rows):
    """Markdown table lines."""
    lines = ['| ' + ' | '.join(header) + ' |', '|' + '---|' * len(header)]
    lines += ['| ' + ' | '.join(str(c) for c in row) + ' |' for row in rows]
    return lines


def failed_cell(result):
    return 'failed: ' + result['error'].replace('|', '\\|')


def replace_section(report, heading, lines, command):
    """The report's text with its `heading` section replaced by lines, which start with that
    heading and a blank line, stamped with `command`, the time and the commit (inserted before
    the peak-memory section when the report has none): for the scripts that, run alone,
    rewrite their own section of docs/benchmarks.md."""
    text = open(report).read()
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    commit = subprocess.run(['git', '-C', repo, 'rev-parse', '--short', 'HEAD'], capture_output=True,
                            text=True).stdout.strip()
    when = datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')
    measured = (f'Measured by `{command}` ({when}, commit `{commit}`, {os.cpu_count()} CPUs), apart from '
                'the rest of this report.')
    # A blank line before the next heading, which a table would otherwise run into.
    section = '\n'.join(lines[:2] + [measured, ''] + lines[2:]).rstrip('\n') + '\n\n'
    start = text.find(heading)
    if start < 0:
        start = end = text.find('## Peak memory')
    else:
        following = text.find('\n## ', start + len(heading))
        end = following + 1 if following >= 0 else len(text)
    return text[:start] + section + text[end:]


def section_main(doc, heading, section, add_arguments=None):
    """The main of a script that, run alone, rewrites its one section of docs/benchmarks.md (or
    --out): parses --animc, --data, --out and the script's own arguments (add_arguments(parser)),
    calls section(args, sequences) -> (Markdown lines, failures) with the data folder's
    sequences as dicts (name, pc2, ply), writes the section stamped with the command, and exits
    1 when anything failed."""
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    p = argparse.ArgumentParser(description=doc.split('\n')[0])
    p.add_argument('--animc', default=os.path.join(repo, 'build', 'animc', 'animc'))
    p.add_argument('--data', default=os.path.normpath(os.path.join(repo, '..', 'shared', 'data')))
    p.add_argument('--out', default=os.path.join(repo, 'docs', 'benchmarks.md'))
    if add_arguments:
        add_arguments(p)
    args = p.parse_args()
    args.animc = os.path.abspath(args.animc)
    sequences = [{'name': n, 'pc2': pc2, 'ply': ply} for n, pc2, ply in find_sequences(args.data)]
    lines, failures = section(args, sequences)
    command = shlex.join([os.path.relpath(os.path.abspath(sys.argv[0]), repo)] + sys.argv[1:])
    text = replace_section(args.out, heading, lines, command)
    with open(args.out, 'w') as f:
        f.write(text)
    log(f'wrote the section to {args.out} ({failures} failure(s))')
    sys.exit(1 if failures else 0)


def run_measured(cmd):
    """Run cmd; return (wall seconds, peak RSS in KiB or None, stdout). Uses
    /usr/bin/time -v if present, else a Python child reporting RUSAGE_CHILDREN."""
    t0 = time.monotonic()
    if os.access('/usr/bin/time', os.X_OK):
        p = subprocess.run(['/usr/bin/time', '-v'] + cmd, capture_output=True, text=True)
        m = re.search(r'Maximum resident set size \(kbytes\): (\d+)', p.stderr)
        rss = int(m.group(1)) if m else None
    else:
        wrapper = ('import resource, subprocess, sys\n'
                   'r = subprocess.run(sys.argv[1:]).returncode\n'
                   'print("maxrss", resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, file=sys.stderr)\n'
                   'sys.exit(r)\n')
        p = subprocess.run([sys.executable, '-c', wrapper] + cmd, capture_output=True, text=True)
        m = re.search(r'maxrss (\d+)', p.stderr)
        rss = int(m.group(1)) if m else None  # Linux: KiB
    seconds = time.monotonic() - t0
    if p.returncode != 0:
        raise RuntimeError(f'{shlex.join(cmd)} failed (exit {p.returncode}):\n{p.stderr.strip()}')
    return seconds, rss, p.stdout
