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

template <int kBits>
uint32_t decodeTree(RangeDecoder& rc, BitTreeModel<kBits>& m) {
  uint32_t node = 1;
  for (int i = 0; i < kBits; ++i) node = node * 2 + uint32_t(rc.decode(m.node[node]));
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
