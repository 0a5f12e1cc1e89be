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
    decoder_.reset();  // the last group's decoding state, before the encoder's own
    auto encoder = codec_.makeEncoder(options_, topology_, path_);
    payloads.assign(frame_count, {});
    stats_.assign(frame_count, {});
    for (uint32_t k = 0; k < frame_count; ++k)
      encoder->encodeFrame(frames + k * frameSize(), k == 0, payloads[k], stats_[k]);
    payloads_ = payloads;
  }

  // Decodes the group's own payloads as a reader would, from its intra frame on: a large
  // group's reconstructions are not kept beside its frames while it competes (auto) or waits
  // for its batch, and a group nobody asks about is never decoded. Frames asked in order
  // decode once each.
  bool reconstruction(uint32_t k, float* xyz) const override {
    if (!decoder_ || k < next_) {
      auto made = codec_.makeDecoder(options_, topology_, DecoderOptions(), "", path_);
      if (!made.ok()) return false;
      decoder_ = std::move(made.value());
      next_ = 0;
    }
    for (; next_ <= k; ++next_) {
      const Status decoded =
          decoder_->decodeFrame(ByteReader(payloads_[next_].data(), payloads_[next_].size()), frame_, nullptr);
      if (!decoded.ok()) {
        decoder_.reset();  // its own payloads: a bug, not bad input
        return false;
      }
    }
    std::memcpy(xyz, frame_.data(), frameSize() * sizeof(float));
    return true;
  }

  FrameCodingStats frameStats(uint32_t k) const override { return stats_[k]; }

 private:
  size_t frameSize() const { return size_t(3) * topology_.vertex_count; }

  const CodecEntry& codec_;
  CodecOptions options_;
  const Topology& topology_;
  SimdPath path_;
  std::vector<FrameCodingStats> stats_;         // of the last group's frames
  std::vector<std::vector<uint8_t>> payloads_;  // the last group's
  mutable std::unique_ptr<FrameDecoder> decoder_;
  mutable uint32_t next_ = 0;  // the frame decoder_ decodes next
  mutable std::vector<float> frame_;
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
