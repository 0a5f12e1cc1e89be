// SPDX-License-Identifier: Apache-2.0
#include "codecs/auto/options.h"

#include <string>

#include "codecs/affine_octree/options.h"
#include "codecs/wavelet/options.h"

namespace animc {

Status AutoOptions::validate() const {
  if (rate != TrajectoryRate::kTargetKg && rate != TrajectoryRate::kMaxError)
    return invalidArgument("--codec auto takes --target-kg or --max-error");
  TrajectoryOptions t;
  t.rate = rate;
  t.rate_value = rate_value;
  t.group_frames = group_frames;
  ANIMC_RETURN_IF_ERROR(t.validate());
  if (candidates.empty() || candidates.size() > kMaxAutoCandidates)
    return invalidArgument(std::to_string(candidates.size()) + " candidate codecs (1 to " +
                           std::to_string(kMaxAutoCandidates) + ")");
  for (const AutoCandidate& c : candidates)
    if (c.codec == CodecId::kAuto) return invalidArgument("auto cannot be its own candidate");
  return Status();
}

void AutoOptions::write(ByteWriter& w) const {
  w.u8(uint8_t(rate));
  w.f64(rate_value);
  w.u32(group_frames);
  w.u8(uint8_t(candidates.size()));
  for (const AutoCandidate& c : candidates) {
    w.u8(uint8_t(c.codec));
    w.u16(uint16_t(c.params.size()));
    for (uint8_t b : c.params) w.u8(b);
  }
}

Result<AutoOptions> AutoOptions::read(ByteReader& r) {
  AutoOptions o;
  ANIMC_ASSIGN_OR_RETURN(uint8_t rate, r.u8("Rate_Mode"));
  o.rate = TrajectoryRate(rate);
  ANIMC_ASSIGN_OR_RETURN(o.rate_value, r.f64("Rate_Value"));
  ANIMC_ASSIGN_OR_RETURN(o.group_frames, r.u32("Group_Frames"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t count, r.u8("Candidate_Count"));
  if (count < 1 || count > kMaxAutoCandidates)
    return corrupt("codec parameters: " + std::to_string(count) + " candidate codecs");
  for (uint8_t i = 0; i < count; ++i) {
    AutoCandidate c;
    ANIMC_ASSIGN_OR_RETURN(uint8_t id, r.u8("Candidate_Codec_Id"));
    c.codec = CodecId(id);
    ANIMC_ASSIGN_OR_RETURN(uint16_t length, r.u16("Candidate_Params_Length"));
    ANIMC_ASSIGN_OR_RETURN(ByteReader params, r.subReader(length, "Candidate_Params"));
    c.params.assign(params.cursor(), params.cursor() + length);
    o.candidates.push_back(std::move(c));
  }
  if (r.remaining() != 0) return corrupt("codec parameters: " + std::to_string(r.remaining()) + " unread bytes");
  Status s = o.validate();
  if (!s.ok()) return corrupt("codec parameters: " + s.message());
  return o;
}

AutoOptions withCandidates(AutoOptions o) {
  o.candidates.clear();
  Trajectory2Options trajectory;
  trajectory.trajectory.rate = o.rate;
  trajectory.trajectory.rate_value = o.rate_value;
  trajectory.trajectory.group_frames = o.group_frames;
  ByteWriter w;
  trajectory.write(w);
  o.candidates.push_back({CodecId::kTrajectory2, w.bytes()});
  ByteWriter other;
  if (o.rate == TrajectoryRate::kTargetKg) {
    WaveletOptions wavelet;
    wavelet.target_kg = o.rate_value;
    wavelet.write(other);
    o.candidates.push_back({CodecId::kWavelet, other.bytes()});
  } else {
    AffineOctreeOptions octree;
    octree.max_error = o.rate_value;
    octree.write(other);
    o.candidates.push_back({CodecId::kAffineOctree, other.bytes()});
  }
  return o;
}

}  // namespace animc
