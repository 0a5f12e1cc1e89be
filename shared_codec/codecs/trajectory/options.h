// SPDX-License-Identifier: Apache-2.0
// Encoder settings of the trajectory codec (docs/trajectory.md). They travel in the
// container's codec parameters; the decoder needs none of them (every group says what it
// holds), so they are there for `animc info`.
#pragma once
#include <cstdint>

#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

struct TrajectoryOptions {
  // Rate control by target error, in percent of the KG error: each group gets the coarsest
  // coefficient step whose decoded frames have a squared error <= (target_kg / 100)^2 times
  // the group's sum of |x - centroid|^2, so the sequence's KG error is <= target_kg.
  double target_kg = 0.3;
  // Instead of a target: one fixed coefficient step, a fraction of the first frame's
  // bounding-box diagonal (0 = use target_kg).
  double step = 0;
  // Most frames in one group when the I-frame interval does not set it: memory is
  // O(vertices x group frames), and longer groups cost fewer bits.
  uint32_t group_frames = 512;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<TrajectoryOptions> read(ByteReader& r);
};

// Ranges accepted by validate(), by the decoder and, for the group limits, by the payload
// reader: a group holds at most kMaxTrajectoryGroupFrames frames, and its coefficients
// (vertices x components) at most kMaxTrajectoryCoefficients values.
constexpr double kMaxTrajectoryTargetKg = 100;
constexpr double kMinTrajectoryStep = 1e-9;
constexpr double kMaxTrajectoryStep = 1;
constexpr uint32_t kMaxTrajectoryGroupFrames = 1024;
constexpr uint64_t kMaxTrajectoryCoefficients = uint64_t(1) << 26;

}  // namespace animc
