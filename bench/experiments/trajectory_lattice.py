#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for the trajectory codec's next version (issue 40): decoded positions
snapped to the lattice the source's coordinates lie on.

Game formats store vertex animation on lattices: MD2 one of 256 values per axis and frame
(a scale and an offset per frame), MD3 multiples of 1/64. Three of the four shared sequences
are such lattices (oa_* on 1/64, sydney_md2 on a lattice per frame and axis). Below the
lattice's own rounding noise, a KG target makes a transform coder spend its bits on that
noise. If the file says which lattice each frame's axis lies on, a decoder can round every
decoded coordinate to it: a coordinate decoded within half a step of its value comes out
exact.

Priced by trajectory_coding.py's model (one group, PCA, neighbour prediction) at the step that
meets each KG target, with and without the snap; the lattice costs 2 x 32 bits per frame and
axis that has one (a fixed lattice would cost less: an upper bound). The encoder would use the
snap only where it pays, so the last column is the smaller of the two.

  usage: bench/experiments/trajectory_lattice.py ANIMC DATA_DIR [--kg 0.1,0.3,0.45,1]
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import trajectory_coding as model  # noqa: E402
from bench_common import table  # noqa: E402


def lattice(values):
    """(offset, step) when every value is offset + step * integer (the step being the smallest
    gap), else None."""
    unique = np.unique(values)
    gaps = np.diff(unique)
    if len(gaps) == 0 or gaps.min() <= 0:
        return None
    step = gaps.min()
    ratio = gaps / step
    if np.abs(ratio - np.rint(ratio)).max() > 1e-3:
        return None
    return float(unique[0]), float(step)


def lattices(frames):
    """(offsets, steps) arrays (frames, 3), step 0 where a frame's axis has no lattice."""
    f = frames.shape[0]
    offsets, steps = np.zeros((f, 3)), np.zeros((f, 3))
    for t in range(f):
        for d in range(3):
            found = lattice(frames[t, :, d])
            if found:
                offsets[t, d], steps[t, d] = found
    return offsets, steps


def snapped(rows, offsets, steps):
    """Rows (vertices, 3G: x over the frames, then y, then z) rounded to each column's lattice."""
    offset = offsets.T.reshape(-1)  # column d * g + t
    step = steps.T.reshape(-1)
    has = step > 0
    out = rows.copy()
    out[:, has] = offset[has] + step[has] * np.rint((rows[:, has] - offset[has]) / step[has])
    return out


def cost(group, transformed, predictor, order, q, snap):
    """(bits, squared error) of the group at step q, as trajectory_coding.code prices it, the
    decoded rows snapped to the lattices, which cost 64 bits each, when snap = (offsets, steps)."""
    if not snap:
        return model.code([(group, transformed, None)], 'pca', predictor, order, q)
    bits, sq = model.code([(group, transformed, None)], 'pca', predictor, order, q, lambda rows: snapped(rows, *snap))
    return bits + 64 * int((snap[1] > 0).sum()), sq


def at_target(frames, predictor, order, target, snap):
    transformed = model.transform(frames, 'pca')
    return model.search_step(frames, lambda q: cost(frames, transformed, predictor, order, q, snap), target)


def lattice_noise_kg(frames, steps):
    """KG error of the lattice's own rounding (uniform noise of each step)."""
    denominator = float(((frames - frames.mean(axis=1, keepdims=True)) ** 2).sum())
    return 100 * math.sqrt(frames.shape[1] * float((steps ** 2).sum()) / 12 / denominator)


def main():
    parser = model.experiment_parser(__doc__)
    args = parser.parse_args()
    rows = []
    for name, pc2_path, ply_path, frames, faces, static in model.load_sequences(args.animc, args.data_dir):
        f, v, _ = frames.shape
        order, predictor = model.coded_order_predictor(v, faces)
        offsets, steps = lattices(frames)
        share = float((steps > 0).mean())
        for target in map(float, args.kg.split(',')):
            plain, _ = at_target(frames, predictor, order, target, None)
            cells = [(plain + 8 * static) / (v * f)]
            if share > 0:
                snap, kg = at_target(frames, predictor, order, target, (offsets, steps))
                cells.append((snap + 8 * static) / (v * f))
            else:
                cells.append(cells[0])
            rows.append([name, f'{100 * share:.0f} %', f'{lattice_noise_kg(frames, steps):.3f}', f'{target:g}'] +
                        [f'{c:.3f}' for c in cells] + [f'{min(cells) / cells[0]:.3f}'])
            print(rows[-1], file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'frame axes on a lattice', 'lattice noise KG %', 'KG %', 'plain bpvf',
                           'snapped bpvf', 'best / plain'], rows)))


if __name__ == '__main__':
    main()
