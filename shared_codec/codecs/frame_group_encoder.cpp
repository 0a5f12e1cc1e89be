// SPDX-License-Identifier: Apache-2.0
#include "codecs/frame_group_encoder.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace animc {
namespace {

class FrameGroupEncoder final : public GroupEncoder {
 public:
  FrameGroupEncoder(const CodecEntry& codec, const CodecOptions& options, const Topology& topology, SimdPath path)
      : codec_(codec), options_(options), topology_(topology), path_(path) {}

  uint32_t maxGroupFrames() const override { return UINT32_MAX; }

  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    const size_t size = frameSize();
    auto encoder = codec_.makeEncoder(options_, topology_, path_);
    payloads.assign(frame_count, {});
    stats_.assign(frame_count, {});
    frames_.resize(frame_count * size);
    for (uint32_t k = 0; k < frame_count; ++k) {
      encoder->encodeFrame(frames + k * size, k == 0, payloads[k], stats_[k]);
      const std::vector<double>& r = encoder->reconstruction();
      std::copy(r.begin(), r.end(), frames_.begin() + k * size);  // decoders output floats
    }
  }

  void reconstruction(uint32_t k, float* xyz) const override {
    std::memcpy(xyz, frames_.data() + k * frameSize(), frameSize() * sizeof(float));
  }

  FrameCodingStats frameStats(uint32_t k) const override { return stats_[k]; }

 private:
  size_t frameSize() const { return size_t(3) * topology_.vertex_count; }

  const CodecEntry& codec_;
  CodecOptions options_;
  const Topology& topology_;
  SimdPath path_;
  std::vector<FrameCodingStats> stats_;  // of the last group's frames
  std::vector<float> frames_;            // the last group as decoded, 3N floats a frame
};

}  // namespace

std::unique_ptr<GroupEncoder> makeFrameGroupEncoder(const CodecEntry& codec, const CodecOptions& options,
                                                    const Topology& topology, SimdPath path) {
  return std::make_unique<FrameGroupEncoder>(codec, options, topology, path);
}

std::unique_ptr<GroupEncoder> makeAnyGroupEncoder(const CodecEntry& codec, const CodecOptions& options,
                                                  const Topology& topology, SimdPath path) {
  if (codec.makeGroupEncoder) return codec.makeGroupEncoder(options, topology, path);
  return makeFrameGroupEncoder(codec, options, topology, path);
}

}  // namespace animc
