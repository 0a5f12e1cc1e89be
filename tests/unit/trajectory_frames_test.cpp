// SPDX-License-Identifier: Apache-2.0
// The frames a trajectory group gives (GroupFrames): the kernel finds the frames with a value
// that is not finite or above 1e30 in size, frame by frame, whichever way the frames are asked
// for and on every kernel path, and the lanes past the last vertex never count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "api.h"
#include "codecs/codec_registry.h"
#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/group_frames.h"
#include "core/simd_math.h"
#include "test_sequences.h"

namespace animc {
namespace {

constexpr uint32_t kFrames = 6;

// One component over a grid. Each vertex's coefficient is `coefficient`, but the last
// vertex's is `last`; the mean's and the basis's x runs are given for frames 0..5.
TrajectoryGroup oneComponent(const CodingOrder& order, float mean_step, std::vector<int32_t> mean_x, float basis_step,
                             std::vector<int32_t> basis_x, int32_t coefficient, int32_t last) {
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
  const size_t n = order.vertex.size();
  g.coefficients.resize(n);
  for (size_t p = 0; p < n; ++p) g.coefficients[p] = order.vertex[p] == n - 1 ? last : coefficient;
  return g;
}

// Which frames GroupFrames refuses, asked for forwards, then backwards.
std::vector<std::vector<uint32_t>> refusedFrames(const TrajectoryGroup& g, const CodingOrder& order, SimdPath path) {
  std::vector<std::vector<uint32_t>> refused(2);
  for (int backwards = 0; backwards < 2; ++backwards) {
    GroupFrames frames;
    GroupBasis basis = dequantisedBasis(g);
    frames.reset(basis, g, order, path);
    std::vector<float> xyz(3 * order.vertex.size());
    for (uint32_t i = 0; i < kFrames; ++i) {
      const uint32_t t = backwards ? kFrames - 1 - i : i;
      if (!frames.frame(t, xyz.data())) refused[backwards].push_back(t);
    }
    std::sort(refused[backwards].begin(), refused[backwards].end());
  }
  return refused;
}

// Grids of 15 vertices (one kernel step of 16 lanes or two of 8, the last lane past the last
// vertex) and of 21 (with 16 lanes, a step of 16, then one of 5 with 8 lanes).
TEST(TrajectoryFrames, OnlyTheFramesWithABadValueAreRefused) {
  for (int rows : {5, 7}) {
    const Topology topology = testing_support::gridTopology(3, rows);
    const CodingOrder order(topology);
    for (SimdPath path : availableSimdPaths()) {
      SCOPED_TRACE(testing::Message() << topology.vertex_count << " vertices, path " << int(path));
      // The last vertex alone: 20 x 1e29 = 2e30 at frame 5; 2 x 3e38 = infinity at frame 1.
      const TrajectoryGroup huge = oneComponent(order, 1, {}, 1e29f, {0, 0, 0, 0, 0, 20}, 0, 1);
      EXPECT_EQ(refusedFrames(huge, order, path), (std::vector<std::vector<uint32_t>>{{5}, {5}}));
      const TrajectoryGroup infinite = oneComponent(order, 1, {}, 1e37f, {0, 30, 0, 0, 0, 0}, 0, 2);
      EXPECT_EQ(refusedFrames(infinite, order, path), (std::vector<std::vector<uint32_t>>{{1}, {1}}));
      // At frame 3 the mean is 1.5e30 and every vertex's coefficient cancels it to 0: only the
      // lanes past the last vertex, which are no vertex, hold 1.5e30.
      const TrajectoryGroup cancelled =
          oneComponent(order, 1e29f, {0, 0, 0, 15, 0, 0}, 1e29f, {0, 0, 0, -15, 0, 0}, 1, 1);
      EXPECT_EQ(refusedFrames(cancelled, order, path), (std::vector<std::vector<uint32_t>>{{}, {}}));
      GroupFrames frames;
      GroupBasis basis = dequantisedBasis(cancelled);
      frames.reset(basis, cancelled, order, path);
      std::vector<float> xyz(3 * order.vertex.size(), 1.0f);
      ASSERT_TRUE(frames.frame(3, xyz.data()));
      EXPECT_EQ(xyz[0], 0.0f);
      EXPECT_EQ(xyz[xyz.size() - 3], 0.0f);
    }
  }
}

// A trajectory decoder keeps the group it decoded last while the same payload bytes come
// back (a random access into it): a payload that differs in any byte must decode as a fresh
// decoder decodes it, refused or not.
TEST(TrajectoryFrames, TheGroupIsKeptOnlyForTheSameBytes) {
  const MemorySequence seq = testing_support::gridSequence(9, 6, 8, 1.0, 0.5);
  EncodeSettings settings;
  settings.trajectory();
  std::vector<float> all;
  for (const auto& frame : seq.frames()) all.insert(all.end(), frame.begin(), frame.end());
  std::vector<std::vector<uint8_t>> payloads;
  settings.entry()
      .makeGroupEncoder(settings.options, seq.topology(), bestSimdPath())
      ->encodeGroup(all.data(), 8, payloads);
  const std::vector<uint8_t>& group = payloads[0];
  auto decoder = [&] {
    return settings.entry().makeDecoder(settings.options, seq.topology(), {}, "grid", bestSimdPath()).value();
  };
  auto kept = decoder();
  std::vector<float> xyz;
  ASSERT_TRUE(kept->decodeFrame(ByteReader(group.data(), group.size()), xyz, nullptr).ok());
  ASSERT_EQ(xyz.size(), seq.frames()[0].size());
  for (size_t at = 1; at < group.size(); at += 3) {
    std::vector<uint8_t> changed = group;
    changed[at] ^= 0x55;
    std::vector<float> kept_xyz, fresh_xyz;
    const Status a = kept->decodeFrame(ByteReader(changed.data(), changed.size()), kept_xyz, nullptr);
    const Status b = decoder()->decodeFrame(ByteReader(changed.data(), changed.size()), fresh_xyz, nullptr);
    ASSERT_EQ(a.ok(), b.ok()) << "byte " << at;
    EXPECT_EQ(a.message(), b.message()) << "byte " << at;
    if (a.ok()) {
      EXPECT_EQ(kept_xyz, fresh_xyz) << "byte " << at;
    }
    // Back to the group decoded at first: its frame 0 again.
    ASSERT_TRUE(kept->decodeFrame(ByteReader(group.data(), group.size()), kept_xyz, nullptr).ok());
    EXPECT_EQ(kept_xyz, xyz) << "byte " << at;
  }
}

// A group read with its basis as floats (as the decoders read it) has the floats that
// dequantising its integers gives, bit for bit, and the same coefficients; it keeps no
// integer rows. Every row has its own values and step, so a row stored with another's step,
// or a mean stored as a basis row, shows.
TEST(TrajectoryFrames, ABasisReadAsFloatsIsItsIntegersDequantised) {
  const Topology topology = testing_support::gridTopology(4, 5);
  const CodingOrder order(topology);
  TrajectoryGroup g;
  g.frames = 7;
  g.components = 3;
  g.coefficient_step = 0.75f;
  g.mean_step = 0.3f;
  g.basis_step = {0.1f, 0.013f, 7.5f};
  const size_t row = size_t(3) * g.frames;
  for (size_t i = 0; i < row; ++i) g.mean.push_back(int32_t(i * i) - 40);
  for (size_t i = 0; i < g.components * row; ++i) g.basis.push_back(int32_t((i * 37) % 101) - 50);
  for (size_t i = 0; i < order.vertex.size() * g.components; ++i)
    g.coefficients.push_back(int32_t((i * 13) % 23) - 11);
  std::vector<uint8_t> payload;
  writeTrajectoryGroup(g, order, payload);
  const ByteReader coded(payload.data() + 1, payload.size() - 1);  // after the Frame_Type

  TrajectoryGroup as_integers, as_floats;
  ASSERT_TRUE(readTrajectoryGroup(coded, order, UINT64_MAX, as_integers).ok());
  EXPECT_EQ(as_integers.mean, g.mean);
  EXPECT_EQ(as_integers.basis, g.basis);
  GroupBasis floats;
  ASSERT_TRUE(readTrajectoryGroup(coded, order, UINT64_MAX, as_floats, &floats).ok());
  EXPECT_TRUE(as_floats.mean.empty());
  EXPECT_TRUE(as_floats.basis.empty());
  EXPECT_TRUE(std::equal(as_floats.coefficients.begin(), as_floats.coefficients.end(), g.coefficients.begin(),
                         g.coefficients.end()));
  const GroupBasis expected = dequantisedBasis(g);
  EXPECT_EQ(floats.frames, expected.frames);
  EXPECT_EQ(floats.components, expected.components);
  EXPECT_TRUE(std::equal(floats.mean.begin(), floats.mean.end(), expected.mean.begin(), expected.mean.end()));
  EXPECT_TRUE(std::equal(floats.basis.begin(), floats.basis.end(), expected.basis.begin(), expected.basis.end()));
}

}  // namespace
}  // namespace animc
