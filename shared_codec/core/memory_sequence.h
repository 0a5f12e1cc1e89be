// SPDX-License-Identifier: Apache-2.0
// A sequence held in memory: for the MeshLab plugins (layers are already in memory), tests
// and benchmarks. Everything else streams.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/sequence.h"

namespace animc {

class MemorySequence final : public FrameSource {
 public:
  MemorySequence(Topology topology, std::vector<std::vector<float>> frames, double frame_rate = 25.0,
                 std::string name = "memory")
      : topology_(std::move(topology)), frames_(std::move(frames)), frame_rate_(frame_rate),
        name_(std::move(name)) {}

  const Topology& topology() const override { return topology_; }
  int64_t frameCount() const override { return int64_t(frames_.size()); }
  double frameRate() const override { return frame_rate_; }
  Result<bool> next(std::vector<float>& xyz) override {
    if (next_ >= frames_.size()) return false;
    const std::vector<float>& f = frames_[next_];
    if (f.size() != 3 * size_t(topology_.vertex_count))
      return badInput(where() + ": has " + std::to_string(f.size() / 3) + " vertices, expected " +
                      std::to_string(topology_.vertex_count));
    xyz = f;
    ++next_;
    return true;
  }
  std::string where() const override { return name_ + " frame " + std::to_string(next_); }

  void rewind() { next_ = 0; }
  const std::vector<std::vector<float>>& frames() const { return frames_; }

 private:
  Topology topology_;
  std::vector<std::vector<float>> frames_;
  double frame_rate_;
  std::string name_;
  size_t next_ = 0;
};

// The next frames of source, read into memory: all that are left, or at most max_frames.
Result<std::vector<std::vector<float>>> readFrames(
    FrameSource& source, int64_t max_frames = std::numeric_limits<int64_t>::max());

// Reads every frame of source into memory.
Result<MemorySequence> readAll(FrameSource& source);

}  // namespace animc
