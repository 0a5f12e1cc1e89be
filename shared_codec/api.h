// SPDX-License-Identifier: Apache-2.0
// The flat API of the codec library, used by animc and the MeshLab plugins alike:
// encode a stream of frames to an .ams file, and read one back as a stream of frames.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "codecs/codec_registry.h"
#include "container/container_reader.h"
#include "core/sequence.h"
#include "core/status.h"

namespace animc {

struct EncodeSettings {
  CodecOptions options;  // the chosen codec's options (Affine-Octree's defaults by default)
  uint32_t iframe_interval = 0;  // an intra frame every K frames; 0 = the first frame only

  CodecId codec() const { return codecOf(options).id; }
  const CodecEntry& entry() const { return codecOf(options); }
  // The options of that codec; the mutable ones choose that codec first (with its defaults)
  // when another one was chosen, so `s.wavelet().step = 1e-3` selects the wavelet codec.
  AffineOctreeOptions& octree();
  WaveletOptions& wavelet();
  const AffineOctreeOptions& octree() const { return std::get<AffineOctreeOptions>(options); }
  const WaveletOptions& wavelet() const { return std::get<WaveletOptions>(options); }

  Status validate() const { return entry().validate(options); }
};

struct EncodeReport {
  uint32_t vertices = 0;
  uint64_t triangles = 0;
  int64_t frames = 0;
  uint64_t intra_frames = 0;
  uint64_t cells = 0;  // octree leaves over all inter frames
  uint64_t file_bytes = 0;
  uint64_t static_bytes = 0;  // header, connectivity and the first frame
  double encode_seconds = 0;  // coding only: excludes reading the input
};

// Sees each original frame with its reconstruction as the decoder will produce it, so the
// caller can measure errors without decoding the file again.
using FrameObserver =
    std::function<void(int64_t frame, const float* original, const std::vector<double>& reconstructed)>;

// Encodes every frame of source into out_path (written atomically: on any error, nothing
// appears there). progress is called once per frame.
Result<EncodeReport> encodeSequence(FrameSource& source, const EncodeSettings& settings,
                                    const std::string& out_path, const ProgressFn& progress = {},
                                    const FrameObserver& observer = {});

// An .ams file as a stream of frames; seek() gives random access through the frame index,
// decoding only the frame group that holds the frame asked for.
class AmsSource final : public FrameSource {
 public:
  // Starts at frame 0. progressive: decode fewer bitplanes or bytes of each frame (wavelet
  // files whose detail frames a decoder may cut, WaveletOptions::cuttable(); asking it of any
  // other file is an error).
  static Result<std::unique_ptr<AmsSource>> open(const std::string& path,
                                                 const DecoderLimits& limits = {},
                                                 const WaveletDecodeControl& progressive = {});

  const Topology& topology() const override { return reader_->topology(); }
  int64_t frameCount() const override { return int64_t(reader_->info().frame_count); }
  double frameRate() const override { return reader_->info().header.frame_rate; }
  Result<bool> next(std::vector<float>& xyz) override;
  std::string where() const override;

  Status seek(int64_t frame);
  // Vertex-frames that decoding frames [first, last) costs: from the start of the group that
  // holds `first` (a decoder cannot start inside a group) to `last`.
  uint64_t decodeWork(int64_t first, int64_t last) const;
  // kLimitExceeded, saying how to raise the limit, when decodeWork(first, last) exceeds the
  // open() limits' max_vertex_frames. Call it before decoding a range.
  Status checkDecodeWork(int64_t first, int64_t last) const;
  const ContainerInfo& info() const { return reader_->info(); }
  const EncodeSettings& settings() const { return settings_; }

 private:
  AmsSource() = default;
  std::string path_;
  std::unique_ptr<ContainerReader> reader_;
  std::unique_ptr<FrameDecoder> decoder_;
  DecoderLimits limits_;
  EncodeSettings settings_;
  int64_t next_frame_ = 0;
  size_t group_ = 0;
  // A seek succeeded and no frame was read since: a seek to next_frame_ has nothing to do
  // (open() leaves the source there, and callers seek to their first frame).
  bool positioned_ = false;
  std::vector<uint8_t> payload_;
};

// What checkAmsFile() saw of a file that passed.
struct AmsCheck {
  EncodeSettings settings;
  uint32_t vertices = 0;
  uint64_t triangles = 0;
  int64_t frames = 0;
  uint64_t groups = 0;
  uint64_t file_bytes = 0;
};

// The whole-file check of `animc test`: opens the file (header, index, the CRC of every section
// but the frame groups', the first group), then enters every group (its CRC, its frame numbers
// against the index) and decodes every frame, keeping none; the last group must end right after
// its last frame. Opening a file alone (AmsSource::open(), `animc info`) checks the first group
// only.
Result<AmsCheck> checkAmsFile(const std::string& path, const DecoderLimits& limits = {});

}  // namespace animc
