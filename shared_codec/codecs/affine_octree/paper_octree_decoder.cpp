// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <cstring>
#include <string>

#include "codecs/affine_octree/paper_octree.h"

namespace animc {

struct PaperOctreeDecoder::Walk {
  const PFrameInput& in;
  RangeDecoder rc;
  std::vector<double>& recon;
};

Status PaperOctreeDecoder::decode(const PFrameInput& in, ByteReader payload,
                                  std::vector<double>& recon) {
  const Cell root = partition_.reset(*in.reference, in.max_depth);
  recon.resize(in.reference->size());
  Walk w{in, RangeDecoder(payload.cursor(), payload.remaining()), recon};
  ANIMC_RETURN_IF_ERROR(decodeCell(w, root));
  if (w.rc.overran()) return corrupt("octree frame: coded data ends early or is damaged");
  return Status();
}

Status PaperOctreeDecoder::decodeCell(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  if (n == 0) return Status();
  if (w.rc.overran()) return corrupt("octree frame: coded data ends early or is damaged");
  if (n <= kPaperMaxLeafPositions) return decodePositions(w, cell);
  const std::vector<double>& u = *w.in.reference;
  if (cell.depth < w.in.max_depth && w.rc.decode(models_->split[cell.depth])) {
    Cell children[8];
    partition_.split(cell, children);
    for (const Cell& child : children) ANIMC_RETURN_IF_ERROR(decodeCell(w, child));
    return Status();
  }
  if (w.rc.decode(models_->positions_leaf)) return decodePositions(w, cell);
  double a[12];
  for (int i = 0; i < 12; ++i)
    a[i] = dequantiseUnit(decodeWide(w.rc, models_->affine[i], bits_), kPaperAffineMin,
                          kPaperAffineMax, bits_);
  const uint32_t* idx = partition_.vertices(cell);
  for (uint32_t i = 0; i < cell.end - cell.begin; ++i)
    applyAffine34(a, &u[3 * size_t(idx[i])], &w.recon[3 * size_t(idx[i])]);
  return Status();
}

Status PaperOctreeDecoder::decodePositions(Walk& w, const Cell& cell) {
  const uint32_t* idx = partition_.vertices(cell);
  for (uint32_t i = 0; i < cell.end - cell.begin; ++i) {
    double* r = &w.recon[3 * size_t(idx[i])];
    const bool escape = w.rc.decode(models_->escape);
    for (int a = 0; a < 3; ++a) {
      if (escape) {
        const uint64_t hi = w.rc.decodeRaw(32);
        const uint64_t bits = (hi << 32) | w.rc.decodeRaw(32);
        std::memcpy(&r[a], &bits, 8);
        if (!std::isfinite(r[a]) || std::fabs(r[a]) > 1e12)
          return corrupt("octree frame: stored position of vertex " +
                         std::to_string(idx[i]) + " out of range");
      } else {
        r[a] = dequantiseUnit(decodeWide(w.rc, models_->position[a], bits_), kPaperPositionMin,
                              kPaperPositionMax, bits_);
      }
    }
  }
  return Status();
}

}  // namespace animc
