// SPDX-License-Identifier: Apache-2.0
// The progressive bitplane coder: exact to the step, progressive by plane and by byte,
// within its budget, and safe on garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "codecs/wavelet/bitplane_coder.h"
#include "codecs/wavelet/bitplane_contexts.h"
#include "entropy/range_coder.h"

namespace animc {
namespace {

struct Coefficients {
  std::vector<double> values;
  std::vector<uint8_t> classes;
  std::vector<uint32_t> parents;
  BitplaneLayout layout() const { return BitplaneLayout{classes.data(), parents.data(), classes.size()}; }
};

// Laplacian-like values, larger for the first (coarse) groups, parents pointing backwards.
Coefficients makeCoefficients(size_t groups, uint32_t seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> magnitude(1.0);
  Coefficients c;
  for (size_t g = 0; g < groups; ++g) {
    const double scale = 50.0 / (1.0 + double(g) / 8.0);
    for (int a = 0; a < 3; ++a) c.values.push_back((rng() & 1 ? 1 : -1) * scale * magnitude(rng));
    c.classes.push_back(uint8_t(g < 20 ? 0 : 1 + g % 15));
    c.parents.push_back(g == 0 ? kNoParent : uint32_t(g / 2));
  }
  return c;
}

double squaredError(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

// Encodes c down to `step` (within `budget` bytes when not 0): the stream and what the encoder
// expects a full decode to give.
void encode(const Coefficients& c, double step, std::vector<uint8_t>& bytes, std::vector<double>& encoder_view,
            uint64_t budget = 0, const BitplaneHistory* context = nullptr, BitplaneHistory* history = nullptr) {
  BitplaneEncodeSettings settings;
  settings.path = bestSimdPath();
  settings.step = step;
  settings.byte_budget = budget;
  settings.context = context;
  encodeBitplanes(c.values.data(), c.layout(), settings, bytes, encoder_view, history);
}

Status decode(const std::vector<uint8_t>& bytes, size_t size, const Coefficients& c, int max_planes,
              std::vector<double>& out, int* planes = nullptr, double step = 0.01,
              const BitplaneHistory* context = nullptr, BitplaneHistory* history = nullptr) {
  std::vector<uint8_t> exact(bytes.begin(), bytes.begin() + size);  // exact-size copy for ASan
  ByteReader in(exact.data(), exact.size());
  BitplaneDecodeSettings settings;
  settings.path = bestSimdPath();
  settings.step = step;
  settings.max_planes = max_planes;
  settings.context = context;
  return decodeBitplanes(in, c.layout(), settings, out, planes, history);
}

TEST(WaveletBitplane, TemporalContextTableMatchesItsDefinition) {
  // Encoder and decoder share the table, so a wrong entry would still round-trip: compare
  // it with the rule it encodes, for every plane and every bit length a history can hold.
  struct NoIo {};
  for (int p = 0; p < kMaxBitplanes; ++p) {
    const uint64_t fields = PlaneWalk<NoIo>::temporalFields(p);
    for (int b = 0; b <= kMaxBitplanes; ++b) {
      const int expected = (b != 0) + (b > p) + (b > p + 1);
      EXPECT_EQ(int((fields >> (2 * b)) & 3), expected) << "plane " << p << ", previous bit length " << b;
    }
  }
}

TEST(WaveletBitplane, ReconstructionMatchesItsFormulaForEveryMagnitude) {
  // The kernel picks offsets, zeros and signs by masks and reads bit lengths from double
  // exponents (four lanes at a time where the CPU has AVX2): compare it with the plain formula,
  // on the edges (0, 1, powers of two and their neighbours, the largest magnitude) and on an
  // odd count, so that the scalar tail runs too.
  std::vector<uint32_t> k = {0, 1, 2, 3, 4, 7, 8, (1u << 24) - 1, 1u << 24, (1u << 31) - 1};
  std::mt19937 rng(7);
  for (int i = 0; i < 21; ++i) k.push_back(rng() >> (1 + rng() % 31));
  std::vector<uint8_t> negative(k.size());
  for (size_t i = 0; i < k.size(); ++i) negative[i] = uint8_t(i % 3 == 1);
  for (SimdPath path : availableSimdPaths())
  for (int q : {0, 5}) {
    SCOPED_TRACE(int(path));
    const double scale = std::ldexp(0.3, q);
    std::vector<double> out(k.size());
    std::vector<uint8_t> lengths(k.size()), signs(k.size());
    reconstructCoefficients(path, k.data(), negative.data(), k.size(), q, scale, out.data(), lengths.data(), signs.data());
    for (size_t i = 0; i < k.size(); ++i) {
      const double magnitude = k[i] == 0 ? 0.0 : (double(k[i]) + (k[i] == 1 ? kFreshOffset : kRefinedOffset)) * scale;
      const double expected = negative[i] ? -magnitude : magnitude;
      EXPECT_EQ(std::memcmp(&out[i], &expected, sizeof expected), 0) << "k = " << k[i] << ", q = " << q;
      EXPECT_EQ(int(lengths[i]), k[i] == 0 ? 0 : 32 - __builtin_clz(k[i]) + q) << "k = " << k[i];
      EXPECT_EQ(signs[i], negative[i]);
    }
  }
}

TEST(WaveletBitplane, FullStreamIsExactToTheStepAndMatchesTheEncoder) {
  const Coefficients c = makeCoefficients(400, 1);
  std::vector<uint8_t> bytes;
  std::vector<double> encoder_view, decoded;
  encode(c, 0.01, bytes, encoder_view);
  ASSERT_TRUE(decode(bytes, bytes.size(), c, 0, decoded).ok());
  EXPECT_EQ(decoded, encoder_view);
  for (size_t i = 0; i < c.values.size(); ++i) EXPECT_LE(std::fabs(decoded[i] - c.values[i]), 0.01);
}

TEST(WaveletBitplane, ErrorFallsWithEveryBitplaneDecoded) {
  const Coefficients c = makeCoefficients(400, 2);
  std::vector<uint8_t> bytes;
  std::vector<double> full, decoded;
  encode(c, 0.01, bytes, full);
  double previous = squaredError(c.values, std::vector<double>(c.values.size(), 0.0));
  const int planes = bytes[0] & 0x7f;
  ASSERT_GT(planes, 8);
  for (int p = 1; p <= planes; ++p) {
    int used = 0;
    ASSERT_TRUE(decode(bytes, bytes.size(), c, p, decoded, &used).ok());
    EXPECT_EQ(used, p);
    const double error = squaredError(c.values, decoded);
    EXPECT_LT(error, previous) << "plane " << p;
    previous = error;
  }
}

TEST(WaveletBitplane, EveryTruncationDecodesAndMoreBytesNeverHurt) {
  const Coefficients c = makeCoefficients(150, 3);
  std::vector<uint8_t> bytes;
  std::vector<double> full, decoded;
  encode(c, 0.01, bytes, full);
  double previous = INFINITY;
  int decodable = 0;
  for (size_t size = 0; size <= bytes.size(); ++size) {
    const Status s = decode(bytes, size, c, 0, decoded);
    if (!s.ok()) {  // only a cut inside the block's header may fail, as truncated
      EXPECT_EQ(s.code(), StatusCode::kTruncated) << size << ": " << s.message();
      EXPECT_EQ(decodable, 0) << "a longer prefix failed after a shorter one decoded: " << size;
      continue;
    }
    ++decodable;
    const double error = squaredError(c.values, decoded);
    EXPECT_LE(error, previous * (1 + 1e-12)) << size;
    previous = error;
  }
  EXPECT_GT(decodable, int(bytes.size()) - 40);
  EXPECT_EQ(decoded, full);
}

TEST(WaveletBitplane, BudgetIsRespectedAndMoreBudgetMeansLessError) {
  const Coefficients c = makeCoefficients(500, 4);
  double previous = INFINITY;
  for (uint64_t budget : {40, 100, 250, 600, 1500}) {
    std::vector<uint8_t> bytes;
    std::vector<double> encoder_view, decoded;
    encode(c, 0.001, bytes, encoder_view, budget);
    EXPECT_LE(bytes.size(), budget + 8) << budget;
    if (budget >= 250) {
      EXPECT_GE(bytes.size(), budget * 8 / 10) << budget;
    }
    ASSERT_TRUE(decode(bytes, bytes.size(), c, 0, decoded, nullptr, 0.001).ok());
    EXPECT_EQ(decoded, encoder_view);
    const double error = squaredError(c.values, decoded);
    EXPECT_LT(error, previous);
    previous = error;
  }
}

// A second frame close to the first, coded with the first's history as temporal context:
// both sides agree, and the context saves bytes.
TEST(WaveletBitplane, TemporalContextRoundTripsAndHelps) {
  const Coefficients first = makeCoefficients(600, 8);
  Coefficients second = first;
  std::mt19937 rng(9);
  std::normal_distribution<double> noise(0.0, 0.5);
  for (double& v : second.values) v = 0.8 * v + noise(rng);
  std::vector<uint8_t> bytes;
  std::vector<double> view;
  BitplaneHistory history, decoder_history;
  encode(first, 0.01, bytes, view, 0, nullptr, &history);
  std::vector<double> decoded;
  ASSERT_TRUE(decode(bytes, bytes.size(), first, 0, decoded, nullptr, 0.01, nullptr, &decoder_history).ok());
  EXPECT_EQ(decoder_history.bits, history.bits);
  EXPECT_EQ(decoder_history.negative, history.negative);
  std::vector<uint8_t> with, without;
  std::vector<double> view_with, view_without;
  encode(second, 0.01, with, view_with, 0, &history);
  encode(second, 0.01, without, view_without);
  EXPECT_EQ(view_with, view_without);  // the context changes the bytes, not the values
  EXPECT_LT(with.size(), without.size() * 97 / 100);
  ASSERT_TRUE(decode(with, with.size(), second, 0, decoded, nullptr, 0.01, &decoder_history).ok());
  EXPECT_EQ(decoded, view_with);
}

// The encoder's preview of a cut is exactly what a stream cut there decodes to.
TEST(WaveletBitplane, CutPreviewMatchesAForcedCut) {
  const Coefficients c = makeCoefficients(300, 10);
  auto workspace = makeBitplaneWorkspace();
  const BitplaneCutPreview preview(bestSimdPath(), c.values.data(), c.layout(), 0.01, workspace.get());
  ASSERT_GT(preview.planeCount(), 4);
  for (int planes : {1, 3, preview.planeCount()})
    for (size_t blocks : {size_t(1), preview.blockCount() / 2, preview.blockCount()}) {
      std::vector<double> expected, decoded;
      preview.decoded(planes, blocks, expected);
      BitplaneEncodeSettings settings;
      settings.path = bestSimdPath();
      settings.step = 0.01;
      settings.max_planes = planes;
      settings.last_plane_blocks = blocks;
      std::vector<uint8_t> bytes;
      std::vector<double> view;
      encodeBitplanes(c.values.data(), c.layout(), settings, bytes, view);
      EXPECT_EQ(view, expected) << planes << " planes, " << blocks << " blocks";
      ASSERT_TRUE(decode(bytes, bytes.size(), c, 0, decoded).ok());
      EXPECT_EQ(decoded, expected);
    }
}

TEST(WaveletBitplane, AllZeroCostsOneByte) {
  Coefficients c = makeCoefficients(10, 5);
  std::fill(c.values.begin(), c.values.end(), 0.0);
  BitplaneEncodeSettings settings;
  std::vector<uint8_t> bytes;
  std::vector<double> decoded;
  encodeBitplanes(c.values.data(), c.layout(), settings, bytes, decoded);
  EXPECT_EQ(bytes.size(), 1u);
}

TEST(WaveletBitplane, GarbageNeverCrashes) {
  const Coefficients c = makeCoefficients(60, 6);
  std::mt19937 rng(7);
  std::vector<double> decoded;
  int failures = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> bytes(1 + rng() % 200);
    for (uint8_t& b : bytes) b = uint8_t(rng());
    const Status s = decode(bytes, bytes.size(), c, 0, decoded);
    failures += !s.ok();
    if (s.ok()) {
      ASSERT_EQ(decoded.size(), c.values.size());
      for (double v : decoded) ASSERT_TRUE(std::isfinite(v));
    }
  }
  EXPECT_GT(failures, 1000);
}

}  // namespace
}  // namespace animc
