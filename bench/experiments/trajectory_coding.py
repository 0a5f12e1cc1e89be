#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for codec 3 (issue 27): how many bits trajectory coding over frame groups
needs at a KG error, before any of it is written in C++.

Each group of G frames is coded on its own (random access stays). Per group, every vertex's
trajectory (its G positions) goes through an orthonormal temporal transform:
  dct     the DCT-II of each coordinate's G values (fixed basis, nothing to send);
  pca     the principal components of the 3G-long trajectories (CoDDyaC's trajectory space);
  pca-xyz one G-long basis shared by x, y and z (3V series);
  pca-mcC pca after motion compensation of C clusters of vertices (k-means of their
          trajectories): per cluster and frame, the affine map of its first-frame positions
          that fits best is subtracted and its 12 parameters sent, quantised and coded along
          time (affine_motion, motion_cost).
For the pca kinds the mean trajectory (32-bit floats) and the basis vectors that carry a
non-zero coefficient are sent, each vector quantised with a step matched to its importance and
coded as differences along time (basis_cost).
Coefficients are quantised with one step q (orthonormal transforms keep the squared error, so
one step is what minimises the error for the bits), the integers predicted from the vertex's
already-coded neighbours (breadth-first order, rounded mean), and the residuals' cost taken as
an adaptive arithmetic coder's: an Elias-gamma bucket with adaptive counts per component band,
raw bits inside the bucket, one sign bit. q is bisected until the sequence's KG error meets the
target. The estimate is for the motion only; the whole-file figure adds the header and
connectivity bytes an .ams of the sequence has.

Against it: our codecs at the same KG, from `animc encode --json` (affine-octree max-error sweep,
log-log interpolated; wavelet --target-kg).

  usage: bench/experiments/trajectory_coding.py ANIMC DATA_DIR [--groups 32,64] [--kinds pca,dct]
         [--basis-factor F] [--no-prediction] [--cotangent] [--no-ours]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from collections import deque

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import pc2  # noqa: E402
import ply  # noqa: E402
from bench_common import find_sequences, loglog_interp  # noqa: E402

TARGETS = (0.3, 1.0)
# Variants measured against the design (command-line flags): the basis step's factor on
# q / sigma_k, and whether coefficients are predicted from neighbours at all.
VARIANT = {'basis_factor': 1.0, 'prediction': True}


def dct_matrix(n):
    k = np.arange(n)[:, None]
    m = np.cos(np.pi * (np.arange(n)[None, :] + 0.5) * k / n) * math.sqrt(2 / n)
    m[0] /= math.sqrt(2)
    return m


def cotangent_weights(positions, faces):
    """{(v, w): weight} of each edge of the mesh at `positions`: half the sum of the cotangents
    of the angles opposite it (the cotangent Laplacian's), at least a thousandth of the mean, so
    that obtuse triangles do not make weights negative or zero."""
    weights = {}
    for tri in faces:
        for i in range(3):
            a, b, c = tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]  # the angle at a, opposite edge b-c
            u, w = positions[b] - positions[a], positions[c] - positions[a]
            sine = np.linalg.norm(np.cross(u, w))
            cot = float(np.dot(u, w) / sine) if sine > 0 else 0.0
            for e in ((b, c), (c, b)):
                weights[e] = weights.get(e, 0.0) + cot / 2
    floor = 1e-3 * np.mean([abs(x) for x in weights.values()])
    return {e: max(x, floor) for e, x in weights.items()}


def adjacency(vertex_count, faces):
    """The set of each vertex's neighbours on the mesh."""
    neighbours = [set() for _ in range(vertex_count)]
    for a, b, c in faces:
        neighbours[a] |= {b, c}
        neighbours[b] |= {a, c}
        neighbours[c] |= {a, b}
    return neighbours


def induced_faces(faces, members, vertex_count):
    """The triangles whose corners all lie in `members`, in indices into members."""
    local = np.full(vertex_count, -1)
    local[members] = np.arange(len(members))
    sub = np.array([local[list(t)] for t in faces], dtype=int).reshape(-1, 3)
    return sub[(sub >= 0).all(axis=1)]


