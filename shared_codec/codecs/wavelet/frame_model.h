// SPDX-License-Identifier: Apache-2.0
// What the wavelet encoder and decoder both hold: the transform built on the current
// parametric mesh, the coding order and contexts of the coefficients, and the last
// reconstructed coefficients (the reference of P-frames, closed loop).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "codecs/wavelet/bitplane_coder.h"
#include "codecs/wavelet/options.h"
#include "codecs/wavelet/wavelet_transform.h"
#include "core/sequence.h"

namespace animc {

// How a detail frame predicts its coefficients, per group of vertices (base vertices, then
// removed ones): selector k <= kDampingSteps predicts previous + (k / kDampingSteps) *
// (previous - the one before), i.e. 0 = the paper's P-frame, kDampingSteps = linear
// extrapolation, in between damped (quantisation noise of the references is amplified by
// extrapolation); kIntraSelector = no temporal prediction (base vertices: the parametric
// mesh's, details: 0). All references are reconstructed coefficients (closed loop).
constexpr int kPredictionGroups = 2;
constexpr uint8_t kDampingSteps = 8;
constexpr uint8_t kIntraSelector = kDampingSteps + 1;

struct Prediction {
  std::array<uint8_t, kPredictionGroups> selector{};
  static Prediction intra() {
    Prediction p;
    p.selector.fill(kIntraSelector);
    return p;
  }
  bool isIntra() const {
    for (uint8_t s : selector)
      if (s != kIntraSelector) return false;
    return true;
  }
};

class WaveletFrameModel {
 public:
  // path: the kernels' version (core/simd_math.h) of the model and its transform.
  WaveletFrameModel(const WaveletOptions& options, const Topology& topology, SimdPath path);
  SimdPath simdPath() const { return path_; }

  // Starts a frame group on a parametric mesh (a decoded parametric frame), which is also the
  // reconstruction of that frame; the hierarchy is rebuilt unless it was built on this mesh.
  void setParametric(const std::vector<double>& parametric_xyz);
  bool ready() const { return transform_ != nullptr; }
  // Whether the references a prediction needs exist (selectors above 0 need two
  // reconstructed frames since the last parametric frame; selectors are <= kIntraSelector).
  bool canPredict(const Prediction& prediction) const;
  // The prediction leaving the smallest weighted residual energy (a proxy for its rate);
  // intra only when temporal is false.
  Prediction choosePrediction(const std::vector<double>& coefficients, bool temporal) const;

  const WaveletTransform& transform() const { return *transform_; }
  BitplaneLayout layout() const { return BitplaneLayout{classes_.data(), parents_.data(), classes_.size()}; }
  size_t coefficientCount() const { return 3 * classes_.size(); }
  // Temporal contexts of a frame: the previous frame's decoded residual for predicted
  // frames; none for I-frames, which must decode on their own, nor in files whose frames a
  // decoder may cut (its history would then differ from the encoder's).
  const BitplaneHistory* contextFor(const Prediction& prediction) const {
    return prediction.isIntra() || options_.cuttable() ? nullptr : &context_;
  }
  // Where the coder leaves this frame's history; accept() makes it the next context. None
  // when no frame reads it (cuttable files), which spares the coder that pass.
  BitplaneHistory* nextHistory() { return options_.cuttable() ? nullptr : &next_context_; }
  BitplaneWorkspace* workspace() const { return workspace_.get(); }
  double step() const { return step_; }

  // Weighted residual of coefficients against their prediction, in coding order.
  void residual(const std::vector<double>& coefficients, const Prediction& prediction,
                std::vector<double>& out) const;
  // Adds a decoded residual to the prediction; the result becomes the reference of the next
  // frame and its inverse transform the reconstructed frame.
  void accept(const std::vector<double>& decoded_residual, const Prediction& prediction);

  const std::vector<double>& reconstruction() const { return reconstruction_; }
  // The frame accept() would reconstruct from this residual, leaving the model unchanged
  // (encoder-side search of a cut).
  void previewReconstruction(const std::vector<double>& decoded_residual, const Prediction& prediction,
                             std::vector<double>& xyz);

 private:
  // The transform and the coding order, classes, parents and runs that follow from it.
  void buildHierarchy(const std::vector<double>& parametric_xyz);
  // run(begin, end, references, predictor) for each run of coding positions that share a
  // selector; predictor: a PredictorTag (frame_model.cpp), the selector's kind of prediction.
  template <class Run>
  void forEachRun(const Prediction& prediction, Run run) const;
  void addResidual(const std::vector<double>& decoded_residual, const Prediction& prediction,
                   std::vector<double>& coefficients) const;

  WaveletOptions options_;
  const Topology& topology_;
  SimdPath path_;
  std::unique_ptr<WaveletTransform> transform_;
  std::vector<double> hierarchy_mesh_;  // the parametric mesh transform_ was built on
  std::vector<uint32_t> order_;     // vertices in coding order: base, then coarse to fine
  std::vector<uint8_t> classes_;    // significance class of each vertex, in coding order
  std::vector<uint32_t> parents_;   // coding position of the vertex it collapses onto
  BitplaneHistory context_, next_context_;
  BitplaneWorkspacePtr workspace_ = makeBitplaneWorkspace();
  struct PredictionRun {
    uint32_t begin, end;
    uint8_t group;
  };
  std::vector<PredictionRun> runs_;  // the runs of coding positions of one group
  // The coding positions of the last vertex and the last coding position, ascending: the
  // points where reading a Quad (one double past the point) would pass an array's end.
  std::array<uint32_t, 2> quad_stops_{};
  std::vector<double> intra_reference_, previous_, before_previous_, next_, reconstruction_;
  std::vector<double> preview_;
  int history_ = 0;  // reconstructed frames since the last parametric frame (capped at 2)
  double step_ = 1;
};

}  // namespace animc
