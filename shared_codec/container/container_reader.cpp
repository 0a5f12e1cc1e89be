// SPDX-License-Identifier: Apache-2.0
#include "container/container_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "codecs/codec_registry.h"
#include "container/connectivity_coder.h"
#include "container/crc32.h"
#include "io/byte_reader.h"

namespace animc {
namespace {

constexpr uint64_t kMaxHeadBytes = 1 << 16;
// CONN has no maximum of its own (docs/format.md section 5): only the file size bounds it, and
// a Length past the end of the file is a cut file (rule 4), not a section too large.
constexpr uint64_t kNoMaximum = UINT64_MAX;

std::string at(uint64_t offset) { return " at byte " + std::to_string(offset); }

}  // namespace

ContainerReader::~ContainerReader() = default;

Status ContainerReader::readAt(uint64_t offset, void* out, size_t size, const char* what) {
  if (offset > info_.file_bytes || size > info_.file_bytes - offset)
    return truncated(std::string(what) + at(offset) + ": file ends early");
  // No name here: callers add it (open() and the decoder), so it is named once.
  return source_->readAt(offset, out, size);
}

Result<std::vector<uint8_t>> ContainerReader::readSection(uint64_t offset, const char* tag, uint64_t max_bytes) {
  uint8_t head[12];
  ANIMC_RETURN_IF_ERROR(readAt(offset, head, 12, tag));
  if (std::memcmp(head, tag, 4) != 0) {
    const std::string name = std::string(tag, tag[3] == ' ' ? 3 : 4);
    // END is looked for in the last 24 bytes: not finding it usually means a cut file.
    if (std::strcmp(tag, kTagEnd) == 0)
      return truncated("no END section in the last 24 bytes: the file is truncated or unfinished");
    return corrupt("expected section " + name + at(offset));
  }
  ByteReader r(head + 4, 8, offset + 4);
  ANIMC_ASSIGN_OR_RETURN(uint64_t length, r.u64("Section_Length"));
  // Rules 3 and 4 of docs/format.md section 5, in that order. The 12 bytes just read lie in
  // the file, so `room` >= 12; Length may be any u64, so nothing is added to it.
  if (length > max_bytes) return limitExceeded(std::string(tag) + " section too large" + at(offset));
  const uint64_t room = info_.file_bytes - offset;
  if (room < kSectionOverhead || length > room - kSectionOverhead)
    return truncated(std::string(tag) + " section" + at(offset) + " runs past the end of the file (truncated)");
  std::vector<uint8_t> payload(length + 4);
  ANIMC_RETURN_IF_ERROR(readAt(offset + 12, payload.data(), payload.size(), tag));
  ByteReader crc_reader(payload.data() + length, 4, offset + 12 + length);
  ANIMC_ASSIGN_OR_RETURN(uint32_t crc, crc_reader.u32("Section_CRC"));
  if (crc != crc32Update(0, payload.data(), length))
    return corrupt(std::string(tag) + " section" + at(offset) + ": CRC mismatch");
  payload.resize(length);
  info_.sections.push_back({tag, offset, length});
  return payload;
}

Result<std::unique_ptr<ContainerReader>> ContainerReader::open(const std::string& path, const DecoderLimits& limits) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ByteSource> source, openFileSource(path));
  return open(std::move(source), path, limits);
}

Result<std::unique_ptr<ContainerReader>> ContainerReader::open(std::unique_ptr<ByteSource> source,
                                                               const std::string& name, const DecoderLimits& limits) {
  std::unique_ptr<ContainerReader> r(new ContainerReader());
  r->limits_ = limits;
  r->source_ = std::move(source);
  r->info_.file_bytes = r->source_->size();
  Status s = r->openHeader();
  if (!s.ok()) return s.withContext(name);
  return r;
}