def coded_order_predictor(vertex_count, faces, edge_weights=None):
    """The breadth-first coding order and, per vertex, its neighbours coded before it, weighted
    equally, or by edge_weights (normalised over those neighbours) when given."""
    neighbours = adjacency(vertex_count, faces)
    position = np.full(vertex_count, -1)
    order = []
    for root in range(vertex_count):
        if position[root] >= 0:
            continue
        position[root] = len(order)
        queue = deque([root])
        while queue:
            v = queue.popleft()
            order.append(v)
            for w in sorted(neighbours[v]):
                if position[w] < 0:
                    position[w] = len(order) + len(queue)
                    queue.append(w)
    rows, cols, vals = [], [], []
    for v in range(vertex_count):
        earlier = [w for w in neighbours[v] if position[w] < position[v]]
        weights = [edge_weights[(v, w)] if edge_weights else 1.0 for w in earlier]
        for w, weight in zip(earlier, weights):
            rows.append(v)
            cols.append(w)
            vals.append(weight / sum(weights))
    return np.array(order), (np.array(rows, dtype=int), np.array(cols, dtype=int), np.array(vals))


def predict(predictor, values):
    """The rounded mean of each vertex's earlier neighbours' integers (0 without any)."""
    rows, cols, vals = predictor
    out = np.zeros_like(values, dtype=float)
    np.add.at(out, rows, vals[:, None] * values[cols])
    return np.rint(out).astype(np.int64)


def adaptive_bits(symbols, alphabet):
    """Bits an adaptive frequency model (counts start at 0.5, Krichevsky-Trofimov) spends on the
    symbols: the product of its probabilities does not depend on their order, so it has the
    closed form log2 of Gamma(n + M/2) / Gamma(M/2) / prod Gamma(n_s + 1/2) / Gamma(1/2)."""
    n = len(symbols)
    if n == 0:
        return 0.0
    counts = np.bincount(symbols, minlength=alphabet)
    nats = math.lgamma(n + alphabet / 2) - math.lgamma(alphabet / 2)
    nats -= sum(math.lgamma(c + 0.5) - math.lgamma(0.5) for c in counts if c)
    return nats / math.log(2)


def residual_bits(residuals, row_band=None):
    """residuals: (vertices in coding order, components). One context per component band, and
    per band of rows when row_band (one per row) is given."""
    bits = 0.0
    magnitude = np.abs(residuals)
    bucket = np.where(magnitude > 0, np.floor(np.log2(np.maximum(magnitude, 1))).astype(int) + 1, 0)
    bits += float((np.maximum(bucket - 1, 0)).sum() + (magnitude > 0).sum())  # mantissa + sign
    column_band = np.array([min(int(math.log2(k + 1)), 7) for k in range(residuals.shape[1])])
    row_band = np.zeros(len(residuals), dtype=int) if row_band is None else row_band
    for r in np.unique(row_band):
        for c in np.unique(column_band):
            bits += adaptive_bits(bucket[np.ix_(row_band == r, column_band == c)].reshape(-1), 48)
    return bits


def clusters_of(group, count, iterations=12):
    """k-means of the vertices' trajectories over the group (vertices moving together), seeded
    by farthest-point sampling: a cluster index per vertex."""
    rows = group.transpose(1, 2, 0).reshape(group.shape[1], -1)
    centres = [rows[0]]
    distance = ((rows - centres[0]) ** 2).sum(axis=1)
    for _ in range(1, count):
        centres.append(rows[int(distance.argmax())])
        distance = np.minimum(distance, ((rows - centres[-1]) ** 2).sum(axis=1))
    centres = np.array(centres)
    for _ in range(iterations):
        labels = (-2 * rows @ centres.T + (centres ** 2).sum(axis=1)).argmin(axis=1)
        for c in range(count):
            if (labels == c).any():
                centres[c] = rows[labels == c].mean(axis=0)
    return labels


def affine_motion(group, count):
    """Motion compensation of near-rigid parts: per cluster of vertices and per frame, the
    affine map (3 x 4) from the cluster's centred first-frame positions that best fits its
    vertices. (prediction (g, v, 3), [(values (g, 12), weight of each of the 12 parameters)]):
    an error d in parameter j of a cluster moves its vertices by d times their coordinate j,
    weight_j^2 d^2 in total."""
    g, v, _ = group.shape
    labels = clusters_of(group, count)
    prediction = np.zeros_like(group)
    params = []
    for c in range(count):
        index = np.flatnonzero(labels == c)
        if len(index) == 0:
            continue
        rest = group[0, index] - group[0, index].mean(axis=0)
        design = np.hstack([rest, np.ones((len(index), 1))])  # (m, 4)
        targets = group[:, index, :].transpose(1, 0, 2).reshape(len(index), 3 * g)
        affine = np.linalg.lstsq(design, targets, rcond=None)[0].reshape(4, g, 3)
        prediction[:, index, :] = np.einsum('mj,jtd->tmd', design, affine)
        weights = np.sqrt((design ** 2).sum(axis=0))
        params.append((affine.transpose(1, 0, 2).reshape(g, 12), np.repeat(weights, 3)))
    return prediction, params


