// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/progressive_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <tuple>

#include "codecs/wavelet/boundary_loops.h"
#include "codecs/wavelet/collapse_batch.h"
#include "codecs/wavelet/collapse_option_cache.h"

namespace animc {
namespace {

double meanEdgeLength(const Topology& topology, const std::vector<double>& xyz) {
  double sum = 0;
  size_t count = 0;
  for (const Triangle& t : topology.triangles)
    for (int i = 0; i < 3; ++i) {
      const size_t a = 3 * size_t(t[i]), b = 3 * size_t(t[(i + 1) % 3]);
      sum += std::sqrt((xyz[a] - xyz[b]) * (xyz[a] - xyz[b]) + (xyz[a + 1] - xyz[b + 1]) * (xyz[a + 1] - xyz[b + 1]) +
                       (xyz[a + 2] - xyz[b + 2]) * (xyz[a + 2] - xyz[b + 2]));
      ++count;
    }
  return count ? sum / double(count) : 0.0;
}

// Seams: boundary vertices at exactly the same parametric position (texture seams, split
// normals) move together, so every copy but the lowest-numbered one is removed first,
// predicted by that one, and welded onto it, which also closes the seam for the levels
// above. Only non-adjacent boundary vertices are welded: coincident neighbours (a
// coarse parametric grid merging close vertices) are degenerate edges, not seams. Exact
// comparisons and index order keep it deterministic.
int weldSeams(LevelMesh& mesh, const std::vector<double>& xyz, const CollapseOptionCache& cache,
              std::vector<uint8_t>& removed, ProgressiveMesh& pm) {
  std::vector<uint32_t> order(removed.size());
  std::iota(order.begin(), order.end(), 0u);
  auto position = [&](uint32_t v) { return std::make_tuple(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return position(a) < position(b) || (position(a) == position(b) && a < b);
  });
  std::vector<uint32_t> times(removed.size(), 0), corners;
  int welded = 0;
  for (size_t first = 0, end = 0; first < order.size(); first = end) {
    const uint32_t original = order[first];
    for (end = first + 1; end < order.size() && position(order[end]) == position(original); ++end) {
      const uint32_t copy = order[end];
      if (!onBoundary(mesh, original, times, corners) || !onBoundary(mesh, copy, times, corners) ||
          mesh.adjacent(copy, original))
        continue;
      const Candidate seam{0.0, copy, original, CollapseKind::kSeam};
      pm.collapses.push_back(recordCollapse(mesh, cache, seam, {original}, 0, pm));
      removed[copy] = 1;
      ++welded;
    }
  }
  for (const Collapse& c : pm.collapses) mesh.weld(c.vertex, c.target);
  return welded;
}

}  // namespace

Status checkHierarchyCost(const Topology& topology) {
  if (topology.vertex_count == 0) return Status();  // nothing to build
  std::vector<uint32_t> triangles_at(topology.vertex_count, 0);
  for (const Triangle& t : topology.triangles)
    for (uint32_t v : t) ++triangles_at[v];
  uint64_t cost = 0;
  uint32_t busiest = 0;
  for (uint32_t v = 0; v < topology.vertex_count; ++v) {
    cost += uint64_t(triangles_at[v]) * triangles_at[v];
    if (triangles_at[v] > triangles_at[busiest]) busiest = v;
  }
  auto culprit = [&] {
    return "vertex " + std::to_string(busiest) + " is in " + std::to_string(triangles_at[busiest]) + " triangles";
  };
  if (triangles_at[busiest] > kMaxTrianglesAtVertex)
    return limitExceeded("the wavelet codec's hierarchy takes at most " + std::to_string(kMaxTrianglesAtVertex) +
                         " triangles at a vertex: " + culprit());
  const uint64_t limit = kMaxRingCostPerTriangle * topology.triangles.size() + kRingCostAllowance;
  if (cost > limit)
    return limitExceeded("the wavelet codec's hierarchy would take too long on this mesh: " + culprit() +
                         " (sum over vertices of their triangle count squared " + std::to_string(cost) +
                         ", limit " + std::to_string(limit) + " for " + std::to_string(topology.triangles.size()) +
                         " triangles)");
  return Status();
}

ProgressiveMesh buildProgressiveMesh(const Topology& topology, const std::vector<double>& parametric_xyz,
                                     const HierarchySettings& settings) {
  ProgressiveMesh pm;
  pm.vertex_count = topology.vertex_count;
  LevelMesh mesh(topology);
  std::vector<uint8_t> removed(topology.vertex_count, 0);
  double max_length = settings.first_length_factor * meanEdgeLength(topology, parametric_xyz);
  CollapseOptionCache cache(topology.vertex_count, settings.path);
  if (settings.weld_seams && weldSeams(mesh, parametric_xyz, cache, removed, pm) > 0) {
    pm.level_count = 1;
    mesh.rebuildIncidence();
  }
  BoundaryLoops loops(mesh, topology.vertex_count);  // the welded seams are no longer boundary
  Batch::Vertices vertices(removed);
  for (int level = 0; level < settings.max_levels; ++level, max_length *= settings.length_growth) {
    bool any_valid = false;
    const int applied = Batch(mesh, parametric_xyz, max_length, settings, loops, vertices, cache, pm).apply(any_valid);
    if (!any_valid) break;
    if (applied == 0) continue;
    ++pm.level_count;
    mesh.reclaimSpace();
  }
  pm.base = vertices.live;
  pm.base_triangles = mesh.liveTriangles();
  return pm;
}

}  // namespace animc
