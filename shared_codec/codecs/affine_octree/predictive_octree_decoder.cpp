// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include "codecs/affine_octree/predictive_octree.h"
#include "core/simd_math.h"

namespace animc {

struct PredictiveOctreeDecoder::Walk {
  const PFrameInput& in;
  double step;
  RangeDecoder rc;
  RawBitReader raw;
  std::vector<double>& recon;
};

Status PredictiveOctreeDecoder::decode(const PFrameInput& in, ByteReader payload,
                                       std::vector<double>& recon) {
  recon.resize(in.reference->size());
  contexts_.beginFrame();
  Walk w{in, residualStep(in.max_error), RangeDecoder(payload.cursor(), payload.remaining()),
         RawBitReader(payload.cursor(), payload.remaining()), recon};
  const Cell root = partition_.reset(*in.reference, in.max_depth);
  if (root.end != root.begin) decodeCell(w, root);
  const size_t coded_bytes = size_t(w.rc.position() - payload.cursor());
  if (w.rc.overran() || w.raw.overran() || coded_bytes + w.raw.bytesUsed() > payload.remaining() + kFinishReadAhead)
    return corrupt("octree frame: coded data ends early or is damaged");
  return Status();
}

// Damaged data is found once the frame is decoded, not cell by cell: the walk is as short
// whatever the data (at most 8 children for each of the at most max_depth · n splits, n the
// vertex count, since the non-empty cells of a depth hold distinct vertices), and a decoder
// that reads past its input gets zeros.
// (The cell is never empty: empty children are skipped before the call.)
void PredictiveOctreeDecoder::decodeCell(Walk& w, const Cell& cell) {
  if (canSplit(cell, w.in.max_depth) && w.rc.decode(models_->split[cell.depth])) {
    Cell children[8];
    partition_.split(cell, children);
    for (const Cell& child : children)
      if (child.end != child.begin) decodeCell(w, child);
    return;
  }
  decodeLeaf(w, cell);
}

void PredictiveOctreeDecoder::decodeLeaf(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* idx = partition_.vertices(cell);
  PredictiveModels& pm = *models_;
  int64_t coded[12];
  decodeParameters(w, n, coded);
  points_.gather(w.in, idx, n);
  const LeafModel& m = points_.model;
  const CentredAffine a = codedAffine(m, correctionSteps(m.frame, n, w.step), coded);
  predictPoints(path_, points_.reference(), n, m.frame.centroid, a, idx, w.recon.data());
  if (!w.rc.decode(pm.residuals_zero[n <= kMinLinearVertices])) decodeResiduals(w, idx, n);
}

namespace {

// The entropy-decoding loops, written once and compiled twice: for any CPU and for x86-64
// CPUs with AVX2 and BMI2, whose one-micro-operation shifts by a variable amount speed up
// every model update. Each works on a local copy of the decoder, which the compiler keeps in
// registers only because its address never leaves the loop.

// Most of the bits of a frame on the game sequences, whose leaves are small.
__attribute__((always_inline)) inline void parametersLoop(RangeDecoder& decoder, RawBitReader& raw_bits,
                                                          PredictiveModels& pm, bool linear, int64_t coded[12]) {
  RangeDecoder rc = decoder;
  RawBitReader raw = raw_bits;
  for (int r = 0; r < 3; ++r) coded[r] = decodeClassed(rc, raw, pm.translation[r]);
  for (int k = 3; k < 12; ++k) coded[k] = linear ? decodeClassed(rc, raw, pm.linear) : 0;
  decoder = rc;
  raw_bits = raw;
}

// The hot loop of busy frames: a flag per vertex, then one adaptive integer per coordinate
// (decodeIntInline() written out), added onto the prediction. A zero residual, the usual
// one, changes nothing: the context is already zero (ResidualContexts::beginFrame()), and
// adding +0.0 would only turn a -0.0 prediction into +0.0, which denormalise() maps to the
// same coordinate (the frame's minimum is never -0.0: frame_passes.cpp).
__attribute__((always_inline)) inline void residualsLoop(RangeDecoder& decoder, PredictiveModels& pm,
                                                         ResidualContexts& contexts, const uint32_t* vertices,
                                                         uint32_t n, double step, double* recon) {
  RangeDecoder rc = decoder;
  IntegerModel<kResidualContexts>& ints = pm.residuals;
  for (uint32_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(vertices[i]);
    if (!rc.decode(pm.vertex_residual[contexts.vertexContext(v)])) continue;
    // Unrolled: most coordinates cost one zero flag, beside which counting the axes is a
    // large share of the loop.
#pragma GCC unroll 3
    for (size_t c = v; c < v + 3; ++c) {
      const int ctx = contexts.contextAt(c);
      if (!rc.decode(ints.zero[ctx])) continue;
      const int64_t r = decodeMagnitudeAndSign(rc, ints, ctx);
      recon[c] += double(r) * step;
      contexts.setAt(c, r);
    }
  }
  decoder = rc;
}

// noinline: see cell_kernels.cpp (portable versions).
__attribute__((noinline)) void parametersPortable(RangeDecoder& rc, RawBitReader& raw, PredictiveModels& pm, bool linear,
                                                  int64_t coded[12]) {
  parametersLoop(rc, raw, pm, linear, coded);
}
__attribute__((noinline)) void residualsPortable(RangeDecoder& rc, PredictiveModels& pm, ResidualContexts& contexts,
                                                 const uint32_t* vertices, uint32_t n, double step, double* recon) {
  residualsLoop(rc, pm, contexts, vertices, n, step, recon);
}

#if ANIMC_AVX2_PATH
ANIMC_TARGET_AVX2 void parametersAvx2(RangeDecoder& rc, RawBitReader& raw, PredictiveModels& pm, bool linear,
                                      int64_t coded[12]) {
  parametersLoop(rc, raw, pm, linear, coded);
}
ANIMC_TARGET_AVX2 void residualsAvx2(RangeDecoder& rc, PredictiveModels& pm, ResidualContexts& contexts,
                                     const uint32_t* vertices, uint32_t n, double step, double* recon) {
  residualsLoop(rc, pm, contexts, vertices, n, step, recon);
}
#endif

}  // namespace

void PredictiveOctreeDecoder::decodeParameters(Walk& w, uint32_t n, int64_t coded[12]) {
  const bool linear = n >= kMinLinearVertices;
#if ANIMC_AVX2_PATH
  if (useAvx2(path_)) return parametersAvx2(w.rc, w.raw, *models_, linear, coded);
#endif
  parametersPortable(w.rc, w.raw, *models_, linear, coded);
}

void PredictiveOctreeDecoder::decodeResiduals(Walk& w, const uint32_t* vertices, uint32_t n) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path_)) return residualsAvx2(w.rc, *models_, contexts_, vertices, n, w.step, w.recon.data());
#endif
  residualsPortable(w.rc, *models_, contexts_, vertices, n, w.step, w.recon.data());
}

}  // namespace animc