def motion_cost(params, q):
    """(bits, squared error) of the affine parameters at step q / weight (each then costs the
    error of one coefficient's step), coded as differences along time."""
    bits, sq = 0.0, 0.0
    for values, weights in params:
        steps = q / np.maximum(weights, 1e-300)
        ints = np.rint(values / steps).astype(np.int64)
        sq += float((((values - ints * steps) * weights) ** 2).sum())
        bits += 16 * len(weights) + residual_bits(np.diff(ints, axis=0, prepend=0))
    return bits, sq


def transform(group, kind):
    """(mean, basis (components, length), coefficients (rows, components), whether the basis is
    fixed): rows are vertex-coordinates (dct, pca-xyz: length G) or vertices (pca: length 3G)."""
    g, v, _ = group.shape
    if kind == 'dct':
        rows = group.transpose(1, 2, 0).reshape(3 * v, g)
        basis = dct_matrix(g)
        return np.zeros(g), basis, rows @ basis.T, True
    if kind == 'pca' or kind.startswith('pca-mc'):
        rows = group.transpose(1, 2, 0).reshape(v, 3 * g)
    elif kind == 'pca-xyz':
        rows = group.transpose(1, 2, 0).reshape(3 * v, g)
    else:
        raise ValueError(kind)
    mean = rows.mean(axis=0)
    _, _, basis = np.linalg.svd(rows - mean, full_matrices=False)
    return mean, basis, (rows - mean) @ basis.T, False


def basis_cost(basis, singular, q, used, segments):
    """(bits, quantised basis) of the used basis vectors. Vector k gets the step q / sigma_k (an
    error d in it moves every vertex by its coefficient times d: sigma_k spreads that over the
    group as the coefficients' own step q would), and its values are coded as differences along
    time within each of its segments (x, y, z of a trajectory), which are smooth."""
    quantised = np.zeros_like(basis)
    bits = 0.0
    for k in used:
        step = VARIANT['basis_factor'] * q / max(singular[k], 1e-300)
        ints = np.rint(basis[k] / step).astype(np.int64)
        quantised[k] = ints * step
        deltas = np.concatenate([np.diff(seg, prepend=0) for seg in np.split(ints, segments)])
        bits += 16 + residual_bits(deltas[:, None])  # the step's exponent, then the values
    return bits, quantised


def code(groups, kind, predictor, order, q, output=None):
    """(bits, squared error) of the whole sequence at step q; output, when given, is what a
    decoder does to its rows (vertices, one trajectory each) before they are compared."""
    bits, sq = 0.0, 0.0
    for group, (mean, basis, coefficients, fixed), params in groups:
        g, v, _ = group.shape
        if params:
            b, e = motion_cost(params, q)
            bits, sq = bits + b, sq + e
        cq = np.rint(coefficients / q).astype(np.int64)
        used = np.flatnonzero(np.abs(cq).sum(axis=0) > 0)
        quantised = basis
        if not fixed:
            b, quantised = basis_cost(basis, np.linalg.norm(coefficients, axis=0), q, used,
                                      1 if kind == 'pca-xyz' else 3)
            bits += b + 32 * mean.size
        rows = mean + (cq * q) @ quantised
        rows = output(rows) if output else rows
        original = group.transpose(1, 2, 0).reshape(rows.shape)
        sq += float(((rows - original) ** 2).sum())
        # A vertex's coefficients side by side, component by component (x y z of each for the
        # kinds with one row per coordinate), so that the context bands follow the component.
        per_vertex = cq.reshape(v, -1, cq.shape[1]).transpose(0, 2, 1).reshape(v, -1)
        residual = per_vertex - predict(predictor, per_vertex) if VARIANT['prediction'] else per_vertex
        bits += residual_bits(residual[order])
    return bits, sq


def search_step(frames, cost, target):
    """(bits, KG %) at the coarsest step q (bisected on log2 q) whose cost(q) = (bits, squared
    error) meets the KG target on the frames."""
    denominator = float(((frames - frames.mean(axis=1, keepdims=True)) ** 2).sum())
    scale = math.log2(float(np.ptp(frames, axis=(0, 1)).max()))
    lo, hi = scale - 24, scale  # log2 of q
    best = None
    for _ in range(20):
        mid = (lo + hi) / 2
        bits, sq = cost(2 ** mid)
        kg = 100 * math.sqrt(sq / denominator)
        if kg <= target:
            best, lo = (bits, kg), mid
        else:
            hi = mid
    return best


def at_target(frames, groups, kind, predictor, order, target):
    return search_step(frames, lambda q: code(groups, kind, predictor, order, q), target)


