// Which neighbour a vertex would collapse onto within one level, and at what cost: the
// validity rules (link condition, no duplicate or flipped triangles) and the memoryless
// quadric of the vertex's current triangles.
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

}  // namespace animc
