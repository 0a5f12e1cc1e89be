// SPDX-License-Identifier: Apache-2.0
// Writes an .ams file as frames arrive (memory O(one frame group's bookkeeping), not O(file)):
// header and CONN first, one GRUP section per frame group streamed to disk, then INDX and END.
// The sink commits only when finish() succeeds (a file sink: nothing appears at its path before).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <memory>
#include "codecs/codec_ids.h"
#include "core/sequence.h"
#include "core/status.h"

namespace animc {

// File_Header's version and HEAD's fields.
struct ContainerHeader {
  uint16_t format_version = 1;  // formatVersionFor() the CONN written
  CodecId codec = CodecId::kAffineOctree;
  std::vector<uint8_t> codec_params;  // serialised by the codec's options
  uint32_t vertex_count = 0;
  uint64_t triangle_count = 0;
  double frame_rate = 25.0;
  uint32_t iframe_interval = 0;
};

class ContainerWriter {
 public:
  // Writes File_Header and HEAD; CONN follows with addConnectivity(), before the first frame.
  Status open(std::unique_ptr<ByteSink> sink, const ContainerHeader& header);
  // The CONN section of coded connectivity (encodeConnectivity()).
  Status addConnectivity(const std::vector<uint8_t>& coded);
  // Opens with File_Header, HEAD and CONN as another file holds them (`start`, its bytes up to
  // its first GRUP), for a file joined from parts.
  Status openCopy(std::unique_ptr<ByteSink> sink, const std::vector<uint8_t>& start);
  // Appends one coded frame; intra frames start a new GRUP section.
  Status addFrame(const std::vector<uint8_t>& payload, bool intra);
  // Appends a whole GRUP section of another file holding frame_count frames (its CRC stays
  // valid: First_Frame, rewritten here, is outside it).
  Status addGroupSection(std::vector<uint8_t> section, uint32_t frame_count);
  Status finish();

  // Bytes so far; after finish(), the size of the file.
  uint64_t bytesWritten() const { return sink_ ? sink_->tell() : final_bytes_; }

 private:
  Status writeSection(const char* tag, const std::vector<uint8_t>& payload);
  Status closeGroup();
  Status put(const void* data, size_t size, bool in_crc);

  std::unique_ptr<ByteSink> sink_;
  uint64_t frames_ = 0;
  struct GroupEntry {
    uint64_t offset, first_frame;
  };
  std::vector<GroupEntry> groups_;
  bool group_open_ = false;
  uint32_t group_frames_ = 0;
  uint32_t group_crc_ = 0;
  uint64_t final_bytes_ = 0;
};

}  // namespace animc
