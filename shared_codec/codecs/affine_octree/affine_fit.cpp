#include "codecs/affine_octree/affine_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

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

CellFrame cellFrame(const std::vector<double>& u, const uint32_t* idx, size_t n) {
  CellFrame f{{0, 0, 0}, 0};
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = u[3 * size_t(idx[0]) + a];
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double x = u[3 * size_t(idx[i]) + a];
      f.centroid[a] += x;
      lo[a] = std::min(lo[a], x);
      hi[a] = std::max(hi[a], x);
    }
  for (int a = 0; a < 3; ++a) f.centroid[a] /= double(n);
  const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
  f.radius = std::max(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz), 1e-9);
  return f;
}

// Plain loops rather than Eigen: the matrices are 3x3, and this runs for every cell the
// encoder's search visits and every leaf the decoder reads.
void fitCentred(const std::vector<double>& u, const std::vector<double>& q, const uint32_t* idx,
                size_t n, const CellFrame& frame, const double prior_L[9], CentredAffine& out) {
  const double* c = frame.centroid;
  double sum_m[3] = {0, 0, 0}, sum_d[3] = {0, 0, 0};
  double cov[9] = {0}, cross[9] = {0};  // Σ d·dᵀ and Σ m·dᵀ, row-major
  for (size_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(idx[i]);
    const double d[3] = {u[v] - c[0], u[v + 1] - c[1], u[v + 2] - c[2]};
    const double m[3] = {q[v] - u[v], q[v + 1] - u[v + 1], q[v + 2] - u[v + 2]};
    for (int r = 0; r < 3; ++r) {
      sum_m[r] += m[r];
      sum_d[r] += d[r];
      for (int k = 0; k < 3; ++k) {
        cov[3 * r + k] += d[r] * d[k];
        cross[3 * r + k] += m[r] * d[k];
      }
    }
  }
  const double inv_n = 1.0 / double(n);
  const double lambda = kRidge * double(n) * frame.radius * frame.radius;
  double a[9], b[9];
  for (int r = 0; r < 3; ++r) {
    out.t[r] = sum_m[r] * inv_n;  // the centroid's displacement
    for (int k = 0; k < 3; ++k) {
      // Σ (m - m̄)·dᵀ = Σ m·dᵀ - m̄·(Σ d)ᵀ, and the ridge pulls L towards the prior.
      b[3 * r + k] = cross[3 * r + k] - out.t[r] * sum_d[k] + lambda * prior_L[3 * r + k];
      a[3 * r + k] = cov[3 * r + k] + (r == k ? lambda : 0.0);
    }
  }
  // L = b · a⁻¹, a symmetric positive definite (λ > 0): inverse by cofactors.
  const double inv[9] = {a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
                         a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
                         a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3]};
  const double det = a[0] * inv[0] + a[1] * inv[3] + a[2] * inv[6];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      out.L[3 * r + k] = (b[3 * r] * inv[k] + b[3 * r + 1] * inv[3 + k] + b[3 * r + 2] * inv[6 + k]) / det;
}

}  // namespace animc
