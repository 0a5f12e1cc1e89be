// SPDX-License-Identifier: Apache-2.0
// `--codec auto` (docs/auto.md): every group coded by each candidate codec, the smallest
// kept. Each frame payload is the index of its group's codec, then that codec's payload.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "codecs/auto/sampling.h"
#include "codecs/codec_registry.h"
#include "codecs/frame_group_encoder.h"
#include "core/parallel.h"

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

// How much smaller than a frame-by-frame candidate's estimate (sampling.h) a group codec's
// payload must be for that candidate to be skipped.
constexpr double kSkipShare = 0.75;
// The first frame of a run whose size stands for the group's other frames: the one before it
// (the first inter frame) predicts from one decoded frame where the affine-octree codec's
// later frames use two, and cost more than the group's frames do.
constexpr uint32_t kSteadyRunFrame = 2;
// A group of more frames than this (as floats) runs its candidates one after the other even
// with threads to spare: beside each other, their working sets (each a few times the group's)
// would add up. The group codecs still split their own work over the threads.
constexpr uint64_t kMaxBesideGroupBytes = uint64_t(1) << 26;

class AutoEncoder final : public GroupEncoder {
 public:
  AutoEncoder(const AutoOptions& options, const Topology& topology, SimdPath path)
      : topology_(topology), group_frames_(options.group_frames) {
    for (const AutoCandidate& c : options.candidates) {
      auto candidate = candidateOf(c);
      if (!candidate.ok() || !candidate.value().entry->checkMesh(topology).ok()) continue;
      const Candidate& chosen = candidate.value();
      encoders_.push_back(makeAnyGroupEncoder(*chosen.entry, chosen.options, topology_, path));
      frame_by_frame_.push_back(chosen.entry->makeGroupEncoder == nullptr);
      index_.push_back(uint8_t(&c - options.candidates.data()));
    }
    payloads_.resize(encoders_.size());
  }

  uint32_t maxGroupFrames() const override {
    uint32_t frames = group_frames_;
    for (const auto& e : encoders_) frames = std::min(frames, e->maxGroupFrames());
    return frames;
  }

  // Every candidate codes the group and the smallest is kept (the first of equal ones), but
  // in a group of 2 x kSampleRunFrames frames or more a frame-by-frame candidate first codes
  // a sample of it (sampling.h): when the group codecs' best is well below the whole group's
  // size estimated from the sample, that candidate is not run in full. With more than one
  // thread the frame-by-frame candidates (sample or group) run on a thread of their own beside
  // the group codecs, which keep the caller's threads, unless the group is large.
  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    const std::vector<uint32_t> sample = sampleRunStarts(frame_count);
    const bool sampled = !sample.empty();
    std::vector<double> estimates(encoders_.size(), 0);
    auto codeFrameByFrame = [&] {
      for (size_t i = 0; i < encoders_.size(); ++i) {
        if (!frame_by_frame_[i]) continue;
        if (sampled)
          estimates[i] = estimatedBytes(*encoders_[i], frames, frame_count, sample);
        else
          encoders_[i]->encodeGroup(frames, frame_count, payloads_[i]);
      }
    };
    auto codeGroups = [&] {
      for (size_t i = 0; i < encoders_.size(); ++i)
        if (!frame_by_frame_[i]) encoders_[i]->encodeGroup(frames, frame_count, payloads_[i]);
    };
    if (uint64_t(frame_count) * 12 * topology_.vertex_count > kMaxBesideGroupBytes) {
      codeFrameByFrame();
      codeGroups();
    } else {
      runBeside(codeFrameByFrame, codeGroups);
    }
    size_t group_best = SIZE_MAX;
    for (size_t i = 0; i < encoders_.size(); ++i)
      if (!frame_by_frame_[i]) group_best = std::min(group_best, bytes(payloads_[i]));
    best_ = SIZE_MAX;
    for (size_t i = 0; i < encoders_.size(); ++i) {
      if (frame_by_frame_[i] && sampled) {
        if (double(group_best) <= kSkipShare * estimates[i]) continue;
        encoders_[i]->encodeGroup(frames, frame_count, payloads_[i]);
      }
      if (best_ == SIZE_MAX || bytes(payloads_[i]) < bytes(payloads_[best_])) best_ = i;
    }
    payloads = std::move(payloads_[best_]);
    for (auto& p : payloads) p.insert(p.begin(), index_[best_]);
  }

  bool reconstruction(uint32_t k, float* xyz) const override { return encoders_[best_]->reconstruction(k, xyz); }

 private:
  // A group's bytes from the runs of frames that sample it, each coded as a group of its own:
  // the first run's intra frame, then the mean of the runs' frames from kSteadyRunFrame on.
  double estimatedBytes(GroupEncoder& encoder, const float* frames, uint32_t frame_count,
                        const std::vector<uint32_t>& run_starts) {
    const size_t frame_floats = size_t(3) * topology_.vertex_count;
    double intra = 0, others = 0;
    for (uint32_t first : run_starts) {
      encoder.encodeGroup(frames + first * frame_floats, kSampleRunFrames, sample_);
      if (first == run_starts.front()) intra = double(sample_[0].size());
      for (uint32_t k = kSteadyRunFrame; k < kSampleRunFrames; ++k) others += double(sample_[k].size());
    }
    const double per_frame = others / double(run_starts.size() * (kSampleRunFrames - kSteadyRunFrame));
    return intra + per_frame * (frame_count - 1);
  }

  static size_t bytes(const std::vector<std::vector<uint8_t>>& payloads) {
    size_t n = 0;
    for (const auto& p : payloads) n += p.size();
    return n;
  }

  const Topology& topology_;
  uint32_t group_frames_;
  std::vector<std::unique_ptr<GroupEncoder>> encoders_;
  std::vector<bool> frame_by_frame_;
  std::vector<uint8_t> index_;                               // in the file's candidate list
  std::vector<std::vector<std::vector<uint8_t>>> payloads_;  // of each candidate, for the last group
  std::vector<std::vector<uint8_t>> sample_;                 // payloads of a run of frames
  size_t best_ = 0;                                          // the candidate kept for the last group
};

