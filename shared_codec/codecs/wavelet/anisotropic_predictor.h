// SPDX-License-Identifier: Apache-2.0
// The anisotropic predictor of the paper (section 3.1): the value at a removed vertex that
// minimises the sum over the edges around it of w_e * (second difference across e)^2, the
// weights favouring flat edges over creases. Coefficients come from the parametric mesh
// only, so they are computed once and every frame is predicted with the same stencils.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/progressive_mesh.h"

namespace animc {

struct AnisotropyParams {
  double epsilon = 0.1;  // the paper's epsilon_w
  double sigma = 0.3;    // the paper's sigma_w
  // A stencil whose weights' absolute values sum above this extrapolates too far (thin
  // triangles on coarse levels) and would amplify quantisation errors level after level;
  // such vertices fall back to the average of their ring (docs/wavelet.md).
  double max_stencil_l1 = 3.0;
};

// Stencil of collapse i: prediction = sum over s in [first[i], first[i+1]) of
// weight[s] * position[vertex[s]]. The weights sum to 1 (affine invariance), and every
// stencil vertex is still present on the coarser level.
struct PredictionStencils {
  std::vector<uint32_t> first;
  std::vector<uint32_t> vertex;
  std::vector<double> weight;
};

PredictionStencils buildPredictor(const ProgressiveMesh& pm, const std::vector<double>& parametric_xyz,
                                  const AnisotropyParams& params = {});

// Dihedral weight of an edge whose two triangles have unit normals with dot product
// normal_dot: epsilon + exp((normal_dot - 1) / (2 sigma^2)) (docs/wavelet.md on the sign).
double edgeWeight(double normal_dot, const AnisotropyParams& params);

}  // namespace animc
