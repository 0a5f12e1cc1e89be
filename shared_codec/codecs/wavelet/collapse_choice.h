// Which neighbour a vertex would collapse onto within one level, and at what cost: the
// validity rules (link condition, no duplicate or flipped triangles) and the memoryless
// quadric of the vertex's current triangles. Interior vertices have a closed ring, boundary
// vertices an open fan.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/level_mesh.h"

namespace animc {

// One valid target of a vertex's collapse, with its cost and the length of the edge (the
// level's length bound is applied by the caller, so options stay valid from level to level
// while the vertex's neighbourhood does not change).
struct CollapseOption {
  uint32_t target = kNoVertex;
  double cost = 0;
  double length = 0;
};

// ring: v's ordered ring (LevelMesh::orderedRing). Appends to `out` every neighbour that is
// a valid target, in ring order.
void interiorCollapseOptions(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                             const std::vector<uint32_t>& ring, double min_normal_cosine,
                             std::vector<CollapseOption>& out);

// The same for a boundary vertex v with open fan `fan` (LevelMesh::openFan): it may only
// collapse along a boundary edge, onto fan.front() or fan.back(), so that the boundary stays
// a curve and v can be predicted from its two boundary neighbours; v needs >= 2 triangles.
// The cost adds the squared distance of v to the chord between them (what the boundary curve
// loses).
void boundaryCollapseOptions(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                             const std::vector<uint32_t>& fan, double min_normal_cosine,
                             std::vector<CollapseOption>& out);

// The cheapest option within max_length (the first of equal ones); null when none fits.
const CollapseOption* cheapestWithin(const std::vector<CollapseOption>& options, double max_length);

}  // namespace animc
