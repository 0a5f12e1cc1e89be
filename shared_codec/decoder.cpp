// SPDX-License-Identifier: Apache-2.0
// The public Decoder (animc/animc.h): a container reader over a file or memory, the codec's
// frame decoder, and the cursor that turns frame(k) into "seek to k's group, decode forward".
#include "api.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>

#include "core/parallel.h"

namespace animc {
namespace {

// Groups a thread has in one batch of decodeGroups(), and in a reader's run of frames
// (decodeChunkEnd()): the threads take the batch's groups one at a time, so that a slow group
// (of another codec, or with more components) holds up the others less than in a batch of one
// group a thread, each batch waiting for its slowest.
constexpr size_t kGroupsPerThread = 4;

// The settings a stream was written with, from its HEAD section.
Result<EncodeSettings> readSettings(const ContainerHeader& h) {
  const CodecEntry* codec = findCodec(uint8_t(h.codec));
  if (codec == nullptr) return unsupported("codec id " + std::to_string(int(h.codec)) + " is not supported");
  ByteReader params(h.codec_params.data(), h.codec_params.size());
  EncodeSettings settings;
  ANIMC_ASSIGN_OR_RETURN(settings.options, codec->read(params));
  settings.iframe_interval = h.iframe_interval;
  return settings;
}

StreamInfo streamInfo(const ContainerInfo& c, const EncodeSettings& s) {
  StreamInfo info;
  info.format_version = c.format_version;
  info.codec = s.entry().name;
  info.codec_id = uint8_t(s.codec());
  info.settings = s.entry().settings(s.options);
  info.settings_text = s.entry().describe(s.options);
  info.vertices = c.header.vertex_count;
  info.triangles = c.header.triangle_count;
  info.frames = int64_t(c.frame_count);
  info.frame_rate = c.header.frame_rate;
  info.iframe_interval = c.header.iframe_interval;
  info.groups = c.groupCount();
  info.bytes = c.file_bytes;
  info.static_bytes = c.static_bytes;
  return info;
}

// Decodes one payload into xyz, or only reads it when its frame is not wanted (FrameDecoder::
// skipFrame); the first frame of a group must be an intra frame.
Status decodePayload(FrameDecoder& codec, const std::vector<uint8_t>& payload, bool group_start,
                     std::vector<float>& xyz, const std::string& where, bool wanted = true) {
  bool intra = false;
  const ByteReader reader(payload.data(), payload.size());
  Status s = wanted ? codec.decodeFrame(reader, xyz, &intra) : codec.skipFrame(reader, xyz, &intra);
  if (!s.ok()) return s.withContext(where);
  if (group_start && !intra) return corrupt(where + ": a frame group does not start with an intra frame");
  return Status();
}

}  // namespace

struct Decoder::Impl {
  std::string name;  // of the stream, in messages
  unsigned threads = 1;
  DecoderOptions decoding;  // as opened: its limits, and what the group decoders of frames() are made with
  std::unique_ptr<ContainerReader> reader;
  std::unique_ptr<FrameDecoder> codec;
  EncodeSettings settings;
  StreamInfo info;
  std::vector<uint8_t> payload;
  std::vector<float> xyz;
  int64_t next_frame = 0;  // what the reader's cursor decodes next
  size_t group = 0;
  bool positioned = false;  // the cursor is at next_frame (a group was entered)

  // Decoders of their own for the groups decoded at once by frames(), one a group.
  std::vector<std::unique_ptr<FrameDecoder>> group_codecs;

