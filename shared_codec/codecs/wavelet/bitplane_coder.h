// SPDX-License-Identifier: Apache-2.0
// Progressive bitplane coding of real coefficients (paper section 4.2), most significant
// plane first. Coefficients come in groups of three (the components of one vertex) and the
// vertices in blocks of kBlockVertices consecutive ones in coding order. In each plane a
// block not yet significant codes one flag (does any of its coefficients become significant
// here?), a vertex not yet significant one flag, then its components; coefficients already
// significant code their refinement bit. Significance and sign decisions go through the
// adaptive binary range coder; refinement bits are raw bits of the same coder (no model).
// Significance contexts combine the plane, the vertex's class, the parent's state and, for
// P-frames, what the same coefficient did in the previous frame (temporal context). The
// stream can stop after any block of any plane: the decoder then knows each magnitude to the
// planes it received and reconstructs inside the remaining interval, biased towards zero
// (residuals are roughly Laplacian).
//
// Block layout (docs/wavelet.md): u8 Plane_Count (bit 7: has checkpoints), then, when
// Plane_Count > 0: varint Coded_Planes, varint Last_Plane_Stop (blocks coded in the last
// plane), varint Range_Bytes, [Coded_Planes - 1 varints: range bytes needed for each complete
// plane, as increments], and Range_Bytes of range-coder data.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/simd_math.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

constexpr int kBitplaneClasses = 16;
constexpr int kMaxBitplanes = 31;
// The largest magnitude in steps the planes carry (encoders check fitsBitplanes).
constexpr uint32_t kMaxBitplaneMagnitude = (1u << kMaxBitplanes) - 1;
constexpr size_t kBlockVertices = 16;
constexpr uint32_t kNoParent = UINT32_MAX;

// The coefficients as the coder sees them, in coding order: `vertices` groups of 3, each
// vertex with a class (< kBitplaneClasses) and a parent vertex coded before it (an index
// < its own, or kNoParent). Both sides must pass the same layout.
struct BitplaneLayout {
  const uint8_t* classes = nullptr;
  const uint32_t* parents = nullptr;
  size_t vertices = 0;
  size_t count() const { return 3 * vertices; }
};

// What a decoded frame leaves for the temporal contexts of the next one, per coefficient in
// coding order: the bit length of its decoded magnitude in steps (0 = zero) and its sign.
struct BitplaneHistory {
  std::vector<uint8_t> bits;
  std::vector<uint8_t> negative;
  void reset(size_t count) {
    bits.assign(count, 0);
    negative.assign(count, 0);
  }
};

// Buffers reused from frame to frame (no allocation per frame once sized).
struct BitplaneWorkspace;
struct BitplaneWorkspaceDeleter {
  void operator()(BitplaneWorkspace* w) const;
};
using BitplaneWorkspacePtr = std::unique_ptr<BitplaneWorkspace, BitplaneWorkspaceDeleter>;
BitplaneWorkspacePtr makeBitplaneWorkspace();

// Whether every value is below 2^31 - 1 steps, the largest magnitude the planes carry. An
// encoder must not code values that do not fit: the coder would clamp them without a word.
bool fitsBitplanes(const std::vector<double>& values, double step);

struct BitplaneEncodeSettings {
  double step = 1;              // quantisation step of plane 0 (> 0)
  uint64_t byte_budget = 0;     // bytes for the whole block; 0 = no limit
  bool checkpoints = true;
  int max_planes = 0;           // 0 = down to plane 0
  // Forced cut: the last plane coded (the lowest allowed by max_planes) stops after this
  // many blocks; 0 = complete.
  size_t last_plane_blocks = 0;
  // Temporal contexts from the previous frame (null: none). Its size must be layout.count().
  const BitplaneHistory* context = nullptr;
  SimdPath path = SimdPath::kPortable;  // the kernels' version (core/simd_math.h): same bytes
};

// values: layout.count() entries in coding order. Appends the block to out; decoded receives
// what the decoder will reconstruct, history (optional) what it leaves for the next frame.
void encodeBitplanes(const double* values, const BitplaneLayout& layout,
                     const BitplaneEncodeSettings& settings, std::vector<uint8_t>& out,
                     std::vector<double>& decoded, BitplaneHistory* history = nullptr,
                     BitplaneWorkspace* workspace = nullptr);

// Encoder-side search of a cut (rate control by target error). The planes encodeBitplanes
// would write for these values; then, for a cut after `planes` planes of which the last
// stops after `blocks` blocks, what the decoder would reconstruct (no coding involved).
class BitplaneCutPreview {
 public:
  BitplaneCutPreview(SimdPath path, const double* values, const BitplaneLayout& layout, double step,
                     BitplaneWorkspace* workspace);
  int planeCount() const { return planes_; }
  size_t blockCount() const { return (layout_.vertices + kBlockVertices - 1) / kBlockVertices; }
  void decoded(int planes, size_t blocks, std::vector<double>& out) const;

 private:
  BitplaneLayout layout_;
  double step_;
  BitplaneWorkspace* workspace_;
  int planes_ = 0;
};

struct BitplaneDecodeSettings {
  double step = 1;
  int max_planes = 0;  // decode at most this many planes; 0 = all that were sent
  const BitplaneHistory* context = nullptr;  // must be what the encoder used
  SimdPath path = SimdPath::kPortable;  // the kernels' version (core/simd_math.h): same frames
};

// Reads one block from in (which must end where the block ends, or earlier if the payload
// was cut: the decoder then uses the complete planes its checkpoints vouch for).
// planes_decoded (optional) receives the number of planes used.
Status decodeBitplanes(ByteReader& in, const BitplaneLayout& layout,
                       const BitplaneDecodeSettings& settings, std::vector<double>& decoded,
                       int* planes_decoded = nullptr, BitplaneHistory* history = nullptr,
                       BitplaneWorkspace* workspace = nullptr);

}  // namespace animc
