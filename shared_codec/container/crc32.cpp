// SPDX-License-Identifier: Apache-2.0
#include "container/crc32.h"

#include <lzma.h>

namespace animc {

// liblzma's CRC-32 is the same one (polynomial, pre- and post-inversion) and processes several
// bytes per step; the library links liblzma anyway, and every frame group is checked in full
// before it is decoded.
uint32_t crc32Update(uint32_t crc, const uint8_t* data, size_t size) { return lzma_crc32(data, size, crc); }

}  // namespace animc