  std::string where(int64_t frame) const { return name + " frame " + std::to_string(frame); }
  std::string where() const { return where(next_frame); }
  Status enterGroupOf(int64_t frame);
  // Decodes frame next_frame into xyz (when wanted: see FrameDecoder::skipFrame).
  Status decodeNext(bool wanted = true);
  int64_t groupEnd(size_t g) const;
  Status readPayloads(size_t g, int64_t last, std::vector<std::vector<uint8_t>>& payloads);
  Status decodeGroups(int64_t first, int64_t last, float* xyz, const ProgressFn& progress = {});
  Status decodeGroupPart(FrameDecoder& codec, size_t g, const std::vector<std::vector<uint8_t>>& payloads,
                         int64_t first, float* xyz) const;
  // The two halves of Decoder::checkDecodeWork, for a range inside the stream.
  Status checkWork(int64_t first, int64_t last) const;
  Status checkOutput(int64_t first, int64_t last, uint64_t output_bytes) const;
};

Status Decoder::Impl::enterGroupOf(int64_t frame) {
  group = reader->groupOf(uint64_t(frame));
  Status s = reader->beginGroup(group);
  if (!s.ok()) return s.withContext(name);
  next_frame = int64_t(reader->groupFirstFrame(group));
  positioned = true;
  return Status();
}

// Decodes frame next_frame, entering the next group when the current one ends.
Status Decoder::Impl::decodeNext(bool wanted) {
  auto got = reader->nextFrame(payload);
  if (!got.ok()) return got.status().withContext(where());
  if (!got.value()) {  // end of this group: the next one starts with an intra frame
    Status s = reader->beginGroup(++group);
    if (!s.ok()) return s.withContext(name);
    got = reader->nextFrame(payload);
    if (!got.ok()) return got.status().withContext(where());
    if (!got.value()) return corrupt(where() + ": empty frame group");
  }
  const bool group_start = next_frame == int64_t(reader->groupFirstFrame(group));
  ANIMC_RETURN_IF_ERROR(decodePayload(*codec, payload, group_start, xyz, where(), wanted));
  ++next_frame;
  return Status();
}

int64_t Decoder::Impl::groupEnd(size_t g) const {
  return g + 1 < reader->groupCount() ? int64_t(reader->groupFirstFrame(g + 1)) : info.frames;
}

// Group g's frames up to `payloads`' count, decoded by `codec`; those from frame `first` on go
// to xyz, one after the other (3N floats each), unless xyz is null (then every frame is
// decoded, as verify() checks them all). Frames before `first` are only read, as frame() does.
Status Decoder::Impl::decodeGroupPart(FrameDecoder& codec, size_t g, const std::vector<std::vector<uint8_t>>& payloads,
                                      int64_t first, float* xyz) const {
  const int64_t start = int64_t(reader->groupFirstFrame(g));
  std::vector<float> frame;
  for (size_t i = 0; i < payloads.size(); ++i) {
    const int64_t k = start + int64_t(i);
    const bool wanted = xyz == nullptr || k >= first;
    ANIMC_RETURN_IF_ERROR(decodePayload(codec, payloads[i], i == 0, frame, where(k), wanted));
    if (xyz && k >= first) std::copy(frame.begin(), frame.end(), xyz + size_t(k - first) * frame.size());
  }
  return Status();
}

// The payloads of group g's frames before `last`, read in order (its CRC checked on entering
// it); a group read to its end is checked for bytes after its last frame.
Status Decoder::Impl::readPayloads(size_t g, int64_t last, std::vector<std::vector<uint8_t>>& payloads) {
  Status s = reader->beginGroup(g);
  if (!s.ok()) return s.withContext(name);
  const int64_t end = std::min(groupEnd(g), last);
  for (int64_t k = int64_t(reader->groupFirstFrame(g)); k < end; ++k) {
    payloads.emplace_back();
    auto got = reader->nextFrame(payloads.back());
    if (!got.ok()) return got.status().withContext(where(k));
    if (!got.value()) return corrupt(where(k) + ": the frame group ends before this frame");
  }
  if (end == groupEnd(g)) {
    std::vector<uint8_t> after;
    auto got = reader->nextFrame(after);
    if (!got.ok()) return got.status().withContext(name);
  }
  return Status();
}

// Frames [first, last) of two or more groups: up to one group a thread at once, each by a
// decoder of its own, from payloads read in order by this thread.
Status Decoder::Impl::decodeGroups(int64_t first, int64_t last, float* xyz, const ProgressFn& progress) {
  const size_t g_first = reader->groupOf(uint64_t(first)), g_last = reader->groupOf(uint64_t(last - 1));
  positioned = false;  // the cursor is left anywhere
  const size_t batch = kGroupsPerThread * threads;
  for (size_t g0 = g_first; g0 <= g_last; g0 += batch) {
    const size_t count = std::min<size_t>(batch, g_last + 1 - g0);
    // A group that cannot be read ends the batch there; the groups before it are decoded
    // first, so that the error reported is the first in frame order, as one thread finds it.
    std::vector<std::vector<std::vector<uint8_t>>> payloads(count);
    Status read_failure;
    size_t readable = 0;
    while (readable < count && (read_failure = readPayloads(g0 + readable, last, payloads[readable])).ok()) ++readable;
    // One decoder a thread, which takes the next group when done with one: every group starts
    // afresh from its intra frame, so any decoder gives it the same frames.
    const size_t workers = std::min<size_t>(threads, readable);
    while (group_codecs.size() < workers) {
      ANIMC_ASSIGN_OR_RETURN(auto codec, settings.entry().makeDecoder(settings.options, reader->topology(), decoding,
                                                                      name, bestSimdPath()));
      group_codecs.push_back(std::move(codec));
    }
    std::vector<Status> status(readable);
    std::atomic<size_t> next{0};
    parallelFor(workers, [&](size_t worker) {
      for (size_t i; (i = next.fetch_add(1)) < readable;) {
        const int64_t start = int64_t(reader->groupFirstFrame(g0 + i));
        float* out = xyz ? xyz + size_t(std::max<int64_t>(0, start - first)) * 3 * info.vertices : nullptr;
        status[i] = decodeGroupPart(*group_codecs[worker], g0 + i, payloads[i], std::max(first, start), out);
      }
    });
    for (const Status& s : status) ANIMC_RETURN_IF_ERROR(s);
    ANIMC_RETURN_IF_ERROR(read_failure);
    const int64_t done = std::min(groupEnd(g0 + count - 1), last) - first;
    if (progress && !progress(int(100 * done / (last - first)), "checking")) return cancelled();
  }
  return Status();
}

struct DecoderAccess {
  static Result<Decoder> open(std::unique_ptr<ByteSource> source, const std::string& name,
                              const DecoderOptions& options) {
    auto impl = std::make_unique<Decoder::Impl>();
    impl->name = name;
    impl->threads = resolveThreads(options.threads);
    impl->decoding = options;
    {
      ThreadBudget budget(impl->threads);  // for the connectivity's pieces (format 2)
      ANIMC_ASSIGN_OR_RETURN(impl->reader, ContainerReader::open(std::move(source), name, options.limits));
    }
    auto settings = readSettings(impl->reader->info().header);
    if (!settings.ok()) return settings.status().withContext(name);
    impl->settings = settings.value();
    ANIMC_ASSIGN_OR_RETURN(
        impl->codec, impl->settings.entry().makeDecoder(impl->settings.options, impl->reader->topology(), options, name,
                                                        bestSimdPath()));
    impl->info = streamInfo(impl->reader->info(), impl->settings);
    // The first group is checked on opening (its CRC), as the container reader promises.
    ANIMC_RETURN_IF_ERROR(impl->enterGroupOf(0));
    return Decoder(std::move(impl));
  }
  static const Decoder::Impl& impl(const Decoder& d) { return *d.impl_; }
};

Result<Decoder> Decoder::openFile(const std::string& path, const DecoderOptions& options) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ByteSource> source, openFileSource(path));
  return DecoderAccess::open(std::move(source), path, options);
}

