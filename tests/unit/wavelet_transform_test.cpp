// SPDX-License-Identifier: Apache-2.0
// The wavelet transform: forward then inverse gives the frame back, on synthetic and real
// meshes, with and without local frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "codecs/wavelet/wavelet_transform.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::bboxDiagonal;
using testing_support::gridFrame;
using testing_support::gridTopology;
using testing_support::realSequence;
using testing_support::toDouble;

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

class WaveletTransformRoundTrip : public ::testing::TestWithParam<bool> {};
// One test per real sequence and axes, so that a sequence the data folders lack is listed as
// not run.
class WaveletTransformOnSequence : public ::testing::TestWithParam<std::tuple<const char*, bool>> {};

TEST_P(WaveletTransformOnSequence, InverseUndoesForward) {
  const auto [name, local_frames] = GetParam();
  ANIMC_REQUIRE_SEQUENCE(name);
  {
    MemorySequence seq = realSequence(name, 30);
    ASSERT_EQ(seq.frames().size(), 30u);
    const WaveletTransform transform(bestSimdPath(), seq.topology(), toDouble(seq.frames()[0]), local_frames);
    for (size_t f : {size_t(0), size_t(29)}) {
      const std::vector<double> x = toDouble(seq.frames()[f]);
      std::vector<double> coefficients, back;
      transform.forward(x.data(), coefficients);
      transform.inverse(coefficients, back);
      EXPECT_LE(maxAbsDifference(x, back), 1e-5 * bboxDiagonal(seq.frames()[f]));
    }
  }
}

std::string axesName(bool local_frames) { return local_frames ? "LocalFrames" : "WorldAxes"; }

INSTANTIATE_TEST_SUITE_P(Wavelet, WaveletTransformRoundTrip, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) { return axesName(info.param); });
INSTANTIATE_TEST_SUITE_P(
    Real, WaveletTransformOnSequence,
    ::testing::Combine(::testing::Values("chickenCrossing", "oa_gargoyle_upper"), ::testing::Bool()),
    [](const ::testing::TestParamInfo<std::tuple<const char*, bool>>& info) {
      return std::string(std::get<0>(info.param)) + "_" + axesName(std::get<1>(info.param));
    });

// The transform as plainly as it can be written. Collapse i's prediction from positions
// xyz: its stencil's sum of weight * position, x, y, z alike, in stencil order.
Eigen::Vector3d plainPrediction(const WaveletTransform& transform, size_t i, const std::vector<double>& xyz) {
  const PredictionStencils& stencils = transform.stencils();
  Eigen::Vector3d p(0, 0, 0);
  for (uint32_t s = stencils.first[i]; s < stencils.first[i + 1]; ++s)
    for (int a = 0; a < 3; ++a) p[a] += stencils.weight[s] * xyz[3 * size_t(stencils.vertex[s]) + a];
  return p;
}

// Collapse i's frame: the world axes, or the local frame of its ring's positions in xyz.
LocalFrame plainFrame(const WaveletTransform& transform, bool local_frames, size_t i, const std::vector<double>& xyz) {
  if (!local_frames) return LocalFrame();
  const ProgressiveMesh& pm = transform.hierarchy();
  const Collapse& c = pm.collapses[i];
  std::vector<double> cosines, sines;
  for (uint32_t k = 0; k < c.ring_size; ++k) {
    cosines.push_back(std::cos(2 * 3.14159265358979323846 * k / c.ring_size));
    sines.push_back(std::sin(2 * 3.14159265358979323846 * k / c.ring_size));
  }
  return localFrame(xyz.data(), &pm.ring[c.ring_begin], cosines.data(), sines.data(), c.ring_size);
}

