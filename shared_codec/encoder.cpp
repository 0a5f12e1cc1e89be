// SPDX-License-Identifier: Apache-2.0
// The public Encoder (animc/animc.h): options by name, checks of what it is given, and the
// loop of one frame through the codec into the container.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "api.h"
#include "codecs/frame_group_encoder.h"
#include "container/connectivity_coder.h"
#include "container/container_writer.h"
#include "core/parallel.h"
#include "core/uninitialised_vector.h"
#include "encoder_access.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

using Clock = std::chrono::steady_clock;

// The largest group of a frame-by-frame codec the encoder gathers to code groups on several
// threads (its frames as floats).
constexpr uint64_t kMaxGatheredGroupBytes = uint64_t(1) << 27;

// A codec's options as its registry entry reads them from a command line.
class MapOptionValues final : public OptionValues {
 public:
  explicit MapOptionValues(const std::map<std::string, std::string>& values) : values_(values) {}
  bool has(const std::string& name) const override { return values_.count(name) != 0; }
  std::string get(const std::string& name, const std::string& fallback) const override {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
  }

 private:
  const std::map<std::string, std::string>& values_;
};

bool hasFlag(const CodecEntry& codec, const std::string& name) {
  for (const auto* flags : {&codec.value_flags, &codec.switch_flags})
    if (std::find(flags->begin(), flags->end(), name) != flags->end()) return true;
  return false;
}

Status checkTopology(const Topology& t, const CodecEntry& codec) {
  if (t.vertex_count == 0) return badInput("the mesh has no vertices");
  if (t.triangles.empty()) return badInput("the mesh has no triangles");
  for (size_t i = 0; i < t.triangles.size(); ++i)
    for (uint32_t v : t.triangles[i])
      if (v >= t.vertex_count)
        return badInput("triangle " + std::to_string(i) + " uses vertex " + std::to_string(v) + " of " +
                        std::to_string(t.vertex_count));
  // A file the default decoder would refuse is not worth writing.
  const DecoderLimits limits;
  if (t.vertex_count > limits.max_vertices || t.triangles.size() > limits.max_triangles)
    return invalidArgument("the mesh has " + std::to_string(t.vertex_count) + " vertices and " +
                           std::to_string(t.triangles.size()) + " triangles; decoders accept at most " +
                           std::to_string(limits.max_vertices) + " and " + std::to_string(limits.max_triangles));
  return codec.checkMesh(t);
}

// Checks every coordinate of a frame, a block at a time on the calling thread's budget: a large
// frame is a pass over memory that would otherwise hold up the caller. The first bad
// coordinate is the one named, whatever the threads.
Status checkFrame(const float* xyz, uint32_t vertex_count, int64_t frame) {
  const size_t floats = size_t(vertex_count) * 3;
  std::vector<size_t> bad((floats + kFloatsPerTask - 1) / kFloatsPerTask, SIZE_MAX);
  parallelForBlocks(floats, kFloatsPerTask, 2, [&](size_t b, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (!std::isfinite(xyz[i]) || std::fabs(xyz[i]) > float(kMaxCoordinate)) {
        bad[b] = i;
        return;
      }
  });
  for (size_t i : bad)
    if (i != SIZE_MAX)
      return badInput("frame " + std::to_string(frame) + ": vertex " + std::to_string(i / 3) +
                      " has a NaN, infinite or huge coordinate");
  return Status();
}

std::vector<uint8_t> codecParameters(const EncodeSettings& s) {
  ByteWriter w;
  s.entry().write(s.options, w);
  return w.bytes();
}

}  // namespace

struct Encoder::Impl {
  EncodeSettings settings;
  Topology topology;
  ContainerWriter writer;
  unsigned threads = 1;
  // A frame-by-frame codec on one thread codes each frame as it comes (codec). Otherwise the
  // frames are gathered into groups, and up to one group a thread is coded at once, each by
  // a group coder of its own (the codec's own for a group codec).
  std::unique_ptr<FrameEncoder> codec;
  std::vector<std::unique_ptr<GroupEncoder>> group_coders;
  uint32_t max_group_frames = 0;
  EncodeSummary summary;
  std::vector<uint8_t> payload;
  std::vector<float> reconstruction;
  int64_t reconstruction_frame = -1;  // the frame `reconstruction` holds
  // Group mode: the frames gathered (3N floats each) in the groups they make, the last one
  // open; and the first frame of each group of the last batch coded, then its end.
  UninitialisedVector<float> pending;
  // The frames of the last batch coded, for original() until the next frame comes (then
  // they make room for it: the group's frames are never held twice).
  UninitialisedVector<float> coded;
  const float* last_added = nullptr;     // the caller's, frame by frame
  std::vector<uint32_t> pending_groups;  // frame counts of the closed groups
  uint32_t open_frames = 0;
  std::vector<int64_t> coded_first;
  bool finished = false;

