// SPDX-License-Identifier: Apache-2.0
#include "codecs/codec_registry.h"

namespace animc {

const std::vector<const CodecEntry*>& allCodecs() {
  // A new codec: one line here, in Codec_Id order, and its options in codec_options.h.
  static const std::vector<const CodecEntry*> codecs = {&kAffineOctreeEntry, &kWaveletEntry, &kTrajectoryEntry,
                                                        &kAutoEntry, &kTrajectory2Entry};
  return codecs;
}

const CodecEntry* findCodec(uint8_t id) {
  for (const CodecEntry* entry : allCodecs())
    if (uint8_t(entry->id) == id) return entry;
  return nullptr;
}

Result<const CodecEntry*> findCodecByName(const std::string& name) {
  std::string names;
  for (const CodecEntry* entry : allCodecs()) {
    if (name == entry->name) return entry;
    names += (names.empty() ? "" : ", ") + std::string(entry->name);
  }
  return invalidArgument("unknown codec '" + name + "' (" + names + ")");
}

const CodecEntry& codecOf(const CodecOptions& options) { return *allCodecs()[options.index()]; }

const char* codecName(CodecId id) {
  const CodecEntry* entry = findCodec(uint8_t(id));
  return entry != nullptr ? entry->name : "unknown";
}

std::string knownCodecList() {
  std::string list;
  for (const CodecEntry* entry : allCodecs())
    list += (list.empty() ? "" : ", ") + std::to_string(int(entry->id)) + " (" + entry->name + ")";
  return list;
}

}  // namespace animc
