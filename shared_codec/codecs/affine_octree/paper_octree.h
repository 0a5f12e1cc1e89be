// SPDX-License-Identifier: Apache-2.0
// P-frames of the "paper" profile: the Affine-Octree method as published. A cell whose
// quantised affine leaves every vertex within ME is a leaf; otherwise it splits into eight,
// and cells of at most four vertices (or at the depth limit) store positions.
// docs/affine_octree.md lists every choice the paper leaves open.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "codecs/affine_octree/affine_fit.h"
#include "codecs/affine_octree/octree_shared.h"
#include "codecs/affine_octree/options.h"
#include "codecs/affine_octree/pframe.h"
#include "core/status.h"
#include "entropy/bit_tree.h"
#include "io/byte_reader.h"

namespace animc {

// The fixed quantisation ranges (the paper's predefined amin/amax), in root-cube units.
constexpr double kPaperAffineMin = -2.0;
constexpr double kPaperAffineMax = 2.0;
constexpr double kPaperPositionMin = -1.0;
constexpr double kPaperPositionMax = 2.0;
constexpr uint32_t kPaperMaxLeafPositions = 4;

struct PaperModels {
  BitModel split[kMaxDepthLimit + 1];
  BitModel positions_leaf;  // a cell of more than 4 vertices at the depth limit
  BitModel escape;          // a stored position outside the quantisation range: raw bits
  WideSymbolModel affine[12];
  WideSymbolModel position[3];
};

struct PaperFrameStats {
  uint64_t cells = 0;  // leaves: affine or stored positions
};

class PaperOctreeEncoder {
 public:
  PaperOctreeEncoder(int bits, SimdPath path) : bits_(bits), partition_(path) {}
  void reset() { models_ = std::make_unique<PaperModels>(); }
  // Codes one frame; recon receives the decoder's reconstruction (normalised units).
  void encode(const PFrameInput& in, std::vector<uint8_t>& out, std::vector<double>& recon,
              PaperFrameStats& stats);

 private:
  struct Walk;
  void encodeCell(Walk& w, const Cell& cell);
  void encodePositions(Walk& w, const Cell& cell);

  int bits_;
  std::unique_ptr<PaperModels> models_ = std::make_unique<PaperModels>();
  OctreePartition partition_;
};

class PaperOctreeDecoder {
 public:
  PaperOctreeDecoder(int bits, SimdPath path) : bits_(bits), partition_(path) {}
  void reset() { models_ = std::make_unique<PaperModels>(); }
  Status decode(const PFrameInput& in, ByteReader payload, std::vector<double>& recon);

 private:
  struct Walk;
  Status decodeCell(Walk& w, const Cell& cell);
  Status decodePositions(Walk& w, const Cell& cell);

  int bits_;
  std::unique_ptr<PaperModels> models_ = std::make_unique<PaperModels>();
  OctreePartition partition_;
};

// Shared arithmetic of the two sides.
uint32_t quantiseUnit(double value, double lo, double hi, int bits);
// Inline: the decoder calls these for every coded value and every vertex.
inline double dequantiseUnit(uint32_t q, double lo, double hi, int bits) {
  return lo + double(q) * (hi - lo) / double((1u << bits) - 1);
}
inline void applyAffine34(const double a[12], const double* u, double* out) {
  for (int r = 0; r < 3; ++r)
    out[r] = a[4 * r] * u[0] + a[4 * r + 1] * u[1] + a[4 * r + 2] * u[2] + a[4 * r + 3];
}

}  // namespace animc
