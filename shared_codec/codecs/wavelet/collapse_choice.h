// Which neighbour a vertex would collapse onto within one level, and at what cost: the
// validity rules (link condition, no duplicate or flipped triangles) and the memoryless
// quadric of the vertex's current triangles. Interior vertices have a closed ring, boundary
// vertices an open fan.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/level_mesh.h"

namespace animc {

struct CollapseChoice {
  uint32_t target = kNoVertex;
  double cost = 0;
  bool fits_length = false;  // the edge is within the level's length bound
};

// ring: v's ordered ring (LevelMesh::orderedRing). Returns target == kNoVertex when no
// neighbour is a valid target. Among valid targets, those within max_length win, then cost.
CollapseChoice chooseCollapse(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                              const std::vector<uint32_t>& ring, double max_length,
                              double min_normal_cosine);

// The same for a boundary vertex v with open fan `fan` (LevelMesh::openFan): it may only
// collapse along a boundary edge, onto fan.front() or fan.back(), so that the boundary stays
// a curve and v can be predicted from its two boundary neighbours; v needs >= 2 triangles.
// The cost adds the squared distance of v to the chord between them (what the boundary curve
// loses).
CollapseChoice chooseBoundaryCollapse(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                                      const std::vector<uint32_t>& fan, double max_length,
                                      double min_normal_cosine);

}  // namespace animc
