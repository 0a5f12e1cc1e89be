// SPDX-License-Identifier: Apache-2.0
#include "api.h"

#include <algorithm>

#include "core/atomic_file.h"
#include "core/large_memory.h"
#include "encoder_access.h"

namespace animc {

AffineOctreeOptions& EncodeSettings::octree() {
  if (!std::holds_alternative<AffineOctreeOptions>(options)) options = AffineOctreeOptions();
  return std::get<AffineOctreeOptions>(options);
}

WaveletOptions& EncodeSettings::wavelet() {
  if (!std::holds_alternative<WaveletOptions>(options)) options = WaveletOptions();
  return std::get<WaveletOptions>(options);
}

TrajectoryOptions& EncodeSettings::trajectory() {
  if (!std::holds_alternative<TrajectoryOptions>(options)) options = TrajectoryOptions();
  return std::get<TrajectoryOptions>(options);
}

Trajectory2Options& EncodeSettings::trajectory2() {
  if (!std::holds_alternative<Trajectory2Options>(options)) options = Trajectory2Options();
  return std::get<Trajectory2Options>(options);
}

AutoOptions& EncodeSettings::automatic() {
  if (!std::holds_alternative<AutoOptions>(options)) options = withCandidates(AutoOptions());
  return std::get<AutoOptions>(options);
}

Result<EncodeSummary> encodeSequence(FrameSource& source, const EncodeSettings& settings, const std::string& out_path,
                                     const ProgressFn& progress, const FrameObserver& observer) {
  // Settings and mesh are checked before the output file is created.
  ANIMC_RETURN_IF_ERROR(settings.validate());
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ByteSink> sink, fileSink(out_path));
  return encodeSequence(source, settings, std::move(sink), progress, observer);
}

Result<EncodeSummary> encodeSequence(FrameSource& source, const EncodeSettings& settings,
                                     std::unique_ptr<ByteSink> sink, const ProgressFn& progress,
                                     const FrameObserver& observer) {
  // The encoder's own copy of the mesh, in huge pages: a large mesh's triangles are tens of
  // megabytes written here for the first time.
  Topology topology;
  topology.vertex_count = source.topology().vertex_count;
  resizeWithHugePages(topology.triangles, source.topology().triangles.size());
  std::copy(source.topology().triangles.begin(), source.topology().triangles.end(), topology.triangles.begin());
  auto created = createEncoder(settings, std::move(topology), source.frameRate(), std::move(sink));
  if (!created.ok()) return created.status().withContext(source.where());
  Encoder& encoder = created.value();
  const int64_t total = source.frameCount();
  std::vector<float> xyz;
  // The observer sees a group's frames when the encoder has coded it, in the encoder's own
  // copy: a large group is never held twice.
  int64_t observed = 0;
  auto observe = [&]() -> Status {
    for (; observed < encoder.reconstructedFrames(); ++observed) {
      const float* reconstruction = encoder.reconstruction(observed);
      if (reconstruction == nullptr)
        return corrupt("internal error: the codec cannot decode its own frame " + std::to_string(observed));
      observer(observed, EncoderAccess::original(encoder, observed), reconstruction);
    }
    return Status();
  };
  for (int64_t frame = 0;; ++frame) {
    const std::string where = source.where();  // before next() moves past the frame
    ANIMC_ASSIGN_OR_RETURN(bool more, source.next(xyz));
    if (!more) break;
    Status s = encoder.addFrame(xyz.data());
    if (!s.ok()) return s.withContext(where);
    if (observer) ANIMC_RETURN_IF_ERROR(observe());
    if (progress) {
      const int pct = total > 0 ? int(std::min<int64_t>(99, 100 * (frame + 1) / total)) : 0;
      if (!progress(pct, "encoding")) return cancelled();
    }
  }
  auto summary = encoder.finish();
  if (!summary.ok()) return summary.status().withContext(source.where());
  if (observer) ANIMC_RETURN_IF_ERROR(observe());
  if (progress) progress(100, "encoded");
  return summary;
}

Result<std::unique_ptr<AmsSource>> AmsSource::open(const std::string& path, const DecoderLimits& limits,
                                                   const WaveletDecodeControl& progressive, uint32_t threads) {
  DecoderOptions options;
  options.limits = limits;
  options.progressive = progressive;
  options.threads = threads;
  ANIMC_ASSIGN_OR_RETURN(Decoder decoder, Decoder::openFile(path, options));
  return std::make_unique<AmsSource>(std::move(decoder));
}

Status AmsSource::seek(int64_t frame) {
  if (frame < 0 || frame >= frameCount())
    return invalidArgument("frame " + std::to_string(frame) + " outside [0, " + std::to_string(frameCount()) + ")");
  next_frame_ = frame;
  return Status();
}

Result<bool> AmsSource::next(std::vector<float>& xyz) {
  if (next_frame_ >= frameCount()) return false;
  const size_t size = size_t(topology().vertex_count) * 3;
  if (next_frame_ < chunk_first_ || next_frame_ >= chunk_end_) {
    const int64_t end = decodeChunkEnd(decoder_, next_frame_);
    chunk_end_ = chunk_first_ = next_frame_;  // empty until the frames are there
    chunk_.resize(size_t(end - next_frame_) * size);
    ANIMC_RETURN_IF_ERROR(decoder_.frames(next_frame_, end, chunk_.data()));
    chunk_end_ = end;
  }
  const float* frame = chunk_.data() + size_t(next_frame_ - chunk_first_) * size;
  xyz.assign(frame, frame + size);
  ++next_frame_;
  return true;
}

std::string AmsSource::where() const { return streamName(decoder_) + " frame " + std::to_string(next_frame_); }

Result<AmsCheck> checkAmsFile(const std::string& path, const DecoderLimits& limits, uint32_t threads) {
  DecoderOptions options;
  options.limits = limits;
  options.threads = threads;
  ANIMC_ASSIGN_OR_RETURN(Decoder decoder, Decoder::openFile(path, options));
  ANIMC_RETURN_IF_ERROR(decoder.verify());
  AmsCheck check;
  check.settings = streamSettings(decoder);
  check.vertices = decoder.info().vertices;
  check.triangles = decoder.info().triangles;
  check.frames = decoder.info().frames;
  check.groups = decoder.info().groups;
  ANIMC_ASSIGN_OR_RETURN(check.groups_by_codec, groupsByCodec(decoder));
  check.file_bytes = decoder.info().bytes;
  return check;
}

}  // namespace animc
