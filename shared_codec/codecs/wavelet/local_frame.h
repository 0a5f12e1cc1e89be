// SPDX-License-Identifier: Apache-2.0
// The local frame of a removed vertex (paper eq. 1), from the positions of its one ring on
// the coarser level only, so the decoder can rebuild it before the vertex itself: the
// tangent masks t1 = sum cos(2 pi k / K) p_k, t2 = sum sin(2 pi k / K) p_k of the ring, the
// normal their cross product. A degenerate ring falls back to the world axes.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

namespace animc {

struct LocalFrame {
  Eigen::Vector3d normal{0, 0, 1}, tangent{1, 0, 0}, bitangent{0, 1, 0};

  // Detail d in world coordinates -> (normal, tangent, bitangent) components (back:
  // toWorld() in wavelet_transform.cpp).
  Eigen::Vector3d toLocal(const Eigen::Vector3d& d) const {
    return Eigen::Vector3d(normal.dot(d), tangent.dot(d), bitangent.dot(d));
  }
};

// cosines / sines: the K mask weights; xyz: positions; ring: K vertex indices.
inline LocalFrame localFrame(const double* xyz, const uint32_t* ring, const double* cosines,
                             const double* sines, size_t k) {
  Eigen::Vector3d t1 = Eigen::Vector3d::Zero(), t2 = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d p(xyz[3 * size_t(ring[i])], xyz[3 * size_t(ring[i]) + 1], xyz[3 * size_t(ring[i]) + 2]);
    t1 += cosines[i] * p;
    t2 += sines[i] * p;
  }
  LocalFrame f;
  const Eigen::Vector3d n = t1.cross(t2);
  const double nn = n.norm(), scale = t1.norm() * t2.norm();
  if (!(nn > 1e-9 * scale) || !(scale > 0) || !std::isfinite(nn)) return f;
  f.normal = n / nn;
  f.tangent = (t1 - t1.dot(f.normal) * f.normal).normalized();
  f.bitangent = f.normal.cross(f.tangent);
  return f;
}

}  // namespace animc
