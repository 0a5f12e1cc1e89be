// SPDX-License-Identifier: Apache-2.0
// The refinement of a part's basis and coefficients (PartEncoder::refine()): the frames a
// decoder makes of the part have less error at every step, and never more where the part's
// weakest components are noise (a mesh of few motions); a very large part is left alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/part_encoder.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::gridFrame;
using testing_support::gridSequence;
using testing_support::gridTopology;

const std::vector<uint32_t> kWholeMesh;  // a part's members: every vertex of the mesh

// One group of a sequence as the trajectory encoder holds it: its frames, one after another,
// and what its parts share.
class Group {
 public:
  explicit Group(const MemorySequence& sequence) : order_(sequence.topology()) {
    for (const std::vector<float>& frame : sequence.frames()) frames_.insert(frames_.end(), frame.begin(), frame.end());
    context_.options.rate = TrajectoryRate::kTargetKg;  // the decomposition stops as the encoder's does
    context_.options.rate_value = 0.1;
    context_.path = bestSimdPath();
    context_.original = frames_.data();
    context_.mesh_vertices = sequence.topology().vertex_count;
    context_.frames = uint32_t(sequence.frames().size());
    context_.spread = spread(sequence.frames());
  }

  bool wholeMeshIsRefinable() { return PartEncoder(context_, order_, kWholeMesh).refinable(); }

  // The squared error of the whole mesh as one part, quantised at step q after `rounds`
  // rounds of refinement.
  double squaredError(double q, int rounds) {
    context_.refinement_rounds = 0;
    PartEncoder part(context_, order_, kWholeMesh);
    part.extend(32);  // as the encoder starts a part: by subspace iteration
    context_.refinement_rounds = rounds;
    return part.measure(q, false).squared;
  }

 private:
  // Sum over the frames of |x - centroid|^2 (the KG error's denominator).
  static double spread(const std::vector<std::vector<float>>& frames) {
    double sum = 0;
    for (const std::vector<float>& xyz : frames) {
      const size_t n = xyz.size() / 3;
      for (int c = 0; c < 3; ++c) {
        double centroid = 0;
        for (size_t v = 0; v < n; ++v) centroid += xyz[3 * v + c];
        centroid /= double(n);
        for (size_t v = 0; v < n; ++v) sum += (xyz[3 * v + c] - centroid) * (xyz[3 * v + c] - centroid);
      }
    }
    return sum;
  }

  std::vector<float> frames_;
  CodingOrder order_;
  GroupContext context_;
};

TEST(TrajectoryRefinement, LowersTheErrorAtEveryStep) {
  Group group(gridSequence(12, 10, 40, 1.0, 1.0));
  for (double q : {0.002, 0.01, 0.05}) {
    const double plain = group.squaredError(q, 0), refined = group.squaredError(q, 2);
    EXPECT_LT(refined, 0.98 * plain) << "step " << q;
  }
}

// A travelling sine wave on a still grid is a few components, and on coordinates rounded to
// 1/4096 (as the golden input two_motions) the rest are the decomposition's noise floor, whose
// vectors are far from orthogonal: fitted to those too, the part decoded at 10^6 times the
// error.
TEST(TrajectoryRefinement, NeverRaisesTheErrorOfAMeshOfFewMotions) {
  std::vector<std::vector<float>> frames;
  for (int f = 0; f < 24; ++f) {
    frames.push_back(gridFrame(10, 8, f, 1.0, 0.0));
    for (float& c : frames.back()) c = std::round(c * 4096) / 4096;
  }
  Group group(MemorySequence(gridTopology(10, 8), frames));
  for (double q : {1e-4, 1e-3, 0.01}) {
    const double plain = group.squaredError(q, 0), refined = group.squaredError(q, 2);
    EXPECT_LE(refined, plain) << "step " << q;
  }
}

// Above 2^16 vertices a part is not refined: its products would cost more than the rest of
// the encoder.
TEST(TrajectoryRefinement, LeavesAPartOfMoreThan65536VerticesAlone) {
  EXPECT_TRUE(Group(gridSequence(256, 256, 2, 1.0, 1.0)).wholeMeshIsRefinable());
  EXPECT_FALSE(Group(gridSequence(257, 256, 2, 1.0, 1.0)).wholeMeshIsRefinable());
}

}  // namespace
}  // namespace animc