  bool groupMode() const { return codec == nullptr; }
  // The floats of a whole group, reserved when a batch starts: a large group is then never
  // copied as it grows, nor held twice meanwhile (pages past the last frame stay untouched
  // when the sequence is shorter). Further groups of a batch grow it as they come.
  size_t groupFloats() const {
    const uint32_t interval = settings.iframe_interval;
    const uint32_t group = interval > 0 ? std::min(interval, max_group_frames) : max_group_frames;
    return size_t(group) * 3 * topology.vertex_count;
  }
  int64_t pendingFrames() const;
  bool groupEnds(int64_t next_frame) const;
  Status codeBatch();
  Status writeFrame(const std::vector<uint8_t>& payload, const FrameCodingStats& stats);
};

int64_t Encoder::Impl::pendingFrames() const {
  int64_t frames = open_frames;
  for (uint32_t g : pending_groups) frames += g;
  return frames;
}

// Whether the open group closes before frame next_frame: the I-frame interval starts a
// group there, or the group is as long as the codec takes.
bool Encoder::Impl::groupEnds(int64_t next_frame) const {
  const uint32_t interval = settings.iframe_interval;
  return open_frames > 0 && ((interval > 0 && next_frame % interval == 0) || open_frames >= max_group_frames);
}

// Codes the closed groups gathered, one a thread, and writes them in order.
Status Encoder::Impl::codeBatch() {
  const size_t count = pending_groups.size();
  while (group_coders.size() < count)
    group_coders.push_back(makeAnyGroupEncoder(settings.entry(), settings.options, topology, bestSimdPath()));
  std::vector<size_t> offset(count + 1, 0);
  for (size_t i = 0; i < count; ++i) offset[i + 1] = offset[i] + pending_groups[i];
  const size_t frame_size = size_t(3) * topology.vertex_count;
  std::vector<std::vector<std::vector<uint8_t>>> payloads(count);
  const auto start = Clock::now();
  {
    ThreadBudget budget(threads);
    parallelFor(count, [&](size_t i) {
      group_coders[i]->encodeGroup(pending.data() + offset[i] * frame_size, pending_groups[i], payloads[i]);
    });
  }
  summary.encode_seconds += std::chrono::duration<double>(Clock::now() - start).count();
  for (size_t i = 0; i < count; ++i)
    for (uint32_t k = 0; k < pending_groups[i]; ++k)
      ANIMC_RETURN_IF_ERROR(writeFrame(payloads[i][k], group_coders[i]->frameStats(k)));
  const int64_t first = summary.frames - open_frames - int64_t(offset[count]);
  coded_first.clear();
  for (size_t i = 0; i <= count; ++i) coded_first.push_back(first + int64_t(offset[i]));
  // A batch is coded when its last group closes: pending holds just the batch.
  coded.swap(pending);
  pending.clear();
  pending_groups.clear();
  reconstruction_frame = -1;
  return Status();
}

Status Encoder::Impl::writeFrame(const std::vector<uint8_t>& bytes, const FrameCodingStats& stats) {
  ANIMC_RETURN_IF_ERROR(writer.addFrame(bytes, stats.intra));
  if (summary.static_bytes == 0) summary.static_bytes = writer.bytesWritten();
  summary.intra_frames += stats.intra;
  summary.cells += stats.cells;
  return Status();
}

