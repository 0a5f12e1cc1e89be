// SPDX-License-Identifier: Apache-2.0
// Fixed-width symbols as a binary tree of adaptive bits (most significant bit first), so each
// node learns the distribution of its prefix: the "adaptive arithmetic coder over k-bit
// symbols" of the Affine-Octree paper, without a k-bit frequency table.
#pragma once
#include <cstdint>

#include "entropy/range_coder.h"

namespace animc {

template <int kBits>
struct BitTreeModel {
  BitModel node[1 << kBits];
};

template <int kBits>
void encodeTree(RangeEncoder& rc, BitTreeModel<kBits>& m, uint32_t value) {
  uint32_t node = 1;
  for (int i = kBits - 1; i >= 0; --i) {
    const int bit = int((value >> i) & 1);
    rc.encode(m.node[node], bit);
    node = node * 2 + uint32_t(bit);
  }
}

// Each level's probability is that of a child of the node just decoded: both children's are
// fetched while the bit is decoded and the right one selected after, which keeps the memory
// load off the chain from one bit to the next.
// Always inlined: called out of line, it would take the caller's decoder by address, which
// forces the caller's local copy (see predictive_octree_decoder.cpp) out of registers.
template <int kBits>
__attribute__((always_inline)) inline uint32_t decodeTree(RangeDecoder& decoder, BitTreeModel<kBits>& m) {
  RangeDecoder rc = decoder;  // a local copy the compiler can keep in registers
  uint32_t node = 1;
  uint32_t p0 = m.node[1].p0;
  // Unrolled: a loop exit is a mispredicted branch per tree.
#pragma GCC unroll 8
  for (int i = 0; i < kBits; ++i) {
    const bool inner = i + 1 < kBits;
    const uint32_t p0_left = inner ? m.node[2 * node].p0 : 0;
    const uint32_t p0_right = inner ? m.node[2 * node + 1].p0 : 0;
    const int bit = rc.decodeWithProbability(p0);
    m.node[node].updateData(bit);
    node = node * 2 + uint32_t(bit);
    p0 = bit ? p0_right : p0_left;
  }
  decoder = rc;
  return node - (1u << kBits);
}

// A k-bit value (8 <= k <= 24): top 8 bits through one tree, the next up to 8 through a second,
// anything below raw (those bits are close to uniform noise).
struct WideSymbolModel {
  BitTreeModel<8> high;
  BitTreeModel<8> low;
};

inline void encodeWide(RangeEncoder& rc, WideSymbolModel& m, uint32_t value, int bits) {
  const int low_bits = bits - 8 < 8 ? bits - 8 : 8;
  const int raw_bits = bits - 8 - low_bits;
  encodeTree(rc, m.high, value >> (bits - 8));
  if (low_bits > 0) {
    const uint32_t low = (value >> raw_bits) & ((1u << low_bits) - 1);
    encodeTree(rc, m.low, low << (8 - low_bits));
  }
  if (raw_bits > 0) rc.encodeRaw(value & ((1u << raw_bits) - 1), raw_bits);
}

inline uint32_t decodeWide(RangeDecoder& rc, WideSymbolModel& m, int bits) {
  const int low_bits = bits - 8 < 8 ? bits - 8 : 8;
  const int raw_bits = bits - 8 - low_bits;
  uint32_t value = decodeTree(rc, m.high);
  if (low_bits > 0) value = (value << low_bits) | (decodeTree(rc, m.low) >> (8 - low_bits));
  if (raw_bits > 0) value = (value << raw_bits) | rc.decodeRaw(raw_bits);
  return value;
}

}  // namespace animc
