// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/collapse_option_cache.h"

#include "core/parallel.h"

namespace animc {

void CollapseOptionCache::prepare(Entry& e, const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                                  const HierarchySettings& settings, FanGeometry& fan, FanQuery& query) {
  e.stale = false;
  VertexCollapses& c = e.collapses;
  if (e.ring_kept) {  // same fan shape, new geometry
    e.ring_kept = false;
    c.prepare(xyz, v, e.closed_ring, fan);
    return;
  }
  e.ring_found = e.closed_ring = false;
  e.kind = CollapseKind::kInterior;
  if (mesh.triangleCount(v) > kMaxCollapseTriangles) {
    c.clear();  // not removable; its ring is not even walked
  } else if (mesh.orderedRing(v, c.ring, query)) {
    e.ring_found = e.closed_ring = true;
    c.prepare(xyz, v, true, fan);
  } else if (settings.collapse_boundaries && mesh.openFan(v, c.ring, query)) {
    e.ring_found = true;
    e.kind = CollapseKind::kBoundary;
    c.prepare(xyz, v, false, fan);
  } else {
    c.clear();
  }
}

void CollapseOptionCache::prepareStale(const LevelMesh& mesh, const std::vector<double>& xyz,
                                       const std::vector<uint32_t>& vertices, const HierarchySettings& settings) {
  // A task per thread, each a run of whole arenas' vertices: a task's scratch holds a mark per
  // mesh vertex, too much to make for each arena. On one thread, at() prepares them one by one.
  const size_t arenas = arenas_.size(), vertex_count = entries_.size();
  const size_t tasks = std::min<size_t>(ThreadBudget::current(), arenas);
  if (tasks <= 1) return;
  while (task_fans_.size() < tasks) {
    task_fans_.push_back(std::make_unique<FanGeometry>());
    task_fans_.back()->path = fan_.path;
    task_queries_.push_back(std::make_unique<FanQuery>(uint32_t(vertex_count)));
  }
  constexpr double kCostPerVertex = 400;  // operations: a ring walk, its fan and its options
  parallelFor(tasks, kCostPerVertex * double(vertices.size()) / double(tasks), [&](size_t task) {
    const uint32_t first = uint32_t(arenas * task / tasks * kArenaVertices);
    const uint32_t end = uint32_t(std::min<size_t>(vertex_count, arenas * (task + 1) / tasks * kArenaVertices));
    auto v = std::lower_bound(vertices.begin(), vertices.end(), first);
    for (; v != vertices.end() && *v < end; ++v) {
      Entry& e = entries_[*v];
      if (e.stale) prepare(e, mesh, xyz, *v, settings, *task_fans_[task], *task_queries_[task]);
    }
  });
  // The shared fan may hold a vertex whose ring was prepared again above: found again on need.
  fan_.vertex = kNoVertex;
}

}  // namespace animc