def our_codecs(animc, pc2_path, ply_path, targets):
    """{target: (affine-octree bpvf interpolated, wavelet bpvf)} and the static bytes."""
    points, static, wavelet = [], None, {}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'x.ams')
        for me in (0.0015, 0.002, 0.003, 0.004, 0.006, 0.008, 0.011, 0.016, 0.022, 0.03, 0.045):
            r = json.loads(subprocess.run([animc, 'encode', pc2_path, '--mesh', ply_path, '-o', out,
                                           '--codec', 'affine-octree', '--max-error', str(me), '--json'],
                                          check=True, capture_output=True, text=True).stdout)
            points.append((r['kg_error'], r['bpvf']))
            static = r['static_bytes']
        for target in targets:
            r = json.loads(subprocess.run([animc, 'encode', pc2_path, '--mesh', ply_path, '-o', out, '--codec',
                                           'wavelet', '--target-kg', str(target), '--step', '1e-5', '--json'],
                                          check=True, capture_output=True, text=True).stdout)
            wavelet[target] = r['bpvf']
    return {t: (loglog_interp(points, t), wavelet[t]) for t in targets}, static


def our_static_bytes(animc, pc2_path, ply_path):
    """What an .ams of the sequence spends outside its motion (affine-octree's static bytes)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'x.ams')
        r = json.loads(subprocess.run([animc, 'encode', pc2_path, '--mesh', ply_path, '-o', out, '--codec',
                                       'affine-octree', '--json'], check=True, capture_output=True, text=True).stdout)
    return r['static_bytes']


def experiment_parser(doc):
    """The arguments every design measurement takes: ANIMC, DATA_DIR and --kg targets."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument('animc')
    parser.add_argument('data_dir')
    parser.add_argument('--kg', default='0.1,0.3,0.45,1')
    return parser


def load_sequences(animc, data_dir):
    """(name, pc2 path, ply path, frames in double, faces, the static bytes an .ams of it has) of
    each sequence in data_dir."""
    for name, pc2_path, ply_path in find_sequences(data_dir):
        frames, _ = pc2.read_pc2(pc2_path)
        yield (name, pc2_path, ply_path, frames.astype(np.float64), ply.read_ply_faces(ply_path),
               our_static_bytes(animc, pc2_path, ply_path))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('animc')
    parser.add_argument('data_dir')
    parser.add_argument('--groups', default='16,32,64')
    parser.add_argument('--kinds', default='dct,pca,pca-xyz')
    parser.add_argument('--basis-factor', type=float, default=1.0)
    parser.add_argument('--no-prediction', action='store_true')
    parser.add_argument('--cotangent', action='store_true',
                        help="weigh the neighbours' prediction by the cotangent Laplacian of the mean frame")
    parser.add_argument('--no-ours', action='store_true', help="leave out our codecs' columns (0 there)")
    args = parser.parse_args()
    VARIANT.update(basis_factor=args.basis_factor, prediction=not args.no_prediction)
    print('| sequence | KG % | affine-octree bpvf | wavelet bpvf | ' +
          ' | '.join(f'{k} G={g}' for k in args.kinds.split(',') for g in args.groups.split(',')) + ' |')
    for name, pc2_path, ply_path in find_sequences(args.data_dir):
        frames, _ = pc2.read_pc2(pc2_path)
        frames = frames.astype(np.float64)
        faces = ply.read_ply_faces(ply_path)
        f, v, _ = frames.shape
        weights = cotangent_weights(frames.mean(axis=0), faces) if args.cotangent else None
        order, predictor = coded_order_predictor(v, faces, weights)
        if args.no_ours:
            ours, static = {t: (0.0, 0.0) for t in TARGETS}, our_static_bytes(args.animc, pc2_path, ply_path)
        else:
            ours, static = our_codecs(args.animc, pc2_path, ply_path, TARGETS)
        for target in TARGETS:
            octree, wavelet = ours[target]
            cells = []
            for kind in args.kinds.split(','):
                for g in map(int, args.groups.split(',')):
                    parts = [frames[s:s + g] for s in range(0, f, g)]
                    groups = []
                    for p in parts:
                        params = None
                        if kind.startswith('pca-mc'):  # PCA of what the affine motion leaves
                            prediction, params = affine_motion(p, int(kind[len('pca-mc'):]))
                            p = p - prediction
                        groups.append((p, transform(p, kind), params))
                    bits, _ = at_target(frames, groups, kind, predictor, order, target)
                    cells.append((bits + 8 * static) / (v * f))
            print(f'| {name} | {target} | {octree:.3f} | {wavelet:.3f} | ' +
                  ' | '.join(f'{c:.3f}' for c in cells) + ' |', flush=True)


if __name__ == '__main__':
    main()
