// SPDX-License-Identifier: Apache-2.0
// The trajectory codec's coding order is docs/format.md's breadth-first walk (12.3), and each
// position's earlier neighbours are exactly its neighbours placed before it, in index order:
// checked against a plain rendering of that definition on a mesh of several pieces, with
// vertex labels shuffled so that the walk jumps around, and a vertex in no triangle. A group
// read while its order is walked beside it, on a second thread, is the group read after it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "codecs/trajectory/group_coding.h"
#include "core/parallel.h"
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

// A group of three components with values that vary from vertex to vertex, so that every
// prediction context is met and a coefficient read too early would come out wrong.
TrajectoryGroup variedGroup(uint32_t vertices) {
  TrajectoryGroup g;
  g.frames = 4;
  g.components = 3;
  g.coefficient_step = 0.5f;
  g.mean_step = 0.25f;
  g.mean.assign(3 * g.frames, 7);
  g.basis_step.assign(g.components, 0.125f);
  g.basis.assign(size_t(g.components) * 3 * g.frames, -3);
  g.coefficients.resize(size_t(vertices) * g.components);
  std::mt19937 random(5);
  for (int32_t& c : g.coefficients) c = int32_t(random() % 9) - 4;
  return g;
}

TEST(CodingOrder, AGroupReadBesideItsWalkIsTheGroupReadAfterIt) {
  // Many steps of the walk's progress reports, so that the reading catches up with the walk.
  const Topology topology = testing_support::gridTopology(150, 120);
  const CodingOrder order(topology);
  const TrajectoryGroup group = variedGroup(topology.vertex_count);
  std::vector<uint8_t> payload;
  writeTrajectoryGroup(group, order, payload);
  const ByteReader coded(payload.data() + 1, payload.size() - 1);  // after the Frame_Type
  for (unsigned threads : {1u, 2u}) {
    SCOPED_TRACE(testing::Message() << threads << " thread(s)");
    ThreadBudget budget(threads);
    std::unique_ptr<const CodingOrder> walked;
    TrajectoryGroup read;
    ASSERT_TRUE(walkAndReadTrajectoryGroup(topology, coded, UINT64_MAX, walked, read).ok());
    ASSERT_TRUE(walked);
    EXPECT_TRUE(std::equal(walked->vertex.begin(), walked->vertex.end(), order.vertex.begin(), order.vertex.end()));
    EXPECT_TRUE(std::equal(walked->first.begin(), walked->first.end(), order.first.begin(), order.first.end()));
    EXPECT_TRUE(std::equal(walked->earlier.begin(), walked->earlier.end(), order.earlier.begin(), order.earlier.end()));
    EXPECT_TRUE(std::equal(read.coefficients.begin(), read.coefficients.end(), group.coefficients.begin(),
                           group.coefficients.end()));
    EXPECT_EQ(read.mean, group.mean);
    EXPECT_EQ(read.basis, group.basis);

    // A damaged group is refused, and the order walked beside it is still whole.
    const ByteReader cut(payload.data() + 1, payload.size() / 2);
    walked.reset();
    EXPECT_FALSE(walkAndReadTrajectoryGroup(topology, cut, UINT64_MAX, walked, read).ok());
    ASSERT_TRUE(walked);
    EXPECT_TRUE(std::equal(walked->vertex.begin(), walked->vertex.end(), order.vertex.begin(), order.vertex.end()));
    EXPECT_TRUE(std::equal(walked->first.begin(), walked->first.end(), order.first.begin(), order.first.end()));
    EXPECT_TRUE(std::equal(walked->earlier.begin(), walked->earlier.end(), order.earlier.begin(), order.earlier.end()));
  }
}

}  // namespace
}  // namespace animc
