// SPDX-License-Identifier: Apache-2.0
#include "core/adjacency.h"

#include <algorithm>

#include "core/parallel.h"

namespace animc {
namespace {

// Rows a thread takes at a time when they are sorted and packed.
constexpr uint32_t kVerticesPerTask = 16384;

}  // namespace

VertexAdjacency::VertexAdjacency(const Topology& topology, Neighbours kept) : first_(topology.vertex_count + 1, 0) {
  const uint32_t n = topology.vertex_count;
  // Every directed edge is listed once from each of its triangles (counted, then filled); the
  // rows are then sorted and stripped of repeats on threads, each into its own rows, and
  // packed: the same rows on any thread count.
  std::vector<uint32_t> listed(n + 1, 0);  // start of each vertex's listing
  for (const Triangle& t : topology.triangles)
    for (int i = 0; i < 3; ++i) listed[t[i] + 1] += 2;
  for (uint32_t v = 0; v < n; ++v) listed[v + 1] += listed[v];
  UninitialisedVector<uint32_t> all(listed[n]);
  {
    std::vector<uint32_t> fill(listed.begin(), listed.end() - 1);
    for (const Triangle& t : topology.triangles)
      for (int i = 0; i < 3; ++i) {
        all[fill[t[i]]++] = t[(i + 1) % 3];
        all[fill[t[i]]++] = t[(i + 2) % 3];
      }
  }
  const size_t tasks = (size_t(n) + kVerticesPerTask - 1) / kVerticesPerTask;
  const double task_cost = double(kVerticesPerTask) * 40;
  auto task_rows = [&](size_t i, auto&& row) {
    const uint32_t end = uint32_t(std::min<size_t>(n, (i + 1) * kVerticesPerTask));
    for (uint32_t v = uint32_t(i * kVerticesPerTask); v < end; ++v) row(v);
  };
  parallelFor(tasks, task_cost, [&](size_t i) {
    task_rows(i, [&](uint32_t v) {
      uint32_t* const begin = all.data() + listed[v];
      uint32_t* const end = all.data() + listed[v + 1];
      std::sort(begin, end);
      uint32_t* out = begin;
      for (const uint32_t* it = begin; it != end; ++it)
        if ((it == begin || *it != *(it - 1)) && *it != v && (kept == Neighbours::kAll || *it < v)) *out++ = *it;
      first_[v + 1] = uint32_t(out - begin);  // the row's length, until the sum below
    });
  });
  for (uint32_t v = 0; v < n; ++v) first_[v + 1] += first_[v];
  neighbours_.resize(first_[n] + 1);  // +1 keeps &neighbours_[first_[v]] valid when empty
  parallelFor(tasks, task_cost / 4, [&](size_t i) {
    task_rows(i, [&](uint32_t v) {
      std::copy(all.data() + listed[v], all.data() + listed[v] + (first_[v + 1] - first_[v]),
                neighbours_.data() + first_[v]);
    });
  });
}

}  // namespace animc
