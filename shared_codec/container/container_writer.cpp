// SPDX-License-Identifier: Apache-2.0
#include "container/container_writer.h"

#include "container/crc32.h"
#include "container/format.h"
#include "io/byte_writer.h"

namespace animc {

Status ContainerWriter::put(const void* data, size_t size, bool in_crc) {
  if (in_crc) group_crc_ = crc32Update(group_crc_, static_cast<const uint8_t*>(data), size);
  return sink_->write(data, size);
}

// The payload goes to the sink as it is, between its tag and length and its CRC: a large one
// (a mesh's connectivity) is not copied into a fresh buffer first.
Status ContainerWriter::writeSection(const char* tag, const std::vector<uint8_t>& payload) {
  ByteWriter head, tail;
  head.append(reinterpret_cast<const uint8_t*>(tag), 4);
  head.u64(payload.size());
  tail.u32(crc32Update(0, payload.data(), payload.size()));
  ANIMC_RETURN_IF_ERROR(sink_->write(head.bytes().data(), head.size()));
  ANIMC_RETURN_IF_ERROR(sink_->write(payload.data(), payload.size()));
  return sink_->write(tail.bytes().data(), tail.size());
}

Status ContainerWriter::open(std::unique_ptr<ByteSink> sink, const ContainerHeader& header) {
  if (sink_) return invalidArgument("the container writer is already open");
  sink_ = std::move(sink);
  ByteWriter start;
  start.append(kMagic, 4);
  start.u16(header.format_version);
  start.u16(0);
  ANIMC_RETURN_IF_ERROR(sink_->write(start.bytes().data(), start.size()));
  ByteWriter head;
  head.u8(uint8_t(header.codec));
  head.varint(header.codec_params.size());
  head.append(header.codec_params);
  head.u32(header.vertex_count);
  head.u64(header.triangle_count);
  head.f64(header.frame_rate);
  head.u32(header.iframe_interval);
  return writeSection(kTagHead, head.bytes());
}

Status ContainerWriter::addConnectivity(const std::vector<uint8_t>& coded) {
  if (!sink_) return invalidArgument("the container writer is not open");
  return writeSection(kTagConnectivity, coded);
}

Status ContainerWriter::openCopy(std::unique_ptr<ByteSink> sink, const std::vector<uint8_t>& start) {
  if (sink_) return invalidArgument("the container writer is already open");
  sink_ = std::move(sink);
  return sink_->write(start.data(), start.size());
}

Status ContainerWriter::addGroupSection(std::vector<uint8_t> section, uint32_t frame_count) {
  if (!sink_) return invalidArgument("the container writer is not open");
  ANIMC_RETURN_IF_ERROR(closeGroup());
  if (section.size() < kSectionOverhead + kGroupFieldBytes) return invalidArgument("not a GRUP section");
  ByteWriter first;
  first.u64(frames_);
  std::copy(first.bytes().begin(), first.bytes().end(), section.begin() + 12);
  groups_.push_back({sink_->tell(), frames_});
  frames_ += frame_count;
  return sink_->write(section.data(), section.size());
}

Status ContainerWriter::addFrame(const std::vector<uint8_t>& payload, bool intra) {
  if (!sink_) return invalidArgument("the container writer is not open");
  if (!group_open_ && !intra) return invalidArgument("the first frame must be intra");
  if (!intra && group_frames_ == UINT32_MAX)
    return invalidArgument("more than 2^32 - 1 frames in one group: use an I-frame interval");
  if (intra) {
    ANIMC_RETURN_IF_ERROR(closeGroup());
    groups_.push_back({sink_->tell(), frames_});
    // Length and frame count are patched by closeGroup().
    ByteWriter w;
    w.append(reinterpret_cast<const uint8_t*>(kTagGroup), 4);
    w.u64(0);
    ANIMC_RETURN_IF_ERROR(sink_->write(w.bytes().data(), w.size()));
    group_crc_ = 0;
    group_frames_ = 0;
    ByteWriter first;
    first.u64(frames_);
    first.u32(0);
    ANIMC_RETURN_IF_ERROR(put(first.bytes().data(), first.size(), false));
    group_open_ = true;
  }
  ByteWriter len;
  len.varint(payload.size());
  ANIMC_RETURN_IF_ERROR(put(len.bytes().data(), len.size(), true));
  ANIMC_RETURN_IF_ERROR(put(payload.data(), payload.size(), true));
  ++group_frames_;
  ++frames_;
  return Status();
}

Status ContainerWriter::closeGroup() {
  if (!group_open_) return Status();
  const uint64_t start = groups_.back().offset;
  const uint64_t end = sink_->tell();
  // The group's CRC covers its frames; First_Frame and Frame_Count, known only now, are
  // checked against INDX instead (docs/format.md, GRUP).
  ByteWriter fields;
  fields.u64(groups_.back().first_frame);
  fields.u32(group_frames_);
  ByteWriter patch;
  patch.u64(end - start - 12);
  ANIMC_RETURN_IF_ERROR(sink_->seek(start + 4));
  ANIMC_RETURN_IF_ERROR(sink_->write(patch.bytes().data(), patch.size()));
  ANIMC_RETURN_IF_ERROR(sink_->write(fields.bytes().data(), fields.size()));
  ANIMC_RETURN_IF_ERROR(sink_->seek(end));
  ByteWriter crc;
  crc.u32(group_crc_);
  ANIMC_RETURN_IF_ERROR(sink_->write(crc.bytes().data(), crc.size()));
  group_open_ = false;
  return Status();
}

Status ContainerWriter::finish() {
  if (!sink_) return invalidArgument("the container writer is not open");
  if (frames_ == 0) return invalidArgument("no frames to write");
  ANIMC_RETURN_IF_ERROR(closeGroup());
  const uint64_t index_offset = sink_->tell();
  ByteWriter index;
  index.u64(frames_);
  index.u32(uint32_t(groups_.size()));
  for (const GroupEntry& g : groups_) {
    index.u64(g.offset);
    index.u64(g.first_frame);
  }
  ANIMC_RETURN_IF_ERROR(writeSection(kTagIndex, index.bytes()));
  ByteWriter end;
  end.u64(index_offset);
  ANIMC_RETURN_IF_ERROR(writeSection(kTagEnd, end.bytes()));
  final_bytes_ = sink_->tell();
  ANIMC_RETURN_IF_ERROR(sink_->commit());
  sink_.reset();
  return Status();
}

}  // namespace animc
