// SPDX-License-Identifier: Apache-2.0
// Encoder settings of the trajectory codec (docs/trajectory.md). They travel in the
// container's codec parameters; the decoder needs none of them (every group says what it
// holds), so they are there for `animc info`.
#pragma once
#include <cstdint>

#include "codecs/option_values.h"
#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

// How a group's coefficient step is chosen (Rate_Mode in the codec parameters).
enum class TrajectoryRate : uint8_t {
  // The coarsest step whose decoded frames have a squared error <= (value / 100)^2 times
  // the group's sum of |x - centroid|^2: the sequence's KG error is then <= value (percent).
  kTargetKg = 0,
  // One fixed step, value times the group's first-frame bounding-box diagonal.
  kStep = 1,
  // The coarsest step whose decoded vertices are all within value times the side of their
  // frame's bounding cube (1 for a point), as the affine-octree codec's max error.
  kMaxError = 2,
  // The finest step whose group payload fits value bits per vertex per frame.
  kBitsPerVertexFrame = 3,
};

struct TrajectoryOptions {
  TrajectoryRate rate = TrajectoryRate::kTargetKg;
  double rate_value = 0.3;
  // Most frames in one group when the I-frame interval does not set it: memory is
  // O(vertices x group frames), and longer groups cost fewer bits.
  uint32_t group_frames = 512;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<TrajectoryOptions> read(ByteReader& r);
};

// Codec 5 (trajectory, version 2): the same settings, and the most parts a group is cut into.
struct Trajectory2Options {
  TrajectoryOptions trajectory;
  uint32_t parts = 8;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<Trajectory2Options> read(ByteReader& r);
};

// "target KG", "step", "max error", "bpvf".
const char* rateName(TrajectoryRate rate);

// --group-frames of the trajectory and auto codecs, `fallback` when not given.
Result<uint32_t> groupFramesFlag(const OptionValues& values, uint32_t fallback);

// Ranges accepted by validate(), by the decoder and, for the group limits, by the payload
// reader: a group holds at most kMaxTrajectoryGroupFrames frames, and its coefficients
// (vertices x components) at most kMaxTrajectoryCoefficients values.
constexpr double kMaxTrajectoryTargetKg = 100;
constexpr double kMinTrajectoryStep = 1e-9;
constexpr double kMaxTrajectoryStep = 1;
constexpr double kMinTrajectoryMaxError = 1e-6;
constexpr double kMaxTrajectoryMaxError = 0.5;
constexpr double kMaxTrajectoryBpvf = 1024;
constexpr uint32_t kMaxTrajectoryGroupFrames = 1024;
constexpr uint64_t kMaxTrajectoryCoefficients = uint64_t(1) << 25;
constexpr uint32_t kMaxTrajectoryParts = 64;

}  // namespace animc
