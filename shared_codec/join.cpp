// SPDX-License-Identifier: Apache-2.0
// joinStreams (animc/animc.h): the GRUP sections of consecutive parts copied after one HEAD and
// CONN, with their First_Frame numbered anew, then one INDX and END.
#include "api.h"
#include "container/container_writer.h"

namespace animc {
namespace {

Result<std::unique_ptr<ContainerReader>> openPart(const StreamPart& part) {
  if (part.data == nullptr) return ContainerReader::open(part.path);
  return ContainerReader::open(memorySource(part.data, part.size), part.path, DecoderLimits());
}

}  // namespace

Result<uint64_t> joinStreams(const std::vector<StreamPart>& parts, std::unique_ptr<ByteSink> sink) {
  if (parts.empty()) return invalidArgument("join: no parts to join");
  if (!sink) return invalidArgument("join: no sink to write to");
  ContainerWriter writer;
  std::vector<uint8_t> start;
  uint64_t frames = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& name = parts[i].path;
    ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ContainerReader> reader, openPart(parts[i]));
    auto bytes = reader->startBytes();
    if (!bytes.ok()) return bytes.status().withContext(name);
    if (i == 0) {
      start = std::move(bytes).value();
      ANIMC_RETURN_IF_ERROR(writer.openCopy(std::move(sink), start));
    } else if (bytes.value() != start) {
      return invalidArgument(name + ": its codec settings, I-frame interval, mesh or frame rate differ from " +
                             parts[0].path + "'s; parts to join must be encoded with the same ones");
    }
    frames += reader->info().frame_count;
    if (frames > DecoderLimits().max_frames)
      return invalidArgument("join: more than " + std::to_string(DecoderLimits().max_frames) +
                             " frames, above what decoders accept");
    for (size_t g = 0; g < reader->groupCount(); ++g) {
      auto section = reader->groupSection(g);
      if (!section.ok()) return section.status().withContext(name);
      ANIMC_RETURN_IF_ERROR(writer.addGroupSection(std::move(section).value(), uint32_t(reader->groupFrameCount(g))));
    }
  }
  ANIMC_RETURN_IF_ERROR(writer.finish());
  return frames;
}

}  // namespace animc
