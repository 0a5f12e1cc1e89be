// SPDX-License-Identifier: Apache-2.0
// Reads an .ams file without trusting it: every count, offset and length is checked against
// the file size and DecoderLimits before anything is allocated, and every section's CRC is
// verified before its content is used. Frame groups are read one frame at a time, so memory
// stays O(largest frame) whatever the file size.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "container/container_writer.h"
#include "container/format.h"
#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_source.h"

namespace animc {

struct SectionInfo {
  std::string tag;
  uint64_t offset = 0;  // of the tag
  uint64_t payload_bytes = 0;
};

struct ContainerInfo {
  uint16_t format_version = 0;
  ContainerHeader header;
  uint64_t frame_count = 0;
  uint64_t file_bytes = 0;
  // Header, HEAD, CONN and the first frame (only up to the first GRUP for a codec that codes
  // whole groups, whose first frame carries a group's motion): what motion does not pay.
  uint64_t static_bytes = 0;
  std::vector<SectionInfo> sections;  // HEAD, CONN, each GRUP, INDX, END in file order

  uint64_t groupCount() const {
    uint64_t groups = 0;
    for (const SectionInfo& section : sections) groups += section.tag == kTagGroup;
    return groups;
  }
};

class ContainerReader {
 public:
  ~ContainerReader();
  static Result<std::unique_ptr<ContainerReader>> open(const std::string& path, const DecoderLimits& limits = {});
  // `name` stands for the source in messages.
  static Result<std::unique_ptr<ContainerReader>> open(std::unique_ptr<ByteSource> source, const std::string& name,
                                                       const DecoderLimits& limits);

  const ContainerInfo& info() const { return info_; }
  const Topology& topology() const { return topology_; }
  size_t groupCount() const { return groups_.size(); }
  size_t groupOf(uint64_t frame) const;
  uint64_t groupFirstFrame(size_t group) const { return groups_[group].first_frame; }

  // Verifies group g's CRC and makes nextFrame() return its frames in order. The group whose
  // CRC was verified last is not read again for it: a random access goes back into the same
  // group again and again, and the source's bytes do not change (byte_source.h).
  Status beginGroup(size_t group);
  // The file's bytes before its first GRUP (File_Header, HEAD, CONN), as stored.
  Result<std::vector<uint8_t>> startBytes();
  // Group g's whole GRUP section as stored, its CRC and frame numbers verified first.
  Result<std::vector<uint8_t>> groupSection(size_t group);
  uint64_t groupFrameCount(size_t group) const {
    return (group + 1 < groups_.size() ? groups_[group + 1].first_frame : info_.frame_count) -
           groups_[group].first_frame;
  }
  // The next frame's payload of the current group; false after its last frame.
  Result<bool> nextFrame(std::vector<uint8_t>& payload);
  // The first byte of group g's first frame payload, the group's header checked but not its
  // CRC (a caller that needs that has checked the group already); the cursor does not move.
  Result<uint8_t> firstPayloadByte(size_t group);

 private:
  ContainerReader() = default;
  Status readAt(uint64_t offset, void* out, size_t size, const char* what);
  Result<std::vector<uint8_t>> readSection(uint64_t offset, const char* tag, uint64_t max_bytes);
  Status openHeader();
  Status openIndex(uint64_t conn_end);
  Status measureFirstFrame();
  // Group g's header against the index (tag, length, frame numbers): its frame records' bytes.
  Status checkGroupHead(size_t group, uint64_t& frames_begin, uint64_t& frames_end);
  // Group g's CRC over its frame records' bytes [frames_begin, frames_end).
  Status verifyGroupCrc(size_t group, uint64_t frames_begin, uint64_t frames_end);
  // The length of the frame record at `position` (before frames_end), its payload's start.
  Result<uint64_t> frameRecord(uint64_t position, uint64_t frames_end, uint64_t& payload_start);

  struct Group {
    uint64_t offset, first_frame, end;  // end: offset of whatever follows the section
  };
  std::unique_ptr<ByteSource> source_;
  DecoderLimits limits_;
  ContainerInfo info_;
  Topology topology_;
  std::vector<Group> groups_;
  // Current group cursor.
  uint64_t cursor_ = 0, frames_end_ = 0, frames_left_ = 0;
  size_t verified_group_ = SIZE_MAX;  // the group whose CRC beginGroup() verified last
};

}  // namespace animc
