// SPDX-License-Identifier: Apache-2.0
// The raw-bit stream kept at the end of a payload, and the classed integers that use it beside
// the range coder: round trips at every class boundary, the two streams sharing one buffer,
// the rate estimate against the real size, and damaged input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "entropy/classed_integer.h"
#include "entropy/raw_bits.h"

namespace animc {
namespace {

TEST(RawBits, ReadBackFromTheEndAfterOtherBytes) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<uint8_t> payload(rng() % 20, 0xAB);  // stands for the range coder's bytes
    const size_t front = payload.size();
    std::vector<std::pair<uint32_t, int>> fields;
    RawBitWriter writer;
    size_t total_bits = 0;
    for (int i = int(rng() % 300); i > 0; --i) {
      const int bits = int(rng() % 33);
      const uint32_t value = bits == 0 ? 0 : uint32_t(rng()) >> (32 - bits);
      writer.write(value, bits);
      fields.push_back({value, bits});
      total_bits += size_t(bits);
    }
    writer.appendTo(payload);
    ASSERT_EQ(payload.size(), front + (total_bits + 7) / 8);
    RawBitReader reader(payload.data(), payload.size());
    for (const auto& [value, bits] : fields) ASSERT_EQ(reader.read(bits), value) << "trial " << trial;
    EXPECT_EQ(reader.bytesUsed(), (total_bits + 7) / 8);
    EXPECT_FALSE(reader.overran());
    // The padding of the last byte is still inside the data; a bit beyond it is not.
    reader.read(int((8 - total_bits % 8) % 8));
    EXPECT_FALSE(reader.overran());
    if (front == 0) {
      reader.read(1);
      EXPECT_TRUE(reader.overran()) << "trial " << trial;
    }
  }
}

// Every magnitude around each class boundary comes back from its class and low bits.
TEST(ClassedInteger, ClassesCoverEveryMagnitudeOnce) {
  for (int e = 0; e <= 30; ++e) {
    for (int64_t delta = -3; delta <= 3; ++delta) {
      const int64_t mag = (int64_t(1) << e) + delta;
      if (mag < 1 || mag > (int64_t(1) << 30)) continue;
      const uint32_t c = magnitudeClass(uint64_t(mag));
      ASSERT_GE(c, 1u);
      ASSERT_LE(c, kMaxMagnitudeClass);
      // The raw bits after the sign: the ones below the class's two leading bits.
      ASSERT_EQ(rawBitsOfClass(c), 1 + lowBitsOfClass(c));
      const uint64_t low = uint64_t(mag) & ((uint64_t(1) << lowBitsOfClass(c)) - 1);
      ASSERT_EQ(magnitudeOf(c, low), uint64_t(mag)) << "class " << c;
      // The class's range starts at its lowest magnitude.
      ASSERT_GE(uint64_t(mag), magnitudeOf(c, 0));
    }
  }
}

std::vector<int64_t> sampleValues(std::mt19937& rng) {
  std::vector<int64_t> values = {0, 1, -1, 2, -3, 4, -5, 6, 7, 8, 255, -256, 257, 32767, 49151, -49152,
                                 65536, (int64_t(1) << 30), -(int64_t(1) << 30)};
  for (int i = 0; i < 3000; ++i) {
    const int e = int(rng() % (i % 50 == 0 ? 31 : 10));  // mostly small, a few huge
    const int64_t mag = int64_t(rng() % (uint64_t(1) << e)) + (rng() % 4 == 0 ? 0 : 1);
    values.push_back(rng() % 2 ? mag : -mag);
  }
  return values;
}

TEST(ClassedInteger, RoundTripBesideTheRangeCoder) {
  std::mt19937 rng(11);
  const std::vector<int64_t> values = sampleValues(rng);
  std::vector<uint8_t> payload;
  double estimated_bits = 0;
  {
    RangeEncoder rc(payload);
    RawBitWriter raw;
    ClassedIntegerModel m[2];
    BitModel flag;
    for (size_t i = 0; i < values.size(); ++i) {
      estimated_bits += classedCost(m[i % 2], values[i]);
      encodeClassed(rc, raw, m[i % 2], values[i]);
      rc.encode(flag, int(i % 3 == 0));  // other range-coded data in between
    }
    rc.finish();
    raw.appendTo(payload);
  }
  RangeDecoder rc(payload.data(), payload.size());
  RawBitReader raw(payload.data(), payload.size());
  ClassedIntegerModel m[2];
  BitModel flag;
  for (size_t i = 0; i < values.size(); ++i) {
    ASSERT_EQ(decodeClassed(rc, raw, m[i % 2]), values[i]) << "value " << i;
    ASSERT_EQ(rc.decode(flag), int(i % 3 == 0));
  }
  EXPECT_FALSE(rc.overran());
  EXPECT_FALSE(raw.overran());
  // Nothing between the two streams; the range decoder's read-ahead runs into the raw bits
  // by at most kFinishReadAhead bytes, and decodes right all the same (above).
  const size_t read = size_t(rc.position() - payload.data()) + raw.bytesUsed();
  EXPECT_GE(read, payload.size());
  EXPECT_LE(read, payload.size() + kFinishReadAhead);
  // The estimate the encoder's rate decisions use is close to what coding costs (the flags
  // in between are about 0.92 bits each).
  const double flag_bits = 0.92 * double(values.size());
  EXPECT_NEAR(estimated_bits + flag_bits, 8.0 * double(payload.size()), 0.02 * 8.0 * double(payload.size()));
}

// Garbage decodes to bounded values, and nearly always trips one of the checks a frame makes
// (a few random buffers happen to read as short valid streams).
TEST(ClassedInteger, DamagedStreamsStayBounded) {
  std::mt19937 rng(5);
  int flagged = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<uint8_t> payload(1 + rng() % 64);
    for (uint8_t& b : payload) b = uint8_t(rng());
    RangeDecoder rc(payload.data(), payload.size());
    RawBitReader raw(payload.data(), payload.size());
    ClassedIntegerModel m;
    for (int i = 0; i < 200; ++i) {
      const int64_t v = decodeClassed(rc, raw, m);
      ASSERT_LT(std::llabs(v), int64_t(1) << 31);
    }
    flagged += rc.overran() || raw.overran() ||
               size_t(rc.position() - payload.data()) + raw.bytesUsed() > payload.size();
  }
  EXPECT_GT(flagged, 180);
}

}  // namespace
}  // namespace animc
