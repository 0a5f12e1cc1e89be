// SPDX-License-Identifier: Apache-2.0
// Which neighbour a vertex would collapse onto within one level, and at what cost: the
// validity rules (link condition, no duplicate or flipped triangles) and the memoryless
// quadric of the vertex's current triangles. Interior vertices have a closed ring, boundary
// vertices an open fan.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/level_mesh.h"
#include "core/simd_math.h"

namespace animc {

// A vertex in more triangles is never removed, and no collapse may leave its target in more
// (counted as the two vertices' triangles less the two an interior edge loses). Ring walks and
// checks cost the square of a vertex's triangle count at every level that touches it; this
// keeps that bounded whatever welded seams or earlier collapses made of the mesh (real meshes
// stay far below: the shared sequences build the same hierarchies with a bound of 30).
constexpr uint32_t kMaxCollapseTriangles = 256;

// One target of a vertex's collapse, with its cost and the length of the edge (the level's
// length bound is applied when choosing, so options stay usable from level to level while
// the vertex's neighbourhood does not change).
struct CollapseOption {
  uint32_t target = kNoVertex;
  uint32_t ring_position = 0;  // of the target in the vertex's ring
  double cost = 0;
  double length = 0;
};

// A vertex's fan: its ring vertices' positions and spokes (ring vertex minus vertex), the
// normals (twice their area long) and twice the areas of its triangles (v, ring[i],
// ring[i+1]). Scratch that VertexCollapses fills when it needs it, shared by all vertices so
// that the per-vertex entries of a large mesh stay small.
struct FanGeometry {
  uint32_t vertex = kNoVertex;  // whose fan it holds (its ring as last prepared)
  size_t triangles = 0;
  SimdPath path = SimdPath::kPortable;  // the cost kernels' version (the hierarchy build's)

  // By axis (structure of arrays), so that ring vertices i and i + 1, or triangles i and
  // i + 1, load as one Pair. The ring arrays repeat the first vertex after the last (where a
  // closed fan's last triangle ends); every array has room for three values more, which lanes
  // beyond the last vertex or triangle read or write (their results are not used).
  double* position(int axis) { return array(axis); }  // of the ring vertices
  double* spoke(int axis) { return array(3 + axis); }  // ring vertex minus vertex
  double* normal(int axis) { return array(6 + axis); }
  double* twiceArea() { return array(9); }
  // prepare()'s: the options' costs and lengths, and the option numbers in cost order.
  double* cost() { return array(10); }
  double* length() { return array(11); }
  uint32_t* order() { return order_.data(); }
  // Room for a ring of k vertices; the arrays only grow, so that refilling them neither
  // allocates nor clears.
  void reserve(size_t k);

  // The portable cost computation's: the triangles that have a plane (area not <= 0), as five
  // Pairs each, the normal's x, y, z, twice and half the area, every value in both lanes.
  std::vector<Pair> planes;

 private:
  double* array(int i) { return arrays_.data() + i * stride_; }
  size_t stride_ = 0;
  std::vector<double> arrays_;  // 12 arrays of stride_ doubles
  std::vector<uint32_t> order_;  // stride_
};

// What an option's validity depends on besides the vertex's own ring: the mesh as the level
// started, the parametric positions, the normal bound, and when each vertex's triangles last
// changed; and the fan scratch the checks fill.
struct CollapseChecks {
  const LevelMesh& mesh;
  const std::vector<double>& xyz;
  double min_normal_cosine;
  // Per vertex: the number of batches applied once the last one that changed its triangles
  // was (0: none has). A validity found when fewer had been applied than that of the target
  // is stale: the target's triangles have changed since.
  const std::vector<uint32_t>& changed_by;
  uint32_t batches;  // applied so far
  FanGeometry& fan;
};

// A vertex's collapse options on the current level. Costs and lengths are computed for every
// target at once; the validity rules (link condition, no duplicate, degenerate or flipped
// triangle), which cost several times more, only for the targets a level's choice reaches.
// Costs and lengths stand while v's own triangles are unchanged, a validity while its
// target's are too (valid()).
class VertexCollapses {
 public:
  // Its arrays are allocated from `arena`.
  explicit VertexCollapses(std::pmr::memory_resource* arena) : ring(arena), options_(arena) {}

  // v's ordered ring (LevelMesh::orderedRing) or open fan (LevelMesh::openFan); fill it,
  // then call prepare().
  VertexRing ring;

  // Closed ring: every neighbour is a target. Open fan: only fan.front() and fan.back(), so
  // that the boundary stays a curve and v can be predicted from its two boundary neighbours;
  // v needs >= 2 triangles, and the cost adds the squared distance of v to the chord between
  // them (what the boundary curve loses).
  void prepare(const std::vector<double>& xyz, uint32_t v, bool closed, FanGeometry& scratch);
  void clear() {  // v cannot be removed on this level
    options_.clear();
    has_nan_cost_ = false;
  }

  // The options are kept in (cost, ring position) order. The first one at or after `from`
  // within max_length, or kNone.
  static constexpr size_t kNone = SIZE_MAX;
  size_t nextWithin(double max_length, size_t from = 0) const;
  const CollapseOption& option(size_t i) const { return options_[i].choice; }
  // Whether some option's cost is NaN (then costs are not totally ordered).
  bool hasNanCost() const { return has_nan_cost_; }

  // Whether option i keeps the mesh sound: found on first need, then known until the
  // target's triangles change (v's own change calls for prepare()); costs and lengths stand.
  bool valid(size_t i, const CollapseChecks& checks);
  // The first valid option at or after `from` within max_length, or kNone.
  size_t nextValidWithin(const CollapseChecks& checks, double max_length, size_t from = 0);
  // Whether some option is valid, whatever its length.
  bool anyValid(const CollapseChecks& checks);

 private:
  enum class Validity : uint8_t { kUnknown, kValid, kInvalid };
  struct Option {
    CollapseOption choice;
    Validity validity = Validity::kUnknown;
    uint32_t checked_after = 0;  // CollapseChecks::batches when the validity was found
  };
  // Computes the fan into the scratch on first need (prepare() left it there for the first
  // checks).
  bool keepsMeshSound(const CollapseOption& option, const CollapseChecks& checks) const;
  void computeFan(const std::vector<double>& xyz, FanGeometry& scratch) const;
  void computeCosts(FanGeometry& scratch, double curve) const;
#if ANIMC_AVX2_PATH
  void computeCostsAvx2(FanGeometry& scratch, double curve) const;
#endif
  void addOptionsByCost(FanGeometry& scratch);
  // Option i (before sorting) targets ring position i of a closed ring; those of an open fan
  // its two ends (i = 0, 1).
  size_t optionCount() const { return closed_ ? ring.size() : 2; }
  uint32_t ringPosition(size_t option) const { return uint32_t(closed_ || option == 0 ? option : ring.size() - 1); }

  uint32_t vertex_ = kNoVertex;
  bool closed_ = true;
  bool has_nan_cost_ = false;
  std::pmr::vector<Option> options_;  // by cost, then ring position
};

}  // namespace animc
