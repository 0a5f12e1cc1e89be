// SPDX-License-Identifier: Apache-2.0
// The collapse options of every vertex on the current level of the hierarchy build
// (progressive_mesh.cpp), kept between batches and prepared again only where a batch changed
// a vertex's triangles.
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <memory_resource>
#include <vector>

#include "codecs/wavelet/collapse_choice.h"
#include "codecs/wavelet/level_mesh.h"
#include "codecs/wavelet/progressive_mesh.h"

namespace animc {

// Each vertex's collapse options on the current level. Its ring, costs and lengths depend on
// its own triangles, an option's validity also on the target's (link condition, duplicate
// triangles, fan size). A batch changes the triangles of its vertices and their rings only:
// those vertices are prepared again, and their neighbours' options onto them see from the
// batch count (changed_by) that their validity must be found again (a third of the vertices
// a batch reaches are such neighbours).
class CollapseOptionCache {
 public:
  struct Entry {
    explicit Entry(std::pmr::memory_resource* arena) : collapses(arena) {}
    bool stale = true;
    bool ring_found = false;   // by LevelMesh::orderedRing or openFan
    bool closed_ring = false;  // by orderedRing
    bool ring_kept = false;    // stale, but the ring is still v's (see keepRing)
    CollapseKind kind = CollapseKind::kInterior;
    VertexCollapses collapses;  // its ring is v's closed ring, or open fan on a boundary
  };

  CollapseOptionCache(uint32_t vertex_count, SimdPath path) : changed_by_(vertex_count, 0), query_(vertex_count) {
    fan_.path = path;
    arenas_.resize((size_t(vertex_count) + kArenaVertices - 1) / kArenaVertices);
    for (auto& arena : arenas_) arena = std::make_unique<std::pmr::monotonic_buffer_resource>();
    entries_.reserve(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v) entries_.emplace_back(arenas_[v / kArenaVertices].get());
  }

  // v's entry, prepared first if its triangles changed since.
  Entry& at(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v, const HierarchySettings& settings) {
    Entry& e = entries_[v];
    if (e.stale) prepare(e, mesh, xyz, v, settings, fan_, query_);
    return e;
  }

  // Prepares the stale entries of `vertices` (ascending) on threads, a block of vertices
  // (one arena) at a time, each thread with its own scratch: the entries come out the same
  // as at() makes them one by one, on any number of threads.
  void prepareStale(const LevelMesh& mesh, const std::vector<double>& xyz, const std::vector<uint32_t>& vertices,
                    const HierarchySettings& settings);
  // Before the batch is applied: v collapses onto u, and w is in v's ring without flanking the
  // edge (v, u). Then w's triangles that hold v become u's and none dies, and u is no neighbour
  // of w (the link condition), so w's steps stay the same with v replaced by u, from the same
  // first triangle: its new ring is its ring with v replaced by u, and needs no walk.
  void keepRing(uint32_t w, uint32_t v, uint32_t u) {
    Entry& e = entries_[w];
    if (e.stale || !e.ring_found) return;
    VertexRing& ring = e.collapses.ring;
    const auto at = std::find(ring.begin(), ring.end(), v);
    if (at == ring.end()) return;
    *at = u;
    e.ring_kept = true;
  }

  // After the batch is applied: v has collapsed onto u, and w, whose ring was closed, flanks
  // the edge (v, u). w's triangle with v and u died and its other one with v became u's, so
  // its steps are the same without v: its new ring is its ring without v, started (as a walk
  // would) at the corner after w in the first triangle of its list. A ring of three would
  // become two: walked again, and found not to be a ring.
  void keepFlankRing(const LevelMesh& mesh, uint32_t w, uint32_t v) {
    Entry& e = entries_[w];
    if (e.stale || !e.closed_ring || e.collapses.ring.size() < 4) return;
    VertexRing& ring = e.collapses.ring;
    const auto at = std::find(ring.begin(), ring.end(), v);
    if (at == ring.end()) return;
    ring.erase(at);
    const Triangle& first = mesh.triangle(*mesh.trianglesBegin(w));
    const uint32_t start = first[0] == w ? first[1] : (first[1] == w ? first[2] : first[0]);
    const auto from = std::find(ring.begin(), ring.end(), start);
    if (from == ring.end()) return;  // cannot happen; then the ring is walked again
    std::rotate(ring.begin(), from, ring.end());
    e.ring_kept = true;
  }
  // A vertex's entry as last prepared, and its ring: unchanged until the level's collapses are
  // applied (they mark every vertex whose ring they change stale).
  Entry& entry(uint32_t v) { return entries_[v]; }
  const VertexRing& ring(uint32_t v) const { return entries_[v].collapses.ring; }

  // When a batch is applied: `changed` lists the vertices whose triangles it changes (the
  // removed ones and their rings).
  void markChanged(const std::vector<uint32_t>& changed) {
    ++batches_;
    for (uint32_t x : changed) {
      entries_[x].stale = true;
      changed_by_[x] = batches_;
    }
  }

  // LevelMesh::flapAcross(a, b, v) for an edge (a, b) of v's ring: when a's fresh entry holds
  // its closed ring, whose triangles (a, ring[m-1], ring[m]) and (a, ring[m], ring[m+1]) are
  // the two that hold b = ring[m], the flap is the one of ring[m-1], ring[m+1] that is not v,
  // found without walking a's triangles.
  uint32_t flapAcross(const LevelMesh& mesh, uint32_t a, uint32_t b, uint32_t v) const {
    const Entry& e = entries_[a];
    if (e.stale || !e.closed_ring) return mesh.flapAcross(a, b, v);
    const VertexRing& ring = e.collapses.ring;
    const size_t k = ring.size();
    for (size_t m = 0; m < k; ++m) {
      if (ring[m] != b) continue;
      const uint32_t previous = ring[m == 0 ? k - 1 : m - 1], next = ring[m + 1 == k ? 0 : m + 1];
      if (next == v) return previous;
      if (previous == v) return next;
      break;
    }
    return mesh.flapAcross(a, b, v);
  }

  CollapseChecks checks(const LevelMesh& mesh, const std::vector<double>& xyz, double min_normal_cosine) {
    return {mesh, xyz, min_normal_cosine, changed_by_, batches_, fan_};
  }

 private:
  // Vertices whose entries share an arena, which one thread at a time prepares.
  static constexpr uint32_t kArenaVertices = 4096;

  static void prepare(Entry& e, const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                      const HierarchySettings& settings, FanGeometry& fan, FanQuery& query);

  // Every entry's ring and options: allocated as they grow, never freed one by one (a
  // vertex's arrays grow geometrically, and there are a few per vertex), all released with
  // the cache. Saves a malloc and a free per array.
  std::vector<std::unique_ptr<std::pmr::monotonic_buffer_resource>> arenas_;
  std::vector<Entry> entries_;
  std::vector<uint32_t> changed_by_;  // CollapseChecks::changed_by
  uint32_t batches_ = 0;
  FanGeometry fan_;  // the fan of the vertex being prepared or checked, shared by every entry
  FanQuery query_;   // at()'s
  // prepareStale()'s scratch, one for each of its tasks, made on first use.
  std::vector<std::unique_ptr<FanGeometry>> task_fans_;
  std::vector<std::unique_ptr<FanQuery>> task_queries_;
};

}  // namespace animc