class AutoDecoder final : public FrameDecoder {
 public:
  explicit AutoDecoder(std::vector<std::unique_ptr<FrameDecoder>> decoders) : decoders_(std::move(decoders)) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    return read(payload, xyz, intra, true);
  }
  Status skipFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    return read(payload, xyz, intra, false);
  }

 private:
  // The frame's candidate decodes it, or skips it when it is not wanted.
  Status read(ByteReader payload, std::vector<float>& xyz, bool* intra, bool wanted) {
    ANIMC_ASSIGN_OR_RETURN(uint8_t index, payload.u8("Candidate_Index"));
    if (index >= decoders_.size())
      return corrupt("auto frame: candidate " + std::to_string(index) + " of " + std::to_string(decoders_.size()));
    bool candidate_intra = false;
    const int previous = current_;
    current_ = -1;  // until this frame decodes
    FrameDecoder& candidate = *decoders_[index];
    ANIMC_RETURN_IF_ERROR(wanted ? candidate.decodeFrame(payload, xyz, &candidate_intra)
                                 : candidate.skipFrame(payload, xyz, &candidate_intra));
    if (!candidate_intra && index != previous)
      return corrupt("auto frame: a frame group changes codec after its intra frame");
    current_ = index;
    if (intra) *intra = candidate_intra;
    return Status();
  }

  std::vector<std::unique_ptr<FrameDecoder>> decoders_;
  int current_ = -1;  // the candidate of the group being decoded
};

}  // namespace

std::vector<uint32_t> sampleRunStarts(uint32_t frame_count) {
  const uint32_t runs = std::min(kMostSampleRuns, frame_count / (2 * kSampleRunFrames));
  std::vector<uint32_t> starts;
  for (uint32_t run = 0; run < runs; ++run)
    starts.push_back(runs == 1 ? 0 : uint32_t(uint64_t(frame_count - kSampleRunFrames) * run / (runs - 1)));
  return starts;
}

std::unique_ptr<GroupEncoder> makeAutoEncoder(const AutoOptions& options, const Topology& topology, SimdPath path) {
  return std::make_unique<AutoEncoder>(options, topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeAutoDecoder(const AutoOptions& options, const Topology& topology,
                                                      const DecoderOptions& decoding, const std::string& file,
                                                      SimdPath path) {
  if (decoding.progressive.partial())
    return invalidArgument(file +
                           ": progressive decoding (fewer bitplanes or bytes) needs a wavelet-coded "
                           "file; this one is auto");
  std::vector<std::unique_ptr<FrameDecoder>> decoders;
  for (const AutoCandidate& c : options.candidates) {
    auto candidate = candidateOf(c);
    if (!candidate.ok()) return candidate.status().withContext(file);
    ANIMC_ASSIGN_OR_RETURN(
        auto decoder, candidate.value().entry->makeDecoder(candidate.value().options, topology, decoding, file, path));
    decoders.push_back(std::move(decoder));
  }
  return std::unique_ptr<FrameDecoder>(std::make_unique<AutoDecoder>(std::move(decoders)));
}

}  // namespace animc