Status ContainerReader::openHeader() {
  uint8_t start[kFileHeaderBytes];
  if (info_.file_bytes < kFileHeaderBytes + kEndSectionBytes)
    return truncated("file truncated or not an .ams file: " + std::to_string(info_.file_bytes) +
                     " bytes, the smallest .ams file has " + std::to_string(kFileHeaderBytes + kEndSectionBytes));
  ANIMC_RETURN_IF_ERROR(readAt(0, start, sizeof start, "File_Header"));
  if (std::memcmp(start, kMagic, 4) != 0) return corrupt("not an .ams file (bad magic)");
  ByteReader h(start + 4, 4, 4);
  ANIMC_ASSIGN_OR_RETURN(info_.format_version, h.u16("Format_Version"));
  ANIMC_ASSIGN_OR_RETURN(uint16_t reserved, h.u16("Reserved"));
  if (info_.format_version == 0 || info_.format_version > kNewestFormatVersion)
    return unsupported("format version " + std::to_string(info_.format_version) +
                       " is not supported (this build reads formats 1 to " + std::to_string(kNewestFormatVersion) +
                       "; a newer animcompress may read it)");
  if (reserved != 0) return corrupt("reserved header bits are set");

  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> head, readSection(kFileHeaderBytes, kTagHead, kMaxHeadBytes));
  ByteReader r(head.data(), head.size(), kFileHeaderBytes + 12);
  ContainerHeader& hd = info_.header;
  ANIMC_ASSIGN_OR_RETURN(uint8_t codec, r.u8("Codec_Id"));
  if (findCodec(codec) == nullptr)
    return unsupported("codec id " + std::to_string(codec) + " is not supported (this build reads " + knownCodecList() +
                       "; a newer animcompress may read it)");
  hd.codec = CodecId(codec);
  ANIMC_ASSIGN_OR_RETURN(uint64_t params_bytes, r.varint("Codec_Params_Length"));
  if (params_bytes > r.remaining()) return r.truncatedAt("Codec_Params");
  hd.codec_params.assign(r.cursor(), r.cursor() + params_bytes);
  ANIMC_RETURN_IF_ERROR(r.skip(params_bytes, "Codec_Params"));
  ANIMC_ASSIGN_OR_RETURN(hd.vertex_count, r.u32("Vertex_Count"));
  ANIMC_ASSIGN_OR_RETURN(hd.triangle_count, r.u64("Triangle_Count"));
  ANIMC_ASSIGN_OR_RETURN(hd.frame_rate, r.f64("Frame_Rate"));
  ANIMC_ASSIGN_OR_RETURN(hd.iframe_interval, r.u32("IFrame_Interval"));
  if (r.remaining() != 0) return corrupt("HEAD section has " + std::to_string(r.remaining()) + " unread bytes");
  if (hd.vertex_count == 0) return corrupt("Vertex_Count is 0");
  if (hd.vertex_count > limits_.max_vertices)
    return limitExceeded("Vertex_Count " + std::to_string(hd.vertex_count) + " above the limit of " +
                         std::to_string(limits_.max_vertices));
  if (hd.triangle_count > limits_.max_triangles)
    return limitExceeded("Triangle_Count " + std::to_string(hd.triangle_count) + " above the limit");
  if (!(hd.frame_rate > 0 && hd.frame_rate < 1e6)) return corrupt("Frame_Rate out of range");

  const uint64_t conn_offset = kFileHeaderBytes + kSectionOverhead + head.size();
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> conn, readSection(conn_offset, kTagConnectivity, kNoMaximum));
  ANIMC_RETURN_IF_ERROR(decodeConnectivity(ByteReader(conn.data(), conn.size(), conn_offset + 12), info_.format_version,
                                           hd.vertex_count, hd.triangle_count, topology_));
  ANIMC_RETURN_IF_ERROR(openIndex(conn_offset + kSectionOverhead + conn.size()));
  return measureFirstFrame();
}

Status ContainerReader::openIndex(uint64_t conn_end) {
  const uint64_t end_offset = info_.file_bytes - kEndSectionBytes;
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> end, readSection(end_offset, kTagEnd, 8));
  ByteReader e(end.data(), end.size(), end_offset + 12);
  ANIMC_ASSIGN_OR_RETURN(uint64_t index_offset, e.u64("Index_Offset"));
  if (index_offset < conn_end || index_offset > end_offset)
    return corrupt("Index_Offset " + std::to_string(index_offset) + " outside the file's data");
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> index, readSection(index_offset, kTagIndex, end_offset - index_offset));
  if (index_offset + kSectionOverhead + index.size() != end_offset) return corrupt("bytes between INDX and END");
  ByteReader r(index.data(), index.size(), index_offset + 12);
  ANIMC_ASSIGN_OR_RETURN(info_.frame_count, r.u64("Frame_Count"));
  ANIMC_ASSIGN_OR_RETURN(uint32_t group_count, r.u32("Group_Count"));
  if (info_.frame_count > limits_.max_frames)
    return limitExceeded("Frame_Count " + std::to_string(info_.frame_count) + " above the limit of " +
                         std::to_string(limits_.max_frames));
  if (info_.frame_count == 0 || info_.frame_count > info_.file_bytes)
    return corrupt("Frame_Count " + std::to_string(info_.frame_count) + " impossible for this file");
  if (group_count == 0 || group_count > info_.frame_count || r.remaining() != 16 * uint64_t(group_count))
    return corrupt("Group_Count " + std::to_string(group_count) + " does not match the index size");
  groups_.resize(group_count);
  for (uint32_t g = 0; g < group_count; ++g) {
    ANIMC_ASSIGN_OR_RETURN(groups_[g].offset, r.u64("Group_Offset"));
    ANIMC_ASSIGN_OR_RETURN(groups_[g].first_frame, r.u64("Group_First_Frame"));
    const uint64_t min_offset = g == 0 ? conn_end : groups_[g - 1].offset + kSectionOverhead + kGroupFieldBytes + 1;
    const bool first_ok = g == 0 ? groups_[g].first_frame == 0 : groups_[g].first_frame > groups_[g - 1].first_frame;
    if ((g == 0 && groups_[g].offset != conn_end) || groups_[g].offset < min_offset ||
        groups_[g].offset >= index_offset || !first_ok || groups_[g].first_frame >= info_.frame_count)
      return corrupt("index entry " + std::to_string(g) + " is inconsistent");
  }
  for (uint32_t g = 0; g < group_count; ++g) {
    groups_[g].end = g + 1 < group_count ? groups_[g + 1].offset : index_offset;
    info_.sections.push_back({kTagGroup, groups_[g].offset, groups_[g].end - groups_[g].offset - kSectionOverhead});
  }
  return Status();
}

