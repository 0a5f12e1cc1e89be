// SPDX-License-Identifier: Apache-2.0
// Signed integers through the binary range coder: a zero flag, a sign, an Elias-gamma style
// exponent in unary with adaptive bits, the two leading mantissa bits adaptive and the rest
// raw. Small values (the common case after prediction) cost a fraction of a bit.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "entropy/range_coder.h"

namespace animc {

constexpr int kMaxExponent = 32;  // |v| < 2^32, so a corrupt stream cannot loop or overflow

template <int kContexts>
struct IntegerModel {
  BitModel zero[kContexts];
  BitModel sign[kContexts];
  BitModel exponent[kContexts][kMaxExponent];
  BitModel mantissa[kMaxExponent][4];  // leading two bits, as a 2-level bit tree
};

template <class Model>
void encodeInt(RangeEncoder& rc, Model& m, int ctx, int64_t v) {
  rc.encode(m.zero[ctx], v != 0);
  if (v == 0) return;
  rc.encode(m.sign[ctx], v < 0);
  const uint64_t mag = uint64_t(v < 0 ? -v : v);  // >= 1
  int e = 63 - __builtin_clzll(mag);               // mag in [2^e, 2^(e+1))
  for (int i = 0; i < e; ++i) rc.encode(m.exponent[ctx][i], 1);
  if (e < kMaxExponent - 1) rc.encode(m.exponent[ctx][e], 0);
  int left = e;
  int node = 1;
  for (int i = 0; i < 2 && left > 0; ++i) {
    const int bit = int((mag >> (left - 1)) & 1);
    rc.encode(m.mantissa[e][node], bit);
    node = node * 2 + bit;
    --left;
  }
  if (left > 0) rc.encodeRaw(uint32_t(mag & ((uint64_t(1) << left) - 1)), left);
}

// The rest of a non-zero value.
template <class Model>
inline int64_t decodeMagnitudeAndSign(RangeDecoder& rc, Model& m, int ctx) {
  const bool negative = rc.decodeData(m.sign[ctx]);
  int e = 0;
  while (e < kMaxExponent - 1 && rc.decode(m.exponent[ctx][e])) ++e;
  uint64_t mag = 1;
  int left = e;
  int node = 1;
  for (int i = 0; i < 2 && left > 0; ++i) {
    const int bit = rc.decodeData(m.mantissa[e][node]);
    node = node * 2 + bit;
    mag = (mag << 1) | uint64_t(bit);
    --left;
  }
  if (left > 0) mag = (mag << left) | rc.decodeRaw(left);
  return negative ? -int64_t(mag) : int64_t(mag);
}

// Kept out of line so the common zero case inlines.
template <class Model>
__attribute__((noinline)) int64_t decodeNonZero(RangeDecoder& decoder, Model& m, int ctx) {
  RangeDecoder rc = decoder;  // a local copy the compiler can keep in registers
  const int64_t v = decodeMagnitudeAndSign(rc, m, ctx);
  decoder = rc;
  return v;
}

template <class Model>
inline int64_t decodeInt(RangeDecoder& rc, Model& m, int ctx) {
  if (!rc.decode(m.zero[ctx])) return 0;
  return decodeNonZero(rc, m, ctx);
}

// The same, entirely inline: for a hot loop that keeps a local copy of the decoder, which
// stays in registers only if its address never leaves the loop.
template <class Model>
inline int64_t decodeIntInline(RangeDecoder& rc, Model& m, int ctx) {
  if (!rc.decode(m.zero[ctx])) return 0;
  return decodeMagnitudeAndSign(rc, m, ctx);
}

// Estimated cost in bits of coding bit with model m, without coding it (rate decisions):
// -log2(p) from a table over the probability's top 10 bits, so estimates cost no libm call.
struct BitCostTable {
  float bits[1025];
  BitCostTable() {
    for (int i = 0; i <= 1024; ++i) bits[i] = float(-std::log2((i + 0.5) / 1025.0));
  }
};
// Built before main(), not as a function's static: that one's guard would be tested on
// every call of this hot function.
inline const BitCostTable kBitCostTable;
inline double bitCost(const BitModel& m, int bit) {
  const uint32_t p = bit ? kProbOne - m.p0 : m.p0;
  return kBitCostTable.bits[p >> (kProbBits - 10)];
}

template <class Model>
__attribute__((noinline)) double nonZeroCost(const Model& m, int ctx, int64_t v) {
  const uint64_t mag = uint64_t(v < 0 ? -v : v);
  const int e = 63 - __builtin_clzll(mag);
  double bits = bitCost(m.zero[ctx], 1) + 1.0;  // zero flag, sign
  for (int i = 0; i < e; ++i) bits += bitCost(m.exponent[ctx][i], 1);
  if (e < kMaxExponent - 1) bits += bitCost(m.exponent[ctx][e], 0);
  return bits + e;  // mantissa bits counted as raw
}

// Zero, by far the most common value after prediction, is costed inline.
template <class Model>
inline double intCost(const Model& m, int ctx, int64_t v) {
  return v == 0 ? bitCost(m.zero[ctx], 0) : nonZeroCost(m, ctx, v);
}

}  // namespace animc
