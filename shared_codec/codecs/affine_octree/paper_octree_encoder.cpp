// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <cstring>

#include "codecs/affine_octree/paper_octree.h"

namespace animc {

struct PaperOctreeEncoder::Walk {
  const PFrameInput& in;
  RangeEncoder rc;
  std::vector<double>& recon;
  PaperFrameStats& stats;
};

void PaperOctreeEncoder::encode(const PFrameInput& in, std::vector<uint8_t>& out,
                                std::vector<double>& recon, PaperFrameStats& stats) {
  const Cell root = partition_.reset(*in.reference, in.max_depth);
  recon.resize(in.reference->size());
  Walk w{in, RangeEncoder(out), recon, stats};
  encodeCell(w, root);
  w.rc.finish();
}

void PaperOctreeEncoder::encodeCell(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  if (n == 0) return;
  if (n <= kPaperMaxLeafPositions) return encodePositions(w, cell);
  const std::vector<double>& u = *w.in.reference;
  const std::vector<double>& q = *w.in.target;
  const uint32_t* idx = partition_.vertices(cell);
  Affine34 fit;
  fitAffinePaper(u, q, idx, n, fit);
  double a[12];
  uint32_t coded[12];
  for (int i = 0; i < 12; ++i) {
    coded[i] = quantiseUnit(fit.a[i], kPaperAffineMin, kPaperAffineMax, bits_);
    a[i] = dequantiseUnit(coded[i], kPaperAffineMin, kPaperAffineMax, bits_);
  }
  double worst = 0;
  for (uint32_t i = 0; i < n; ++i) {
    double p[3];
    applyAffine34(a, &u[3 * size_t(idx[i])], p);
    const double* t = &q[3 * size_t(idx[i])];
    worst = std::max(worst, std::hypot(p[0] - t[0], p[1] - t[1], p[2] - t[2]));
  }
  const bool fits = worst <= w.in.max_error;
  if (cell.depth < w.in.max_depth) {
    w.rc.encode(models_->split[cell.depth], !fits);
    if (!fits) {
      Cell children[8];
      partition_.split(cell, children);
      for (const Cell& child : children) encodeCell(w, child);
      return;
    }
  }
  w.rc.encode(models_->positions_leaf, !fits);
  if (!fits) return encodePositions(w, cell);
  ++w.stats.cells;
  for (int i = 0; i < 12; ++i) encodeWide(w.rc, models_->affine[i], coded[i], bits_);
  for (uint32_t i = 0; i < n; ++i) applyAffine34(a, &u[3 * size_t(idx[i])], &w.recon[3 * size_t(idx[i])]);
}

void PaperOctreeEncoder::encodePositions(Walk& w, const Cell& cell) {
  ++w.stats.cells;
  const std::vector<double>& q = *w.in.target;
  const uint32_t* idx = partition_.vertices(cell);
  for (uint32_t i = 0; i < cell.end - cell.begin; ++i) {
    const double* t = &q[3 * size_t(idx[i])];
    double* r = &w.recon[3 * size_t(idx[i])];
    uint32_t coded[3];
    double p[3];
    for (int a = 0; a < 3; ++a) {
      coded[a] = quantiseUnit(t[a], kPaperPositionMin, kPaperPositionMax, bits_);
      p[a] = dequantiseUnit(coded[a], kPaperPositionMin, kPaperPositionMax, bits_);
    }
    // Outside the range, or a grid too coarse for ME: send the exact value instead.
    const bool escape = std::hypot(p[0] - t[0], p[1] - t[1], p[2] - t[2]) > w.in.max_error;
    w.rc.encode(models_->escape, escape);
    for (int a = 0; a < 3; ++a) {
      if (escape) {
        uint64_t bits;
        std::memcpy(&bits, &t[a], 8);
        w.rc.encodeRaw(uint32_t(bits >> 32), 32);
        w.rc.encodeRaw(uint32_t(bits), 32);
        r[a] = t[a];
      } else {
        encodeWide(w.rc, models_->position[a], coded[a], bits_);
        r[a] = p[a];
      }
    }
  }
}

}  // namespace animc
