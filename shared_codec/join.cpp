// SPDX-License-Identifier: Apache-2.0
// joinStreams (animc/animc.h): the GRUP sections of consecutive parts copied after one HEAD and
// CONN, with their First_Frame numbered anew, then one INDX and END.
#include <cstring>

#include "api.h"
#include "container/container_writer.h"
#include "container/format.h"
#include "io/byte_reader.h"

namespace animc {
namespace {

Result<std::unique_ptr<ContainerReader>> openPart(const StreamPart& part) {
  if (part.data == nullptr) return ContainerReader::open(part.path);
  return ContainerReader::open(memorySource(part.data, part.size), part.path, DecoderLimits());
}

// A section's tag and length at `offset`, or false when those 12 bytes or the whole section do
// not lie in the first `size` bytes.
struct SectionFrame {
  char tag[4];
  uint64_t length;
};
bool sectionAt(const uint8_t* data, size_t size, uint64_t offset, SectionFrame& frame) {
  if (offset > size || size - offset < kSectionOverhead) return false;
  ByteReader r(data + offset + 4, 8);
  std::memcpy(frame.tag, data + offset, 4);
  frame.length = r.u64("Length").value();
  return frame.length <= size - offset - kSectionOverhead;
}
bool hasTag(const SectionFrame& frame, const char* tag) { return std::memcmp(frame.tag, tag, 4) == 0; }

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

Result<uint64_t> wholeGroupsOf(const void* data, size_t size, std::unique_ptr<ByteSink> sink) {
  if (!sink) return invalidArgument("no sink to write to");
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (size >= 4 && std::memcmp(bytes, kMagic, 4) != 0) return corrupt("not an .ams stream (no magic number)");
  SectionFrame frame;
  uint64_t offset = kFileHeaderBytes;
  for (const char* tag : {kTagHead, kTagConnectivity}) {
    if (!sectionAt(bytes, size, offset, frame)) return uint64_t(0);
    if (!hasTag(frame, tag))
      return corrupt(std::string("expected section ") + tag + " at offset " + std::to_string(offset));
    offset += kSectionOverhead + frame.length;
  }
  const uint64_t groups_start = offset;
  // First_Frame and Frame_Count are outside the CRC; the index protects them in a whole file,
  // so here they must add up as the index would have them.
  struct WholeGroup {
    uint64_t begin, end;
    uint32_t frames;
  };
  std::vector<WholeGroup> groups;
  uint64_t frames = 0;
  while (sectionAt(bytes, size, offset, frame) && hasTag(frame, kTagGroup) && frame.length >= kGroupFieldBytes) {
    const uint64_t first = ByteReader(bytes + offset + 12, 8).u64("First_Frame").value();
    const uint32_t count = ByteReader(bytes + offset + 20, 4).u32("Frame_Count").value();
    if (first != frames || count == 0)
      return corrupt("GRUP section at offset " + std::to_string(offset) + ": frames " + std::to_string(first) + " + " +
                     std::to_string(count) + " do not follow the " + std::to_string(frames) + " before");
    frames += count;
    const uint64_t end = offset + kSectionOverhead + frame.length;
    groups.push_back({offset, end, count});
    offset = end;
  }
  if (groups.empty()) return uint64_t(0);
  ContainerWriter writer;
  ANIMC_RETURN_IF_ERROR(writer.openCopy(std::move(sink), std::vector<uint8_t>(bytes, bytes + groups_start)));
  for (const WholeGroup& g : groups)
    ANIMC_RETURN_IF_ERROR(writer.addGroupSection(std::vector<uint8_t>(bytes + g.begin, bytes + g.end), g.frames));
  ANIMC_RETURN_IF_ERROR(writer.finish());
  return frames;
}

}  // namespace animc
