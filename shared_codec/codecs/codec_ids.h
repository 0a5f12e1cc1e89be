// SPDX-License-Identifier: Apache-2.0
// Every on-wire identifier of the codecs, in one place (docs/format.md mirrors this file).
#pragma once
#include <cstdint>
#include <string>

namespace animc {

enum class CodecId : uint8_t {
  kAffineOctree = 1,
  kWavelet = 2,  // Guskov & Khodakovsky 2004 (docs/wavelet.md)
};

enum class Profile : uint8_t {
  kPaper = 0,    // the Affine-Octree paper as published (docs/affine_octree.md, "paper")
  kDefault = 1,  // our predictive variant of the same octree (docs/affine_octree.md, "default")
};

const char* codecName(CodecId id);  // "affine-octree", "wavelet"
bool isKnownCodec(uint8_t id);
std::string knownCodecList();  // "1 (affine-octree), 2 (wavelet)"
const char* profileName(Profile p);

}  // namespace animc
