// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/options.h"

#include <string>

namespace animc {
namespace {

struct RateRange {
  double low, high;
  bool low_included;
  const char* unit;
};

RateRange rangeOf(TrajectoryRate rate) {
  switch (rate) {
    case TrajectoryRate::kTargetKg: return {0, kMaxTrajectoryTargetKg, false, " % (KG error)"};
    case TrajectoryRate::kStep: return {kMinTrajectoryStep, kMaxTrajectoryStep, true, " of the diagonal"};
    case TrajectoryRate::kMaxError:
      return {kMinTrajectoryMaxError, kMaxTrajectoryMaxError, true, " of the cube's side"};
    case TrajectoryRate::kBitsPerVertexFrame: return {0, kMaxTrajectoryBpvf, false, " bits per vertex per frame"};
  }
  return {0, 0, false, ""};
}

}  // namespace

const char* rateName(TrajectoryRate rate) {
  switch (rate) {
    case TrajectoryRate::kTargetKg: return "target KG";
    case TrajectoryRate::kStep: return "step";
    case TrajectoryRate::kMaxError: return "max error";
    case TrajectoryRate::kBitsPerVertexFrame: return "bpvf";
  }
  return "unknown";
}

Status TrajectoryOptions::validate() const {
  if (uint8_t(rate) > uint8_t(TrajectoryRate::kBitsPerVertexFrame))
    return invalidArgument("unknown trajectory rate mode " + std::to_string(int(rate)));
  const RateRange r = rangeOf(rate);
  const bool above_low = r.low_included ? rate_value >= r.low : rate_value > r.low;
  if (!(above_low && rate_value <= r.high))
    return invalidArgument(std::string(rateName(rate)) + " " + std::to_string(rate_value) + " outside " +
                           (r.low_included ? "[" : "(") + std::to_string(r.low) + ", " + std::to_string(r.high) + "]" +
                           r.unit);
  if (group_frames < 1 || group_frames > kMaxTrajectoryGroupFrames)
    return invalidArgument("group frames " + std::to_string(group_frames) + " outside [1, " +
                           std::to_string(kMaxTrajectoryGroupFrames) + "]");
  return Status();
}

void TrajectoryOptions::write(ByteWriter& w) const {
  w.u8(uint8_t(rate));
  w.f64(rate_value);
  w.u32(group_frames);
}

namespace {

Status readFields(ByteReader& r, TrajectoryOptions& o) {
  ANIMC_ASSIGN_OR_RETURN(uint8_t rate, r.u8("Rate_Mode"));
  o.rate = TrajectoryRate(rate);
  ANIMC_ASSIGN_OR_RETURN(o.rate_value, r.f64("Rate_Value"));
  ANIMC_ASSIGN_OR_RETURN(o.group_frames, r.u32("Group_Frames"));
  return Status();
}

// The block read whole and valid, or the reason it is not.
template <class Options>
Result<Options> checked(const ByteReader& r, const Options& o) {
  if (r.remaining() != 0) return corrupt("codec parameters: " + std::to_string(r.remaining()) + " unread bytes");
  Status s = o.validate();
  if (!s.ok()) return corrupt("codec parameters: " + s.message());
  return o;
}

}  // namespace

Result<TrajectoryOptions> TrajectoryOptions::read(ByteReader& r) {
  TrajectoryOptions o;
  ANIMC_RETURN_IF_ERROR(readFields(r, o));
  return checked(r, o);
}

Status Trajectory2Options::validate() const {
  ANIMC_RETURN_IF_ERROR(trajectory.validate());
  if (parts < 1 || parts > kMaxTrajectoryParts)
    return invalidArgument("parts " + std::to_string(parts) + " outside [1, " + std::to_string(kMaxTrajectoryParts) +
                           "]");
  return Status();
}

void Trajectory2Options::write(ByteWriter& w) const {
  trajectory.write(w);
  w.u8(uint8_t(parts));
}

Result<Trajectory2Options> Trajectory2Options::read(ByteReader& r) {
  Trajectory2Options o;
  ANIMC_RETURN_IF_ERROR(readFields(r, o.trajectory));
  ANIMC_ASSIGN_OR_RETURN(uint8_t parts, r.u8("Max_Parts"));
  o.parts = parts;
  return checked(r, o);
}

Result<uint32_t> groupFramesFlag(const OptionValues& values, uint32_t fallback) {
  ANIMC_ASSIGN_OR_RETURN(long long frames, values.integer("group-frames", fallback));
  if (frames < 1 || frames > kMaxTrajectoryGroupFrames)
    return invalidArgument("--group-frames must be in [1, " + std::to_string(kMaxTrajectoryGroupFrames) + "]");
  return uint32_t(frames);
}

}  // namespace animc
