// SPDX-License-Identifier: Apache-2.0
#include "codecs/codec_ids.h"

namespace animc {

const char* codecName(CodecId id) {
  switch (id) {
    case CodecId::kAffineOctree: return "affine-octree";
    case CodecId::kWavelet: return "wavelet";
  }
  return "unknown";
}

bool isKnownCodec(uint8_t id) {
  return id == uint8_t(CodecId::kAffineOctree) || id == uint8_t(CodecId::kWavelet);
}

std::string knownCodecList() {
  std::string list;
  for (CodecId id : {CodecId::kAffineOctree, CodecId::kWavelet})
    list += (list.empty() ? "" : ", ") + std::to_string(int(id)) + " (" + codecName(id) + ")";
  return list;
}

const char* profileName(Profile p) {
  switch (p) {
    case Profile::kPaper: return "paper";
    case Profile::kDefault: return "default";
  }
  return "unknown";
}

}  // namespace animc
