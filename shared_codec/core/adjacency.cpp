// SPDX-License-Identifier: Apache-2.0
#include "core/adjacency.h"

#include <algorithm>

namespace animc {

VertexAdjacency::VertexAdjacency(const Topology& topology, Neighbours kept) : first_(topology.vertex_count + 1, 0) {
  // Count each directed edge, fill, then sort and drop duplicates row by row.
  for (const Triangle& t : topology.triangles)
    for (int i = 0; i < 3; ++i) first_[t[i] + 1] += 2;
  for (uint32_t v = 0; v < topology.vertex_count; ++v) first_[v + 1] += first_[v];
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  neighbours_.resize(first_.back() + 1);  // +1 keeps &neighbours_[first_[v]] valid when empty
  for (const Triangle& t : topology.triangles)
    for (int i = 0; i < 3; ++i) {
      neighbours_[fill[t[i]]++] = t[(i + 1) % 3];
      neighbours_[fill[t[i]]++] = t[(i + 2) % 3];
    }
  uint32_t out = 0;
  for (uint32_t v = 0; v < topology.vertex_count; ++v) {
    auto row_begin = neighbours_.begin() + first_[v], row_end = neighbours_.begin() + first_[v + 1];
    std::sort(row_begin, row_end);
    const uint32_t start = out;
    for (auto it = row_begin; it != row_end; ++it)
      if ((it == row_begin || *it != *(it - 1)) && *it != v && (kept == Neighbours::kAll || *it < v))
        neighbours_[out++] = *it;
    first_[v] = start;
  }
  first_[topology.vertex_count] = out;
  // Each edge was listed once from each of its triangles: the rows shrank to half or less.
  neighbours_.resize(out + 1);
  neighbours_.shrink_to_fit();
}

}  // namespace animc
