// SPDX-License-Identifier: Apache-2.0
#include "api.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "container/container_writer.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

using Clock = std::chrono::steady_clock;

Status checkSource(const FrameSource& source) {
  const Topology& t = source.topology();
  if (t.vertex_count == 0) return badInput(source.where() + ": the mesh has no vertices");
  if (t.triangles.empty()) return badInput(source.where() + ": the mesh has no triangles");
  for (size_t i = 0; i < t.triangles.size(); ++i)
    for (uint32_t v : t.triangles[i])
      if (v >= t.vertex_count)
        return badInput(source.where() + ": triangle " + std::to_string(i) + " uses vertex " +
                        std::to_string(v) + " of " + std::to_string(t.vertex_count));
  return Status();
}

// where: the source's description of this frame, taken before next() moved past it.
Status checkFrame(const std::vector<float>& xyz, const std::string& where, int64_t frame) {
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]) || std::fabs(xyz[i]) > 1e30f)
      return badInput(where + " (frame " + std::to_string(frame) + "): vertex " +
                      std::to_string(i / 3) + " has a NaN, infinite or huge coordinate");
  return Status();
}

// A file the default decoder would refuse is not worth writing.
Status checkDecodable(const Topology& t, const CodecEntry& codec) {
  const DecoderLimits limits;
  if (t.vertex_count > limits.max_vertices || t.triangles.size() > limits.max_triangles)
    return invalidArgument("the mesh has " + std::to_string(t.vertex_count) + " vertices and " +
                           std::to_string(t.triangles.size()) + " triangles; decoders accept at most " +
                           std::to_string(limits.max_vertices) + " and " + std::to_string(limits.max_triangles));
  return codec.checkMesh(t);
}

std::vector<uint8_t> codecParameters(const EncodeSettings& s) {
  ByteWriter w;
  s.entry().write(s.options, w);
  return w.bytes();
}

// The settings a file was written with, from its HEAD section.
Result<EncodeSettings> readSettings(const ContainerHeader& h) {
  const CodecEntry* codec = findCodec(uint8_t(h.codec));
  if (codec == nullptr) return unsupported("codec id " + std::to_string(int(h.codec)) + " is not supported");
  ByteReader params(h.codec_params.data(), h.codec_params.size());
  EncodeSettings settings;
  ANIMC_ASSIGN_OR_RETURN(settings.options, codec->read(params));
  settings.iframe_interval = h.iframe_interval;
  return settings;
}

}  // namespace

AffineOctreeOptions& EncodeSettings::octree() {
  if (!std::holds_alternative<AffineOctreeOptions>(options)) options = AffineOctreeOptions();
  return std::get<AffineOctreeOptions>(options);
}

WaveletOptions& EncodeSettings::wavelet() {
  if (!std::holds_alternative<WaveletOptions>(options)) options = WaveletOptions();
  return std::get<WaveletOptions>(options);
}

Result<EncodeReport> encodeSequence(FrameSource& source, const EncodeSettings& settings,
                                    const std::string& out_path, const ProgressFn& progress,
                                    const FrameObserver& observer) {
  ANIMC_RETURN_IF_ERROR(settings.validate());
  ANIMC_RETURN_IF_ERROR(checkSource(source));
  ANIMC_RETURN_IF_ERROR(checkDecodable(source.topology(), settings.entry()));
  const Topology& topology = source.topology();
  ContainerHeader header;
  header.codec = settings.codec();
  header.codec_params = codecParameters(settings);
  header.vertex_count = topology.vertex_count;
  header.triangle_count = topology.triangles.size();
  header.frame_rate = source.frameRate();
  header.iframe_interval = settings.iframe_interval;

  ContainerWriter writer;
  ANIMC_RETURN_IF_ERROR(writer.open(out_path, header, topology));
  std::unique_ptr<FrameEncoder> encoder = settings.entry().makeEncoder(settings.options, topology, bestSimdPath());
  EncodeReport report;
  report.vertices = topology.vertex_count;
  report.triangles = topology.triangles.size();
  const int64_t total = source.frameCount();
  std::vector<float> xyz;
  std::vector<uint8_t> payload;
  double seconds = 0;
  for (;;) {
    const std::string where = source.where();
    ANIMC_ASSIGN_OR_RETURN(bool more, source.next(xyz));
    if (!more) break;
    ANIMC_RETURN_IF_ERROR(checkFrame(xyz, where, report.frames));
    const bool intra = report.frames == 0 ||
                       (settings.iframe_interval > 0 && report.frames % settings.iframe_interval == 0);
    FrameCodingStats stats;
    payload.clear();
    const auto t0 = Clock::now();
    encoder->encodeFrame(xyz.data(), intra, payload, stats);
    seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    ANIMC_RETURN_IF_ERROR(writer.addFrame(payload, stats.intra));
    if (report.frames == 0) report.static_bytes = writer.bytesWritten();
    report.intra_frames += stats.intra;
    report.cells += stats.cells;
    if (observer) observer(report.frames, xyz.data(), encoder->reconstruction());
    ++report.frames;
    if (progress) {
      const int pct = total > 0 ? int(std::min<int64_t>(99, 100 * report.frames / total)) : 0;
      if (!progress(pct, "encoding")) return cancelled();
    }
  }
  if (report.frames == 0) return badInput(source.where() + ": the sequence has no frames");
  ANIMC_RETURN_IF_ERROR(writer.finish());
  report.file_bytes = writer.bytesWritten();
  report.encode_seconds = seconds;
  if (progress) progress(100, "encoded");
  return report;
}