Result<Decoder> Decoder::openMemory(const void* data, size_t size, const DecoderOptions& options,
                                    const std::string& name) {
  if (data == nullptr && size > 0) return invalidArgument(name + ": no data");
  return DecoderAccess::open(memorySource(data, size), name, options);
}

Decoder::Decoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Decoder::Decoder(Decoder&&) noexcept = default;
Decoder& Decoder::operator=(Decoder&&) noexcept = default;
Decoder::~Decoder() = default;

const StreamInfo& Decoder::info() const { return impl_->info; }

const uint32_t* Decoder::triangles() const {
  static_assert(sizeof(Triangle) == 3 * sizeof(uint32_t), "triangles are stored as 3 packed indices");
  const std::vector<Triangle>& triangles = impl_->reader->topology().triangles;
  return triangles.empty() ? nullptr : triangles.front().data();
}

Status Decoder::frame(int64_t k, float* xyz) {
  Impl& d = *impl_;
  if (k < 0 || k >= d.info.frames)
    return invalidArgument(d.name + ": frame " + std::to_string(k) + " outside [0, " + std::to_string(d.info.frames) +
                           ")");
  if (xyz == nullptr) return invalidArgument("no frame buffer");
  ANIMC_RETURN_IF_ERROR(d.checkOutput(k, k + 1, 0));
  ThreadBudget budget(d.threads);
  if (!d.positioned || k < d.next_frame || d.reader->groupOf(uint64_t(k)) != d.group) {
    ANIMC_RETURN_IF_ERROR(d.checkWork(k, k + 1));
    ANIMC_RETURN_IF_ERROR(d.enterGroupOf(k));
  }
  d.positioned = false;  // a failure below leaves the cursor undefined: re-enter next time
  // Only frame k is handed out: the frames before it are only read where the codec allows.
  while (d.next_frame <= k) ANIMC_RETURN_IF_ERROR(d.decodeNext(d.next_frame == k));
  d.positioned = true;
  copyOnThreads(d.xyz.data(), d.xyz.size(), xyz);
  return Status();
}

