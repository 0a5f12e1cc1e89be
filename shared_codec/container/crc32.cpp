// SPDX-License-Identifier: Apache-2.0
#include "container/crc32.h"

#include <array>

namespace animc {
namespace {

// Eight tables, one byte of an 8-byte word each, so that the loop takes eight bytes a step
// (every frame group is checked in full before it is decoded). Plain C++, so that the WASM
// decoder (web/) computes it with the native one's code.
using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr uint32_t kPolynomial = 0xEDB88320u;

Tables makeTables() {
  Tables t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int bit = 0; bit < 8; ++bit) c = (c >> 1) ^ (kPolynomial & (0u - (c & 1u)));
    t[0][i] = c;
  }
  for (uint32_t i = 0; i < 256; ++i)
    for (size_t k = 1; k < 8; ++k) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFF];
  return t;
}

const Tables& tables() {
  static const Tables t = makeTables();
  return t;
}

}  // namespace

uint32_t crc32Update(uint32_t crc, const uint8_t* data, size_t size) {
  const Tables& t = tables();
  uint32_t c = ~crc;
  for (; size >= 8; size -= 8, data += 8) {
    const uint32_t low = c ^ (uint32_t(data[0]) | uint32_t(data[1]) << 8 | uint32_t(data[2]) << 16 |
                              uint32_t(data[3]) << 24);
    c = t[7][low & 0xFF] ^ t[6][(low >> 8) & 0xFF] ^ t[5][(low >> 16) & 0xFF] ^ t[4][low >> 24] ^
        t[3][data[4]] ^ t[2][data[5]] ^ t[1][data[6]] ^ t[0][data[7]];
  }
  for (; size > 0; --size, ++data) c = (c >> 8) ^ t[0][(c ^ *data) & 0xFF];
  return ~c;
}

}  // namespace animc
