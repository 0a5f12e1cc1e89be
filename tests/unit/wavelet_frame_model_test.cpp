// The wavelet frame model: what accept() reconstructs from a decoded residual.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "codecs/wavelet/frame_model.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::sharedSequence;
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

// accept() against its plain formula, bit for bit (whichever kernel this build and CPU run):
// coefficient = prediction + residual / weight, vertices in coding order (base, then the
// collapses coarse to fine), the prediction per group (base, details) the I-frame reference,
// the previous coefficients or previous + s / 8 * (previous - the ones before); then the
// inverse transform.
TEST(WaveletFrameModel, AcceptAddsTheResidualToThePredictionBitForBit) {
  for (const char* name : {"sydney_md2", "oa_gargoyle_upper"}) {
    SCOPED_TRACE(name);
    const MemorySequence seq = sharedSequence(name, 1);
    const std::vector<double> parametric = toDouble(seq.frames()[0]);
    WaveletFrameModel model(WaveletOptions(), seq.topology());
    model.setParametric(parametric);
    const WaveletTransform& transform = model.transform();
    const ProgressiveMesh& pm = transform.hierarchy();
    std::vector<uint32_t> order = pm.base;
    for (size_t i = pm.collapses.size(); i-- > 0;) order.push_back(pm.collapses[i].vertex);

    std::vector<double> previous, before, intra(parametric.size(), 0.0), expected;
    transform.forward(parametric.data(), previous);
    for (uint32_t v : pm.base)
      for (int a = 0; a < 3; ++a) intra[3 * v + a] = previous[3 * v + a];
    std::mt19937_64 random(11);
    // Intra first (and one P-frame) so that two references exist for extrapolation.
    for (const std::array<uint8_t, 2>& selector : std::vector<std::array<uint8_t, 2>>{
             {9, 9}, {0, 0}, {3, 8}, {8, 1}, {9, 5}, {0, 9}}) {
      SCOPED_TRACE(testing::Message() << int(selector[0]) << " " << int(selector[1]));
      Prediction prediction;
      prediction.selector = selector;
      ASSERT_TRUE(model.canPredict(prediction));
      const std::vector<double> residual = randomResidual(parametric.size(), random);
      std::vector<double> coefficients(parametric.size());
      for (size_t i = 0; i < order.size(); ++i) {
        const size_t v = order[i];
        const uint8_t s = selector[i < pm.base.size() ? 0 : 1];
        const double w = transform.weights()[v];
        for (size_t j = 3 * v; j < 3 * v + 3; ++j) {
          const double p = s == 9 ? intra[j] : s == 0 ? previous[j] : previous[j] + s / 8.0 * (previous[j] - before[j]);
          coefficients[j] = p + residual[3 * i + j - 3 * v] / w;
        }
      }
      model.accept(residual, prediction);
      transform.inverse(coefficients, expected);
      ASSERT_EQ(model.reconstruction().size(), expected.size());
      EXPECT_EQ(std::memcmp(model.reconstruction().data(), expected.data(), expected.size() * sizeof(double)), 0);
      before = previous;
      previous = coefficients;
    }
  }
}

}  // namespace
}  // namespace animc
