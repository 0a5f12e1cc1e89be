// SPDX-License-Identifier: Apache-2.0
// The trajectory codec's coding order is docs/format.md's breadth-first walk (12.3), and each
// position's earlier neighbours are exactly its neighbours placed before it, in index order:
// checked against a plain rendering of that definition on a mesh of several pieces, with
// vertex labels shuffled so that the walk jumps around, and a vertex in no triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "codecs/trajectory/group_coding.h"
#include "test_sequences.h"

namespace animc {
namespace {

Topology shuffledPieces() {
  const Topology grid = testing_support::gridTopology(9, 7), small = testing_support::gridTopology(3, 2);
  Topology t;
  t.vertex_count = grid.vertex_count + small.vertex_count + 1;  // the last vertex: in no triangle
  t.triangles = grid.triangles;
  for (Triangle tri : small.triangles) {
    for (uint32_t& v : tri) v += grid.vertex_count;
    t.triangles.push_back(tri);
  }
  std::vector<uint32_t> label(t.vertex_count);
  std::iota(label.begin(), label.end(), 0u);
  std::mt19937 random(11);
  std::shuffle(label.begin(), label.end(), random);
  for (Triangle& tri : t.triangles)
    for (uint32_t& v : tri) v = label[v];
  std::shuffle(t.triangles.begin(), t.triangles.end(), random);
  return t;
}

TEST(CodingOrder, IsTheBreadthFirstWalkWithEachPositionsEarlierNeighbours) {
  const Topology topology = shuffledPieces();
  const uint32_t n = topology.vertex_count;
  std::vector<std::set<uint32_t>> neighbours(n);
  for (const Triangle& t : topology.triangles)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (a != b) neighbours[t[a]].insert(t[b]);
  std::vector<uint32_t> walk, position(n, UINT32_MAX);
  for (uint32_t root = 0; root < n; ++root) {
    if (position[root] != UINT32_MAX) continue;
    std::deque<uint32_t> queue{root};
    position[root] = uint32_t(walk.size());
    walk.push_back(root);
    while (!queue.empty()) {
      const uint32_t v = queue.front();
      queue.pop_front();
      for (uint32_t w : neighbours[v])
        if (position[w] == UINT32_MAX) {
          position[w] = uint32_t(walk.size());
          walk.push_back(w);
          queue.push_back(w);
        }
    }
  }

  const CodingOrder order(topology);
  ASSERT_EQ(std::vector<uint32_t>(order.vertex.begin(), order.vertex.end()), walk);
  ASSERT_EQ(order.first.size(), size_t(n) + 1);
  for (uint32_t p = 0; p < n; ++p) {
    std::vector<uint32_t> expected;
    for (uint32_t w : neighbours[walk[p]])
      if (position[w] < p) expected.push_back(position[w]);
    const std::vector<uint32_t> listed(order.earlier.begin() + order.first[p],
                                       order.earlier.begin() + order.first[p + 1]);
    EXPECT_EQ(listed, expected) << "position " << p;
  }
}

}  // namespace
}  // namespace animc
