// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/options.h"

#include <string>

namespace animc {

Status TrajectoryOptions::validate() const {
  if (step == 0 && !(target_kg > 0 && target_kg <= kMaxTrajectoryTargetKg))
    return invalidArgument("target KG error " + std::to_string(target_kg) + " % outside (0, 100]");
  if (step != 0 && !(step >= kMinTrajectoryStep && step <= kMaxTrajectoryStep))
    return invalidArgument("trajectory step " + std::to_string(step) +
                           " outside [1e-9, 1] (a fraction of the first frame's diagonal)");
  if (group_frames < 1 || group_frames > kMaxTrajectoryGroupFrames)
    return invalidArgument("group frames " + std::to_string(group_frames) + " outside [1, " +
                           std::to_string(kMaxTrajectoryGroupFrames) + "]");
  return Status();
}

void TrajectoryOptions::write(ByteWriter& w) const {
  w.f64(target_kg);
  w.f64(step);
  w.u32(group_frames);
}

Result<TrajectoryOptions> TrajectoryOptions::read(ByteReader& r) {
  TrajectoryOptions o;
  ANIMC_ASSIGN_OR_RETURN(o.target_kg, r.f64("Target_KG"));
  ANIMC_ASSIGN_OR_RETURN(o.step, r.f64("Trajectory_Step"));
  ANIMC_ASSIGN_OR_RETURN(o.group_frames, r.u32("Group_Frames"));
  if (r.remaining() != 0) return corrupt("codec parameters: " + std::to_string(r.remaining()) + " unread bytes");
  Status s = o.validate();
  if (!s.ok()) return corrupt("codec parameters: " + s.message());
  return o;
}

}  // namespace animc
