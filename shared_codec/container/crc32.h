// SPDX-License-Identifier: Apache-2.0
// CRC-32 (IEEE 802.3, reflected, as in zlib and PNG) of each container section.
#pragma once
#include <cstddef>
#include <cstdint>

namespace animc {

// Continue a CRC: crc32Update(crc32Update(0, a), b) == CRC of a followed by b.
uint32_t crc32Update(uint32_t crc, const uint8_t* data, size_t size);

}  // namespace animc