Status Decoder::frames(int64_t first, int64_t last, float* xyz) {
  Impl& d = *impl_;
  if (first < 0 || last > d.info.frames || first >= last)
    return invalidArgument(d.name + ": frames " + std::to_string(first) + " to " + std::to_string(last) +
                           " are not a range of [0, " + std::to_string(d.info.frames) + ")");
  if (xyz == nullptr) return invalidArgument("no frame buffer");
  ANIMC_RETURN_IF_ERROR(d.checkOutput(first, last, 0));
  ANIMC_RETURN_IF_ERROR(d.checkWork(first, last));
  ThreadBudget budget(d.threads);
  if (d.threads > 1 && d.reader->groupOf(uint64_t(first)) != d.reader->groupOf(uint64_t(last - 1)))
    return d.decodeGroups(first, last, xyz);
  // One group, or one thread: the cursor goes on from where it is, as frame() does.
  const size_t size = size_t(3) * d.info.vertices;
  for (int64_t k = first; k < last; ++k) ANIMC_RETURN_IF_ERROR(frame(k, xyz + size_t(k - first) * size));
  return Status();
}

Status Decoder::Impl::checkWork(int64_t first, int64_t last) const {
  const uint64_t start = reader->groupFirstFrame(reader->groupOf(uint64_t(first)));
  const uint64_t work = (uint64_t(last) - start) * info.vertices;
  if (work <= decoding.limits.max_vertex_frames) return Status();
  return limitExceeded(name + ": decoding frames " + std::to_string(first) + " to " + std::to_string(last - 1) +
                       " costs " + std::to_string(work) + " vertex-frames (" + std::to_string(info.vertices) +
                       " vertices, from the start of their frame group), above the limit of " +
                       std::to_string(decoding.limits.max_vertex_frames) +
                       "; decode fewer frames or raise the limit (DecoderLimits::max_vertex_frames, "
                       "animc --max-vertex-frames)");
}

namespace {
// "7168 MB (7516192768 bytes)": MB as MeshLab's memory limit counts them, 2^20 bytes.
std::string bytesText(uint64_t bytes) {
  return std::to_string((bytes + (1 << 19)) >> 20) + " MB (" + std::to_string(bytes) + " bytes)";
}
}  // namespace

Status Decoder::Impl::checkOutput(int64_t first, int64_t last, uint64_t output_bytes) const {
  if (output_bytes == 0) {
    const uint64_t vertex_frames = uint64_t(last - first) * info.vertices;
    // Above 2^62 floats no limit could pass: saturate rather than wrap.
    output_bytes = vertex_frames > (UINT64_MAX / 12) ? UINT64_MAX : 12 * vertex_frames;
  }
  if (output_bytes <= decoding.limits.max_output_bytes) return Status();
  return limitExceeded(name + ": frames " + std::to_string(first) + " to " + std::to_string(last - 1) + " (" +
                       std::to_string(info.vertices) + " vertices each) would take about " + bytesText(output_bytes) +
                       ", above the limit of " + bytesText(decoding.limits.max_output_bytes) +
                       "; decode fewer frames or raise the limit (DecoderLimits::max_output_bytes, "
                       "animc --max-output-bytes)");
}

Status Decoder::checkDecodeWork(int64_t first, int64_t last, uint64_t output_bytes) const {
  const Impl& d = *impl_;
  if (first < 0 || last <= first || first >= d.info.frames) return Status();
  ANIMC_RETURN_IF_ERROR(d.checkOutput(first, last, output_bytes));
  return d.checkWork(first, last);
}

