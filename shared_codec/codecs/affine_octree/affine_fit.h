// SPDX-License-Identifier: Apache-2.0
// Least-squares affine motion of one octree cell: reference positions u (normalised) to
// current positions q, over the vertices idx[0..n).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/simd_math.h"

namespace animc {

// The paper's form: q ≈ A·[u; 1], A row-major 3x4.
struct Affine34 {
  double a[12];
};

// A = Fc·Fpᵀ·(Fp·Fpᵀ)⁻¹. When Fp·Fpᵀ is ill-conditioned (reciprocal condition below
// kSingularRcond: the points are nearly coplanar, collinear or coincident) the inverse is
// replaced by a pseudo-inverse keeping the eigen-directions that carry the first 95 % of
// its energy, as the paper prescribes. Returns whether that happened.
constexpr double kSingularRcond = 1e-7;
constexpr double kKeptEnergy = 0.95;
bool fitAffinePaper(const std::vector<double>& u, const std::vector<double>& q, const uint32_t* idx,
                    size_t n, Affine34& out);

// Our form: q ≈ u + t + L·(u − c), c the centroid of the cell's reference vertices, so t is
// the centroid's displacement and L is small for near-rigid motion. The fit is pulled towards
// a prior L (the cell's motion in the previous frame) with weight kRidge, which keeps it
// well-posed for one, two or coplanar vertices without any special case.
struct CentredAffine {
  double t[3] = {0, 0, 0};
  double L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};
constexpr double kRidge = 1e-3;

struct CellFrame {
  double centroid[3];
  double radius;  // half the diagonal of the vertices' bounding box (>= tiny): their scale
};

// The ridge weight of a fit over n points of that frame: scaled by the points' spread, so that
// it pulls as hard whatever the cell's size.
inline double ridgeWeight(size_t n, const CellFrame& frame) { return kRidge * double(n) * frame.radius * frame.radius; }

// u and q: a cell's points gathered in cell order, kPointStride doubles apart (cell_kernels.h).
// `normal` (optional, row-major 3x3) receives the fit's normal matrix A, the spread of the
// points about their centroid plus the ridge: moving the fit by (δt, δL) adds
// n·|δt|² + Σᵣ δLᵣᵀ·A·δLᵣ (δLᵣ a row of δL) to its squared error plus ridge penalty.
void fitCentred(SimdPath path, const double* u, const double* q, size_t n, const CellFrame& frame,
                const double prior_L[9], CentredAffine& out, double normal[9] = nullptr);

// x and y of the result go through the two lanes of a Pair, z alone; each lane computes
// u + t + ((L₀·d₀ + L₁·d₁) + L₂·d₂) exactly as the scalar formula would.
inline void applyCentred(const CentredAffine& m, const double c[3], const double* u, double* out) {
  const Pair u_xy = loadPair(u);
  const Pair d_xy = u_xy - loadPair(c);
  const double dz = u[2] - c[2];
  const Pair l0 = {m.L[0], m.L[3]}, l1 = {m.L[1], m.L[4]}, l2 = {m.L[2], m.L[5]};
  storePair(out, (u_xy + loadPair(m.t)) + ((l0 * splat(d_xy[0]) + l1 * splat(d_xy[1])) + l2 * splat(dz)));
  out[2] = (u[2] + m.t[2]) + ((m.L[6] * d_xy[0] + m.L[7] * d_xy[1]) + m.L[8] * dz);
}

}  // namespace animc
