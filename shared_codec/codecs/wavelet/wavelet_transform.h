// SPDX-License-Identifier: Apache-2.0
// The wavelet transform of the paper (section 3.2) over a progressive mesh: one detail per
// removed vertex, the difference between its position and the anisotropic prediction from
// the coarser level, in the local frame of its coarser one ring. No update step, so the
// coarse vertices keep their positions and the inverse is exact up to rounding.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/anisotropic_predictor.h"
#include "codecs/wavelet/local_frame.h"
#include "codecs/wavelet/progressive_mesh.h"
#include "core/sequence.h"

namespace animc {

struct CollapseTables;  // wavelet_transform.cpp

class WaveletTransform {
 public:
  // local_frames = false keeps details in world axes (docs/wavelet.md: local frames turn
  // position errors of the coarse levels into detail errors, level after level).
  // path: the kernels' version (core/simd_math.h), of the hierarchy's build too.
  WaveletTransform(SimdPath path, const Topology& topology, const std::vector<double>& parametric_xyz,
                   bool local_frames = true, HierarchySettings settings = {});

  // coefficients (3 * N, vertex indexed): a base vertex keeps its position; a removed vertex
  // holds its detail as (normal, tangent, bitangent) components.
  void forward(const double* xyz, std::vector<double>& coefficients) const;
  void inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const;

  const ProgressiveMesh& hierarchy() const { return pm_; }
  const PredictionStencils& stencils() const { return stencils_; }
  // sqrt(one-ring area where the vertex is removed (base vertices: on the base mesh) / its
  // one-ring area on the full mesh), on the parametric mesh: the paper's L2 normalisation,
  // measured in vertices rather than area because the codec is judged per vertex (KG).
  const std::vector<double>& weights() const { return weights_; }
  // Level of each vertex: collapse batch number, or -1 for base vertices.
  const std::vector<int>& levelOf() const { return level_of_; }

 private:
  void computeWeights(const Topology& topology, const std::vector<double>& xyz);
  // The flat per-collapse arrays (offsets, near-end flags) that tables() hands to the
  // transform kernels.
  void buildCollapseTables();
  CollapseTables tables() const;
  // The positions (or coefficients) of the base vertices (those no collapse removes), from -> to.
  void copyKept(const double* from, double* to) const;

  SimdPath path_;
  bool local_frames_;
  ProgressiveMesh pm_;
  PredictionStencils stencils_;
  std::vector<uint32_t> stencil_offset_;  // 3 * stencils_.vertex: the x of each stencil vertex
  std::vector<uint32_t> collapse_offset_;  // 3 * the vertex of each collapse
  std::vector<uint8_t> near_end_;          // whether a collapse reads the last vertex
  std::vector<uint32_t> ring_offset_;      // 3 * pm_.ring
  std::vector<double> cosines_, sines_;  // tangent masks, aligned with pm_.ring
  std::vector<double> weights_;
  std::vector<int> level_of_;
};

}  // namespace animc