Result<Encoder> EncoderAccess::create(const EncodeSettings& settings, Topology topology, double frame_rate,
                                      std::unique_ptr<ByteSink> sink) {
  ANIMC_RETURN_IF_ERROR(settings.validate());
  ANIMC_RETURN_IF_ERROR(checkTopology(topology, settings.entry()));
  if (!settings.entry().makeEncoder && !settings.entry().makeGroupEncoder)
    return unsupported("this build of the library only decodes (ANIMC_DECODER_ONLY)");
  if (!sink) return invalidArgument("no sink to write to");
  auto impl = std::make_unique<Encoder::Impl>();
  impl->settings = settings;
  impl->topology = std::move(topology);
  impl->threads = resolveThreads(settings.threads);
  ContainerHeader header;
  header.format_version = formatVersionFor(impl->topology.triangles.size(), settings.connectivity_piece);
  header.codec = settings.codec();
  header.codec_params = codecParameters(settings);
  header.vertex_count = impl->topology.vertex_count;
  header.triangle_count = impl->topology.triangles.size();
  header.frame_rate = frame_rate;
  header.iframe_interval = settings.iframe_interval;
  ANIMC_RETURN_IF_ERROR(impl->writer.open(std::move(sink), header));
  const CodecEntry& codec = settings.entry();
  // A frame-by-frame codec gathers its groups for the threads only while a group's frames
  // stay small: otherwise it streams, one frame at a time, as on one thread (the bytes are
  // the same either way).
  const uint64_t group_bytes = uint64_t(settings.iframe_interval) * 12 * impl->topology.vertex_count;
  const bool batch_frames = impl->threads > 1 && settings.iframe_interval > 0 && group_bytes <= kMaxGatheredGroupBytes;
  // The coders are made (their mesh tables), then the connectivity is coded, each on the
  // encoder's threads: a format-2 connectivity in pieces at once.
  std::vector<uint8_t> connectivity;
  {
    ThreadBudget budget(impl->threads);
    if (codec.makeGroupEncoder || batch_frames) {
      impl->group_coders.push_back(makeAnyGroupEncoder(codec, settings.options, impl->topology, bestSimdPath()));
      impl->max_group_frames = impl->group_coders[0]->maxGroupFrames();
    } else {
      impl->codec = codec.makeEncoder(settings.options, impl->topology, bestSimdPath());
    }
    encodeConnectivity(impl->topology, settings.connectivity_piece, connectivity);
  }
  ANIMC_RETURN_IF_ERROR(impl->writer.addConnectivity(connectivity));
  // A group codec's first frame record carries the whole group: not static.
  if (codec.makeGroupEncoder) impl->summary.static_bytes = impl->writer.bytesWritten();
  impl->summary.vertices = impl->topology.vertex_count;
  impl->summary.triangles = impl->topology.triangles.size();
  return Encoder(std::move(impl));
}

const float* EncoderAccess::original(const Encoder& encoder, int64_t frame) {
  const Encoder::Impl& e = *encoder.impl_;
  if (!e.groupMode()) return frame == e.summary.frames - 1 ? e.last_added : nullptr;
  if (e.coded.empty() || frame < e.coded_first.front() || frame >= e.coded_first.back()) return nullptr;
  return e.coded.data() + size_t(frame - e.coded_first.front()) * 3 * e.topology.vertex_count;
}

Result<EncodeSettings> encodeSettingsFrom(const EncoderOptions& options) {
  ANIMC_ASSIGN_OR_RETURN(const CodecEntry* codec, findCodecByName(options.codec));
  for (const auto& [name, value] : options.values)
    if (!hasFlag(*codec, name)) return invalidArgument("--" + name + " does not apply to codec " + codec->name);
  EncodeSettings s;
  ANIMC_ASSIGN_OR_RETURN(s.options, codec->fromFlags(MapOptionValues(options.values)));
  s.iframe_interval = options.iframe_interval;
  s.threads = options.threads;
  s.connectivity_piece = options.connectivity_piece;
  ANIMC_RETURN_IF_ERROR(s.validate());
  return s;
}

Result<Encoder> createEncoder(const EncodeSettings& settings, Topology topology, double frame_rate,
                              std::unique_ptr<ByteSink> sink) {
  return EncoderAccess::create(settings, std::move(topology), frame_rate, std::move(sink));
}

EncoderOptions& EncoderOptions::set(const std::string& name, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);  // parses back to the same double
  values[name] = text;
  return *this;
}

Status EncoderOptions::validate() const { return encodeSettingsFrom(*this).status(); }

std::vector<std::string> codecNames() {
  std::vector<std::string> names;
  for (const CodecEntry* codec : allCodecs()) names.push_back(codec->name);
  return names;
}

Result<Encoder> Encoder::create(const EncoderOptions& options, uint32_t vertex_count, const uint32_t* triangles,
                                size_t triangle_count, std::unique_ptr<ByteSink> sink) {
  ANIMC_ASSIGN_OR_RETURN(EncodeSettings settings, encodeSettingsFrom(options));
  if (!(options.frame_rate > 0 && options.frame_rate < 1e9))
    return invalidArgument("the frame rate must be positive, not " + std::to_string(options.frame_rate));
  if (triangles == nullptr && triangle_count > 0) return invalidArgument("no triangle array");
  Topology topology;
  topology.vertex_count = vertex_count;
  topology.triangles.resize(triangle_count);
  for (size_t i = 0; i < triangle_count; ++i)
    topology.triangles[i] = {triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]};
  return EncoderAccess::create(settings, std::move(topology), options.frame_rate, std::move(sink));
}

