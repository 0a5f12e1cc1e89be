// SPDX-License-Identifier: Apache-2.0
// STED against its definition (docs/metrics.md) on cases small enough to work out by hand.
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "animc/animc.h"
#include "core/memory_sequence.h"
#include "metrics/compare_sequences.h"

namespace animc {
namespace {

using Frame = std::vector<float>;

StedFigures sted(uint32_t n, const std::vector<uint32_t>& triangles, const std::vector<Frame>& original,
                 const std::vector<Frame>& reconstructed, const StedOptions& options = {}) {
  StedAccumulator acc(n, triangles.data(), triangles.size() / 3, options);
  for (size_t f = 0; f < original.size(); ++f) acc.addFrame(original[f].data(), reconstructed[f].data());
  return acc.finish();
}

// The definition's local deviation of one neighbourhood: edges as (original length, relative
// change), weighted by length.
double deviation(const std::vector<std::pair<double, double>>& edges) {
  double w = 0, mean = 0, variance = 0;
  for (auto [l, change] : edges) w += l, mean += l * change;
  mean /= w;
  for (auto [l, change] : edges) variance += l * (change - mean) * (change - mean);
  return std::sqrt(variance / w);
}

const std::vector<uint32_t> kTriangle = {0, 1, 2};

TEST(Sted, AnExactReconstructionScoresZero) {
  const Frame a = {0, 0, 0, 1, 0, 0, 0, 1, 0}, b = {0.5f, 0, 0, 1, 0.5f, 0, 0, 1, 1};
  const StedFigures f = sted(3, kTriangle, {a, b, a}, {a, b, a});
  EXPECT_EQ(f.spatial, 0);
  EXPECT_EQ(f.temporal, 0);
  EXPECT_EQ(f.sted, 0);
}

TEST(Sted, OneStretchedEdgeGivesTheWeightedDeviationOfTheEdgeChanges) {
  // Vertex 1 moves from (1,0,0) to (2,0,0): edge 01 grows from 1 to 2 (change 1), 02 keeps 1
  // (change 0), 12 grows from sqrt 2 to sqrt 5. Every vertex's 1-ring holds all three edges.
  const Frame original = {0, 0, 0, 1, 0, 0, 0, 1, 0}, moved = {0, 0, 0, 2, 0, 0, 0, 1, 0};
  const double expected = deviation({{1, 1}, {1, 0}, {std::sqrt(2.0), std::sqrt(5.0 / 2) - 1}});
  EXPECT_NEAR(expected, 0.38476491099826, 1e-12);  // worked out on paper
  const StedFigures f = sted(3, kTriangle, {original}, {moved});
  EXPECT_NEAR(f.spatial, expected, 1e-12);
  EXPECT_EQ(f.temporal, 0);  // one frame: no temporal edge
  EXPECT_NEAR(f.sted, expected, 1e-12);
}

TEST(Sted, AUniformScaleLeavesTheShapeAndScoresZero) {
  const Frame original = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0.5f};
  Frame doubled = original;
  for (float& c : doubled) c *= 2;
  EXPECT_NEAR(sted(4, {0, 1, 2, 1, 3, 2}, {original}, {doubled}).spatial, 0, 1e-12);
}

TEST(Sted, TheSpatialPartIsLocal) {
  // Two separate triangles, the second scaled by 3: each neighbourhood sees one uniform change.
  const Frame original = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0};
  Frame recon = original;
  for (int i = 9; i < 18; ++i) recon[i] *= 3;
  EXPECT_NEAR(sted(6, {0, 1, 2, 3, 4, 5}, {original}, {recon}).spatial, 0, 1e-12);
}

TEST(Sted, RingsWidenTheNeighbourhood) {
  // Triangles 012 and 132 share edge 12; vertex 3 moves from (1,1,0) to (2,2,0). With one ring,
  // vertex 0 sees only triangle 012 (unchanged), vertices 1 and 2 see all five edges, vertex 3
  // sees 12, 13, 23. With two rings every vertex sees all five.
  const Frame original = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, recon = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 2, 0};
  const std::vector<uint32_t> triangles = {0, 1, 2, 1, 3, 2};
  const double r2 = std::sqrt(2.0), grown = std::sqrt(5.0) - 1;  // 13 and 23 grow from 1 to sqrt 5
  const double five = deviation({{1, 0}, {1, 0}, {r2, 0}, {1, grown}, {1, grown}});
  const double three = deviation({{r2, 0}, {1, grown}, {1, grown}});
  StedOptions one, two;
  two.rings = 2;
  EXPECT_NEAR(sted(4, triangles, {original}, {recon}, one).spatial, (0 + 2 * five + three) / 4, 1e-12);
  EXPECT_NEAR(sted(4, triangles, {original}, {recon}, two).spatial, five, 1e-12);
}

TEST(Sted, TheTemporalPartComparesSpaceTimeStepLengths) {
  // Frame 0's bbox diagonal is 5, so time_step 0.8 gives a time component T = 4. The original
  // moves every vertex by 3 (step length sqrt(9 + 16) = 5); the reconstruction stands still
  // (length 4): |4 - 5| / 5 = 0.2 for every vertex. Shapes are equal, so spatial is 0.
  const Frame first = {0, 0, 0, 3, 0, 0, 0, 4, 0}, moved = {3, 0, 0, 6, 0, 0, 3, 4, 0};
  StedOptions options;
  options.time_step = 0.8;
  options.temporal_weight = 2;
  const StedFigures f = sted(3, kTriangle, {first, moved}, {first, first}, options);
  EXPECT_NEAR(f.spatial, 0, 1e-12);
  EXPECT_NEAR(f.temporal, 0.2, 1e-12);
  EXPECT_NEAR(f.sted, 0.4, 1e-12);  // sqrt(0 + 2^2 * 0.2^2)
}

TEST(Sted, DegenerateInputsGiveZeroNotACrash) {
  const Frame point = {1, 1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_EQ(sted(3, kTriangle, {point, point}, {point, point}).sted, 0);  // no length anywhere
  EXPECT_EQ(sted(3, {0, 1, 7}, {point}, {point}).sted, 0);                // index out of range
  EXPECT_EQ(sted(0, {}, {Frame{}}, {Frame{}}).sted, 0);
}

TEST(Sted, CompareSequencesReportsTheAccumulatorsFigures) {
  const Frame original = {0, 0, 0, 1, 0, 0, 0, 1, 0}, moved = {0, 0, 0, 2, 0, 0, 0, 1, 0};
  Topology topology{3, {{0, 1, 2}}};
  MemorySequence a(topology, {original, moved}), b(topology, {moved, moved});
  StedFigures figures;
  ASSERT_TRUE(compareSequences(a, b, {}, PerFrameErrors::kDrop, &figures).ok());
  const StedFigures direct = sted(3, kTriangle, {original, moved}, {moved, moved});
  EXPECT_GT(direct.sted, 0);
  EXPECT_EQ(figures.sted, direct.sted);
  EXPECT_EQ(figures.temporal, direct.temporal);
}

}  // namespace
}  // namespace animc
