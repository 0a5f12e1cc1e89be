// SPDX-License-Identifier: Apache-2.0
// The per-vertex loops of a leaf: copying its points out of the frames, summing its affine
// fits, predicting its vertices. Each comes in a portable version (Pair) and an AVX2 version
// (Quad) chosen at run time; both compute every value with the same IEEE operations in the
// same order (simd_math.h), so encoder and decoder agree whichever CPU each runs on.
#pragma once
#include <cstddef>
#include <cstdint>

#include "codecs/affine_octree/affine_fit.h"
#include "codecs/affine_octree/octree_shared.h"

namespace animc {

// Gathered points lie kPointStride doubles apart (x, y, z, then a zero), so that a Quad loads
// and stores a whole point.
constexpr size_t kPointStride = 4;

// Copies the points idx[0..n) (n >= 1) of an xyz-interleaved frame to out
// (n·kPointStride doubles) and returns their centroid and radius.
CellFrame gatherPoints(SimdPath path, const double* frame, const uint32_t* idx, size_t n, double* out);
// gatherPoints() without measuring them.
void copyPoints(SimdPath path, const double* frame, const uint32_t* idx, size_t n, double* out);

// Over n gathered points, d = u − c and m = q − u: Σ m, Σ d, Σ d·dᵀ and Σ m·dᵀ (row-major),
// each summed in point order. c is any origin near the points (the fit does not depend on it
// but for rounding).
struct FitSums {
  double m[3], d[3];
  double cov[9], cross[9];
};
FitSums fitSums(SimdPath path, const double* u, const double* q, size_t n, const double c[3]);
// The least-squares motion q ≈ u + t + L·(u − centroid) from those sums, with L pulled
// towards prior_L by the ridge weight lambda: t = Σm / n and
// L = (Σ m·dᵀ − t·(Σd)ᵀ + λ·prior)·(Σ d·dᵀ − (Σd)·(Σd)ᵀ / n + λ·I)⁻¹; `normal`, if given,
// receives the matrix inverted (fitCentred()).
void solveFit(const FitSums& s, size_t n, double lambda, const double prior_L[9], CentredAffine& out,
              double normal[9] = nullptr);

// gatherPoints() of frame f-1 (`reference`), together with the cell's motion from frame f-2
// (`before`, in world units: each point is normalised into `cube` on the way, with
// normalise()'s arithmetic) to f-1: solveFit() of the sums over (before, reference) about the
// first before point, with no prior and the ridge weight fitCentred() gives the reference
// points' frame. In one pass over the indices on AVX2 CPUs, where the before points are never
// stored; `scratch` (n·kPointStride doubles) holds them on the others.
void gatherWithMotion(SimdPath path, const double* reference, const double* before, const RootCube& cube, const uint32_t* idx,
                      size_t n, double* out, double* scratch, CellFrame& frame, CentredAffine& motion);

#if ANIMC_AVX2_PATH
// fitCentred() for CPUs with AVX2 (it calls this itself): the sums above, then the solve with
// a row of each matrix per Quad.
void fitCentredAvx2(const double* u, const double* q, size_t n, const CellFrame& frame, const double prior_L[9],
                    CentredAffine& out, double normal[9]);
#endif

// applyCentred() of every gathered point, written to recon at the point's vertex idx[i].
void predictPoints(SimdPath path, const double* u, size_t n, const double c[3], const CentredAffine& a,
                   const uint32_t* idx, double* recon);

}  // namespace animc
