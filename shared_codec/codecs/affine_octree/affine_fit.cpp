// SPDX-License-Identifier: Apache-2.0
#include "codecs/affine_octree/affine_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/cell_kernels.h"

namespace animc {

bool fitAffinePaper(const std::vector<double>& u, const std::vector<double>& q, const uint32_t* idx,
                    size_t n, Affine34& out) {
  Eigen::Matrix4d g = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, 3, 4> b = Eigen::Matrix<double, 3, 4>::Zero();
  for (size_t i = 0; i < n; ++i) {
    const double* p = &u[3 * size_t(idx[i])];
    const double* c = &q[3 * size_t(idx[i])];
    const Eigen::Vector4d h(p[0], p[1], p[2], 1.0);
    g.noalias() += h * h.transpose();
    b.noalias() += Eigen::Vector3d(c[0], c[1], c[2]) * h.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(g);
  const Eigen::Vector4d lambda = eig.eigenvalues();  // ascending
  const bool singular = !(lambda(0) > kSingularRcond * lambda(3));
  Eigen::Vector4d inv = Eigen::Vector4d::Zero();
  if (!singular) {
    inv = lambda.cwiseInverse();
  } else {
    const double total = std::max(lambda.sum(), 1e-300);
    double kept = 0;
    for (int i = 3; i >= 0 && kept < kKeptEnergy * total; --i) {
      if (lambda(i) <= 0) break;
      inv(i) = 1.0 / lambda(i);
      kept += lambda(i);
    }
  }
  const Eigen::Matrix4d pinv = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
  const Eigen::Matrix<double, 3, 4> a = b * pinv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out.a[4 * r + c] = a(r, c);
  return singular;
}

// Plain loops rather than Eigen: the matrices are 3x3, and this runs for every cell the
// encoder's search visits and every leaf the decoder reads.
void fitCentred([[maybe_unused]] SimdPath path, const double* u, const double* q, size_t n, const CellFrame& frame,
                const double prior_L[9], CentredAffine& out, double normal[9]) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return fitCentredAvx2(u, q, n, frame, prior_L, out, normal);
#endif
  solveFit(fitSums(path, u, q, n, frame.centroid), n, ridgeWeight(n, frame), prior_L, out, normal);
}

void solveFit(const FitSums& s, size_t n, double lambda, const double prior_L[9], CentredAffine& out,
              double normal[9]) {
  const double inv_n = 1.0 / double(n);
  double a[9], b[9];
  for (int r = 0; r < 3; ++r) {
    out.t[r] = s.m[r] * inv_n;  // the centroid's displacement
    for (int k = 0; k < 3; ++k) {
      // Σ (m - m̄)·dᵀ = Σ m·dᵀ - m̄·(Σ d)ᵀ, and the ridge pulls L towards the prior. The
      // spread about the centroid, Σ d·dᵀ - (Σ d)·(Σ d)ᵀ / n, takes the product d_r·d_k,
      // which is d_k·d_r bit for bit: the matrix stays exactly symmetric.
      b[3 * r + k] = s.cross[3 * r + k] - out.t[r] * s.d[k] + lambda * prior_L[3 * r + k];
      a[3 * r + k] = (s.cov[3 * r + k] - (s.d[r] * s.d[k]) * inv_n) + (r == k ? lambda : 0.0);
    }
  }
  if (normal) std::copy(a, a + 9, normal);
  // L = b · a⁻¹, a symmetric positive definite (λ > 0): inverse by cofactors.
  const double inv[9] = {a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
                         a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
                         a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3]};
  const double det = a[0] * inv[0] + a[1] * inv[3] + a[2] * inv[6];
  // Columns 0 and 1 of each row through a Pair: the nine divisions are most of the solve.
  for (int r = 0; r < 3; ++r) {
    const double* row = &b[3 * r];
    const Pair numerator = (splat(row[0]) * loadPair(&inv[0]) + splat(row[1]) * loadPair(&inv[3])) +
                           splat(row[2]) * loadPair(&inv[6]);
    storePair(&out.L[3 * r], numerator / splat(det));
    out.L[3 * r + 2] = (row[0] * inv[2] + row[1] * inv[5] + row[2] * inv[8]) / det;
  }
}

}  // namespace animc
