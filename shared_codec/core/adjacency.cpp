// SPDX-License-Identifier: Apache-2.0
#include "core/adjacency.h"

#include <algorithm>

#include "core/parallel.h"

namespace animc {
namespace {

// Rows a thread takes at a time when they are sorted and packed.
constexpr uint32_t kVerticesPerTask = 16384;

// Every directed edge is listed once from each of its triangles, in triangle order, into the
// rows of `all` (made here) that listed[] starts; listed[v + 1] counts them first. The
// vertices are cut into one range per thread, and each thread reads every triangle but
// writes only the rows of its own range: no two threads write the same row, and each row
// comes out the same however the vertices are cut.
UninitialisedVector<uint32_t> listEdges(const Topology& topology, UninitialisedVector<uint32_t>& listed) {
  const uint32_t n = topology.vertex_count;
  const auto& triangles = topology.triangles;
  const size_t ranges = std::max<size_t>(1, std::min<size_t>(ThreadBudget::current(), n / kVerticesPerTask));
  const double cost = 3.0 * double(triangles.size());
  auto forOwnCorners = [&](size_t range, const auto& corner) {
    const uint32_t first = uint32_t(uint64_t(n) * range / ranges),
                   span = uint32_t(uint64_t(n) * (range + 1) / ranges) - first;
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] - first < span) corner(t, k);
  };
  parallelFor(ranges, cost,
              [&](size_t range) { forOwnCorners(range, [&](const Triangle& t, int k) { listed[t[k] + 1] += 2; }); });
  for (uint32_t v = 0; v < n; ++v) listed[v + 1] += listed[v];
  UninitialisedVector<uint32_t> all(listed[n]);
  UninitialisedVector<uint32_t> fill(listed.begin(), listed.end() - 1);
  parallelFor(ranges, 2 * cost, [&](size_t range) {
    forOwnCorners(range, [&](const Triangle& t, int k) {
      all[fill[t[k]]++] = t[(k + 1) % 3];
      all[fill[t[k]]++] = t[(k + 2) % 3];
    });
  });
  return all;
}

}  // namespace

VertexAdjacency::VertexAdjacency(const Topology& topology, Neighbours kept) : first_(topology.vertex_count + 1, 0) {
  const uint32_t n = topology.vertex_count;
  UninitialisedVector<uint32_t> listed(n + 1, 0);  // start of each vertex's listing
  UninitialisedVector<uint32_t> all = listEdges(topology, listed);
  // The rows are sorted and stripped of repeats on threads, each into its own rows, and
  // packed: the same rows on any thread count.
  parallelForBlocks(n, kVerticesPerTask, 40, [&](size_t, size_t v_begin, size_t v_end) {
    for (uint32_t v = uint32_t(v_begin); v < v_end; ++v) {
      uint32_t* const begin = all.data() + listed[v];
      uint32_t* const end = all.data() + listed[v + 1];
      std::sort(begin, end);
      uint32_t* out = begin;
      for (const uint32_t* it = begin; it != end; ++it)
        if ((it == begin || *it != *(it - 1)) && *it != v && (kept == Neighbours::kAll || *it < v)) *out++ = *it;
      first_[v + 1] = uint32_t(out - begin);  // the row's length, until the sum below
    }
  });
  for (uint32_t v = 0; v < n; ++v) first_[v + 1] += first_[v];
  neighbours_.resize(first_[n] + 1);  // +1 keeps &neighbours_[first_[v]] valid when empty
  parallelForBlocks(n, kVerticesPerTask, 10, [&](size_t, size_t v_begin, size_t v_end) {
    for (size_t v = v_begin; v < v_end; ++v)
      std::copy(all.data() + listed[v], all.data() + listed[v] + (first_[v + 1] - first_[v]),
                neighbours_.data() + first_[v]);
  });
}

}  // namespace animc
