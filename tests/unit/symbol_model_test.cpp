// SPDX-License-Identifier: Apache-2.0
// The 16-symbol adaptive model: its vector update and search against their one-lane
// definitions, its invariants under long skewed runs, and round trips through the range coder
// beside binary decisions, with the rate estimate against the real size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "entropy/integer_coder.h"
#include "entropy/symbol_model.h"

namespace animc {
namespace {

// A symbol drawn mostly from a few small values, with runs of one value (as corrections are
// in quiet stretches), so the starts get pushed to their floors and ceilings.
uint32_t skewedSymbol(std::mt19937& rng, int i) {
  if ((i / 400) % 3 == 1) return 0;
  const uint32_t r = rng() % 100;
  return r < 40 ? 0 : r < 70 ? 1 : r < 85 ? 2 + rng() % 2 : rng() % kSymbols;
}

void expectValid(const SymbolModel& m) {
  ASSERT_EQ(m.start[0], 0);
  ASSERT_EQ(m.start[kSymbols], kProbOne);
  for (int i = 1; i < kSymbols; ++i) {
    ASSERT_GE(m.start[i], uint32_t(i)) << "start " << i;
    ASSERT_LE(m.start[i], kSymbolCeiling + uint32_t(i)) << "start " << i;
    ASSERT_LT(m.start[i], m.start[i + 1]) << "start " << i;
  }
}

TEST(SymbolModel, UpdateFollowsTheDefinitionAndKeepsEverySpan) {
  std::mt19937 rng(21);
  for (int run = 0; run < 3; ++run) {
    SymbolModel m;
    ASSERT_NO_FATAL_FAILURE(expectValid(m));
    const int rates[] = {2, 3, 3, 4, 4, 4, 5};  // then 5 for good
    for (int i = 0; i < 3000; ++i) {
      const uint32_t s = skewedSymbol(rng, i);
      const int rate = rates[i < 6 ? i : 6];
      uint32_t expected[kSymbols + 1];
      for (int k = 0; k <= kSymbols; ++k) {
        // Starts at or below s move towards k, those above towards the ceiling + k, by
        // floor(distance / 2^rate) (rounded towards minus infinity both ways).
        const int32_t target = int32_t(k) + (uint32_t(k) > s ? int32_t(kSymbolCeiling) : 0);
        const int32_t distance = target - int32_t(m.start[k]);
        expected[k] = k == 0 ? 0 : uint32_t(int32_t(m.start[k]) + (distance >> rate));
      }
      m.update(s);
      for (int k = 0; k <= kSymbols; ++k) ASSERT_EQ(m.start[k], expected[k]) << "step " << i << " start " << k;
      ASSERT_NO_FATAL_FAILURE(expectValid(m));
    }
  }
}

TEST(SymbolModel, FindCountsTheStartsAtOrBelowTheTarget) {
  std::mt19937 rng(4);
  SymbolModel m;
  for (int round = 0; round < 20; ++round) {
    for (int i = 0; i < 50; ++i) m.update(skewedSymbol(rng, round * 150 + i));
    for (uint32_t t = 0; t < kProbOne; ++t) {
      uint32_t expected = 0;
      for (int k = 1; k < kSymbols; ++k) expected += m.start[k] <= t;
      ASSERT_EQ(m.find(t), expected) << "round " << round << " target " << t;
    }
  }
}

TEST(SymbolModel, RoundTripBesideBinaryDecisions) {
  std::mt19937 rng(8);
  std::vector<uint32_t> symbols;
  for (int i = 0; i < 6000; ++i) symbols.push_back(skewedSymbol(rng, i));
  std::vector<uint8_t> bytes;
  double estimated_bits = 0;
  {
    RangeEncoder rc(bytes);
    SymbolModel m[2];
    BitModel flag;
    for (size_t i = 0; i < symbols.size(); ++i) {
      estimated_bits += symbolCost(m[i % 2], symbols[i]) + bitCost(flag, int(i % 5 == 0));
      encodeSymbol(rc, m[i % 2], symbols[i]);
      rc.encode(flag, int(i % 5 == 0));
    }
    rc.finish();
  }
  RangeDecoder rc(bytes.data(), bytes.size());
  SymbolModel m[2];
  BitModel flag;
  for (size_t i = 0; i < symbols.size(); ++i) {
    ASSERT_EQ(decodeSymbol(rc, m[i % 2]), symbols[i]) << "symbol " << i;
    ASSERT_EQ(rc.decode(flag), int(i % 5 == 0)) << "flag " << i;
  }
  EXPECT_FALSE(rc.overran());
  EXPECT_LE(size_t(rc.position() - bytes.data()), bytes.size());
  EXPECT_NEAR(estimated_bits, 8.0 * double(bytes.size()), 0.02 * 8.0 * double(bytes.size()));
}

// Garbage decodes to symbols in range, and the spans stay valid whatever the code says.
// (Whether damage is caught is the payload's business: ClassedInteger.DamagedStreamsStayBounded.)
TEST(SymbolModel, DamagedStreamsStayInRange) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<uint8_t> bytes(1 + rng() % 48);
    for (uint8_t& b : bytes) b = uint8_t(rng());
    RangeDecoder rc(bytes.data(), bytes.size());
    SymbolModel m;
    for (int i = 0; i < 300; ++i) ASSERT_LT(decodeSymbol(rc, m), uint32_t(kSymbols));
    ASSERT_NO_FATAL_FAILURE(expectValid(m));
  }
}

}  // namespace
}  // namespace animc
