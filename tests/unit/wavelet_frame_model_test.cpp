// SPDX-License-Identifier: Apache-2.0
// The wavelet frame model: what accept() reconstructs from a decoded residual.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "codecs/wavelet/frame_model.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::realSequence;
using testing_support::toDouble;

// Residuals as the bitplane decoder leaves them: mostly zeros (of either sign), some values.
std::vector<double> randomResidual(size_t size, std::mt19937_64& random) {
  std::normal_distribution<double> normal(0.0, 1e-3);
  std::vector<double> r(size);
  for (double& x : r) {
    const uint64_t pick = random() % 4;
    x = pick == 0 ? 0.0 : pick == 1 ? -0.0 : normal(random);
  }
  return r;
}

// The selectors choosePrediction() should pick for coefficients: per group, the one leaving
// the least sum of w^2 (c - prediction)^2 over the group's coefficients, in coding order,
// expanded as sum w^2 d^2 - 2 a sum w^2 d g + a^2 sum w^2 g^2 (d = c - previous, g = previous -
// before, a = s / 8), intra (sum w^2 (c - reference)^2) unless a damped prediction is lower.
std::array<uint8_t, 2> plainChoice(const WaveletTransform& transform, const std::vector<uint32_t>& order,
                                   const std::vector<double>& c, const std::vector<double>& previous,
                                   const std::vector<double>& before, const std::vector<double>& intra) {
  const size_t base = transform.hierarchy().base.size();
  const bool two = !before.empty();
  double dd[2] = {0, 0}, dg[2] = {0, 0}, gg[2] = {0, 0}, ee[2] = {0, 0};
  for (size_t i = 0; i < order.size(); ++i) {
    const size_t v = order[i], group = i < base ? 0 : 1;
    const double w2 = transform.weights()[v] * transform.weights()[v];
    for (size_t j = 3 * v; j < 3 * v + 3; ++j) {
      const double d = c[j] - previous[j], g = two ? previous[j] - before[j] : 0.0, e = c[j] - intra[j];
      dd[group] += w2 * d * d;
      dg[group] += w2 * d * g;
      gg[group] += w2 * g * g;
      ee[group] += w2 * e * e;
    }
  }
  std::array<uint8_t, 2> selector{};
  for (int group = 0; group < 2; ++group) {
    double best = ee[group];
    selector[group] = 9;
    for (int s = 0; s <= (two ? 8 : 0); ++s) {
      const double a = s / 8.0, energy = dd[group] - 2 * a * dg[group] + a * a * gg[group];
      if (energy < best) {
        best = energy;
        selector[group] = uint8_t(s);
      }
    }
  }
  return selector;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The frame model's kernels (whichever this build and CPU run) against the plain formulas,
// bit for bit: vertices in coding order (base, then the collapses coarse to fine), the
// prediction per group (base, details) the I-frame reference, the previous coefficients or
// previous + s / 8 * (previous - the ones before); residual() = weight * (coefficients -
// prediction), accept() reconstructs the inverse transform of prediction + residual / weight.
// And choosePrediction() picks what plainChoice() does.
TEST(WaveletFrameModel, KernelsFollowThePlainFormulas) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  ANIMC_REQUIRE_SEQUENCE("oa_gargoyle_upper");
  for (SimdPath path : availableSimdPaths())
  for (const char* name : {"sydney_md2", "oa_gargoyle_upper"}) {
    SCOPED_TRACE(std::string(name) + ", path " + std::to_string(int(path)));
    const MemorySequence seq = realSequence(name, 1);
    const std::vector<double> parametric = toDouble(seq.frames()[0]);
    WaveletFrameModel model(WaveletOptions(), seq.topology(), path);
    model.setParametric(parametric);
    const WaveletTransform& transform = model.transform();
    const ProgressiveMesh& pm = transform.hierarchy();
    std::vector<uint32_t> order = pm.base;
    for (size_t i = pm.collapses.size(); i-- > 0;) order.push_back(pm.collapses[i].vertex);

    std::vector<double> previous, before, intra(parametric.size(), 0.0), expected, out;
    transform.forward(parametric.data(), previous);
    for (uint32_t v : pm.base)
      for (int a = 0; a < 3; ++a) intra[3 * v + a] = previous[3 * v + a];
    std::mt19937_64 random(11);
    // Intra first (and one P-frame) so that two references exist for extrapolation.
    for (const std::array<uint8_t, 2>& selector : std::vector<std::array<uint8_t, 2>>{
             {9, 9}, {0, 0}, {3, 8}, {8, 1}, {9, 5}, {0, 9}}) {
      SCOPED_TRACE(testing::Message() << int(selector[0]) << " " << int(selector[1]));
      // Coefficient j of coding position i, its prediction.
      auto predict = [&](size_t i, size_t j) {
        const uint8_t s = selector[i < pm.base.size() ? 0 : 1];
        return s == 9 ? intra[j] : s == 0 ? previous[j] : previous[j] + s / 8.0 * (previous[j] - before[j]);
      };
      // Coefficients near the last ones, as an encoder's next frame.
      std::vector<double> near = previous;
      for (double& x : near) x += std::normal_distribution<double>(0.0, 1e-3)(random);
      EXPECT_EQ(model.choosePrediction(near, true).selector,
                plainChoice(transform, order, near, previous, before, intra));
      Prediction prediction;
      prediction.selector = selector;
      ASSERT_TRUE(model.canPredict(prediction));

      const std::vector<double>& weights = transform.weights();
      std::vector<double> residual(parametric.size());
      for (size_t i = 0; i < order.size(); ++i)
        for (size_t a = 0; a < 3; ++a)
          residual[3 * i + a] = weights[order[i]] * (near[3 * order[i] + a] - predict(i, 3 * order[i] + a));
      model.residual(near, prediction, out);
      EXPECT_TRUE(sameBits(out, residual)) << "residual";

      residual = randomResidual(parametric.size(), random);
      std::vector<double> coefficients(parametric.size());
      for (size_t i = 0; i < order.size(); ++i)
        for (size_t a = 0; a < 3; ++a)
          coefficients[3 * order[i] + a] = predict(i, 3 * order[i] + a) + residual[3 * i + a] / weights[order[i]];
      model.accept(residual, prediction);
      transform.inverse(coefficients, expected);
      EXPECT_TRUE(sameBits(model.reconstruction(), expected)) << "accept";
      before = previous;
      previous = coefficients;
    }
  }
}

}  // namespace
}  // namespace animc
