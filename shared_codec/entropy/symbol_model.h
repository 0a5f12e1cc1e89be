// SPDX-License-Identifier: Apache-2.0
// Adaptive 16-symbol distributions for the range coder: one coding step per symbol, where a
// 4-level bit tree takes four (each with its own multiplication, comparison and model update).
// The decoder finds the symbol with one division and two 8-lane comparisons, and adapts all
// sixteen cumulative frequencies at once with vector arithmetic.
//
// Symbol s spans [start[s], start[s + 1]) of 2^15. After coding s, every start at or below s
// moves towards its floor and every start above it towards its ceiling, by a fraction
// 2^-rate of the distance (the multi-symbol form of BitModel's update). The floor of start[i]
// is i and its ceiling 2^15 - 16 + i, so no symbol's span falls below 1/2^15 and the starts
// stay in increasing order.
#pragma once
#include <cmath>
#include <cstdint>

#include "entropy/range_coder.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace animc {

constexpr int kSymbols = 16;
constexpr uint32_t kSymbolCeiling = kProbOne - kSymbols;  // start[i] <= kSymbolCeiling + i

struct SymbolModel {
  // start[0] = 0 and start[16] = 2^15 never change.
  uint16_t start[kSymbols + 1];
  // Not uint8_t, for BitModel::seen's reason.
  uint16_t seen = 0;

  // Every symbol equally likely.
  SymbolModel() {
    for (int i = 0; i <= kSymbols; ++i) start[i] = uint16_t(i * (kProbOne / kSymbols));
  }

  // Lane k holds start[k + 1], which moves towards k + 1, or k + 1 + kSymbolCeiling above the
  // symbol. The sums and differences are taken modulo 2^16 and the differences read as
  // signed: they lie within ±(2^15 - 1), so that is exact.
  void update(uint32_t symbol) {
    const int rate = nextAdaptationShift(seen);
#if defined(__SSE2__)
    // In intrinsics: from vector extensions GCC compared the constant lane indices with the
    // symbol one lane at a time, with scalar instructions, where it inlined the update into
    // the trajectory decoder.
    const __m128i s = _mm_set1_epi16(int16_t(symbol)), ceiling = _mm_set1_epi16(int16_t(kSymbolCeiling));
    const __m128i shift = _mm_cvtsi32_si128(rate);
    const __m128i index[2] = {_mm_setr_epi16(1, 2, 3, 4, 5, 6, 7, 8), _mm_setr_epi16(9, 10, 11, 12, 13, 14, 15, 16)};
    for (int half = 0; half < 2; ++half) {
      __m128i* at = reinterpret_cast<__m128i*>(&start[1 + 8 * half]);
      const __m128i lanes = _mm_loadu_si128(at);
      const __m128i target = _mm_add_epi16(index[half], _mm_and_si128(_mm_cmpgt_epi16(index[half], s), ceiling));
      _mm_storeu_si128(at, _mm_add_epi16(lanes, _mm_sra_epi16(_mm_sub_epi16(target, lanes), shift)));
    }
#else
    typedef uint16_t Lanes __attribute__((vector_size(32), aligned(2)));
    typedef int16_t SignedLanes __attribute__((vector_size(32), aligned(2)));
    const SignedLanes index = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    const Lanes above = Lanes(index > int16_t(symbol)) & uint16_t(kSymbolCeiling);
    Lanes& lanes = *reinterpret_cast<Lanes*>(&start[1]);
    const Lanes distance = (Lanes(index) + above) - lanes;
    lanes += Lanes(SignedLanes(distance) >> rate);
#endif
  }

  // The symbol whose span holds `target` (< 2^15): the number of starts 1..15 at or below it.
  uint32_t find(uint32_t target) const {
#if defined(__SSE2__)
    // start[16] = 2^15 reads as negative in the signed comparison: its lane is masked off.
    const __m128i t = _mm_set1_epi16(int16_t(target));
    const __m128i low = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&start[1]));
    const __m128i high = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&start[9]));
    const uint32_t above = uint32_t(_mm_movemask_epi8(_mm_cmpgt_epi16(low, t))) |
                           uint32_t(_mm_movemask_epi8(_mm_cmpgt_epi16(high, t))) << 16;
    // The starts increase, so the lanes at or below target come first: two mask bits each.
    const uint32_t at_or_below = ~above & 0x3FFFFFFFu;
    return uint32_t(__builtin_ctz(at_or_below + 1)) >> 1;
#else
    uint32_t symbol = 0;
    for (int i = 1; i < kSymbols; ++i) symbol += start[i] <= target;
    return symbol;
#endif
  }
};

// Estimated bits of coding a symbol (rate decisions): -log2 of its span's share, to within
// 0.01 bits, as whole bits from the leading one's position plus a table over the 8 bits
// below it. (Spans get far narrower than BitModel's probabilities, below which the table of
// bitCost() is coarse.)
struct SpanCostTable {
  float log2_mantissa[256];
  SpanCostTable() {
    for (int i = 0; i < 256; ++i) log2_mantissa[i] = float(std::log2(1.0 + (i + 0.5) / 256.0));
  }
};
inline const SpanCostTable kSpanCostTable;  // before main(), as kBitCostTable
inline double symbolCost(const SymbolModel& m, uint32_t symbol) {
  const uint32_t span = uint32_t(m.start[symbol + 1] - m.start[symbol]);  // 1 .. 2^15
  const int e = 31 - __builtin_clz(span);
  const uint32_t mantissa = ((span << 8) >> e) & 255;  // the 8 bits below the leading one
  return double(kProbBits - e) - double(kSpanCostTable.log2_mantissa[mantissa]);
}

inline void encodeSymbol(RangeEncoder& rc, SymbolModel& m, uint32_t symbol) {
  rc.encodeSpan(m.start[symbol], m.start[symbol + 1]);
  m.update(symbol);
}

// Always inlined, for decodeTree()'s reason (bit_tree.h).
__attribute__((always_inline)) inline uint32_t decodeSymbol(RangeDecoder& decoder, SymbolModel& m) {
  RangeDecoder rc = decoder;
  const uint32_t symbol = m.find(rc.spanTarget());
  rc.decodeSpan(m.start[symbol], m.start[symbol + 1]);
  m.update(symbol);
  decoder = rc;
  return symbol;
}

}  // namespace animc
