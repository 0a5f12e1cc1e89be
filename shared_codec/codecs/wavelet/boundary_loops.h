// SPDX-License-Identifier: Apache-2.0
// Boundary edges and loops of a LevelMesh while the progressive-mesh hierarchy is built
// (progressive_mesh.cpp): which vertices lie on a boundary, and how many each loop keeps.
#pragma once
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "codecs/wavelet/level_mesh.h"

namespace animc {

// f(b) for each boundary edge (v, b), one held by exactly one live triangle: b is once among
// the corners of v's triangles (b > v only, when higher_only). times is all zeros, and left so.
template <class F>
void forEachBoundaryEdge(const LevelMesh& mesh, uint32_t v, bool higher_only, std::vector<uint32_t>& times,
                         std::vector<uint32_t>& corners, F f) {
  corners.clear();  // each once, in order of first appearance
  for (const uint32_t *t = mesh.trianglesBegin(v), *end = mesh.trianglesEnd(v); t != end; ++t)
    for (uint32_t b : mesh.triangle(*t))
      if ((higher_only ? b > v : b != v) && times[b]++ == 0) corners.push_back(b);
  for (uint32_t b : corners) {
    if (times[b] == 1) f(b);
    times[b] = 0;
  }
}

// The boundary loops (edges with one live triangle, joined at shared vertices) and how many
// vertices each still has, so that every loop keeps >= 3. Collapses that pass the link
// condition keep the topology, so loops neither split nor merge: built once, after the
// seams are welded, then only counted down.
struct BoundaryLoops {
  std::vector<uint32_t> loop_of;    // per vertex: a representative vertex of its loop
  std::vector<uint32_t> remaining;  // per representative: vertices on the loop

  BoundaryLoops(const LevelMesh& mesh, uint32_t vertex_count)
      : loop_of(vertex_count), remaining(vertex_count, 0) {
    std::iota(loop_of.begin(), loop_of.end(), 0u);
    const auto edges = boundaryEdges(mesh, vertex_count);
    for (const auto& [a, b] : edges) loop_of[find(a)] = find(b);
    for (uint32_t v = 0; v < vertex_count; ++v) loop_of[v] = find(v);
    std::vector<uint8_t> on_boundary(vertex_count, 0);
    for (const auto& [a, b] : edges) on_boundary[a] = on_boundary[b] = 1;
    for (uint32_t v = 0; v < vertex_count; ++v) remaining[loop_of[v]] += on_boundary[v];
  }

  bool canLose(uint32_t v) const { return remaining[loop_of[v]] > 3; }
  // One vertex less on v's loop, if the loop keeps at least 3.
  bool take(uint32_t v) {
    if (!canLose(v)) return false;
    --remaining[loop_of[v]];
    return true;
  }

 private:
  uint32_t find(uint32_t v) {
    while (loop_of[v] != v) v = loop_of[v] = loop_of[loop_of[v]];
    return v;
  }

  // The boundary edges (a, b), a < b. (Their order does not matter: the loops are the
  // connected components, whatever the order of the unions.)
  static std::vector<std::pair<uint32_t, uint32_t>> boundaryEdges(const LevelMesh& mesh, uint32_t vertex_count) {
    std::vector<std::pair<uint32_t, uint32_t>> out;
    std::vector<uint32_t> times(vertex_count, 0), corners;
    for (uint32_t a = 0; a < vertex_count; ++a)
      forEachBoundaryEdge(mesh, a, true, times, corners, [&](uint32_t b) { out.emplace_back(a, b); });
    return out;
  }
};

// Whether v has a boundary edge. `times` is all zeros, and left so.
inline bool onBoundary(const LevelMesh& mesh, uint32_t v, std::vector<uint32_t>& times, std::vector<uint32_t>& corners) {
  bool any = false;
  forEachBoundaryEdge(mesh, v, false, times, corners, [&](uint32_t) { any = true; });
  return any;
}

}  // namespace animc
