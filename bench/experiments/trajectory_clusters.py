#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): a basis per region
of the mesh (clustered PCA) instead of one for all vertices.

Articulated motion is nearly rigid per part; one basis for the whole mesh needs the components
of every part for every vertex. Clustered PCA (Sattler, Sarlette & Klein 2005) splits the
vertices into C clusters of similar trajectories (k-means, trajectory_coding.clusters_of) and
gives each its own mean, basis and coefficients; each cluster's coefficients are predicted from
its neighbours coded before them within the cluster. One step q for all, priced by
trajectory_coding.py's model at the step that meets each KG target (one group). The labels are
priced as an adaptive model would code them along the breadth-first order of the whole mesh,
with the label of the vertex's first neighbour coded before it as context (clusters of
trajectories are mostly connected parts, so most labels repeat that one).

  usage: bench/experiments/trajectory_clusters.py ANIMC DATA_DIR [--kg 0.1,0.3,0.45,1]
         [--clusters 2,4,8]
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import trajectory_coding as model  # noqa: E402
from bench_common import table  # noqa: E402


def label_bits(labels, faces):
    """Bits of the labels coded along the mesh's breadth-first order, in the context of the
    label of the vertex's first neighbour coded before it."""
    order, (rows, cols, _) = model.coded_order_predictor(len(labels), faces)
    position = np.empty(len(labels), dtype=int)
    position[order] = np.arange(len(order))
    context = np.full(len(labels), -1)
    for v, w in zip(rows, cols):  # the neighbour coded first
        if context[v] < 0 or position[w] < position[context[v]]:
            context[v] = w
    by_context = {}
    for v in order:
        by_context.setdefault(labels[context[v]] if context[v] >= 0 else -1, []).append(labels[v])
    count = int(labels.max()) + 1
    return sum(model.adaptive_bits(np.array(s), count) for s in by_context.values())


def cluster_groups(frames, faces, count):
    """(label bits, [(group of the cluster's vertices, its PCA, predictor, order)]) of `count`
    clusters."""
    labels = model.clusters_of(frames, count) if count > 1 else np.zeros(frames.shape[1], dtype=int)
    out = []
    for c in range(count):
        index = np.flatnonzero(labels == c)
        if len(index) == 0:
            continue
        order, predictor = model.coded_order_predictor(len(index), model.induced_faces(faces, index, len(labels)))
        group = frames[:, index]
        out.append((group, model.transform(group, 'pca'), predictor, order))
    return (label_bits(labels, faces) if count > 1 else 0.0), out


def at_target(frames, clusters, target, label_bits):
    def cost(q):
        bits, sq = label_bits, 0.0
        for group, transformed, predictor, order in clusters:
            b, e = model.code([(group, transformed, None)], 'pca', predictor, order, q)
            bits, sq = bits + b, sq + e
        return bits, sq

    return model.search_step(frames, cost, target)


def main():
    parser = model.experiment_parser(__doc__)
    parser.add_argument('--clusters', default='2,4,8')
    args = parser.parse_args()
    counts = [1] + [int(c) for c in args.clusters.split(',')]
    rows = []
    for name, pc2_path, ply_path, frames, faces, static in model.load_sequences(args.animc, args.data_dir):
        f, v, _ = frames.shape
        prepared = {c: cluster_groups(frames, faces, c) for c in counts}
        print(name, 'label bits a vertex', [f'{prepared[c][0] / v:.2f}' for c in counts], file=sys.stderr)
        for target in map(float, args.kg.split(',')):
            cells = []
            for c in counts:
                bits, _ = at_target(frames, prepared[c][1], target, prepared[c][0])
                cells.append((bits + 8 * static) / (v * f))
            rows.append([name, f'{target:g}'] + [f'{x:.3f}' for x in cells] + [f'{x / cells[0]:.3f}' for x in cells[1:]])
            print(rows[-1], file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'KG %'] + [f'C={c} bpvf' for c in counts] +
                          [f'C={c} / C=1' for c in counts[1:]], rows)))


if __name__ == '__main__':
    main()
