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

// Extent (max - min) of x y z triples along each axis; zeros when there are none.
std::array<double, 3> boxExtent(const std::vector<double>& xyz);

enum class DetailReference : uint8_t {
  kIntra,  // base vertices relative to the parametric mesh's, details relative to zero
  kInter,  // relative to the previous frame's reconstructed coefficients (the paper's P-frame)
  kLinear, // relative to their linear extrapolation from the two previous frames
};

class WaveletFrameModel {
 public:
  WaveletFrameModel(const WaveletOptions& options, const Topology& topology);

  // Rebuilds the hierarchy on a new parametric mesh (a decoded parametric frame), which is
  // also the reconstruction of that frame.
  void setParametric(const std::vector<double>& parametric_xyz);
  bool ready() const { return transform_ != nullptr; }
  // Whether a reference is available (kLinear needs two reconstructed frames since the last
  // parametric frame).
  bool hasReference(DetailReference ref) const;

  const WaveletTransform& transform() const { return *transform_; }
  BitplaneLayout layout() const { return BitplaneLayout{classes_.data(), parents_.data(), classes_.size()}; }
  size_t coefficientCount() const { return classes_.size(); }
  double step() const { return step_; }

  // Weighted residual of coefficients against a reference, in coding order.
  void residual(const std::vector<double>& coefficients, DetailReference ref, std::vector<double>& out) const;
  // Squared norm of that residual, to choose the reference.
  double residualEnergy(const std::vector<double>& coefficients, DetailReference ref) const;
  // Adds a decoded residual to the reference; the result becomes the reference of the next
  // P-frame and its inverse transform the reconstructed frame.
  void accept(const std::vector<double>& decoded_residual, DetailReference ref);

  const std::vector<double>& reconstruction() const { return reconstruction_; }

 private:
  const std::vector<double>& referenceOf(DetailReference ref) const;

  WaveletOptions options_;
  const Topology& topology_;
  std::unique_ptr<WaveletTransform> transform_;
  std::vector<uint32_t> order_;     // vertices in coding order: base, then coarse to fine
  std::vector<uint8_t> classes_;    // significance class of each coded coefficient
  std::vector<uint32_t> parents_;   // the same component of the collapse target, coded earlier
  std::vector<double> intra_reference_, previous_, before_previous_, extrapolated_, reconstruction_;
  int history_ = 0;  // reconstructed frames since the last parametric frame (capped at 2)
  double step_ = 1;
};

}  // namespace animc
