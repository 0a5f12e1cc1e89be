// SPDX-License-Identifier: Apache-2.0
// The animated-mesh model: one triangle list shared by every frame, and frames of N xyz
// positions that are streamed one at a time so memory stays O(N), never O(N * frames).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/status.h"

namespace animc {

// Coordinates beyond this are treated like NaN, in inputs and in what a stream decodes to:
// they overflow any quantisation grid.
constexpr double kMaxCoordinate = 1e30;

using Triangle = std::array<uint32_t, 3>;

struct Topology {
  uint32_t vertex_count = 0;
  std::vector<Triangle> triangles;
};

// A static mesh: the topology plus one frame of positions (x0 y0 z0 x1 ...).
struct Mesh {
  Topology topology;
  std::vector<float> positions;
};

// Streams the frames of a sequence in order. The topology is known before the first frame.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const Topology& topology() const = 0;
  // Number of frames, or -1 when the format cannot tell before reading them all.
  virtual int64_t frameCount() const = 0;
  virtual double frameRate() const { return 25.0; }
  // Fills xyz (resized to 3 * vertex_count) with the next frame. Returns false at the end.
  virtual Result<bool> next(std::vector<float>& xyz) = 0;
  // Name of the thing the next error should blame ("walk/0012.ply", "cow.pc2 frame 7").
  virtual std::string where() const = 0;
};

// Receives frames in order; finish() makes the output visible atomically (temp + rename).
// Destroying a sink without finish() removes whatever it had written.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  virtual Status write(const float* xyz) = 0;
  virtual Status finish() = 0;
};


}  // namespace animc
