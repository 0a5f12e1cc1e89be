// SPDX-License-Identifier: Apache-2.0
// The library's internal side of its public API (animc/animc.h), for animc, the MeshLab plugins
// and the tests: the codec settings as typed options, and adapters between the public Encoder
// and Decoder and the FrameSource streams of the sequence readers and writers.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "animc/animc.h"
#include "codecs/codec_registry.h"
#include "container/container_reader.h"
#include "core/sequence.h"
#include "core/status.h"

namespace animc {

struct EncodeSettings {
  CodecOptions options;          // the chosen codec's options (Affine-Octree's defaults by default)
  uint32_t iframe_interval = 0;  // an intra frame every K frames; 0 = the first frame only
  uint32_t threads = 1;          // EncoderOptions::threads (not written to the stream)
  uint32_t connectivity_piece = kDefaultConnectivityPiece;  // EncoderOptions::connectivity_piece

  CodecId codec() const { return codecOf(options).id; }
  const CodecEntry& entry() const { return codecOf(options); }
  // The options of that codec; the mutable ones choose that codec first (with its defaults)
  // when another one was chosen, so `s.wavelet().step = 1e-3` selects the wavelet codec.
  AffineOctreeOptions& octree();
  WaveletOptions& wavelet();
  TrajectoryOptions& trajectory();
  Trajectory2Options& trajectory2();
  AutoOptions& automatic();
  const AffineOctreeOptions& octree() const { return std::get<AffineOctreeOptions>(options); }
  const WaveletOptions& wavelet() const { return std::get<WaveletOptions>(options); }

  Status validate() const { return entry().validate(options); }
};

// The options of a public EncoderOptions, checked: what Encoder::create() codes with.
Result<EncodeSettings> encodeSettingsFrom(const EncoderOptions& options);

// The public Encoder for settings already made (the CLI, the plugins and the tests hold them
// as EncodeSettings).
Result<Encoder> createEncoder(const EncodeSettings& settings, Topology topology, double frame_rate,
                              std::unique_ptr<ByteSink> sink);

// What a Decoder read of its stream beyond StreamInfo: the sections, the settings as the
// codec's options, the triangles as the library holds them.
const ContainerInfo& containerInfo(const Decoder& decoder);
const EncodeSettings& streamSettings(const Decoder& decoder);
const Topology& streamTopology(const Decoder& decoder);
const std::string& streamName(const Decoder& decoder);
// Where a run of frames from `first` that Decoder::frames() decodes at once, on every thread
// the decoder has, should end: after the groups of one batch, within a bound on memory
// (128 MB of frames, and the output limit); first + 1 with one thread, or when the run would
// not reach past first's group.
int64_t decodeChunkEnd(const Decoder& decoder, int64_t first);

// How many of a stream's groups each codec coded: auto's candidates in the file's order
// (from the index that starts each group's first frame, a few bytes a group; their CRCs are
// verify()'s to check), or the file's codec for all of them.
struct GroupCodecCount {
  std::string codec;
  uint64_t groups = 0;
};
Result<std::vector<GroupCodecCount>> groupsByCodec(const Decoder& decoder);

// Sees each original frame with its reconstruction as the decoder will produce it, so the
// caller can measure errors without decoding the file again.
using FrameObserver = std::function<void(int64_t frame, const float* original, const float* reconstructed)>;

// Encodes every frame of source through an Encoder into out_path (written atomically: on any
// error, nothing appears there). progress is called once per frame.
Result<EncodeSummary> encodeSequence(FrameSource& source, const EncodeSettings& settings, const std::string& out_path,
                                     const ProgressFn& progress = {}, const FrameObserver& observer = {});
// The same into any sink.
Result<EncodeSummary> encodeSequence(FrameSource& source, const EncodeSettings& settings,
                                     std::unique_ptr<ByteSink> sink, const ProgressFn& progress = {},
                                     const FrameObserver& observer = {});

// A Decoder as a stream of frames (for the sequence writers and the metrics).
class AmsSource final : public FrameSource {
 public:
  // Starts at frame 0. progressive: see ProgressiveOptions; threads: DecoderOptions::threads.
  static Result<std::unique_ptr<AmsSource>> open(const std::string& path, const DecoderLimits& limits = {},
                                                 const WaveletDecodeControl& progressive = {}, uint32_t threads = 0);
  explicit AmsSource(Decoder decoder) : decoder_(std::move(decoder)) {}

  const Topology& topology() const override { return streamTopology(decoder_); }
  int64_t frameCount() const override { return decoder_.info().frames; }
  double frameRate() const override { return decoder_.info().frame_rate; }
  Result<bool> next(std::vector<float>& xyz) override;
  std::string where() const override;

  // The frame next() gives next.
  Status seek(int64_t frame);
  Status checkDecodeWork(int64_t first, int64_t last, uint64_t output_bytes = 0) const {
    return decoder_.checkDecodeWork(first, last, output_bytes);
  }
  const ContainerInfo& info() const { return containerInfo(decoder_); }
  const EncodeSettings& settings() const { return streamSettings(decoder_); }
  Decoder& decoder() { return decoder_; }

 private:
  Decoder decoder_;
  int64_t next_frame_ = 0;
  // Frames decoded ahead, several groups at once (decodeChunkEnd()): chunk_first_ on.
  std::vector<float> chunk_;
  int64_t chunk_first_ = 0, chunk_end_ = 0;
};

// What checkAmsFile() saw of a file that passed.
struct AmsCheck {
  EncodeSettings settings;
  uint32_t vertices = 0;
  uint64_t triangles = 0;
  int64_t frames = 0;
  uint64_t groups = 0;
  std::vector<GroupCodecCount> groups_by_codec;
  uint64_t file_bytes = 0;
};

// The whole-file check of `animc test`: Decoder::verify() of the file. Opening a file alone
// (Decoder::openFile(), `animc info`) checks the first group only.
Result<AmsCheck> checkAmsFile(const std::string& path, const DecoderLimits& limits = {}, uint32_t threads = 0);

}  // namespace animc