// Each removed vertex's detail: its position - its prediction, in its frame.
std::vector<double> plainForward(const WaveletTransform& transform, bool local_frames, const std::vector<double>& xyz) {
  const ProgressiveMesh& pm = transform.hierarchy();
  std::vector<double> coefficients = xyz;
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    const size_t v = pm.collapses[i].vertex;
    const Eigen::Vector3d d = Eigen::Vector3d(&xyz[3 * v]) - plainPrediction(transform, i, xyz);
    const Eigen::Vector3d local = plainFrame(transform, local_frames, i, xyz).toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[3 * v + a] = local[a];
  }
  return coefficients;
}

// The vertices in reverse removal order, each its prediction plus its detail taken out of its
// frame.
std::vector<double> plainInverse(const WaveletTransform& transform, bool local_frames,
                                 const std::vector<double>& coefficients) {
  const ProgressiveMesh& pm = transform.hierarchy();
  std::vector<double> xyz = coefficients;
  for (size_t i = pm.collapses.size(); i-- > 0;) {
    const size_t v = pm.collapses[i].vertex;
    const Eigen::Vector3d p = plainPrediction(transform, i, xyz);
    const LocalFrame f = plainFrame(transform, local_frames, i, xyz);
    const double* d = &coefficients[3 * v];
    for (int a = 0; a < 3; ++a)
      xyz[3 * v + a] = p[a] + ((d[0] * f.normal[a] + d[1] * f.tangent[a]) + d[2] * f.bitangent[a]);
  }
  return xyz;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The kernels of every path this build and CPU run (portable, AVX2) against the plain
// formulas, bit for bit: on random values, and on zeros of random signs, whose sums keep or
// lose the sign of zero depending on the order and kind of each operation.
TEST_P(WaveletTransformRoundTrip, KernelsMatchThePlainFormulasBitForBit) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  for (SimdPath path : availableSimdPaths())
  for (const MemorySequence& seq :
       {testing_support::gridSequence(18, 18, 1, 1.0, 0.0), realSequence("sydney_md2", 1)}) {
    SCOPED_TRACE(testing::Message() << seq.topology().vertex_count << " vertices, path " << int(path));
    const WaveletTransform transform(path, seq.topology(), toDouble(seq.frames()[0]), GetParam());
    // The case where a kernel must not read past a point: the last vertex is in stencils.
    const std::vector<uint32_t>& stencil_vertices = transform.stencils().vertex;
    EXPECT_NE(std::count(stencil_vertices.begin(), stencil_vertices.end(), seq.topology().vertex_count - 1), 0);
    std::mt19937_64 random(7);
    std::normal_distribution<double> normal;
    std::vector<double> values(3 * size_t(seq.topology().vertex_count)), out;
    for (bool zeros : {false, true}) {
      SCOPED_TRACE(zeros ? "signed zeros" : "random");
      for (double& c : values) c = zeros ? (random() & 1 ? -0.0 : 0.0) : normal(random);
      transform.inverse(values, out);
      EXPECT_TRUE(sameBits(out, plainInverse(transform, GetParam(), values))) << "inverse";
      transform.forward(values.data(), out);
      EXPECT_TRUE(sameBits(out, plainForward(transform, GetParam(), values))) << "forward";
    }
  }
}

// A rigid motion of the parametric mesh leaves the details in local frames unchanged (the
// paper's motivation for them); in world axes only a translation does.
TEST(WaveletTransform, LocalDetailsAreInvariantUnderRigidMotion) {
  const Topology topology = gridTopology(18, 18);
  const std::vector<double> rest = toDouble(gridFrame(18, 18, 0, 1.0, 0.0));
  const std::vector<double> moved = toDouble(gridFrame(18, 18, 9, 0.0, 1.0));
  const std::vector<double> rest_rigid = toDouble(gridFrame(18, 18, 0, 0.0, 1.0));
  const WaveletTransform transform(bestSimdPath(), topology, rest, true);
  std::vector<double> a, b;
  transform.forward(rest_rigid.data(), a);
  transform.forward(moved.data(), b);
  for (const Collapse& c : transform.hierarchy().collapses)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[3 * c.vertex + k], b[3 * c.vertex + k], 1e-6);  // float inputs
}

}  // namespace
}  // namespace animc
