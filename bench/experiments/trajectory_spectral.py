#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): the PCA coefficients
coded in a spectral domain of the mesh instead of predicted from neighbours.

Codec 3 quantises each component's coefficient field (one value a vertex) and codes the
integers as residuals of the mean of the vertex's neighbours coded before it (DPCM along a
breadth-first order). A transform coder instead projects each field on an orthonormal basis of
the mesh's graph Laplacian eigenvectors (low to high frequency), quantises the projections at
one step and codes them with contexts per component band and frequency band: at low rates the
many small high-frequency projections round to zero, which DPCM's residuals cannot.

Both are priced by trajectory_coding.py's model (one group, the same basis and mean costs, an
adaptive Elias-gamma bucket coder), at the step that meets each KG target, whole-file bpvf with
the static bytes an .ams has. Variants:
  dpcm        codec 3's design model (trajectory_coding.py's `code`);
  graph       eigenvectors of the combinatorial Laplacian (D - A);
  cotangent   eigenvectors of the cotangent Laplacian of the mean frame (symmetric weights);
  patches-P   graph, on patches of about P vertices (breadth-first growth), each its own basis:
              what a decoder could afford (P multiply-adds a coefficient).
  lifting-L   a lifting wavelet over L levels of maximal independent sets (each level's set
              predicted by the mean of its neighbours, the rest updated by half the mean of
              their neighbours' details), which a decoder runs in O(V) a component with
              exact arithmetic; each coefficient quantised at q over its synthesis vector's
              norm, so that each costs the error a step q does in an orthonormal basis.
  predict-L   lifting-L without the update step (an interpolating prediction, open loop).
  haar        a region-adaptive Haar transform (RAHT, as MPEG G-PCC codes point attributes):
              adjacent nodes merged in pairs, shortest edge of the mean frame first, level by
              level, each pair into its weighted sum and difference (orthonormal, O(V), exact).
The eigenvector variants are not a format a decoder could follow bit for bit (eigenvectors of
a floating-point solver are not reproducible across machines): they measure what a spatial
transform can give, the lifting variants what a decoder can run.

  usage: bench/experiments/trajectory_spectral.py ANIMC DATA_DIR [--kg 0.1,0.3,0.45,1]
         [--variants dpcm,graph,cotangent,patches-256]
"""
import math
import os
import sys
from collections import defaultdict, deque

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import trajectory_coding as model  # noqa: E402
from bench_common import table  # noqa: E402


def laplacian(vertex_count, faces, weights=None):
    """Dense symmetric Laplacian: uniform edge weights, or {(v, w): weight}."""
    lap = np.zeros((vertex_count, vertex_count))
    for v, around in enumerate(model.adjacency(vertex_count, faces)):
        for w in around:
            x = weights[(v, w)] if weights else 1.0
            x = (x + weights[(w, v)]) / 2 if weights else x
            lap[v, w] -= x
            lap[v, v] += x
    return lap


def eigenbasis(lap):
    """Columns: orthonormal eigenvectors, lowest frequency first."""
    _, vectors = np.linalg.eigh(lap)
    return vectors


def patches(vertex_count, faces, size):
    """Vertex sets of about `size` vertices, grown breadth-first from unvisited seeds."""
    neighbours = model.adjacency(vertex_count, faces)
    label = np.full(vertex_count, -1)
    out = []
    for seed in range(vertex_count):
        if label[seed] >= 0:
            continue
        members, queue = [], deque([seed])
        label[seed] = len(out)
        while queue and len(members) < size:
            v = queue.popleft()
            members.append(v)
            for w in sorted(neighbours[v]):
                if label[w] < 0 and len(members) + len(queue) < size:
                    label[w] = len(out)
                    queue.append(w)
        for v in queue:  # not reached within the size: free again
            label[v] = -1
        out.append(np.array(members))
    return out


def patch_bases(vertex_count, faces, size):
    """[(vertex indices, eigenbasis of the patch's induced graph)]."""
    bases = []
    for members in patches(vertex_count, faces, size):
        local = {v: i for i, v in enumerate(members)}
        lap = laplacian(len(members), model.induced_faces(faces, members, vertex_count))
        # Vertices of the patch joined only through edges (no whole triangle): keep the graph
        # connected by the patch's edges too.
        for a, b, c in faces:
            for x, y in ((a, b), (b, c), (c, a)):
                if x in local and y in local and lap[local[x], local[y]] == 0:
                    lap[local[x], local[y]] = lap[local[y], local[x]] = -1
                    lap[local[x], local[x]] += 1
                    lap[local[y], local[y]] += 1
        bases.append((members, eigenbasis(lap)))
    return bases


def independent_levels(vertex_count, faces, levels):
    """[(odd vertices, {odd: its even neighbours}, {even: its odd neighbours})] from fine to
    coarse: each level's odd set is a maximal independent set (greedy, lowest degree first) of
    the graph that remains, whose next graph joins vertices with a common odd neighbour."""
    graph = {v: set(w) for v, w in enumerate(model.adjacency(vertex_count, faces))}
    out = []
    for _ in range(levels):
        if len(graph) < 2:
            break
        odd, blocked = [], set()
        for v in sorted(graph, key=lambda v: (len(graph[v]), v)):
            if v not in blocked and graph[v]:
                odd.append(v)
                blocked |= graph[v] | {v}
        odd_set = set(odd)
        predictors = {o: sorted(graph[o]) for o in odd}
        updated = defaultdict(list)
        for o in odd:
            for e in graph[o]:
                updated[e].append(o)
        coarse = {v: {w for w in graph[v] if w not in odd_set} for v in graph if v not in odd_set}
        for o in odd:
            for a in graph[o]:
                coarse[a] |= set(graph[o]) - {a}
        out.append((odd, predictors, dict(updated)))
        graph = coarse
    return out


def lifting_matrix(vertex_count, faces, levels, update):
    """(analysis matrix, band per row: 0 for the coarsest vertices, up to the finest level)."""
    structure = independent_levels(vertex_count, faces, levels)

    def analyse(c):
        c = c.copy()
        for odd, predictors, updated in structure:
            for o in odd:
                c[o] -= c[predictors[o]].mean(axis=0)
            if update:
                for e, around in updated.items():
                    c[e] += update * c[around].mean(axis=0)
        return c

    analysis = analyse(np.eye(vertex_count))
    band = np.full(vertex_count, len(structure) + 1)  # the coarsest vertices
    for level, (odd, _, _) in enumerate(structure):
        band[odd] = level + 1  # finest = 1
    band = band.max() - band  # coarse first
    return analysis, band


def haar_matrix(vertex_count, faces, mean_positions):
    """(orthonormal analysis matrix, band per row: the level a difference was made at, the
    sums of the last nodes in band 0)."""
    rows = np.eye(vertex_count)  # each node's current (sum) row of the analysis
    weight = np.ones(vertex_count)
    graph = {v: set(w) for v, w in enumerate(model.adjacency(vertex_count, faces))}
    where = {v: mean_positions[v] for v in graph}
    out, bands, level = [], [], 0
    while True:
        edges = sorted((float(np.linalg.norm(where[a] - where[b])), a, b) for a in graph for b in graph[a] if a < b)
        if not edges:
            break
        level += 1
        matched, merged = set(), {}
        for _, a, b in edges:
            if a in matched or b in matched:
                continue
            matched |= {a, b}
            wa, wb = weight[a], weight[b]
            total = math.sqrt(wa + wb)
            low = (math.sqrt(wa) * rows[a] + math.sqrt(wb) * rows[b]) / total
            out.append((-math.sqrt(wb) * rows[a] + math.sqrt(wa) * rows[b]) / total)
            bands.append(level)
            rows[a], weight[a] = low, wa + wb
            where[a] = (wa * where[a] + wb * where[b]) / (wa + wb)
            merged[b] = a
        coarse = {}
        for v in graph:
            if v in merged:
                continue
            coarse[v] = set()
        for v, around in graph.items():
            mv = merged.get(v, v)
            for w in around:
                mw = merged.get(w, w)
                if mw != mv:
                    coarse[mv].add(mw)
        graph = coarse
    for v in graph:  # one sum per connected piece
        out.append(rows[v])
        bands.append(level + 1)
    analysis = np.array(out)
    band = np.array(bands)
    order = np.argsort(-band, kind='stable')  # coarse first
    return analysis[order], np.minimum(band.max() - band[order], 11)


def frequency_bands(n):
    return np.array([min(int(math.log2(i + 1)), 11) for i in range(n)])


def spatial_parts(variant, frames, faces):
    """[(vertex indices, analysis matrix, synthesis matrix, band per row)] of the variant: the
    rows of the analysis give a part's coefficients, the synthesis's columns rebuild it, and a
    step q in any coefficient costs the squared error it would in an orthonormal basis."""
    v = frames.shape[1]
    if variant in ('graph', 'cotangent'):
        weights = model.cotangent_weights(frames.mean(axis=0), faces) if variant == 'cotangent' else None
        phi = eigenbasis(laplacian(v, faces, weights))
        return [(np.arange(v), phi.T, phi, frequency_bands(v))]
    if variant.startswith('patches-'):
        return [(members, phi.T, phi, frequency_bands(len(members)))
                for members, phi in patch_bases(v, faces, int(variant.split('-')[1]))]
    if variant.startswith(('lifting-', 'predict-')):
        analysis, band = lifting_matrix(v, faces, int(variant.split('-')[1]), 0.5 if variant[0] == 'l' else 0)
        synthesis = np.linalg.inv(analysis)
        norms = np.linalg.norm(synthesis, axis=0)  # the error one unit of each coefficient makes
        return [(np.arange(v), analysis * norms[:, None], synthesis / norms, band)]
    if variant == 'haar':
        analysis, band = haar_matrix(v, faces, frames.mean(axis=0))
        return [(np.arange(v), analysis, analysis.T, band)]
    raise ValueError(variant)


def measure(frames, faces, variant, target):
    """(bits, KG %) of the sequence as one group at the coarsest step that meets the target."""
    v = frames.shape[1]
    mean, basis, coefficients, fixed = model.transform(frames, 'pca')
    if variant == 'dpcm':
        order, predictor = model.coded_order_predictor(v, faces)
        return model.at_target(frames, [(frames, (mean, basis, coefficients, fixed), None)], 'pca',
                               predictor, order, target)
    sigma = np.linalg.norm(coefficients, axis=0)
    original = frames.transpose(1, 2, 0).reshape(v, -1)
    parts = spatial_parts(variant, frames, faces)
    projections = [analysis @ coefficients[members] for members, analysis, _, _ in parts]

    def cost(q):
        bits, decoded = 0.0, np.zeros_like(coefficients)
        for (members, _, synthesis, band), values in zip(parts, projections):
            ints = np.rint(values / q).astype(np.int64)
            bits += model.residual_bits(ints, band)
            decoded[members] = synthesis @ (ints * q)
        used = np.flatnonzero(np.abs(decoded).sum(axis=0) > 0)
        b, quantised = model.basis_cost(basis, sigma, q, used, 3)
        bits += b + 32 * mean.size
        rows = mean + decoded @ quantised
        return bits, float(((rows - original) ** 2).sum())

    return model.search_step(frames, cost, target)


def main():
    parser = model.experiment_parser(__doc__)
    parser.add_argument('--variants', default='dpcm,graph,cotangent,patches-256')
    args = parser.parse_args()
    variants = args.variants.split(',')
    rows = []
    for name, pc2_path, ply_path, frames, faces, static in model.load_sequences(args.animc, args.data_dir):
        f, v, _ = frames.shape
        for target in map(float, args.kg.split(',')):
            cells = []
            for variant in variants:
                bits, _ = measure(frames, faces, variant, target)
                cells.append((bits + 8 * static) / (v * f))
            rows.append([name, f'{target:g}'] + [f'{c:.3f}' for c in cells] +
                        [f'{c / cells[0]:.3f}' for c in cells[1:]])
            print(rows[-1], file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'KG %'] + [f'{v} bpvf' for v in variants] +
                           [f'{v} / dpcm' for v in variants[1:]], rows)))


if __name__ == '__main__':
    main()