Result<std::unique_ptr<AmsSource>> AmsSource::open(const std::string& path, const DecoderLimits& limits,
                                                   const WaveletDecodeControl& progressive) {
  std::unique_ptr<AmsSource> s(new AmsSource());
  s->path_ = path;
  s->limits_ = limits;
  ANIMC_ASSIGN_OR_RETURN(s->reader_, ContainerReader::open(path, limits));
  auto settings = readSettings(s->reader_->info().header);
  if (!settings.ok()) return settings.status().withContext(path);
  s->settings_ = settings.value();
  ANIMC_ASSIGN_OR_RETURN(s->decoder_, s->settings_.entry().makeDecoder(s->settings_.options, s->reader_->topology(),
                                                                       progressive, path, bestSimdPath()));
  Status st = s->seek(0);
  if (!st.ok()) return st;
  return s;
}

Status AmsSource::seek(int64_t frame) {
  if (frame < 0 || frame >= frameCount())
    return invalidArgument("frame " + std::to_string(frame) + " outside [0, " +
                           std::to_string(frameCount()) + ")");
  if (positioned_ && frame == next_frame_) return Status();
  positioned_ = false;
  group_ = reader_->groupOf(uint64_t(frame));
  Status s = reader_->beginGroup(group_);
  if (!s.ok()) return s.withContext(path_);
  next_frame_ = int64_t(reader_->groupFirstFrame(group_));
  std::vector<float> skipped;
  while (next_frame_ < frame) {
    ANIMC_ASSIGN_OR_RETURN(bool got, next(skipped));
    if (!got) return corrupt(path_ + ": frame group ends early");
  }
  positioned_ = true;
  return Status();
}

Result<bool> AmsSource::next(std::vector<float>& xyz) {
  positioned_ = false;
  if (next_frame_ >= frameCount()) {
    // The last group must end exactly after its last frame: its frame count is checked
    // against the index, so this only finds bytes left over after the last frame.
    auto after = reader_->nextFrame(payload_);
    if (!after.ok()) return after.status().withContext(path_);
    return false;
  }
  auto got = reader_->nextFrame(payload_);
  if (!got.ok()) return got.status().withContext(where());
  if (!got.value()) {  // end of this group: the next one starts with an intra frame
    Status s = reader_->beginGroup(++group_);
    if (!s.ok()) return s.withContext(path_);
    got = reader_->nextFrame(payload_);
    if (!got.ok()) return got.status().withContext(where());
    if (!got.value()) return corrupt(where() + ": empty frame group");
  }
  bool intra = false;
  Status s = decoder_->decodeFrame(ByteReader(payload_.data(), payload_.size()), xyz, &intra);
  if (!s.ok()) return s.withContext(where());
  if (next_frame_ == int64_t(reader_->groupFirstFrame(group_)) && !intra)
    return corrupt(where() + ": a frame group does not start with an intra frame");
  ++next_frame_;
  return true;
}

uint64_t AmsSource::decodeWork(int64_t first, int64_t last) const {
  if (first < 0 || last <= first || first >= frameCount()) return 0;
  const uint64_t start = reader_->groupFirstFrame(reader_->groupOf(uint64_t(first)));
  return (uint64_t(last) - start) * topology().vertex_count;
}

Status AmsSource::checkDecodeWork(int64_t first, int64_t last) const {
  const uint64_t work = decodeWork(first, last);
  if (work <= limits_.max_vertex_frames) return Status();
  return limitExceeded(path_ + ": decoding frames " + std::to_string(first) + " to " + std::to_string(last - 1) +
                       " costs " + std::to_string(work) + " vertex-frames (" + std::to_string(topology().vertex_count) +
                       " vertices, from the start of their frame group), above the limit of " +
                       std::to_string(limits_.max_vertex_frames) +
                       "; decode fewer frames or raise the limit (animc --max-vertex-frames)");
}

std::string AmsSource::where() const { return path_ + " frame " + std::to_string(next_frame_); }

Result<AmsCheck> checkAmsFile(const std::string& path, const DecoderLimits& limits) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<AmsSource> ams, AmsSource::open(path, limits));
  ANIMC_RETURN_IF_ERROR(ams->checkDecodeWork(0, ams->frameCount()));
  std::vector<float> xyz;
  int64_t decoded = 0;
  for (;;) {
    // next() enters each group in turn (checking it) and, after the last frame, checks that
    // nothing follows it in its group.
    ANIMC_ASSIGN_OR_RETURN(bool more, ams->next(xyz));
    if (!more) break;
    ++decoded;
  }
  if (decoded != ams->frameCount())
    return corrupt(path + ": " + std::to_string(decoded) + " frames decoded, the index announces " +
                   std::to_string(ams->frameCount()));
  AmsCheck check;
  check.settings = ams->settings();
  check.vertices = ams->topology().vertex_count;
  check.triangles = ams->topology().triangles.size();
  check.frames = decoded;
  check.groups = ams->info().groupCount();
  check.file_bytes = ams->info().file_bytes;
  return check;
}

}  // namespace animc
