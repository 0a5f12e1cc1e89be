// SPDX-License-Identifier: Apache-2.0
// The triangle mesh of one simplification level: the live triangles and, per vertex, the
// triangles that use it, in the order of the input (a triangle with the vertex at two corners
// twice). A collapse updates the lists it changes; a full rebuild (which renumbers the
// triangles, dropping dead ones, in order) follows seam welding and reclaims the space the
// updates leave behind. Within a level the batch's collapses touch disjoint sets of
// triangles, so queries made against the level's start stay valid while the batch is
// applied.
#pragma once
#include <cstdint>
#include <memory_resource>
#include <utility>
#include <vector>

#include "core/sequence.h"

namespace animc {

constexpr uint32_t kNoVertex = UINT32_MAX;

// A vertex's neighbours in order; with a polymorphic allocator, so that the hierarchy can keep
// the rings of all its vertices in one arena.
using VertexRing = std::pmr::vector<uint32_t>;

// A flag per vertex that clearAll() resets at once (a vertex is marked while it holds the
// current token), so that queries over a few vertices of a large mesh stay cheap.
class VertexMarks {
 public:
  explicit VertexMarks(uint32_t vertex_count) : token_(vertex_count, 0) {}
  void clearAll() {
    if (++current_ == 0) restart();  // wrapped: old tokens could match again
  }
  void mark(uint32_t v) { token_[v] = current_; }
  void mark(const Triangle& t) {
    const uint32_t current = current_;  // loaded once: the stores could alias it
    for (uint32_t v : t) token_[v] = current;
  }
  bool marked(uint32_t v) const { return token_[v] == current_; }

 private:
  void restart();

  std::vector<uint32_t> token_;
  uint32_t current_ = 1;
};

// The scratch of LevelMesh's fan queries (orderedRing, openFan), reused so that they do not
// allocate: one for each thread that queries a mesh.
class FanQuery {
 public:
  explicit FanQuery(uint32_t vertex_count) : step_from_(vertex_count), entered_(vertex_count) {}

 private:
  friend class LevelMesh;
  // Where the current query's steps leave a vertex: `to` while `token` is the query's
  // step_token_ (kNoVertex when several steps leave it); a walk that passes the vertex sets
  // `token` to step_token_ + 1, so that a second visit fails.
  struct StepMark {
    uint32_t token = 0;
    uint32_t to = kNoVertex;
  };
  void nextStepToken();

  std::vector<std::pair<uint32_t, uint32_t>> steps_;  // grows only; step_count_ are used
  size_t step_count_ = 0;
  std::vector<StepMark> step_from_;  // per vertex
  uint32_t step_token_ = 0;
  VertexMarks entered_;  // a step enters the vertex (openFan)
};

class LevelMesh {
 public:
  explicit LevelMesh(const Topology& topology);

  void rebuildIncidence();
  const uint32_t* trianglesBegin(uint32_t v) const { return incident_.data() + first_[v]; }
  const uint32_t* trianglesEnd(uint32_t v) const { return incident_.data() + first_[v] + count_[v]; }
  uint32_t triangleCount(uint32_t v) const { return count_[v]; }
  const Triangle& triangle(uint32_t t) const { return triangles_[t]; }

  // The neighbours of v in cyclic order, following the orientation of its triangles, so that
  // (v, ring[k], ring[k+1]) are its triangles. False when v is on a boundary, non-manifold,
  // in a degenerate triangle or where its triangles disagree on orientation: such vertices
  // are never removed. Queries with different FanQuery objects may run on different threads.
  bool orderedRing(uint32_t v, VertexRing& ring, FanQuery& query) const;
  // The neighbours of a boundary vertex v whose triangles form one open, consistently
  // oriented fan: (v, ring[k], ring[k+1]) are its triangles, ring.front() and ring.back() its
  // two boundary neighbours (edges with one triangle). False otherwise (interior,
  // non-manifold, several fans, degenerate or inconsistently oriented triangles).
  bool openFan(uint32_t v, VertexRing& ring, FanQuery& query) const;
  // The third vertex of the one triangle on edge (a, b) that does not contain v; kNoVertex
  // when the edge has no such triangle or several (boundary, non-manifold).
  uint32_t flapAcross(uint32_t a, uint32_t b, uint32_t v) const;
  // Whether a live triangle has exactly the vertices {a, b, c}, in any order.
  bool hasTriangle(uint32_t a, uint32_t b, uint32_t c) const;
  // Whether u shares an edge with w.
  bool adjacent(uint32_t u, uint32_t w) const;
  // Marks u and its neighbours, so that several adjacent(u, w) are answered by
  // markedNeighbour(w) without walking u's triangles each time; valid until the next call.
  void markNeighbours(uint32_t u) const;
  bool markedNeighbour(uint32_t w) const { return neighbours_.marked(w); }

  // Half-edge collapse v -> u: triangles holding both die, v becomes u in the others. Updates
  // the lists of v, u and the dying triangles' third corners; v's triangles must be distinct
  // and non-degenerate (v has a ring or an open fan).
  void collapse(uint32_t v, uint32_t u);
  // The same triangle edits for a seam copy v of u, whatever its triangles; the lists are
  // left as they were until rebuildIncidence(), which must follow.
  void weld(uint32_t v, uint32_t u);
  // After a batch: a full rebuild once the lists that collapses moved leave more space behind
  // than the live lists take.
  void reclaimSpace();
  std::vector<Triangle> liveTriangles() const;

 private:
  // Each triangle (v, a, b) of v as the step a -> b around v, into the query's steps and
  // step marks; false on a degenerate triangle.
  bool fanSteps(uint32_t v, FanQuery& query) const;
  uint32_t walkSteps(FanQuery& query, uint32_t start, VertexRing& ring, size_t size) const;
  // v's triangles: those that hold u die (dies(t) for each), v becomes u in the others.
  template <class Dies>
  void replaceVertex(uint32_t v, uint32_t u, Dies dies);
  void dropDeadTrianglesAndCount();
  void dropFromList(uint32_t v, uint32_t t);
  void mergeLists(uint32_t u, uint32_t v);

  uint32_t vertex_count_;
  std::vector<Triangle> triangles_;
  std::vector<uint8_t> alive_;
  std::vector<uint32_t> first_;     // per vertex: where its list starts in incident_
  std::vector<uint32_t> count_;     // and how long it is
  std::vector<uint32_t> incident_;  // the lists; a moved list leaves its old place unused
  size_t rebuilt_size_ = 0;         // incident_'s size at the last rebuild
  mutable VertexMarks neighbours_;  // markNeighbours' scratch (one thread per mesh)
};

}  // namespace animc
