#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Bits of one or more animc builds against a base build at equal PSNR (Affine-Octree codec).

usage: bench/compare_builds.py BASE_ANIMC NEW_ANIMC [NEW_ANIMC ...] [--data DIR]
                               [--profile P] [--max-errors "0.006 0.01 ..."] [--at "0.01 0.1"]

Each build encodes every sequence of --data (default ../shared/data from the repository
root) at each max error of --max-errors, and `animc compare --json` measures bpvf and PSNR.
For each max error of --at, the base build's PSNR there is the target; a new build's bpvf at
that PSNR is interpolated between its two neighbouring points (log bpvf, linear in PSNR) and
printed as a change against the base's bpvf, in %. Use it when a change moves the error a
given max error gives, so that comparing at equal max error would mislead. Two encodes run at
once; progress goes to stderr."""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

from bench_common import find_sequences

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def measure(animc, pc2, ply, profile, max_error, scratch):
    out = os.path.join(scratch, "%s_%d_%s_%g.ams" % (os.path.basename(ply), abs(hash(animc)), profile, max_error))
    subprocess.run([animc, "encode", pc2, "--mesh", ply, "--profile", profile,
                    "--max-error", str(max_error), "-o", out], check=True, capture_output=True)
    report = json.loads(subprocess.run([animc, "compare", pc2, out, "--mesh", ply, "--json"],
                                       check=True, capture_output=True).stdout)
    os.remove(out)
    return report["psnr"], report["bpvf"]


def bpvf_at(points, psnr):
    """points: (psnr, bpvf) pairs; log bpvf interpolated linearly in PSNR, None outside."""
    points = sorted(points)
    for (p0, b0), (p1, b1) in zip(points, points[1:]):
        if p0 <= psnr <= p1 and p1 > p0:
            l0, l1 = math.log(b0), math.log(b1)
            return math.exp(l0 + (l1 - l0) * (psnr - p0) / (p1 - p0))
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("builds", nargs="+", help="animc executables, the base first")
    parser.add_argument("--data", default=os.path.join(os.path.dirname(ROOT), "shared", "data"))
    parser.add_argument("--profile", default="predictive")
    parser.add_argument("--max-errors", default="0.006 0.01 0.014 0.07 0.1 0.14")
    parser.add_argument("--at", default="0.01 0.1")
    args = parser.parse_args()
    if len(args.builds) < 2:
        sys.exit("compare_builds.py: give a base build and at least one other")
    max_errors = [float(x) for x in args.max_errors.split()]
    targets = [float(x) for x in args.at.split()]
    if any(t not in max_errors for t in targets):
        sys.exit("compare_builds.py: every --at value must be one of --max-errors")
    sequences = find_sequences(args.data)
    names = [name for name, _pc2, _ply in sequences]
    with tempfile.TemporaryDirectory() as scratch, ThreadPoolExecutor(2) as pool:
        futures = {(b, name, me): pool.submit(measure, b, pc2, ply, args.profile, me, scratch)
                   for b in args.builds for name, pc2, ply in sequences for me in max_errors}
        results = {}
        for i, (job, future) in enumerate(futures.items()):
            results[job] = future.result()
            print("\r%d/%d encodes" % (i + 1, len(futures)), end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
    base = args.builds[0]
    print("bpvf change at the base build's PSNR, builds: " + ", ".join(args.builds[1:]))
    for name in names:
        cells = []
        for target in targets:
            psnr, bpvf = results[(base, name, target)]
            changes = []
            for build in args.builds[1:]:
                value = bpvf_at([results[(build, name, me)] for me in max_errors], psnr)
                changes.append("n/a" if value is None else "%+.2f %%" % ((value / bpvf - 1) * 100))
            cells.append("ME %g (%.2f dB, base %.4f bpvf): %s" % (target, psnr, bpvf, " ".join(changes)))
        print("%s  %s" % (name, "  ".join(cells)))


if __name__ == "__main__":
    main()
