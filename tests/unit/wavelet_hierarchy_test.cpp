// The progressive-mesh hierarchy and the anisotropic predictor of the wavelet codec.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/anisotropic_predictor.h"
#include "codecs/wavelet/progressive_mesh.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::gridFrame;
using testing_support::gridTopology;
using testing_support::sharedSequence;
using testing_support::toDouble;

// Every vertex is either in the base or removed exactly once, and whatever a removed vertex
// is predicted from (its ring, its flaps, its target) is still there one level coarser.
void expectValidHierarchy(const ProgressiveMesh& pm) {
  std::vector<int> removed_at(pm.vertex_count, -1);
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    ASSERT_LT(pm.collapses[i].vertex, pm.vertex_count);
    ASSERT_EQ(removed_at[pm.collapses[i].vertex], -1) << "vertex removed twice";
    removed_at[pm.collapses[i].vertex] = int(i);
  }
  for (uint32_t v : pm.base) EXPECT_EQ(removed_at[v], -1) << "base vertex " << v << " also removed";
  EXPECT_EQ(pm.base.size() + pm.collapses.size(), size_t(pm.vertex_count));
  EXPECT_TRUE(std::is_sorted(pm.base.begin(), pm.base.end()));
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    const Collapse& c = pm.collapses[i];
    if (i > 0) {
      EXPECT_GE(c.level, pm.collapses[i - 1].level);
    }
    auto later = [&](uint32_t w) { return removed_at[w] == -1 || removed_at[w] > int(i); };
    EXPECT_TRUE(later(c.target));
    for (uint32_t k = 0; k < c.ring_size; ++k) {
      EXPECT_TRUE(later(pm.ring[c.ring_begin + k]));
      const uint32_t f = pm.flap[c.ring_begin + k];
      if (f != kNoVertex) {
        EXPECT_TRUE(later(f));
      }
    }
  }
}

TEST(WaveletHierarchy, GridKeepsItsBorderAndRemovesMostInteriorVertices) {
  const Topology topology = gridTopology(20, 16);
  const auto xyz = toDouble(gridFrame(20, 16, 0, 1.0, 0.0));
  const ProgressiveMesh pm = buildProgressiveMesh(topology, xyz);
  expectValidHierarchy(pm);
  for (uint32_t v = 0; v < topology.vertex_count; ++v) {
    const int x = int(v % 20), y = int(v / 20);
    if (x == 0 || y == 0 || x == 19 || y == 15) {
      EXPECT_TRUE(std::binary_search(pm.base.begin(), pm.base.end(), v)) << "border vertex " << v << " removed";
    }
  }
  EXPECT_LT(pm.base.size(), size_t(2 * 20 + 2 * 14 + 40));
  EXPECT_GT(pm.level_count, 2);
}

TEST(WaveletHierarchy, SharedSequencesAreCoveredAndRebuiltIdentically) {
  for (const char* name : {"chickenCrossing", "oa_angelyss_lower", "sydney_md2"}) {
    SCOPED_TRACE(name);
    MemorySequence seq = sharedSequence(name, 1);
    ASSERT_EQ(seq.frames().size(), 1u);
    const auto xyz = toDouble(seq.frames()[0]);
    const ProgressiveMesh a = buildProgressiveMesh(seq.topology(), xyz);
    expectValidHierarchy(a);
    EXPECT_GT(a.collapses.size(), size_t(seq.topology().vertex_count) / 4);
    const ProgressiveMesh b = buildProgressiveMesh(seq.topology(), xyz);
    EXPECT_EQ(a.base, b.base);
    EXPECT_EQ(a.ring, b.ring);
    EXPECT_EQ(a.flap, b.flap);
    ASSERT_EQ(a.collapses.size(), b.collapses.size());
    for (size_t i = 0; i < a.collapses.size(); ++i) {
      EXPECT_EQ(a.collapses[i].vertex, b.collapses[i].vertex);
      EXPECT_EQ(a.collapses[i].target, b.collapses[i].target);
      EXPECT_EQ(a.collapses[i].level, b.collapses[i].level);
    }
  }
}

TEST(WaveletPredictor, EdgeWeightFavoursFlatEdges) {
  const AnisotropyParams p;
  EXPECT_NEAR(edgeWeight(1.0, p), 1.1, 1e-12);
  EXPECT_NEAR(edgeWeight(0.0, p), 0.1 + std::exp(-1.0 / 0.18), 1e-12);
  EXPECT_GT(edgeWeight(0.9, p), edgeWeight(0.5, p));
}

// Second differences vanish on linear functions, so on a flat parametric mesh the predictor
// reproduces every vertex exactly (linear precision), except where it falls back to the ring
// average.
TEST(WaveletPredictor, StencilsAreAffineAndHaveLinearPrecision) {
  const Topology topology = gridTopology(16, 16);
  std::vector<double> flat;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double px = x + 0.3 * std::sin(y), py = y + 0.2 * std::cos(3.0 * x);
      flat.insert(flat.end(), {px, py, 0.5 * px - 0.25 * py});
    }
  const ProgressiveMesh pm = buildProgressiveMesh(topology, flat);
  const PredictionStencils s = buildPredictor(pm, flat);
  ASSERT_EQ(s.first.size(), pm.collapses.size() + 1);
  size_t exact = 0;
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    double sum = 0, predicted[3] = {0, 0, 0};
    for (uint32_t j = s.first[i]; j < s.first[i + 1]; ++j) {
      sum += s.weight[j];
      for (int a = 0; a < 3; ++a) predicted[a] += s.weight[j] * flat[3 * s.vertex[j] + a];
    }
    EXPECT_NEAR(sum, 1.0, 1e-9);
    const uint32_t v = pm.collapses[i].vertex;
    const double miss = std::hypot(predicted[0] - flat[3 * v], predicted[1] - flat[3 * v + 1], predicted[2] - flat[3 * v + 2]);
    exact += miss < 1e-9;
  }
  EXPECT_GE(exact * 10, pm.collapses.size() * 9);
}

}  // namespace
}  // namespace animc
