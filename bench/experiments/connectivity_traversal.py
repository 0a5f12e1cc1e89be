#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for a cheaper connectivity (issue 40): what a triangle list costs when the
triangles may be reordered (and their corners rotated) but the vertices keep their indices.

`CONN` (format.md 6.2) keeps the triangles in their order and their corners in theirs, at 15 to
18.5 bits a triangle on the shared sequences. Vertex order carries meaning (a .pc2 file and every
tool that reads frames index vertices), triangle order does not. This estimates a traversal
coder of the kind Edgebreaker and valence coders are (Rossignac 1999, Touma & Gotsman 1998),
kept simple:

- triangles are visited breadth-first across shared edges, from one seed triangle per
  connected piece; for each edge of a visited triangle that the decoder cannot yet know to be
  closed, one adaptive bit says whether an unvisited triangle lies across it;
- that triangle's third vertex is coded as: an already-seen vertex joined to both ends of the
  edge (its rank among those), another seen vertex (rank among those joined to either end,
  else an index), or a new vertex, whose index is the difference from the last new vertex's,
  a classed integer (adaptive bucket, raw mantissa, sign);
- one adaptive bit a triangle for its orientation against the edge it is reached through.

Costs are those of adaptive models (Krichevsky-Trofimov, trajectory_coding.adaptive_bits), so
an estimate of what a range coder of the codec's kind would spend; the table puts it beside
the `CONN` bytes of today's files (`animc info --json`, section_CONN_bytes, after an encode).

  usage: bench/experiments/connectivity_traversal.py ANIMC DATA_DIR
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from collections import defaultdict, deque

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
import ply  # noqa: E402
import trajectory_coding as model  # noqa: E402
from bench_common import find_sequences, table  # noqa: E402


class Symbols:
    """Symbols per context; bits() prices each context's sequence with an adaptive model."""

    def __init__(self):
        self.by_context = defaultdict(list)
        self.raw = 0.0

    def add(self, context, symbol):
        self.by_context[context].append(symbol)

    def integer(self, context, value):
        magnitude = abs(value)
        bucket = int(math.log2(magnitude)) + 1 if magnitude else 0
        self.add(context, bucket)
        self.raw += max(bucket - 1, 0) + (1 if magnitude else 0)

    def bits(self):
        total = self.raw
        for symbols in self.by_context.values():
            total += model.adaptive_bits(np.array(symbols), max(symbols) + 1)
        return total


def triangle_neighbours(faces):
    """{undirected edge: [triangles]}."""
    around = defaultdict(list)
    for t, (a, b, c) in enumerate(faces):
        for x, y in ((a, b), (b, c), (c, a)):
            around[(min(x, y), max(x, y))].append(t)
    return around


def traversal_bits(vertex_count, faces):
    faces = [tuple(int(x) for x in f) for f in faces]
    around = triangle_neighbours(faces)
    visited = [False] * len(faces)
    seen = np.zeros(vertex_count, dtype=bool)
    joined = defaultdict(set)  # vertex -> vertices it shares a coded triangle with
    coded_sides = defaultdict(int)  # undirected edge -> coded triangles on it
    symbols = Symbols()
    last_new = [-1]

    def code_vertex(v, gate):
        if not seen[v]:
            # The index as a difference from the last new vertex's, counted over the vertices
            # not yet seen (those in between that were seen cannot come again).
            symbols.add('kind', 2)
            lo, hi = sorted((last_new[0] + 1, v))
            skipped = int(seen[lo:hi].sum())
            symbols.integer('new', v - last_new[0] - 1 + (skipped if v <= last_new[0] else -skipped))
            last_new[0] = v
            seen[v] = True
            return
        # Seen vertices: first those on the open boundary next to the edge (joined to one of
        # its ends by an edge with one coded triangle), where a traversal usually closes a fan.
        candidates = []
        if gate:
            x, y = gate
            for end in (x, y):
                for w in sorted(joined[end]):
                    if w not in gate and coded_sides[(min(end, w), max(end, w))] == 1 and w not in candidates:
                        candidates.append(w)
            for end in (x, y):
                for w in sorted(joined[end]):
                    if w not in gate and w not in candidates:
                        candidates.append(w)
        if v in candidates:
            symbols.add('kind', min(candidates.index(v), 1))
            if candidates.index(v) >= 1:
                symbols.integer('rank', candidates.index(v) - 1)
        else:
            symbols.add('kind', 3)
            symbols.raw += math.log2(vertex_count)

    def visit(t):
        visited[t] = True
        a, b, c = faces[t]
        for x, y in ((a, b), (b, c), (c, a)):
            coded_sides[(min(x, y), max(x, y))] += 1
            joined[x].add(y)
            joined[y].add(x)

    for seed in range(len(faces)):
        if visited[seed]:
            continue
        for v in faces[seed]:
            code_vertex(v, None)
        visit(seed)
        queue = deque([seed])
        while queue:
            t = queue.popleft()
            a, b, c = faces[t]
            for x, y in ((a, b), (b, c), (c, a)):
                edge = (min(x, y), max(x, y))
                across = [u for u in around[edge] if not visited[u]]
                # A decoder knows an edge is closed when two coded triangles share it (manifold).
                if coded_sides[edge] >= 2 and not across:
                    continue
                symbols.add('open', 1 if across else 0)
                if not across:
                    continue
                u = across[0]
                if len(around[edge]) > 2:  # non-manifold: which of the others comes next
                    symbols.raw += math.log2(len(around[edge]))
                third = [v for v in faces[u] if v != x and v != y]
                third = third[0] if third else faces[u][0]
                code_vertex(third, (x, y))
                # Orientation against the edge: consistent meshes run the edge the other way.
                i = faces[u].index(x) if x in faces[u] else 0
                symbols.add('flip', 0 if faces[u][(i + 2) % 3] == y else 1)
                visit(u)
                queue.append(u)
            # Degenerate triangles (repeated corners) are coded like any other here; their cost
            # is what a real coder would pay at most.
    return symbols.bits()


def conn_bytes(animc, pc2_path, ply_path):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'x.ams')
        subprocess.run([animc, 'encode', pc2_path, '--mesh', ply_path, '-o', out, '--codec', 'trajectory'],
                       check=True, capture_output=True)
        info = json.loads(subprocess.run([animc, 'info', out, '--json'], check=True, capture_output=True,
                                         text=True).stdout)
    return info['section_CONN_bytes']


def meshes(doc):
    """(name, faces, CONN bytes of today's file) of each sequence of the command line's
    DATA_DIR, the usage `doc` ANIMC DATA_DIR."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument('animc')
    parser.add_argument('data_dir')
    args = parser.parse_args()
    for name, pc2_path, ply_path in find_sequences(args.data_dir):
        yield name, ply.read_ply_faces(ply_path), conn_bytes(args.animc, pc2_path, ply_path)


def main():
    rows = []
    for name, faces, today in meshes(__doc__):
        vertex_count = int(np.max(faces)) + 1
        estimate = traversal_bits(vertex_count, faces) / 8
        t = len(faces)
        rows.append([name, t, today, f'{8 * today / t:.1f}', f'{estimate:.0f}', f'{8 * estimate / t:.1f}',
                     f'{estimate / today:.3f}'])
        print(rows[-1], file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'triangles', 'CONN bytes', 'bits a triangle', 'traversal bytes (estimate)',
                           'bits a triangle', 'traversal / CONN'], rows)))


if __name__ == '__main__':
    main()