Status Decoder::verify(const ProgressFn& progress) {
  Impl& d = *impl_;
  // Nothing is kept, so only the work is bounded, not the output.
  if (d.info.frames > 0) ANIMC_RETURN_IF_ERROR(d.checkWork(0, d.info.frames));
  ThreadBudget budget(d.threads);
  if (d.threads > 1 && d.reader->groupCount() > 1) {
    // Every group is read to its end, and so checked for bytes after its last frame.
    ANIMC_RETURN_IF_ERROR(d.decodeGroups(0, d.info.frames, nullptr, progress));
    return Status();
  }
  ANIMC_RETURN_IF_ERROR(d.enterGroupOf(0));
  d.positioned = false;
  // decodeNext() enters each group in turn, checking its CRC and its numbers.
  while (d.next_frame < d.info.frames) {
    ANIMC_RETURN_IF_ERROR(d.decodeNext());
    if (progress && !progress(int(100 * d.next_frame / d.info.frames), "checking")) return cancelled();
  }
  // The last group must end right after its last frame (its frame count was checked against
  // the index), so this finds only bytes left over after it.
  auto after = d.reader->nextFrame(d.payload);
  if (!after.ok()) return after.status().withContext(d.name);
  if (after.value()) return corrupt(d.name + ": bytes follow the last frame of the last group");
  d.positioned = true;
  return Status();
}

int64_t decodeChunkEnd(const Decoder& decoder, int64_t first) {
  const Decoder::Impl& d = DecoderAccess::impl(decoder);
  if (d.threads <= 1) return first + 1;
  // At most kChunkBytes of frames, and never more than the output limit allows.
  constexpr uint64_t kChunkBytes = uint64_t(1) << 27;
  const uint64_t frame_bytes = uint64_t(12) * std::max<uint32_t>(1, d.info.vertices);
  const int64_t most =
      int64_t(std::max<uint64_t>(1, std::min(kChunkBytes, d.decoding.limits.max_output_bytes) / frame_bytes));
  const int64_t cap = std::min(d.info.frames, first + most);
  // The end of the group kGroupsPerThread x `threads` groups on, or failing that the last group
  // boundary below the cap; inside one group, the cap (the next chunk goes on from there).
  const size_t g = d.reader->groupOf(uint64_t(first));
  int64_t end = d.groupEnd(std::min(g + kGroupsPerThread * d.threads, d.reader->groupCount()) - 1);
  while (end > cap) end = int64_t(d.reader->groupFirstFrame(d.reader->groupOf(uint64_t(end - 1))));
  if (end <= first) end = cap;
  // Frames of one group come one at a time from the cursor anyway (its reconstruction is split
  // over the threads inside): a larger run would only cost memory.
  if (d.reader->groupOf(uint64_t(end - 1)) == g) return first + 1;
  return end;
}

Result<std::vector<GroupCodecCount>> groupsByCodec(const Decoder& decoder) {
  const Decoder::Impl& d = DecoderAccess::impl(decoder);
  if (d.settings.codec() != CodecId::kAuto)
    return std::vector<GroupCodecCount>{{d.settings.entry().name, d.reader->groupCount()}};
  std::vector<GroupCodecCount> counts;
  for (const AutoCandidate& c : std::get<AutoOptions>(d.settings.options).candidates)
    counts.push_back({codecName(c.codec), 0});
  for (size_t g = 0; g < d.reader->groupCount(); ++g) {
    // Each group's first frame starts with the index of its candidate (format.md, section 13).
    auto index = d.reader->firstPayloadByte(g);
    if (!index.ok()) return index.status().withContext(d.name);
    if (index.value() >= counts.size())
      return corrupt(d.name + ": group " + std::to_string(g) + " names no candidate codec");
    ++counts[index.value()].groups;
  }
  return counts;
}

const ContainerInfo& containerInfo(const Decoder& decoder) { return DecoderAccess::impl(decoder).reader->info(); }
const EncodeSettings& streamSettings(const Decoder& decoder) { return DecoderAccess::impl(decoder).settings; }
const Topology& streamTopology(const Decoder& decoder) { return DecoderAccess::impl(decoder).reader->topology(); }
const std::string& streamName(const Decoder& decoder) { return DecoderAccess::impl(decoder).name; }

}  // namespace animc
