// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/options.h"

#include <cmath>
#include <string>

namespace animc {

Status WaveletOptions::validate() const {
  if (!(bits_per_vertex >= 0 && bits_per_vertex <= kMaxBitsPerVertex))
    return invalidArgument("bits per vertex " + std::to_string(bits_per_vertex) + " outside [0, 1024]");
  if (!(step >= kMinWaveletStep && step <= kMaxWaveletStep))
    return invalidArgument("wavelet step " + std::to_string(step) +
                           " outside [1e-9, 1] (a fraction of the parametric mesh's diagonal)");
  if (parametric_bits < kMinParametricBits || parametric_bits > kMaxParametricBits)
    return invalidArgument("parametric bits " + std::to_string(parametric_bits) + " outside [4, 28]");
  if (progressive_p_frames && !temporal_prediction)
    return invalidArgument("progressive P-frames need P-frames (--progressive-p-frames excludes --i-frames-only)");
  if (!(target_kg == 0 || (target_kg > 0 && target_kg <= kMaxTargetKg)))
    return invalidArgument("target KG error " + std::to_string(target_kg) + " % outside (0, 100] (0 = off)");
  return Status();
}

void WaveletOptions::write(ByteWriter& w) const {
  w.f64(bits_per_vertex);
  w.f64(step);
  w.u8(uint8_t(parametric_bits));
  w.u8(uint8_t((temporal_prediction ? 1 : 0) | (truncatable ? 2 : 0) | (local_frames ? 4 : 0) |
               (progressive_p_frames ? 8 : 0)));
  w.f64(target_kg);
}

Result<WaveletOptions> WaveletOptions::read(ByteReader& r) {
  WaveletOptions o;
  ANIMC_ASSIGN_OR_RETURN(o.bits_per_vertex, r.f64("Bits_Per_Vertex"));
  ANIMC_ASSIGN_OR_RETURN(o.step, r.f64("Wavelet_Step"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t bits, r.u8("Parametric_Bits"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t flags, r.u8("Wavelet_Flags"));
  if (flags & ~15u) return corrupt("codec parameters: reserved wavelet flag bits set");
  o.parametric_bits = bits;
  o.temporal_prediction = flags & 1;
  o.truncatable = flags & 2;
  o.local_frames = flags & 4;
  o.progressive_p_frames = flags & 8;
  ANIMC_ASSIGN_OR_RETURN(o.target_kg, r.f64("Target_KG"));
  if (r.remaining() != 0) return corrupt("codec parameters: " + std::to_string(r.remaining()) + " unread bytes");
  Status s = o.validate();
  if (!s.ok()) return corrupt("codec parameters: " + s.message());
  return o;
}

}  // namespace animc
