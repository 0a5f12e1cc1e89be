// SPDX-License-Identifier: Apache-2.0
// Vertex neighbourhoods of a triangle list in compressed rows: neighbours(v) is the sorted
// list of vertices sharing an edge with v. Built once per sequence, O(N + T) memory.
#pragma once
#include <cstdint>
#include <vector>

#include "core/sequence.h"
#include "core/uninitialised_vector.h"

namespace animc {

class VertexAdjacency {
 public:
  // kLower keeps only the neighbours of lower index: half the rows, for coders that predict
  // a vertex from those decoded before it.
  enum class Neighbours { kAll, kLower };
  explicit VertexAdjacency(const Topology& topology, Neighbours kept = Neighbours::kAll);
  const uint32_t* begin(uint32_t v) const { return &neighbours_[first_[v]]; }
  const uint32_t* end(uint32_t v) const { return &neighbours_[0] + first_[v + 1]; }
  uint32_t vertices() const { return uint32_t(first_.size() - 1); }
  // All rows' neighbours together.
  size_t entries() const { return neighbours_.size() - 1; }

 private:
  UninitialisedVector<uint32_t> first_;
  UninitialisedVector<uint32_t> neighbours_;
};

}  // namespace animc
