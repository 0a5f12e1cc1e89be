#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): clustered PCA with
today's codec instead of a model.

trajectory_clusters.py prices a basis per cluster of vertices with trajectory_coding.py's
model. This runs the real encoder instead: the vertices are split into C clusters as there
(k-means of their trajectories), each cluster with the triangles whose corners all lie in it
is written as a sequence of its own and encoded with `animc encode --codec trajectory --step`,
every cluster at one coefficient step q (the step is given as a fraction of each cluster's
first-frame diagonal), and q is bisected until the decoded clusters, put back together, meet
the KG target on the whole sequence. A file holding the clusters would carry the clusters'
group bytes once each, but one connectivity, one header and one record a frame: the size is
the sum of the clusters' group bytes, less the (F - 1) two-byte frame records and 32 section
bytes of every cluster after the first, plus the whole mesh's static bytes and the labels'
bits (as trajectory_clusters.py prices them). C = 1 is `animc encode --target-kg` itself.
With --bench, the decoding time of the clusters' files (each at the step found, one thread,
`animc bench --runs 9`, medians summed) is printed beside that of the one file, as a second
table: a vertex of a cluster is rebuilt from its cluster's components only.

  usage: bench/experiments/trajectory_clusters_real.py ANIMC DATA_DIR [--kg 0.1,0.3,0.45,1]
         [--clusters 2,3,4,6] [--bench]
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import pc2  # noqa: E402
import ply  # noqa: E402
import trajectory_clusters  # noqa: E402
import trajectory_coding as model  # noqa: E402
from trajectory_bits import run_json  # noqa: E402
from bench_common import table  # noqa: E402


def write_pc2(path, frames):
    with open(path, 'wb') as out:
        out.write(pc2.pack_header(pc2.Header(frames.shape[1], 0.0, 1.0, frames.shape[0])))
        out.write(np.ascontiguousarray(frames, dtype='<f4').tobytes())


class Cluster:
    """One cluster written as a sequence of its own."""

    def __init__(self, work, index, frames, faces, members):
        self.members = members
        self.pc2 = os.path.join(work, f'c{index}.pc2')
        self.ply = os.path.join(work, f'c{index}.ply')
        self.ams = os.path.join(work, f'c{index}.ams')
        self.out = os.path.join(work, f'c{index}.out.pc2')
        write_pc2(self.pc2, frames[:, members])
        ply.write_ply(self.ply, frames[0, members], model.induced_faces(faces, members, frames.shape[1]))
        corner = frames[0, members]
        self.diagonal = float(np.linalg.norm(corner.max(axis=0) - corner.min(axis=0))) or 1.0

    def code(self, animc, q):
        """(group bytes, decoded frames) at coefficient step q."""
        r = run_json([animc, 'encode', self.pc2, '--mesh', self.ply, '-o', self.ams, '--codec', 'trajectory',
                      '--step', repr(q / self.diagonal), '--json'])
        subprocess.run([animc, 'decode', self.ams, '-o', self.out, '--format', 'pc2', '--replace'],
                       check=True, capture_output=True)
        decoded, _ = pc2.read_pc2(self.out)
        return r['file_bytes'] - r['static_bytes'], decoded


def decode_seconds(animc, path):
    """Median decoding time of an .ams on one thread."""
    return run_json([animc, 'bench', path, '--runs', '9', '--threads', '1', '--json'])['decode_seconds_median']


def merge_bare_clusters(labels, faces):
    """Labels with every cluster that holds no whole triangle (the encoder needs one) given to
    the cluster most of its vertices' neighbours are in."""
    labels = labels.copy()
    while True:
        whole = {int(labels[t[0]]) for t in faces if labels[t[0]] == labels[t[1]] == labels[t[2]]}
        bare = [c for c in np.unique(labels) if int(c) not in whole]
        if not bare:
            return labels
        members = np.flatnonzero(labels == bare[0])
        around = [labels[w] for t in faces if set(t) & set(members) for w in t if labels[w] != bare[0]]
        labels[members] = np.bincount(around).argmax() if around else labels[labels != bare[0]][0]


def clustered_bits(animc, frames, clusters, label_bits, static_bytes, target):
    f = frames.shape[0]

    def cost(q):
        total, decoded = 0, np.zeros_like(frames)
        for i, c in enumerate(clusters):
            group_bytes, out = c.code(animc, q)
            total += group_bytes - (0 if i == 0 else 2 * (f - 1) + 32)
            decoded[:, c.members] = out
        return 8 * total + label_bits + 8 * static_bytes, float(((decoded - frames) ** 2).sum())

    return model.search_step(frames, cost, target)


def main():
    parser = model.experiment_parser(__doc__)
    parser.add_argument('--clusters', default='2,3,4,6')
    parser.add_argument('--bench', action='store_true', help='also time the decoding (one thread)')
    args = parser.parse_args()
    counts = [int(c) for c in args.clusters.split(',')]
    rows, speed_rows = [], []
    for name, pc2_path, ply_path, frames, faces, static in model.load_sequences(args.animc, args.data_dir):
        f, v, _ = frames.shape
        with tempfile.TemporaryDirectory() as work:
            split = {}
            for count in counts:
                labels = merge_bare_clusters(model.clusters_of(frames, count), faces)
                folder = os.path.join(work, str(count))
                os.mkdir(folder)
                clusters = [Cluster(folder, c, frames, faces, np.flatnonzero(labels == c))
                            for c in range(count) if (labels == c).any()]
                split[count] = (clusters, trajectory_clusters.label_bits(labels, faces))
            for target in map(float, args.kg.split(',')):
                one_path = os.path.join(work, 'one.ams')
                one = run_json([args.animc, 'encode', pc2_path, '--mesh', ply_path, '-o', one_path,
                                '--codec', 'trajectory', '--target-kg', str(target), '--json'])['bpvf']
                cells = [one]
                speeds = [v * f / decode_seconds(args.animc, one_path) / 1e6] if args.bench else []
                for count in counts:
                    bits, _ = clustered_bits(args.animc, frames, *split[count], static, target)
                    cells.append(bits / (v * f))
                    if args.bench:  # the files of the last step tried, within 24 / 2^20 of the one found in log2 q
                        seconds = sum(decode_seconds(args.animc, c.ams) for c in split[count][0])
                        speeds.append(v * f / seconds / 1e6)
                if speeds:
                    speed_rows.append([name, f'{target:g}'] + [f'{x:.0f}' for x in speeds] +
                                      [f'{x / speeds[0]:.2f}' for x in speeds[1:]])
                rows.append([name, f'{target:g}'] + [f'{c:.3f}' for c in cells] +
                            [f'{c / cells[0]:.3f}' for c in cells[1:]])
                print(rows[-1], file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'KG %', 'codec 3 bpvf'] + [f'C={c} bpvf' for c in counts] +
                          [f'C={c} / codec 3' for c in counts], rows)))
    if speed_rows:
        print()
        print('\n'.join(table(['sequence', 'KG %', 'codec 3 M v/s'] + [f'C={c} M v/s' for c in counts] +
                              [f'C={c} / codec 3' for c in counts], speed_rows)))


if __name__ == '__main__':
    main()
