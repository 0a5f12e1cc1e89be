#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Design measurement for a cheaper connectivity that keeps what `CONN` keeps (issue 40): the
triangles in their order and each triangle's corners in theirs (format.md 6.2). The traversal
estimate (connectivity_traversal.py) may reorder triangles; this prices two coders of the same
family that may not, with the same adaptive-model costs (Krichevsky-Trofimov):

- `fifo`: an edge cache, as index-buffer coders of vertex-cache order keep one: the 32 newest
  directed edges of the triangles coded. A triangle that runs one of them backwards is coded
  as its slot, the rotation that puts the edge first, and its third vertex; any other as its
  three corners. A vertex is the next never-seen index, one of the 16 newest vertices, or a
  difference from the index before it.
- `reference`: a triangle that shares an edge with an earlier one is coded as the distance
  back to the latest such triangle, which of that triangle's edges it is, the orientation and
  rotation, and its third vertex; one that shares none, as a distance of 0 and its corners. A
  vertex never seen is the next never-seen index or a difference from the last new vertex; a
  seen one is its rank among the neighbours of the shared edge's ends (newest first) or a
  difference from the index before it.

The table puts each beside the `CONN` bytes of today's files (`animc info --json`,
section_CONN_bytes, after an encode).

  usage: bench/experiments/connectivity_ordered.py ANIMC DATA_DIR
"""
import os
import sys
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench_common import table  # noqa: E402
from connectivity_traversal import Symbols, meshes  # noqa: E402

EDGE_SLOTS = 32
VERTEX_SLOTS = 16


def fifo_bits(faces):
    symbols = Symbols()
    edges, vertices = [], []  # newest first
    state = {'next_new': 0, 'last': 0}

    def code_vertex(v, context):
        if v == state['next_new']:
            symbols.add(context, 0)
        elif v in vertices:
            symbols.add(context, 1 + vertices.index(v))
        else:
            symbols.add(context, 1 + VERTEX_SLOTS)
            symbols.integer('delta ' + context, v - state['last'])
        state['next_new'] = max(state['next_new'], v + 1)
        state['last'] = v

    for face in faces:
        t = tuple(int(x) for x in face)
        hit = None
        for slot, (x, y) in enumerate(edges):
            r = next((r for r in range(3) if t[r] == y and t[(r + 1) % 3] == x), None)
            if r is not None:
                hit = (slot, r)
                break
        if hit:
            slot, r = hit
            symbols.add('slot', slot)
            symbols.add('rotation', r)
            x, y, w = t[r], t[(r + 1) % 3], t[(r + 2) % 3]
            code_vertex(w, 'third')
            del edges[slot]
            added = [(y, w), (w, x)]
        else:
            symbols.add('slot', EDGE_SLOTS)
            for v in t:
                code_vertex(v, 'corner')
            added = [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
        edges[:0] = added
        del edges[EDGE_SLOTS:]
        for v in t:
            if v in vertices:
                vertices.remove(v)
            vertices.insert(0, v)
        del vertices[VERTEX_SLOTS:]
    return symbols.bits()


def reference_bits(faces):
    symbols = Symbols()
    triangles = []
    latest = {}  # undirected edge -> the latest triangle holding it
    neighbours = defaultdict(list)  # vertex -> its neighbours so far, newest last
    seen = set()
    state = {'next_new': 0, 'last': 0, 'last_new': -1, 'rotation': 0}

    def code_vertex(v, gate, context):
        if v not in seen:
            if v == state['next_new']:
                symbols.add(context, 0)
            else:
                symbols.add(context, 1)
                symbols.integer('new', v - state['last_new'] - 1)
            state['last_new'] = v
            seen.add(v)
            while state['next_new'] in seen:
                state['next_new'] += 1
        else:
            ranked = []
            for end in gate or ():
                for u in reversed(neighbours[end]):
                    if u not in gate and u not in ranked:
                        ranked.append(u)
            if v in ranked:
                symbols.add(context, 2)
                symbols.integer('rank', ranked.index(v))
            else:
                symbols.add(context, 3)
                symbols.integer('seen', v - state['last'])
        state['last'] = v

    for i, face in enumerate(faces):
        t = tuple(int(x) for x in face)
        best = None
        for r in range(3):
            j = latest.get(frozenset((t[r], t[(r + 1) % 3])))
            if j is not None and (best is None or j > best[0]):
                best = (j, r)
        if best is None:
            symbols.integer('distance', 0)
            code_vertex(t[0], None, 'corner 0')
            code_vertex(t[1], (t[0],), 'corner 1')
            code_vertex(t[2], (t[0], t[1]), 'corner 2')
        else:
            j, r = best
            symbols.integer('distance', i - j)
            x, y = t[r], t[(r + 1) % 3]
            other = triangles[j]
            side = next(s for s in range(3) if {other[s], other[(s + 1) % 3]} == {x, y})
            symbols.add('edge', side)
            symbols.add('orientation', 0 if (other[side], other[(side + 1) % 3]) == (y, x) else 1)
            symbols.add(f'rotation after {state["rotation"]}', r)
            state['rotation'] = r
            code_vertex(t[(r + 2) % 3], (x, y), 'third')
        triangles.append(t)
        for r in range(3):
            x, y = t[r], t[(r + 1) % 3]
            latest[frozenset((x, y))] = i
            for a, b in ((x, y), (y, x)):
                if b in neighbours[a]:
                    neighbours[a].remove(b)
                neighbours[a].append(b)
    return symbols.bits()


def main():
    rows = []
    for name, faces, today in meshes(__doc__):
        row = [name, len(faces), today, f'{8 * today / len(faces):.1f}']
        for bits in (fifo_bits(faces), reference_bits(faces)):
            row += [f'{bits / 8:.0f}', f'{bits / len(faces):.1f}', f'{bits / 8 / today:.3f}']
        rows.append(row)
        print(row, file=sys.stderr, flush=True)
    print('\n'.join(table(['sequence', 'triangles', 'CONN bytes', 'bits a triangle', 'fifo bytes', 'bits a triangle',
                           'fifo / CONN', 'reference bytes', 'bits a triangle', 'reference / CONN'], rows)))


if __name__ == '__main__':
    main()
