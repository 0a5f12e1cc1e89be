// The wavelet transform: forward then inverse gives the frame back, on synthetic and real
// meshes, with and without local frames.
#include <gtest/gtest.h>

#include "codecs/wavelet/wavelet_transform.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::bboxDiagonal;
using testing_support::gridFrame;
using testing_support::gridTopology;
using testing_support::sharedSequence;
using testing_support::toDouble;

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

class WaveletTransformRoundTrip : public ::testing::TestWithParam<bool> {};

TEST_P(WaveletTransformRoundTrip, InverseUndoesForwardOnSharedSequences) {
  for (const char* name : {"chickenCrossing", "oa_gargoyle_upper"}) {
    SCOPED_TRACE(name);
    MemorySequence seq = sharedSequence(name, 30);
    ASSERT_EQ(seq.frames().size(), 30u);
    const WaveletTransform transform(seq.topology(), toDouble(seq.frames()[0]), GetParam());
    for (size_t f : {size_t(0), size_t(29)}) {
      const std::vector<double> x = toDouble(seq.frames()[f]);
      std::vector<double> coefficients, back;
      transform.forward(x.data(), coefficients);
      transform.inverse(coefficients, back);
      EXPECT_LE(maxAbsDifference(x, back), 1e-5 * bboxDiagonal(seq.frames()[f]));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Wavelet, WaveletTransformRoundTrip, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("LocalFrames") : std::string("WorldAxes");
                         });

// A rigid motion of the parametric mesh leaves the details in local frames unchanged (the
// paper's motivation for them); in world axes only a translation does.
TEST(WaveletTransform, LocalDetailsAreInvariantUnderRigidMotion) {
  const Topology topology = gridTopology(18, 18);
  const std::vector<double> rest = toDouble(gridFrame(18, 18, 0, 1.0, 0.0));
  const std::vector<double> moved = toDouble(gridFrame(18, 18, 9, 0.0, 1.0));
  const std::vector<double> rest_rigid = toDouble(gridFrame(18, 18, 0, 0.0, 1.0));
  const WaveletTransform transform(topology, rest, true);
  std::vector<double> a, b;
  transform.forward(rest_rigid.data(), a);
  transform.forward(moved.data(), b);
  for (const Collapse& c : transform.hierarchy().collapses)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[3 * c.vertex + k], b[3 * c.vertex + k], 1e-6);  // float inputs
}

}  // namespace
}  // namespace animc