Status ContainerReader::measureFirstFrame() {
  // The first frame's length tells what motion does not pay for (motion-only bpvf).
  ANIMC_RETURN_IF_ERROR(beginGroup(0));
  std::vector<uint8_t> payload;
  ANIMC_ASSIGN_OR_RETURN(bool got, nextFrame(payload));
  if (!got) return corrupt("first group has no frames");
  // Everything up to the end of the first frame; for a codec that codes whole groups, whose
  // first frame record carries its group's motion, up to the first group.
  info_.static_bytes = findCodec(uint8_t(info_.header.codec))->makeGroupEncoder ? groups_[0].offset : cursor_;
  if (info_.header.vertex_count > kMaxVerticesPerIntraByte * (payload.size() + 16))
    return corrupt("Vertex_Count " + std::to_string(info_.header.vertex_count) + " cannot fit in a " +
                   std::to_string(payload.size()) + "-byte first frame");
  std::sort(info_.sections.begin(), info_.sections.end(),
            [](const SectionInfo& a, const SectionInfo& b) { return a.offset < b.offset; });
  return Status();
}

size_t ContainerReader::groupOf(uint64_t frame) const {
  // The last group starting at or before `frame` (first frames rise strictly from 0): a binary
  // search, as every Decoder::frame() call asks and a file may hold a group per frame.
  const auto after = std::upper_bound(groups_.begin(), groups_.end(), frame,
                                      [](uint64_t f, const Group& group) { return f < group.first_frame; });
  return after == groups_.begin() ? 0 : size_t(after - groups_.begin()) - 1;
}

}  // namespace animc

