// SPDX-License-Identifier: Apache-2.0
// `--codec auto` (docs/auto.md): every group coded by each candidate codec, the smallest
// kept. Each frame payload is the index of its group's codec, then that codec's payload.
#include <algorithm>
#include <cstring>

#include "codecs/codec_registry.h"

namespace animc {
namespace {

// A candidate's entry and options as its own streams would carry them.
struct Candidate {
  const CodecEntry* entry = nullptr;
  CodecOptions options;
};

Result<Candidate> candidateOf(const AutoCandidate& c) {
  Candidate out;
  out.entry = findCodec(uint8_t(c.codec));
  if (out.entry == nullptr || c.codec == CodecId::kAuto)
    return unsupported("auto: candidate codec id " + std::to_string(int(c.codec)) + " is not supported");
  ByteReader params(c.params.data(), c.params.size());
  ANIMC_ASSIGN_OR_RETURN(out.options, out.entry->read(params));
  return out;
}

// A group coded by one candidate: its payloads and the frames decoders will make of them.
struct CodedGroup {
  std::vector<std::vector<uint8_t>> payloads;
  std::vector<float> frames;  // 3N floats a frame
  size_t bytes() const {
    size_t n = 0;
    for (const auto& p : payloads) n += p.size();
    return n;
  }
};

class AutoEncoder final : public GroupEncoder {
 public:
  AutoEncoder(const AutoOptions& options, const Topology& topology, SimdPath path)
      : topology_(topology), path_(path), group_frames_(options.group_frames) {
    for (const AutoCandidate& c : options.candidates) {
      auto candidate = candidateOf(c);
      if (!candidate.ok() || !candidate.value().entry->checkMesh(topology).ok()) continue;
      candidates_.push_back(candidate.value());
      if (candidate.value().entry->makeGroupEncoder)
        group_encoders_.push_back(candidate.value().entry->makeGroupEncoder(candidate.value().options, topology, path));
      else
        group_encoders_.push_back(nullptr);
      index_.push_back(uint8_t(&c - options.candidates.data()));
    }
  }

  uint32_t maxGroupFrames() const override {
    uint32_t frames = group_frames_;
    for (const auto& g : group_encoders_)
      if (g) frames = std::min(frames, g->maxGroupFrames());
    return frames;
  }

  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    CodedGroup best;
    uint8_t best_index = 0;
    for (size_t i = 0; i < candidates_.size(); ++i) {
      CodedGroup coded = code(i, frames, frame_count);
      if (i == 0 || coded.bytes() < best.bytes()) {
        best = std::move(coded);
        best_index = index_[i];
      }
    }
    payloads.clear();
    for (auto& p : best.payloads) {
      p.insert(p.begin(), best_index);
      payloads.push_back(std::move(p));
    }
    frames_ = std::move(best.frames);
  }

  void reconstruction(uint32_t k, float* xyz) const override {
    const size_t size = size_t(3) * topology_.vertex_count;
    std::memcpy(xyz, frames_.data() + k * size, size * sizeof(float));
  }

 private:
  CodedGroup code(size_t i, const float* frames, uint32_t frame_count) const {
    CodedGroup out;
    const size_t size = size_t(3) * topology_.vertex_count;
    out.frames.resize(frame_count * size);
    if (group_encoders_[i]) {
      group_encoders_[i]->encodeGroup(frames, frame_count, out.payloads);
      for (uint32_t k = 0; k < frame_count; ++k) group_encoders_[i]->reconstruction(k, out.frames.data() + k * size);
      return out;
    }
    // A frame-by-frame codec starts afresh for each group, as its decoder does at the
    // group's intra frame.
    auto encoder = candidates_[i].entry->makeEncoder(candidates_[i].options, topology_, path_);
    for (uint32_t k = 0; k < frame_count; ++k) {
      out.payloads.emplace_back();
      FrameCodingStats stats;
      encoder->encodeFrame(frames + k * size, k == 0, out.payloads.back(), stats);
      const std::vector<double>& r = encoder->reconstruction();
      std::copy(r.begin(), r.end(), out.frames.begin() + k * size);  // decoders output floats
    }
    return out;
  }

  Topology topology_;
  SimdPath path_;
  uint32_t group_frames_;
  std::vector<Candidate> candidates_;
  std::vector<std::unique_ptr<GroupEncoder>> group_encoders_;  // null for frame-by-frame codecs
  std::vector<uint8_t> index_;                                 // in the file's candidate list
  std::vector<float> frames_;                                  // the last group, as decoded
};

class AutoDecoder final : public FrameDecoder {
 public:
  explicit AutoDecoder(std::vector<std::unique_ptr<FrameDecoder>> decoders) : decoders_(std::move(decoders)) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    ANIMC_ASSIGN_OR_RETURN(uint8_t index, payload.u8("Candidate_Index"));
    if (index >= decoders_.size())
      return corrupt("auto frame: candidate " + std::to_string(index) + " of " + std::to_string(decoders_.size()));
    bool candidate_intra = false;
    const int previous = current_;
    current_ = -1;  // until this frame decodes
    ANIMC_RETURN_IF_ERROR(decoders_[index]->decodeFrame(payload, xyz, &candidate_intra));
    if (!candidate_intra && index != previous)
      return corrupt("auto frame: a frame group changes codec after its intra frame");
    current_ = index;
    if (intra) *intra = candidate_intra;
    return Status();
  }

 private:
  std::vector<std::unique_ptr<FrameDecoder>> decoders_;
  int current_ = -1;  // the candidate of the group being decoded
};

}  // namespace

std::unique_ptr<GroupEncoder> makeAutoEncoder(const AutoOptions& options, const Topology& topology, SimdPath path) {
  return std::make_unique<AutoEncoder>(options, topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeAutoDecoder(const AutoOptions& options, const Topology& topology,
                                                      const WaveletDecodeControl& control, const std::string& file,
                                                      SimdPath path) {
  if (control.partial())
    return invalidArgument(file + ": progressive decoding (fewer bitplanes or bytes) needs a wavelet-coded "
                           "file; this one is auto");
  std::vector<std::unique_ptr<FrameDecoder>> decoders;
  for (const AutoCandidate& c : options.candidates) {
    auto candidate = candidateOf(c);
    if (!candidate.ok()) return candidate.status().withContext(file);
    ANIMC_ASSIGN_OR_RETURN(auto decoder, candidate.value().entry->makeDecoder(candidate.value().options, topology,
                                                                             control, file, path));
    decoders.push_back(std::move(decoder));
  }
  return std::unique_ptr<FrameDecoder>(std::make_unique<AutoDecoder>(std::move(decoders)));
}

}  // namespace animc