Encoder::Encoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Encoder::Encoder(Encoder&&) noexcept = default;
Encoder& Encoder::operator=(Encoder&&) noexcept = default;
Encoder::~Encoder() = default;

Status Encoder::addFrame(const float* xyz) {
  Impl& e = *impl_;
  if (e.finished) return invalidArgument("the encoder has finished: it takes no more frames");
  if (xyz == nullptr) return invalidArgument("no frame");
  const int64_t frame = e.summary.frames;
  ThreadBudget budget(e.threads);
  // Before anything changes: a refused frame leaves the encoder as it was.
  ANIMC_RETURN_IF_ERROR(checkFrame(xyz, e.topology.vertex_count, frame));
  if (e.groupMode()) {
    if (!e.coded.empty()) {  // the last batch's frames make room for this one
      e.pending.swap(e.coded);
      e.pending.clear();
      e.coded = UninitialisedVector<float>();
    }
    if (e.pending.empty()) e.pending.reserve(e.groupFloats());
    // Gathered on the threads too, into a buffer without a zero fill (its page faults shared).
    const size_t at = e.pending.size(), floats = size_t(e.topology.vertex_count) * 3;
    e.pending.resize(at + floats);
    copyOnThreads(xyz, floats, e.pending.data() + at);
    ++e.open_frames;
    ++e.summary.frames;
    if (e.groupEnds(e.summary.frames)) {
      e.pending_groups.push_back(e.open_frames);
      e.open_frames = 0;
      if (e.pending_groups.size() >= e.threads) ANIMC_RETURN_IF_ERROR(e.codeBatch());
    }
    return Status();
  }
  const uint32_t interval = e.settings.iframe_interval;
  const bool intra = frame == 0 || (interval > 0 && frame % interval == 0);
  FrameCodingStats stats;
  e.payload.clear();
  const auto start = Clock::now();
  e.codec->encodeFrame(xyz, intra, e.payload, stats);
  e.summary.encode_seconds += std::chrono::duration<double>(Clock::now() - start).count();
  e.reconstruction_frame = -1;
  e.last_added = xyz;
  ++e.summary.frames;
  return e.writeFrame(e.payload, stats);
}

int64_t Encoder::reconstructedFrames() const { return impl_->summary.frames - impl_->pendingFrames(); }

const float* Encoder::reconstruction(int64_t frame) {
  Impl& e = *impl_;
  if (frame < 0 || frame >= reconstructedFrames()) return nullptr;
  if (e.groupMode() && (e.coded_first.empty() || frame < e.coded_first.front())) return nullptr;
  if (!e.groupMode() && frame != e.summary.frames - 1) return nullptr;
  if (e.reconstruction_frame != frame) {
    e.reconstruction.resize(size_t(e.topology.vertex_count) * 3);
    if (e.groupMode()) {
      const size_t i =
          size_t(std::upper_bound(e.coded_first.begin(), e.coded_first.end(), frame) - e.coded_first.begin()) - 1;
      if (!e.group_coders[i]->reconstruction(uint32_t(frame - e.coded_first[i]), e.reconstruction.data()))
        return nullptr;
    } else {
      // The codecs reconstruct in double; decoders output these rounded to float.
      const std::vector<double>& r = e.codec->reconstruction();
      e.reconstruction.assign(r.begin(), r.end());
    }
    e.reconstruction_frame = frame;
  }
  return e.reconstruction.data();
}

const float* Encoder::reconstruction() { return reconstruction(impl_->summary.frames - 1); }

Result<EncodeSummary> Encoder::finish() {
  Impl& e = *impl_;
  if (e.finished) return invalidArgument("the encoder has finished already");
  if (e.summary.frames == 0) return badInput("the sequence has no frames");
  e.finished = true;
  if (e.open_frames > 0) e.pending_groups.push_back(e.open_frames);
  e.open_frames = 0;
  if (!e.pending_groups.empty()) ANIMC_RETURN_IF_ERROR(e.codeBatch());
  ANIMC_RETURN_IF_ERROR(e.writer.finish());
  e.summary.bytes = e.writer.bytesWritten();
  return e.summary;
}

std::string Encoder::describeSettings() const {
  const EncodeSettings& s = impl_->settings;
  return std::string(s.entry().name) + ": " + s.entry().describe(s.options);
}

}  // namespace animc
