// Signed integers as a zero flag, a magnitude class through 4-level bit trees, and the sign
// and the class's low bits raw, in the raw-bit stream (raw_bits.h). After the zero flag the
// range coder takes four steps whatever the value, none of them a branch on the data, where
// the unary exponent of integer_coder.h mispredicts about once per value and its sign and low
// bits lengthen the coder's serial chain. Meant for values that are rarely zero and spread
// over many magnitudes (the default profile's affine corrections); mostly-zero values stay
// with integer_coder.h.
//
// Classes of |v| >= 1: |v| itself below 4; above, 2e + m with e the position of the leading 1
// and m the bit below it ([4,6) is class 4, [6,8) class 5, [8,12) class 6, ...). Classes
// 1..15 go through the Low tree, whose 16th symbol escapes to the High tree for classes
// 16..30, whose 16th escapes to 5 raw bits for classes 31 to kMaxMagnitudeClass.
#pragma once
#include <cstdint>

#include "entropy/bit_tree.h"
#include "entropy/integer_coder.h"
#include "entropy/range_coder.h"
#include "entropy/raw_bits.h"

namespace animc {

constexpr uint32_t kMaxMagnitudeClass = 2 * 30 + 1;  // |v| < 2^31

struct ClassedIntegerModel {
  BitModel zero;
  BitTreeModel<4> low;   // classes 1..15, then the escape
  BitTreeModel<4> high;  // classes 16..30, then the escape
};

inline uint32_t magnitudeClass(uint64_t mag) {
  if (mag < 4) return uint32_t(mag);
  const int e = 63 - __builtin_clzll(mag);
  return uint32_t(2 * e) + uint32_t((mag >> (e - 1)) & 1);
}
// Raw bits of a class >= 1: the sign, then the e - 1 bits below the two leading ones.
inline int rawBitsOfClass(uint32_t c) { return c < 4 ? 1 : int(c >> 1); }
inline uint64_t magnitudeOf(uint32_t c, uint64_t low) {
  return c < 4 ? c : (uint64_t(2 | (c & 1)) << ((c >> 1) - 1)) | low;
}
// The symbols a class >= 1 is coded with in the Low tree and, from class 16, the High tree.
inline uint32_t lowTreeSymbol(uint32_t c) { return c < 16 ? c - 1 : 15; }
inline uint32_t highTreeSymbol(uint32_t c) { return c < 31 ? c - 16 : 15; }

inline void encodeClassed(RangeEncoder& rc, RawBitWriter& raw, ClassedIntegerModel& m, int64_t v) {
  rc.encode(m.zero, v != 0);
  if (v == 0) return;
  const uint64_t mag = uint64_t(v < 0 ? -v : v);
  const uint32_t c = magnitudeClass(mag);
  encodeTree(rc, m.low, lowTreeSymbol(c));
  if (c >= 16) encodeTree(rc, m.high, highTreeSymbol(c));
  if (c >= 31) raw.write(c - 31, 5);
  const int bits = rawBitsOfClass(c);
  const uint64_t low = mag & ((uint64_t(1) << (bits - 1)) - 1);  // empty below class 4
  raw.write(uint32_t((uint64_t(v < 0) << (bits - 1)) | low), bits);
}

// Classes of 16 and more (|v| >= 256), rare enough to go out of line.
__attribute__((noinline)) inline uint32_t decodeHighClass(RangeDecoder& rc, RawBitReader& raw,
                                                          ClassedIntegerModel& m) {
  const uint32_t c = 16 + decodeTree(rc, m.high);
  if (c < 31) return c;
  const uint32_t top = 31 + raw.read(5);
  return top < kMaxMagnitudeClass ? top : kMaxMagnitudeClass;  // a damaged stream's class
}

inline int64_t decodeClassed(RangeDecoder& rc, RawBitReader& raw, ClassedIntegerModel& m) {
  if (!rc.decode(m.zero)) return 0;
  uint32_t c = 1 + decodeTree(rc, m.low);
  if (c == 16) c = decodeHighClass(rc, raw, m);
  const int bits = rawBitsOfClass(c);
  const uint32_t r = raw.read(bits);
  const int64_t mag = int64_t(magnitudeOf(c, r & ((1u << (bits - 1)) - 1)));
  const int64_t negative = -int64_t(r >> (bits - 1));  // all ones or zero: no branch
  return (mag ^ negative) - negative;
}

// Estimated bits of coding v (rate decisions).
template <int kBits>
double treeCost(const BitTreeModel<kBits>& m, uint32_t symbol) {
  double bits = 0;
  uint32_t node = 1;
  for (int i = kBits - 1; i >= 0; --i) {
    const int bit = int((symbol >> i) & 1);
    bits += bitCost(m.node[node], bit);
    node = node * 2 + uint32_t(bit);
  }
  return bits;
}
inline double classedCost(const ClassedIntegerModel& m, int64_t v) {
  if (v == 0) return bitCost(m.zero, 0);
  const uint32_t c = magnitudeClass(uint64_t(v < 0 ? -v : v));
  double bits = bitCost(m.zero, 1) + treeCost(m.low, lowTreeSymbol(c));
  if (c >= 16) bits += treeCost(m.high, highTreeSymbol(c));
  if (c >= 31) bits += 5;
  return bits + rawBitsOfClass(c);
}

}  // namespace animc
