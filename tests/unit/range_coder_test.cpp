// SPDX-License-Identifier: Apache-2.0
// The range coder's two decoding paths: decodeData (masks, for near-random data bits) must
// give exactly what decode (which may branch) gives; and the models' update rule.
#include <gtest/gtest.h>

#include <iterator>
#include <random>
#include <vector>

#include "entropy/range_coder.h"

namespace animc {
namespace {

// Same bits, models, end state and overrun verdict, on real streams (skewed and near-random
// bits, a few models), on truncated ones and on garbage.
TEST(RangeCoder, DecodeDataMatchesDecode) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<uint8_t> bytes;
    const size_t decisions = 1 + rng() % 5000;
    {
      RangeEncoder enc(bytes);
      BitModel models[4];
      for (size_t i = 0; i < decisions; ++i) {
        const int m = int(rng() % 4);
        enc.encode(models[m], int(rng() % 100 < uint32_t(m == 0 ? 50 : 10 + 25 * m)));
      }
      enc.finish();
    }
    if (trial % 4 == 1) bytes.resize(bytes.size() / 2);  // truncated
    if (trial % 4 == 2)
      for (uint8_t& b : bytes) b = uint8_t(rng());  // garbage
    RangeDecoder branching(bytes.data(), bytes.size());
    RangeDecoder masked(bytes.data(), bytes.size());
    BitModel branching_models[4], masked_models[4];
    for (size_t i = 0; i < decisions + 16; ++i) {
      const int m = int(i * 7 % 4);
      ASSERT_EQ(branching.decode(branching_models[m]), masked.decodeData(masked_models[m]))
          << "trial " << trial << " bit " << i;
      ASSERT_EQ(branching_models[m].p0, masked_models[m].p0);
      ASSERT_EQ(branching_models[m].seen, masked_models[m].seen);
    }
    EXPECT_EQ(branching.overran(), masked.overran()) << "trial " << trial;
  }
}

// finish() writes the fewest bytes that fix the decoded values whatever follows them: the
// stream decodes the same with random bytes after it as with zeros (past its end), and the
// flush is short (a range of at least 2^24 always holds a whole block of 2^16, so it needs 2
// bytes at most beside the cache and any 0xFF bytes held back). Streams short or long,
// skewed or not, across many random ends.
TEST(RangeCoder, ShortFinishDecodesWhateverFollows) {
  std::mt19937 rng(3);
  size_t total_flush = 0;
  const int trials = 400;
  for (int trial = 0; trial < trials; ++trial) {
    const size_t decisions = rng() % 300;
    std::vector<int> bits(decisions);
    std::vector<uint8_t> bytes, unfinished;
    RangeEncoder enc(bytes);
    BitModel models[2];
    for (size_t i = 0; i < decisions; ++i) {
      bits[i] = int(rng() % 100 < (i % 2 ? 10u : 50u));
      enc.encode(models[i % 2], bits[i]);
    }
    const size_t before = bytes.size();
    enc.finish();
    total_flush += bytes.size() - before;
    for (int tail = 0; tail < 2; ++tail) {
      std::vector<uint8_t> data = bytes;
      if (tail == 1)
        for (int i = 0; i < 4; ++i) data.push_back(uint8_t(rng()));
      RangeDecoder dec(data.data(), data.size());
      BitModel decoded[2];
      for (size_t i = 0; i < decisions; ++i) ASSERT_EQ(dec.decode(decoded[i % 2]), bits[i]) << trial << " " << i;
      EXPECT_FALSE(dec.overran()) << "trial " << trial;
      EXPECT_LE(size_t(dec.position() - data.data()), bytes.size() + kFinishReadAhead);
    }
  }
  // Mostly the cache and one byte: far below the cache and 4 bytes of a full flush.
  EXPECT_LT(double(total_flush) / trials, 2.5);
}

// The model's update (both forms), against its definition: after a 0, p0 += (2^15 - p0) >> shift; after a
// 1, p0 -= p0 >> shift; the shift following the schedule 2, 3, 3, 4, 4, 4, then 5 for good.
// Every reachable probability, every step of the schedule, both bits.
TEST(RangeCoder, ModelUpdateFollowsItsDefinition) {
  constexpr int kSchedule[] = {2, 3, 3, 4, 4, 4, 5, 5, 5, 5, 5, 5, 5, 5, 5};
  for (int step = 0; step < int(std::size(kSchedule)); ++step) {
    const int shift = kSchedule[step];
    for (uint32_t p0 = 0; p0 <= kProbOne; ++p0) {
      for (int bit = 0; bit < 2; ++bit) {
        BitModel m;
        for (int i = 0; i < step; ++i) m.update(i & 1);  // walk the schedule
        m.p0 = uint16_t(p0);
        BitModel data = m;
        m.update(bit);
        data.updateData(bit);
        const uint32_t expected = bit ? p0 - (p0 >> shift) : p0 + ((kProbOne - p0) >> shift);
        ASSERT_EQ(m.p0, expected) << "step " << step << " p0 " << p0 << " bit " << bit;
        ASSERT_EQ(data.p0, expected) << "updateData, step " << step << " p0 " << p0 << " bit " << bit;
        ASSERT_EQ(data.seen, m.seen);
      }
    }
  }
}

}  // namespace
}  // namespace animc
