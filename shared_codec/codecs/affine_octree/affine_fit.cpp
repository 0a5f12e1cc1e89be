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
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) f.centroid[a] += u[3 * size_t(idx[i]) + a];
  for (int a = 0; a < 3; ++a) f.centroid[a] /= double(n);
  double r2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &u[3 * size_t(idx[i])];
    const double dx = p[0] - f.centroid[0], dy = p[1] - f.centroid[1], dz = p[2] - f.centroid[2];
    r2 = std::max(r2, dx * dx + dy * dy + dz * dz);
  }
  f.radius = std::max(std::sqrt(r2), 1e-9);
  return f;
}

void fitCentred(const std::vector<double>& u, const std::vector<double>& q, const uint32_t* idx,
                size_t n, const CellFrame& frame, const double prior_L[9], CentredAffine& out) {
  Eigen::Vector3d mean_disp = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(idx[i]);
    mean_disp += Eigen::Vector3d(q[v] - u[v], q[v + 1] - u[v + 1], q[v + 2] - u[v + 2]);
  }
  mean_disp /= double(n);
  const Eigen::Vector3d c(frame.centroid[0], frame.centroid[1], frame.centroid[2]);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(idx[i]);
    const Eigen::Vector3d d = Eigen::Vector3d(u[v], u[v + 1], u[v + 2]) - c;
    const Eigen::Vector3d m = Eigen::Vector3d(q[v] - u[v], q[v + 1] - u[v + 1], q[v + 2] - u[v + 2]) - mean_disp;
    cov.noalias() += d * d.transpose();
    cross.noalias() += m * d.transpose();
  }
  const double lambda = kRidge * double(n) * frame.radius * frame.radius;
  const Eigen::Matrix3d prior = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(prior_L);
  const Eigen::Matrix3d lhs = cov + lambda * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d l = (cross + lambda * prior) * lhs.inverse();
  // The centroid displacement absorbs what L predicts for the centroid, which is zero.
  for (int r = 0; r < 3; ++r) {
    out.t[r] = mean_disp(r);
    for (int k = 0; k < 3; ++k) out.L[3 * r + k] = l(r, k);
  }
}

}  // namespace animc
