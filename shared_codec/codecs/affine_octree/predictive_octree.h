// SPDX-License-Identifier: Apache-2.0
// P-frames of the "default" profile: the Affine-Octree family with the paper's open headroom
// taken (docs/affine_octree.md, "default profile", gives each change with its measured gain):
//  - the affine is expressed about the cell centroid (t = centroid motion, L = deformation);
//  - it is predicted from the same cell's motion between the two previous reconstructed
//    frames (the decoder refits it, nothing is sent), and only the correction is coded;
//  - quantisation steps follow from ME instead of a fixed 16 bits;
//  - every vertex gets a residual on a grid of step 2·ME/√3, which bounds its error by ME
//    whatever the split, so splits are chosen by estimated rate + weighted distortion;
//  - flags, residuals and the corrections' magnitude classes go through context-modelled
//    adaptive binary coding; the corrections' signs and low bits go raw, in a raw-bit stream
//    after the range coder's bytes (entropy/classed_integer.h, for decoding speed).
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "codecs/affine_octree/affine_fit.h"
#include "codecs/affine_octree/cell_kernels.h"
#include "codecs/affine_octree/octree_shared.h"
#include "codecs/affine_octree/options.h"
#include "codecs/affine_octree/pframe.h"
#include "codecs/affine_octree/residual_context.h"
#include "core/status.h"
#include "entropy/classed_integer.h"
#include "entropy/integer_coder.h"
#include "io/byte_reader.h"

namespace animc {

constexpr uint32_t kMinLinearVertices = 4;  // fewer vertices: translation only, L from the prior
// Tuned on all four shared sequences; docs/affine_octree.md gives the measurements.
constexpr double kTranslationStep = 0.5;      // in residual steps over √n (correctionSteps())
constexpr double kLinearStep = 1.25;          // in residual steps over √n per cell radius
constexpr double kRateDistortion = 0.1;       // scales the weight of distortion in splits
constexpr double kPruneDistortionBits = 8.0;  // search no deeper below such a quiet leaf
constexpr int64_t kMaxCodedMagnitude = int64_t(1) << 30;

struct PredictiveModels {
  BitModel split[kMaxDepthLimit + 1];
  // The coded affine's corrections: the translation's by axis (the motions along the three
  // axes differ in scale), the linear part's all alike.
  ClassedIntegerModel translation[3], linear;
  BitModel residuals_zero[2];
  BitModel vertex_residual[kResidualContexts];  // whether a vertex has a residual at all
  IntegerModel<kResidualContexts> residuals;    // by ResidualContexts::contextAt()

  // Start from "values are mostly zero" (what prediction is for) rather than from even
  // odds, so the rate estimates of the first frames after an I-frame do not favour
  // needless splits.
  PredictiveModels() {
    for (ClassedIntegerModel& m : translation) m.zero.p0 = uint16_t(0.85 * kProbOne);
    linear.zero.p0 = uint16_t(0.85 * kProbOne);
    for (BitModel& m : residuals.zero) m.p0 = uint16_t(0.85 * kProbOne);
    for (BitModel& m : vertex_residual) m.p0 = uint16_t(0.85 * kProbOne);
  }
};

// The residual grid step for a given ME: the worst error of rounding each axis is step/2,
// so the vertex error is at most √3·step/2 < ME. The margin covers floating-point rounding.
double residualStep(double max_error);

// Whether a cell may split (and so codes a split flag): not at the depth limit, and not when
// it holds so few vertices that eight children could only cost more parameters.
constexpr uint32_t kMinSplitVertices = 2;
inline bool canSplit(const Cell& cell, int max_depth) {
  return cell.depth < max_depth && cell.end - cell.begin >= kMinSplitVertices;
}

// What encoder and decoder derive for a leaf before any of its data: the frame of its
// reference points, and the prior of its affine, the cell's own motion from frame f-2 to
// f-1 assumed to continue (zero without f-2).
struct LeafModel {
  CellFrame frame;
  CentredAffine prior;
};

// A cell's vertices copied out of the frames, in cell order and kPointStride doubles apart
// (cell_kernels.h), so that the per-cell passes (fits, predictions) stream through memory
// instead of hopping through the vertex index; the leaf's model is found on the way. The
// buffers only grow, so cells allocate nothing.
class CellPoints {
 public:
  explicit CellPoints(SimdPath simd_path) : path(simd_path) {}
  // A window of whole's buffers from its point `first` on, for the cells of one subtree of
  // the cell whole gathered last (a subtree searched on a thread): they all lie inside the
  // subtree's range of that cell, which whole's buffers hold, so the window needs no memory
  // of its own, and windows of disjoint subtrees do not overlap.
  CellPoints(CellPoints& whole, size_t first);
  CellPoints(const CellPoints&) = delete;
  CellPoints& operator=(const CellPoints&) = delete;

  void gather(const PFrameInput& in, const uint32_t* idx, size_t n);
  const double* reference() const { return reference_; }
  const double* target() const { return target_; }  // when the input has it
  const double* referencePoint(size_t i) const { return reference_ + kPointStride * i; }
  const double* targetPoint(size_t i) const { return target_ + kPointStride * i; }

  SimdPath path;
  LeafModel model;

