// Progressive bitplane coding of real coefficients (paper section 4.2), most significant
// plane first. A coefficient's first 1 bit (its significance) goes through the adaptive
// binary range coder, in a context of (plane, class, how many of the other coefficients of
// its group are significant, whether its parent is); its sign and every later
// (refinement) bit are sent raw. The stream can stop after any coefficient of any plane: the
// decoder then knows each magnitude to the planes it received and reconstructs the middle
// of the remaining interval.
//
// Block layout (docs/wavelet.md): u8 Plane_Count (bit 7: has checkpoints), then, when
// Plane_Count > 0: varint Coded_Planes, varint Last_Plane_Stop, varint Range_Bytes,
// [Coded_Planes - 1 varints: range bytes needed for each complete plane, as increments],
// and Range_Bytes of range-coder data.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

constexpr int kBitplaneClasses = 16;
constexpr int kMaxBitplanes = 31;  // magnitudes are clamped below 2^31 steps
constexpr uint32_t kNoParent = UINT32_MAX;

// The coefficients as the coder sees them, in coding order: groups of 3 (the components of
// one vertex), each with a class (< kBitplaneClasses) and a parent coded before it
// (a coefficient index < its own, or kNoParent). Both sides must pass the same layout.
struct BitplaneLayout {
  const uint8_t* classes = nullptr;
  const uint32_t* parents = nullptr;
  size_t count = 0;  // a multiple of 3
};

struct BitplaneEncodeSettings {
  double step = 1;              // quantisation step of plane 0 (> 0)
  uint64_t byte_budget = 0;     // bytes for the whole block; 0 = no limit
  bool checkpoints = true;
  int max_planes = 0;           // 0 = down to plane 0
};

// values: layout.count entries in coding order. Appends the block to out; decoded receives
// what the decoder will reconstruct.
void encodeBitplanes(const double* values, const BitplaneLayout& layout,
                     const BitplaneEncodeSettings& settings, std::vector<uint8_t>& out,
                     std::vector<double>& decoded);

struct BitplaneDecodeSettings {
  double step = 1;
  int max_planes = 0;  // decode at most this many planes; 0 = all that were sent
};

// Reads one block from in (which must end where the block ends, or earlier if the payload
// was cut: the decoder then uses the complete planes its checkpoints vouch for).
// planes_decoded (optional) receives the number of planes used.
Status decodeBitplanes(ByteReader& in, const BitplaneLayout& layout,
                       const BitplaneDecodeSettings& settings, std::vector<double>& decoded,
                       int* planes_decoded = nullptr);

}  // namespace animc
