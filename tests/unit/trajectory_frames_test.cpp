// SPDX-License-Identifier: Apache-2.0
// The frames a trajectory group gives (GroupFrames): the kernel finds the frames with a value
// that is not finite or above 1e30 in size as it makes them, frame by frame, whichever way
// the frames are asked for, and the lanes past the last vertex never count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "codecs/trajectory/group_coding.h"
#include "core/simd_math.h"
#include "test_sequences.h"

namespace animc {
namespace {

constexpr uint32_t kFrames = 6;

// One component over a 3 x 5 grid (15 vertices: the last kernel step has 7 lanes of
// vertices and one past them). Each vertex's coefficient is `coefficient`, but vertex 14's
// is 1; the mean's and the basis's x runs are given for frames 0..5.
TrajectoryGroup oneComponent(const CodingOrder& order, float mean_step, std::vector<int32_t> mean_x, float basis_step,
                             std::vector<int32_t> basis_x, int32_t coefficient) {
  TrajectoryGroup g;
  g.frames = kFrames;
  g.components = 1;
  g.coefficient_step = 1;
  g.mean_step = mean_step;
  g.mean.assign(3 * kFrames, 0);
  std::copy(mean_x.begin(), mean_x.end(), g.mean.begin());
  g.basis_step = {basis_step};
  g.basis.assign(3 * kFrames, 0);
  std::copy(basis_x.begin(), basis_x.end(), g.basis.begin());
  g.coefficients.resize(order.vertex.size());
  for (size_t p = 0; p < order.vertex.size(); ++p) g.coefficients[p] = order.vertex[p] == 14 ? 1 : coefficient;
  return g;
}

// Which frames GroupFrames refuses, asked for forwards, then backwards.
std::vector<std::vector<uint32_t>> refusedFrames(const TrajectoryGroup& g, const CodingOrder& order, SimdPath path) {
  std::vector<std::vector<uint32_t>> refused(2);
  for (int backwards = 0; backwards < 2; ++backwards) {
    GroupFrames frames;
    frames.reset(g, order, path);
    std::vector<float> xyz(3 * order.vertex.size());
    for (uint32_t i = 0; i < kFrames; ++i) {
      const uint32_t t = backwards ? kFrames - 1 - i : i;
      if (!frames.frame(t, xyz.data())) refused[backwards].push_back(t);
    }
    std::sort(refused[backwards].begin(), refused[backwards].end());
  }
  return refused;
}

TEST(TrajectoryFrames, OnlyTheFramesWithABadValueAreRefused) {
  const Topology topology = testing_support::gridTopology(3, 5);
  const CodingOrder order(topology);
  for (SimdPath path : availableSimdPaths()) {
    // Vertex 14 alone: 20 x 1e29 = 2e30 at frame 5, infinity at frame 1.
    const TrajectoryGroup huge = oneComponent(order, 1, {}, 1e29f, {0, 0, 0, 0, 0, 20}, 0);
    EXPECT_EQ(refusedFrames(huge, order, path), (std::vector<std::vector<uint32_t>>{{5}, {5}}));
    const TrajectoryGroup infinite = oneComponent(order, 1, {}, 3e38f, {0, 20, 0, 0, 0, 0}, 0);
    EXPECT_EQ(refusedFrames(infinite, order, path), (std::vector<std::vector<uint32_t>>{{1}, {1}}));
    // At frame 3 the mean is 1.5e30 and every vertex's coefficient cancels it to 0: only the
    // lane past the last vertex, which is no vertex, holds 1.5e30.
    const TrajectoryGroup cancelled = oneComponent(order, 1e29f, {0, 0, 0, 15, 0, 0}, 1e29f, {0, 0, 0, -15, 0, 0}, 1);
    EXPECT_EQ(refusedFrames(cancelled, order, path), (std::vector<std::vector<uint32_t>>{{}, {}}));
    GroupFrames frames;
    frames.reset(cancelled, order, path);
    std::vector<float> xyz(3 * order.vertex.size(), 1.0f);
    ASSERT_TRUE(frames.frame(3, xyz.data()));
    EXPECT_EQ(xyz[0], 0.0f);
    EXPECT_EQ(xyz[3 * 14], 0.0f);
  }
}

}  // namespace
}  // namespace animc