 private:
  // Each as large as the largest cell gathered: the root's, every vertex. The target only
  // when encoding, the scratch (frame f-2's points) only for the portable kernel (the AVX2
  // one keeps no copy of them). Empty in a window.
  std::vector<double> own_reference_, own_target_, own_scratch_;
  double* reference_ = nullptr;  // own_reference_'s data, or whole's
  double* target_ = nullptr;
  double* scratch_ = nullptr;
  bool window_ = false;
};

// Prediction of the cell's i-th vertex from the reference frame with the leaf's coded affine.
// (Adding a share of the vertex's own last motion beyond its cell's was tried: it amplifies
// the reconstruction noise and costs far more bits; docs/notes/affine_octree_history.md.)
inline void predictVertex(const CellPoints& points, const LeafModel& m, const CentredAffine& a,
                          size_t i, double out[3]) {
  applyCentred(a, m.frame.centroid, points.referencePoint(i), out);
}
// The quantisation steps of the corrections of a leaf of n vertices. Rounding a correction
// moves all n vertices, so its share of the squared error grows as n, and the step that
// balances that against the correction's bits shrinks as 1/√n; the linear part's also as
// 1/radius, the lever it acts through. (Fixed steps cost more bits at equal PSNR:
// docs/affine_octree.md, step 3.)
struct CorrectionSteps {
  double translation, linear;
};
// (Inline, as codedAffine(): both run once per leaf on the decoder's path.)
inline CorrectionSteps correctionSteps(const CellFrame& frame, size_t n, double residual_step) {
  const double step = residual_step / std::sqrt(double(n));
  return {kTranslationStep * step, kLinearStep * step / frame.radius};
}
// coded[0..2] translation, coded[3..11] linear part, in those steps.
inline CentredAffine codedAffine(const LeafModel& m, const CorrectionSteps& steps, const int64_t coded[12]) {
  CentredAffine a = m.prior;
  for (int r = 0; r < 3; ++r) a.t[r] += double(coded[r]) * steps.translation;
  for (int k = 0; k < 9; ++k) a.L[k] += double(coded[3 + k]) * steps.linear;
  return a;
}

// Rate-distortion quantisation of a leaf's corrections from `prior` to `fit` (what video
// coders call RDOQ): each is rounded to nearest, one step nearer zero or zero, whichever
// costs the fewest bits (estimated from the models) plus `weight` times the squared error it
// adds. The fit is the minimum of that error, which grows from it by n·|δt|² and δLᵣᵀ·A·δLᵣ
// (A the fit's normal matrix, fitCentred()), so a choice is weighed without predicting a
// vertex. The translations are independent; the entries of a row of L are chosen in turn,
// each with the ones before it as chosen. Fills coded[12] (the linear part only when
// n >= kMinLinearVertices) and returns their bits. (Fewer bits than rounding to nearest at
// equal PSNR: docs/affine_octree.md, step 8.)
double quantiseCorrections(const PredictiveModels& pm, const CentredAffine& fit, const CentredAffine& prior,
                           const CorrectionSteps& steps, size_t n, const double normal[9], double weight,
                           int64_t coded[12]);

struct PredictiveFrameStats {
  uint64_t leaves = 0;
};

class PredictiveOctreeEncoder {
 public:
  PredictiveOctreeEncoder(uint32_t vertex_count, SimdPath path)
      : contexts_(vertex_count), partition_(path), points_(path), path_(path) {}
  void reset() {
    models_ = std::make_unique<PredictiveModels>();
    contexts_.restart();
  }
  // False when a value would not fit the stream (a jump of ~2^30 steps): code an I-frame.
  bool encode(const PFrameInput& in, std::vector<uint8_t>& out, std::vector<double>& recon,
              PredictiveFrameStats& stats);

 private:
  struct Node {
    bool split;
    int64_t coded[12];
  };
  struct Walk;
  // What a search writes as it goes: the encoder's own, or a subtree's on a thread.
  struct Search {
    OctreePartition& partition;
    CellPoints& points;
    std::vector<Node>& plan;
  };
  double search(Walk& w, Search& s, const Cell& cell);
  double searchChildren(Walk& w, Search& s, const Cell& cell, const Cell children[8], double leaf_cost);
  struct LeafCost {
    bool all_zero = false;       // no residual to code
    double distortion_bits = 0;  // the distortion's share of the cost
  };
  double evaluateLeaf(Walk& w, Search& s, const Cell& cell, Node& node, LeafCost& out);
  void codeCell(Walk& w, const Cell& cell);
  void codeLeaf(Walk& w, const Cell& cell, const Node& node);

  std::unique_ptr<PredictiveModels> models_ = std::make_unique<PredictiveModels>();
  ResidualContexts contexts_;
  OctreePartition partition_;
  CellPoints points_;
  SimdPath path_;
  std::vector<Node> plan_;
  std::vector<int64_t> residual_;
};

class PredictiveOctreeDecoder {
 public:
  PredictiveOctreeDecoder(uint32_t vertex_count, SimdPath path)
      : contexts_(vertex_count), partition_(path), points_(path), path_(path) {}
  void reset() {
    models_ = std::make_unique<PredictiveModels>();
    contexts_.restart();
  }
  Status decode(const PFrameInput& in, ByteReader payload, std::vector<double>& recon);

 private:
  struct Walk;
  void decodeCell(Walk& w, const Cell& cell);
  void decodeLeaf(Walk& w, const Cell& cell);
  void decodeParameters(Walk& w, uint32_t n, int64_t coded[12]);
  void decodeResiduals(Walk& w, const uint32_t* vertices, uint32_t n);

  std::unique_ptr<PredictiveModels> models_ = std::make_unique<PredictiveModels>();
  ResidualContexts contexts_;
  OctreePartition partition_;
  CellPoints points_;
  SimdPath path_;
};

}  // namespace animc
