// SPDX-License-Identifier: Apache-2.0
#include "codecs/affine_octree/options.h"

#include <cmath>
#include <string>

namespace animc {

const char* profileName(Profile p) {
  switch (p) {
    case Profile::kPaper: return "paper";
    case Profile::kPredictive: return "predictive";
  }
  return "unknown";
}

Status AffineOctreeOptions::validate() const {
  if (profile != Profile::kPaper && profile != Profile::kPredictive)
    return invalidArgument("unknown profile " + std::to_string(int(profile)));
  if (!(max_error >= kMinMaxError && max_error <= kMaxMaxError))
    return invalidArgument("max error " + std::to_string(max_error) + " outside [" +
                           std::to_string(kMinMaxError) + ", " + std::to_string(kMaxMaxError) +
                           "] (a fraction of the root cube's side: 0.01 = 1%)");
  if (bits < kMinBits || bits > kMaxBits)
    return invalidArgument("bits " + std::to_string(bits) + " outside [8, 24]");
  if (max_depth < 1 || max_depth > kMaxDepthLimit)
    return invalidArgument("max depth " + std::to_string(max_depth) + " outside [1, 16]");
  return Status();
}

void AffineOctreeOptions::write(ByteWriter& w) const {
  w.u8(uint8_t(profile));
  w.f64(max_error);
  w.u8(uint8_t(bits));
  w.u8(uint8_t(max_depth));
}

Result<AffineOctreeOptions> AffineOctreeOptions::read(ByteReader& r) {
  AffineOctreeOptions o;
  ANIMC_ASSIGN_OR_RETURN(uint8_t profile, r.u8("Profile"));
  // A profile is a variant of the codec's bitstream (its parameters may differ too): one this
  // build lacks is a newer file, not a broken one.
  if (profile != uint8_t(Profile::kPaper) && profile != uint8_t(Profile::kPredictive))
    return unsupported("codec parameters: affine-octree profile " + std::to_string(profile) +
                       " is not supported (this build reads 0 paper, 1 predictive; a newer animcompress may read it)");
  ANIMC_ASSIGN_OR_RETURN(o.max_error, r.f64("Max_Error"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t bits, r.u8("Bits"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t depth, r.u8("Max_Depth"));
  o.profile = Profile(profile);
  o.bits = bits;
  o.max_depth = depth;
  if (r.remaining() != 0) return corrupt("codec parameters: " + std::to_string(r.remaining()) + " unread bytes");
  Status s = o.validate();
  if (!s.ok()) return corrupt("codec parameters: " + s.message());
  return o;
}

}  // namespace animc
