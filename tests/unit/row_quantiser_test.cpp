// SPDX-License-Identifier: Apache-2.0
// The rate-distortion quantiser of trajectory rows (codecs/trajectory/row_quantiser.h).
#include "codecs/trajectory/row_quantiser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "codecs/trajectory/part_encoder.h"
#include "entropy/classed_integer.h"

namespace animc {
namespace {

constexpr uint32_t kFrames = 200;
constexpr double kStep = 0.01;
// The trajectory encoders' price of a bit, in squared steps of a row whose step moves the
// part by one squared coefficient step.
constexpr RowPrices kPriced = {1, kBitSlope};

// Three smooth runs with noise of a few tenths of a step, as a weak basis vector has.
std::vector<double> noisyRow(uint32_t seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0, 0.3 * kStep);
  std::vector<double> row(3 * kFrames);
  for (uint32_t i = 0; i < row.size(); ++i) row[i] = 0.2 * std::sin(0.05 * i + seed) + noise(random);
  return row;
}

std::vector<int32_t> quantised(const std::vector<double>& row, const RowPrices& prices) {
  std::vector<int32_t> out(row.size());
  quantiseRow(row.data(), kFrames, kStep, prices, out.data());
  return out;
}

// Bytes of the row as the trajectory groups code it: each run's differences along time,
// through one adaptive classed-integer model.
size_t codedBytes(const std::vector<int32_t>& values) {
  std::vector<uint8_t> bytes;
  RangeEncoder rc(bytes);
  RawBitWriter raw;
  ClassedIntegerModel model;
  for (uint32_t c = 0; c < 3; ++c) {
    int64_t previous = 0;
    for (uint32_t t = 0; t < kFrames; ++t) {
      encodeClassed(rc, raw, model, values[c * kFrames + t] - previous);
      previous = values[c * kFrames + t];
    }
  }
  rc.finish();
  raw.appendTo(bytes);
  return bytes.size();
}

// Squared error in steps.
double squaredError(const std::vector<double>& row, const std::vector<int32_t>& values) {
  double sum = 0;
  for (size_t i = 0; i < row.size(); ++i) sum += std::pow(row[i] / kStep - values[i], 2);
  return sum;
}

TEST(RowQuantiser, RoundsToNearestWhenBitsHaveNoPrice) {
  const std::vector<double> row = noisyRow(1);
  const std::vector<int32_t> out = quantised(row, RowPrices{});
  for (size_t i = 0; i < row.size(); ++i) EXPECT_EQ(out[i], int32_t(std::nearbyint(row[i] / kStep))) << i;
}

TEST(RowQuantiser, RoundsEachValueDownOrUp) {
  const std::vector<double> row = noisyRow(2);
  const std::vector<int32_t> out = quantised(row, kPriced);
  for (size_t i = 0; i < row.size(); ++i) {
    const double u = row[i] / kStep;
    EXPECT_TRUE(out[i] == std::floor(u) || out[i] == std::ceil(u)) << i << ": " << u << " -> " << out[i];
  }
}

TEST(RowQuantiser, KeepsARunFlatWhereItsNoiseCostsMoreBitsThanError) {
  // 3.4 steps, and 3.55 at every tenth value: rounded to nearest, each of those codes two
  // differences for a tenth of a squared step less error.
  std::vector<double> row(3 * kFrames);
  for (size_t i = 0; i < row.size(); ++i) row[i] = (i % 10 == 5 ? 3.55 : 3.4) * kStep;
  const std::vector<int32_t> out = quantised(row, kPriced);
  for (size_t i = 0; i < row.size(); ++i) EXPECT_EQ(out[i], 3) << i;
  const std::vector<int32_t> cheap = quantised(row, {1, 1e-6});
  EXPECT_EQ(cheap[5], 4);  // at a negligible price, nearest again
}

TEST(RowQuantiser, SavesMoreBitsThanTheErrorItAddsIsWorth) {
  for (uint32_t seed = 3; seed < 8; ++seed) {
    const std::vector<double> row = noisyRow(seed);
    const std::vector<int32_t> nearest = quantised(row, RowPrices{}), priced = quantised(row, kPriced);
    const double saved_bits = 8.0 * (double(codedBytes(nearest)) - double(codedBytes(priced)));
    const double added_error = squaredError(row, priced) - squaredError(row, nearest);
    EXPECT_GT(saved_bits, 0) << seed;
    EXPECT_LT(added_error, kPriced.error_per_bit * saved_bits) << seed;
  }
}

}  // namespace
}  // namespace animc
