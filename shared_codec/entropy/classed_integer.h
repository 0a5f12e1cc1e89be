// SPDX-License-Identifier: Apache-2.0
// Signed integers as a zero flag, a magnitude class through adaptive 16-symbol models
// (symbol_model.h), and the sign and the class's low bits raw, in the raw-bit stream
// (raw_bits.h). After the zero flag the range coder takes one step per value, not a branch on
// the data, where the unary exponent of integer_coder.h mispredicts about once per value and
// its sign and low bits lengthen the coder's serial chain. Meant for values that are often
// nonzero and spread over many magnitudes (the default profile's affine corrections);
// mostly-zero values stay with integer_coder.h.
//
// Classes of |v| >= 1: |v| itself below 4; above, 2e + m with e the position of the leading 1
// and m the bit below it ([4,6) is class 4, [6,8) class 5, [8,12) class 6, ...). Classes
// 1..15 are symbols 0..14 of the Low model, whose symbol 15 escapes to the High model for
// classes 16..30, whose symbol 15 escapes to 5 raw bits for classes 31 to kMaxMagnitudeClass.
// (The zero flag stays a bit of its own: folded into the Low model as a 16th class, it made
// decoding a little faster but cost more bits at coarse errors, where half the values are
// zero and the classes of the others were then learnt from half as many of them;
// docs/notes/affine_octree_history.md has the figures.)
#pragma once
#include <cstdint>

#include "entropy/integer_coder.h"
#include "entropy/range_coder.h"
#include "entropy/raw_bits.h"
#include "entropy/symbol_model.h"

namespace animc {

constexpr uint32_t kMaxMagnitudeClass = 2 * 30 + 1;  // |v| < 2^31

struct ClassedIntegerModel {
  BitModel zero;
  SymbolModel low;   // classes 1..15, then the escape
  SymbolModel high;  // classes 16..30, then the escape
};

inline uint32_t magnitudeClass(uint64_t mag) {
  if (mag < 4) return uint32_t(mag);
  const int e = 63 - __builtin_clzll(mag);
  return uint32_t(2 * e) + uint32_t((mag >> (e - 1)) & 1);
}
// Raw bits of a class >= 1: the sign, then the low bits: none below class 4, above it the
// e - 1 bits below the two leading ones.
inline int lowBitsOfClass(uint32_t c) { return c < 4 ? 0 : int(c >> 1) - 1; }
inline int rawBitsOfClass(uint32_t c) { return 1 + lowBitsOfClass(c); }
inline uint64_t magnitudeOf(uint32_t c, uint64_t low) {
  return c < 4 ? c : (uint64_t(2 | (c & 1)) << ((c >> 1) - 1)) | low;
}
// The symbols a class >= 1 is coded with in the Low model and, from class 16, the High model;
// each model's last symbol is its escape.
constexpr uint32_t kEscape = kSymbols - 1;
constexpr uint32_t kFirstHighClass = 1 + kEscape;              // 16
constexpr uint32_t kFirstRawClass = kFirstHighClass + kEscape;  // 31
inline uint32_t lowSymbol(uint32_t c) { return c < kFirstHighClass ? c - 1 : kEscape; }
inline uint32_t highSymbol(uint32_t c) { return c < kFirstRawClass ? c - kFirstHighClass : kEscape; }

inline void encodeClassed(RangeEncoder& rc, RawBitWriter& raw, ClassedIntegerModel& m, int64_t v) {
  rc.encode(m.zero, v != 0);
  if (v == 0) return;
  const uint64_t mag = uint64_t(v < 0 ? -v : v);
  const uint32_t c = magnitudeClass(mag);
  encodeSymbol(rc, m.low, lowSymbol(c));
  if (c >= kFirstHighClass) encodeSymbol(rc, m.high, highSymbol(c));
  if (c >= kFirstRawClass) raw.write(c - kFirstRawClass, 5);
  const int low_bits = lowBitsOfClass(c);
  const uint64_t low = mag & ((uint64_t(1) << low_bits) - 1);
  raw.write(uint32_t((uint64_t(v < 0) << low_bits) | low), rawBitsOfClass(c));
}

// Classes of 16 and more (|v| >= 256). Rare, but inlined all the same: a call would take
// the caller's decoders by address and so keep them out of registers (bit_tree.h).
__attribute__((always_inline)) inline uint32_t decodeHighClass(RangeDecoder& rc, RawBitReader& raw,
                                                          ClassedIntegerModel& m) {
  const uint32_t c = kFirstHighClass + decodeSymbol(rc, m.high);
  if (c < kFirstRawClass) return c;
  const uint32_t top = kFirstRawClass + raw.read(5);
  return top < kMaxMagnitudeClass ? top : kMaxMagnitudeClass;  // a damaged stream's class
}

// Always inlined, for decodeHighClass()'s reason.
__attribute__((always_inline)) inline int64_t decodeClassed(RangeDecoder& rc, RawBitReader& raw,
                                                            ClassedIntegerModel& m) {
  if (!rc.decode(m.zero)) return 0;
  uint32_t c = 1 + decodeSymbol(rc, m.low);
  if (c == kFirstHighClass) c = decodeHighClass(rc, raw, m);
  const int low_bits = lowBitsOfClass(c);
  const uint32_t r = raw.read(rawBitsOfClass(c));
  const int64_t mag = int64_t(magnitudeOf(c, r & ((1u << low_bits) - 1)));
  const int64_t negative = -int64_t(r >> low_bits);  // all ones or zero: no branch
  return (mag ^ negative) - negative;
}

// Estimated bits of coding v (rate decisions).
inline double classedCost(const ClassedIntegerModel& m, int64_t v) {
  if (v == 0) return bitCost(m.zero, 0);
  const uint32_t c = magnitudeClass(uint64_t(v < 0 ? -v : v));
  double bits = bitCost(m.zero, 1) + symbolCost(m.low, lowSymbol(c));
  if (c >= kFirstHighClass) bits += symbolCost(m.high, highSymbol(c));
  if (c >= kFirstRawClass) bits += 5;
  return bits + rawBitsOfClass(c);
}

}  // namespace animc