namespace animc {

Status ContainerReader::checkGroupHead(size_t g, uint64_t& frames_begin, uint64_t& frames_end) {
  if (g >= groups_.size()) return invalidArgument("no frame group " + std::to_string(g));
  const Group& group = groups_[g];
  uint8_t head[12 + kGroupFieldBytes];
  ANIMC_RETURN_IF_ERROR(readAt(group.offset, head, sizeof head, "GRUP"));
  if (std::memcmp(head, kTagGroup, 4) != 0) return corrupt("expected section GRUP" + at(group.offset));
  ByteReader r(head + 4, sizeof head - 4, group.offset + 4);
  ANIMC_ASSIGN_OR_RETURN(uint64_t length, r.u64("Section_Length"));
  ANIMC_ASSIGN_OR_RETURN(uint64_t first_frame, r.u64("First_Frame"));
  ANIMC_ASSIGN_OR_RETURN(uint32_t frame_count, r.u32("Frame_Count"));
  if (length < kGroupFieldBytes || group.offset + kSectionOverhead + length != group.end)
    return corrupt("GRUP section" + at(group.offset) + ": length does not match the index");
  if (first_frame != group.first_frame || frame_count != groupFrameCount(g))
    return corrupt("GRUP section" + at(group.offset) + ": frame numbers do not match the index");
  frames_begin = group.offset + 12 + kGroupFieldBytes;
  frames_end = group.offset + 12 + length;
  return Status();
}

Status ContainerReader::beginGroup(size_t g) {
  uint64_t frames_begin = 0, frames_end = 0;
  ANIMC_RETURN_IF_ERROR(checkGroupHead(g, frames_begin, frames_end));
  if (g != verified_group_) ANIMC_RETURN_IF_ERROR(verifyGroupCrc(g, frames_begin, frames_end));
  cursor_ = frames_begin;
  frames_end_ = frames_end;
  frames_left_ = groupFrameCount(g);
  return Status();
}

Status ContainerReader::verifyGroupCrc(size_t g, uint64_t frames_begin, uint64_t frames_end) {
  verified_group_ = SIZE_MAX;
  // Verify the CRC before decoding anything, streaming so memory stays small.
  std::vector<uint8_t> block(std::min<uint64_t>(frames_end - frames_begin, 1 << 20));
  uint32_t crc = 0;
  for (uint64_t pos = frames_begin; pos < frames_end;) {
    const size_t n = size_t(std::min<uint64_t>(block.size(), frames_end - pos));
    ANIMC_RETURN_IF_ERROR(readAt(pos, block.data(), n, "GRUP"));
    crc = crc32Update(crc, block.data(), n);
    pos += n;
  }
  uint8_t stored[4];
  ANIMC_RETURN_IF_ERROR(readAt(frames_end, stored, 4, "GRUP CRC"));
  ByteReader c(stored, 4, frames_end);
  ANIMC_ASSIGN_OR_RETURN(uint32_t expected, c.u32("Section_CRC"));
  if (crc != expected) return corrupt("GRUP section" + at(groups_[g].offset) + ": CRC mismatch");
  verified_group_ = g;
  return Status();
}

Result<uint64_t> ContainerReader::frameRecord(uint64_t position, uint64_t frames_end, uint64_t& payload_start) {
  uint8_t len_bytes[10];
  const size_t avail = size_t(std::min<uint64_t>(10, frames_end - position));
  ANIMC_RETURN_IF_ERROR(readAt(position, len_bytes, avail, "Frame_Length"));
  ByteReader r(len_bytes, avail, position);
  ANIMC_ASSIGN_OR_RETURN(uint64_t length, r.varint("Frame_Length"));
  payload_start = position + r.position();
  if (length > limits_.max_frame_bytes)
    return limitExceeded("Frame_Length " + std::to_string(length) + at(position) + " above the limit of " +
                         std::to_string(limits_.max_frame_bytes));
  if (length > frames_end - payload_start)
    return corrupt("Frame_Length " + std::to_string(length) + at(position) + " runs past its group");
  return length;
}

Result<bool> ContainerReader::nextFrame(std::vector<uint8_t>& payload) {
  if (frames_left_ == 0) {
    if (cursor_ != frames_end_) return corrupt("GRUP has bytes after its last frame" + at(cursor_));
    return false;
  }
  uint64_t start = 0;
  ANIMC_ASSIGN_OR_RETURN(uint64_t length, frameRecord(cursor_, frames_end_, start));
  payload.resize(size_t(length));
  ANIMC_RETURN_IF_ERROR(readAt(start, payload.data(), payload.size(), "frame"));
  cursor_ = start + length;
  --frames_left_;
  return true;
}

Result<uint8_t> ContainerReader::firstPayloadByte(size_t g) {
  uint64_t frames_begin = 0, frames_end = 0, start = 0;
  ANIMC_RETURN_IF_ERROR(checkGroupHead(g, frames_begin, frames_end));
  if (frames_begin == frames_end) return corrupt("GRUP section" + at(groups_[g].offset) + ": no frame");
  ANIMC_ASSIGN_OR_RETURN(uint64_t length, frameRecord(frames_begin, frames_end, start));
  if (length == 0) return corrupt("empty frame" + at(frames_begin));
  uint8_t byte = 0;
  ANIMC_RETURN_IF_ERROR(readAt(start, &byte, 1, "frame"));
  return byte;
}

Result<std::vector<uint8_t>> ContainerReader::startBytes() {
  std::vector<uint8_t> bytes(size_t(groups_[0].offset));
  ANIMC_RETURN_IF_ERROR(readAt(0, bytes.data(), bytes.size(), "HEAD and CONN"));
  return bytes;
}

Result<std::vector<uint8_t>> ContainerReader::groupSection(size_t g) {
  ANIMC_RETURN_IF_ERROR(beginGroup(g));
  const Group& group = groups_[g];
  std::vector<uint8_t> bytes(size_t(group.end - group.offset));
  ANIMC_RETURN_IF_ERROR(readAt(group.offset, bytes.data(), bytes.size(), "GRUP"));
  return bytes;
}

}  // namespace animc
