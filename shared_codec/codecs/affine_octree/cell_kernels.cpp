// SPDX-License-Identifier: Apache-2.0
#include "codecs/affine_octree/cell_kernels.h"

#include <algorithm>
#include <cmath>

#include "core/simd_math.h"

namespace animc {
namespace {

CellFrame frameOf(const double sum[3], const double lo[3], const double hi[3], size_t n) {
  CellFrame f;
  for (int a = 0; a < 3; ++a) f.centroid[a] = sum[a] / double(n);
  const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
  f.radius = std::max(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz), 1e-9);
  return f;
}

// ---- Portable versions: x and y through a Pair, z alone. ----
// Not inlined into the dispatching functions at the end: a dispatcher would then save the
// registers the portable loop needs on every call, the AVX2 calls included (several calls
// per leaf).

// Copies points out and keeps their running sum and box, starting from the first point's.
struct PointGatherer {
  PointBox box;
  Pair sum_xy = splat(0);
  double sum_z = 0;

  explicit PointGatherer(const double* first) : box(first) {}
  void add(const double* p, double* out) {
    const Pair xy = loadPair(p);
    const double z = p[2];
    storePair(out, xy);
    storePair(out + 2, Pair{z, 0.0});
    sum_xy += xy;
    sum_z += z;
    box.add(xy, z);
  }
  CellFrame frame(size_t n) const {
    const double sum[3] = {sum_xy[0], sum_xy[1], sum_z};
    const double lo[3] = {box.lo_xy[0], box.lo_xy[1], box.lo_z}, hi[3] = {box.hi_xy[0], box.hi_xy[1], box.hi_z};
    return frameOf(sum, lo, hi, n);
  }
};

__attribute__((noinline)) CellFrame gatherPointsPortable(const double* frame, const uint32_t* idx, size_t n, double* out) {
  PointGatherer g(&frame[3 * size_t(idx[0])]);
  for (size_t i = 0; i < n; ++i) g.add(&frame[3 * size_t(idx[i])], &out[kPointStride * i]);
  return g.frame(n);
}

__attribute__((noinline)) void copyPointsPortable(const double* frame, const uint32_t* idx, size_t n, double* out) {
  for (size_t i = 0; i < n; ++i) {
    const double* p = &frame[3 * size_t(idx[i])];
    storePair(&out[kPointStride * i], loadPair(p));
    storePair(&out[kPointStride * i + 2], Pair{p[2], 0.0});
  }
}

// Two passes rather than one: 21 running sums in one loop do not fit the 16 registers, and
// a sum spilled to memory makes every iteration wait for the previous one's store. Names
// give the matrix entries each lane sums.
void sumMotionAndSpread(const double* u, const double* q, size_t n, const double c[3], FitSums& s) {
  const Pair c_xy = loadPair(c);
  Pair m_xy = splat(0), d_xy = splat(0), cov_00_01 = splat(0), cov_02_12 = splat(0);
  double m_z = 0, d_z = 0, cov_11 = 0, cov_22 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &u[kPointStride * i];
    const Pair u_xy = loadPair(p);
    const Pair dxy = u_xy - c_xy;
    const double dz = p[2] - c[2];
    m_xy += loadPair(&q[kPointStride * i]) - u_xy;
    m_z += q[kPointStride * i + 2] - p[2];
    d_xy += dxy;
    d_z += dz;
    cov_00_01 += splat(dxy[0]) * dxy;
    cov_11 += dxy[1] * dxy[1];
    cov_02_12 += dxy * splat(dz);
    cov_22 += dz * dz;
  }
  s.m[0] = m_xy[0], s.m[1] = m_xy[1], s.m[2] = m_z;
  s.d[0] = d_xy[0], s.d[1] = d_xy[1], s.d[2] = d_z;
  const double cov[9] = {cov_00_01[0], cov_00_01[1], cov_02_12[0], cov_00_01[1], cov_11,
                         cov_02_12[1], cov_02_12[0], cov_02_12[1], cov_22};
  std::copy(cov, cov + 9, s.cov);
}

void sumCross(const double* u, const double* q, size_t n, const double c[3], FitSums& s) {
  const Pair c_xy = loadPair(c);
  Pair x_00_01 = splat(0), x_10_11 = splat(0), x_20_21 = splat(0), x_02_12 = splat(0);
  double x_22 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &u[kPointStride * i];
    const Pair u_xy = loadPair(p);
    const Pair dxy = u_xy - c_xy;
    const double dz = p[2] - c[2];
    const Pair mxy = loadPair(&q[kPointStride * i]) - u_xy;
    const double mz = q[kPointStride * i + 2] - p[2];
    x_00_01 += splat(mxy[0]) * dxy;
    x_10_11 += splat(mxy[1]) * dxy;
    x_20_21 += splat(mz) * dxy;
    x_02_12 += mxy * splat(dz);
    x_22 += mz * dz;
  }
  const double cross[9] = {x_00_01[0], x_00_01[1], x_02_12[0], x_10_11[0], x_10_11[1],
                           x_02_12[1], x_20_21[0], x_20_21[1], x_22};
  std::copy(cross, cross + 9, s.cross);
}

__attribute__((noinline)) FitSums fitSumsPortable(const double* u, const double* q, size_t n, const double c[3]) {
  FitSums s;
  sumMotionAndSpread(u, q, n, c, s);
  sumCross(u, q, n, c, s);
  return s;
}

__attribute__((noinline)) void normalisePoints(const double* frame, const RootCube& cube, const uint32_t* idx,
                                               size_t n, double* out) {
  const PointNormaliser normaliser(cube);
  for (size_t i = 0; i < n; ++i) {
    normaliser.apply(&frame[3 * size_t(idx[i])], &out[kPointStride * i]);
    out[kPointStride * i + 3] = 0.0;
  }
}

const double kNoPrior[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};

// gatherWithMotion() of a single point, the most common leaf on smooth sequences at fine
// errors: its fit is its own motion with no deformation, which is what
// solving the sums gives for n = 1 (L = ±0, t = the motion; the spread is zero and the ridge
// keeps the system invertible), without the solve.
__attribute__((noinline)) void gatherOneWithMotion(const double* reference, const double* before,
                                                   const RootCube& cube, uint32_t v, double* out, CellFrame& frame,
                                                   CentredAffine& motion) {
  const double* p = &reference[3 * size_t(v)];
  double b[3];
  PointNormaliser(cube).apply(&before[3 * size_t(v)], b);
  for (int a = 0; a < 3; ++a) {
    out[a] = p[a];
    motion.t[a] = 0.0 + (p[a] - b[a]);  // as the sums: +0 plus the point's motion
  }
  out[3] = 0.0;
  for (double& l : motion.L) l = 0.0;
  frame = frameOf(p, p, p, 1);
}

void gatherWithMotionPortable(const double* reference, const double* before, const RootCube& cube,
                              const uint32_t* idx, size_t n, double* out, double* scratch, CellFrame& frame,
                              CentredAffine& motion) {
  frame = gatherPointsPortable(reference, idx, n, out);
  normalisePoints(before, cube, idx, n, scratch);
  const double origin[3] = {scratch[0], scratch[1], scratch[2]};
  solveFit(fitSumsPortable(scratch, out, n, origin), n, ridgeWeight(n, frame), kNoPrior, motion);
}

__attribute__((noinline)) void predictPointsPortable(const double* u, size_t n, const double c[3], const CentredAffine& a,
                           const uint32_t* idx, double* recon) {
  for (size_t i = 0; i < n; ++i) applyCentred(a, c, &u[kPointStride * i], &recon[3 * size_t(idx[i])]);
}

#if ANIMC_AVX2_PATH
// ---- AVX2 versions: a whole point per Quad (lane 3 unused). ----

// PointGatherer with a whole point per Quad. The constructor adds the first point: the box of
// one point is that point, the same values as adding it to a box started from it, with one
// load less.
struct QuadGatherer {
  Quad sum, lo, hi;

  ANIMC_TARGET_AVX2 QuadGatherer(Quad p, double* out) {
    storeQuad(out, p);
    sum = splatQuad(0) + p;
    lo = hi = p;
  }
  ANIMC_TARGET_AVX2 void add(Quad p, double* out) {
    storeQuad(out, p);
    sum += p;
    lo = minQuad(lo, p);
    hi = maxQuad(hi, p);
  }
  ANIMC_TARGET_AVX2 CellFrame frame(size_t n) const {
    const double s[3] = {sum[0], sum[1], sum[2]}, l[3] = {lo[0], lo[1], lo[2]}, h[3] = {hi[0], hi[1], hi[2]};
    return frameOf(s, l, h, n);
  }
};

ANIMC_TARGET_AVX2 CellFrame gatherPointsAvx2(const double* frame, const uint32_t* idx, size_t n, double* out) {
  QuadGatherer g(loadXyz(&frame[3 * size_t(idx[0])]), out);
  for (size_t i = 1; i < n; ++i) g.add(loadXyz(&frame[3 * size_t(idx[i])]), &out[kPointStride * i]);
  return g.frame(n);
}

ANIMC_TARGET_AVX2 void copyPointsAvx2(const double* frame, const uint32_t* idx, size_t n, double* out) {
  for (size_t i = 0; i < n; ++i) storeQuad(&out[kPointStride * i], loadXyz(&frame[3 * size_t(idx[i])]));
}

// One pass: the 21 sums fit in seven Quads. Σ d·dᵀ comes from d·d (the diagonal) and d·d'
// with d' = (d1, d2, d0) (the three products off it); Σ m·dᵀ from m·d, m·d' and m·d''
// with d'' = (d2, d0, d1). Each entry is the same product the scalar formula sums.
struct QuadFitSums {
  Quad m, d, dd, dd1, md, md1, md2;

  ANIMC_TARGET_AVX2 QuadFitSums() : m(splatQuad(0)), d(m), dd(m), dd1(m), md(m), md1(m), md2(m) {}
  ANIMC_TARGET_AVX2 void add(Quad u, Quad q, Quad c) {
    const Quad di = u - c;
    const Quad mi = q - u;
    const Quad di1 = yzx(di);
    const Quad di2 = zxy(di);
    m += mi;
    d += di;
    dd += di * di;
    dd1 += di * di1;
    md += mi * di;
    md1 += mi * di1;
    md2 += mi * di2;
  }
};
ANIMC_TARGET_AVX2 inline QuadFitSums quadFitSums(const double* u, const double* q, size_t n, const double c[3]) {
  const Quad c4 = {c[0], c[1], c[2], 0.0};
  QuadFitSums s;
  for (size_t i = 0; i < n; ++i) s.add(loadQuad(&u[kPointStride * i]), loadQuad(&q[kPointStride * i]), c4);
  return s;
}

// solveFit() with a row of each 3x3 matrix per Quad. Each entry is the same IEEE expression
// as there: products commute exactly, and the cofactors are taken as cross products of rows,
// which equal the columns bit for bit (the sums make Σ d·dᵀ, and so the spread, exactly
// symmetric, and the ridge adds 0.0 off the diagonal on both sides).
ANIMC_TARGET_AVX2 inline __attribute__((always_inline)) void solveQuadFit(const QuadFitSums& s, size_t n,
                                                                          double lambda, const double prior_L[9],
                                                                          CentredAffine& out, double normal[9]) {
  const Quad inv_n = splatQuad(1.0 / double(n));
  const Quad t = s.m * inv_n;
  // The spread about the centroid: Σ d·dᵀ − (Σd)·(Σd)ᵀ / n, diagonal and off it.
  const Quad spread = s.dd - (s.d * s.d) * inv_n, spread1 = s.dd1 - (s.d * yzx(s.d)) * inv_n;
  // Rows of that + λ·I and of Σ m·dᵀ (fitSumsAvx2() lists their entries). (λ·0 = +0.0 as
  // solveFit() adds; a Quad{λ, 0, 0, 0} made GCC emit a register vmovq that valgrind 3.19
  // cannot decode.)
  const Quad lam = splatQuad(lambda);
  const Quad a[3] = {__builtin_shufflevector(spread, spread1, 0, 4, 6, 3) + lam * Quad{1.0, 0.0, 0.0, 0.0},
                     __builtin_shufflevector(spread, spread1, 4, 1, 5, 3) + lam * Quad{0.0, 1.0, 0.0, 0.0},
                     __builtin_shufflevector(spread, spread1, 6, 5, 2, 3) + lam * Quad{0.0, 0.0, 1.0, 0.0}};
  const Quad md_md1 = __builtin_shufflevector(s.md, s.md1, 0, 4, 1, 5);  // md0 md1_0 md_1 md1_1
  const Quad cross[3] = {__builtin_shufflevector(md_md1, s.md2, 0, 1, 4, 3),
                         __builtin_shufflevector(md_md1, s.md2, 5, 2, 3, 3),
                         __builtin_shufflevector(__builtin_shufflevector(s.md1, s.md2, 2, 6, 2, 3), s.md, 0, 1, 6, 3)};
  if (normal)
    for (int r = 0; r < 3; ++r) storeXyz(&normal[3 * r], a[r]);
  // b = Σ (m - m̄)·dᵀ + λ·prior, as in solveFit().
  Quad b[3];
  for (int r = 0; r < 3; ++r)
    b[r] = (cross[r] - splatQuad(t[r]) * s.d) + lam * loadXyz(&prior_L[3 * r]);
  // Rows of the cofactor matrix: inv row 0 = a₁ × a₂, row 1 = a₂ × a₀, row 2 = a₀ × a₁.
  Quad inv[3];
  for (int r = 0; r < 3; ++r) {
    const Quad& x = a[(r + 1) % 3];
    const Quad& y = a[(r + 2) % 3];
    inv[r] = yzx(x) * zxy(y) - zxy(x) * yzx(y);
  }
  const double det = a[0][0] * inv[0][0] + a[0][1] * inv[1][0] + a[0][2] * inv[2][0];
  storeXyz(out.t, t);
  for (int r = 0; r < 3; ++r) {
    const Quad numerator = (splatQuad(b[r][0]) * inv[0] + splatQuad(b[r][1]) * inv[1]) + splatQuad(b[r][2]) * inv[2];
    storeXyz(&out.L[3 * r], numerator / splatQuad(det));
  }
}

// The before points are normalised (lane 3 stays 0: (0 - 0) · inv) and summed as they come,
// about the first of them.
ANIMC_TARGET_AVX2 void gatherWithMotionAvx2(const double* reference, const double* before, const RootCube& cube,
                                            const uint32_t* idx, size_t n, double* out, CellFrame& frame,
                                            CentredAffine& motion) {
  const Quad min = {cube.min[0], cube.min[1], cube.min[2], 0.0}, inv = splatQuad(1.0 / cube.side);
  const auto beforePoint = [&](size_t i) ANIMC_TARGET_AVX2 { return (loadXyz(&before[3 * size_t(idx[i])]) - min) * inv; };
  const Quad origin = beforePoint(0), first = loadXyz(&reference[3 * size_t(idx[0])]);
  QuadGatherer gatherer(first, out);
  QuadFitSums s;
  s.add(origin, first, origin);
  for (size_t i = 1; i < n; ++i) {
    const Quad r = loadXyz(&reference[3 * size_t(idx[i])]);
    gatherer.add(r, &out[kPointStride * i]);
    s.add(beforePoint(i), r, origin);
  }
  frame = gatherer.frame(n);
  solveQuadFit(s, n, ridgeWeight(n, frame), kNoPrior, motion, nullptr);
}

ANIMC_TARGET_AVX2 FitSums fitSumsAvx2(const double* u, const double* q, size_t n, const double c[3]) {
  const QuadFitSums s = quadFitSums(u, q, n, c);
  return FitSums{{s.m[0], s.m[1], s.m[2]},
                 {s.d[0], s.d[1], s.d[2]},
                 {s.dd[0], s.dd1[0], s.dd1[2], s.dd1[0], s.dd[1], s.dd1[1], s.dd1[2], s.dd1[1], s.dd[2]},
                 {s.md[0], s.md1[0], s.md2[0], s.md2[1], s.md[1], s.md1[1], s.md1[2], s.md2[2], s.md[2]}};
}

ANIMC_TARGET_AVX2 void predictPointsAvx2(const double* u, size_t n, const double c[3], const CentredAffine& a,
                                         const uint32_t* idx, double* recon) {
  const Quad c4 = {c[0], c[1], c[2], 0.0}, t4 = {a.t[0], a.t[1], a.t[2], 0.0};
  const Quad l0 = {a.L[0], a.L[3], a.L[6], 0.0}, l1 = {a.L[1], a.L[4], a.L[7], 0.0},
             l2 = {a.L[2], a.L[5], a.L[8], 0.0};
  for (size_t i = 0; i < n; ++i) {
    const Quad ui = loadQuad(&u[kPointStride * i]);
    const Quad di = ui - c4;
    const Quad p = (ui + t4) + ((l0 * splatQuad(di[0]) + l1 * splatQuad(di[1])) + l2 * splatQuad(di[2]));
    double* out = &recon[3 * size_t(idx[i])];  // three lanes only: the next vertex follows
    storePair(out, Pair{p[0], p[1]});
    out[2] = p[2];
  }
}
#endif

}  // namespace

#if ANIMC_AVX2_PATH
// fitCentred() (affine_fit.cpp): the sums in one pass, then the solve with a row of each
// matrix per Quad.
ANIMC_TARGET_AVX2 void fitCentredAvx2(const double* u, const double* q, size_t n, const CellFrame& frame,
                                      const double prior_L[9], CentredAffine& out, double normal[9]) {
  solveQuadFit(quadFitSums(u, q, n, frame.centroid), n, ridgeWeight(n, frame), prior_L, out, normal);
}
#endif

CellFrame gatherPoints([[maybe_unused]] SimdPath path, const double* frame, const uint32_t* idx, size_t n, double* out) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return gatherPointsAvx2(frame, idx, n, out);
#endif
  return gatherPointsPortable(frame, idx, n, out);
}

void gatherWithMotion([[maybe_unused]] SimdPath path, const double* reference, const double* before, const RootCube& cube, const uint32_t* idx,
                      size_t n, double* out, double* scratch, CellFrame& frame, CentredAffine& motion) {
  if (n == 1) return gatherOneWithMotion(reference, before, cube, idx[0], out, frame, motion);
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return gatherWithMotionAvx2(reference, before, cube, idx, n, out, frame, motion);
#endif
  gatherWithMotionPortable(reference, before, cube, idx, n, out, scratch, frame, motion);
}

void copyPoints([[maybe_unused]] SimdPath path, const double* frame, const uint32_t* idx, size_t n, double* out) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return copyPointsAvx2(frame, idx, n, out);
#endif
  copyPointsPortable(frame, idx, n, out);
}

FitSums fitSums([[maybe_unused]] SimdPath path, const double* u, const double* q, size_t n, const double c[3]) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return fitSumsAvx2(u, q, n, c);
#endif
  return fitSumsPortable(u, q, n, c);
}

void predictPoints([[maybe_unused]] SimdPath path, const double* u, size_t n, const double c[3], const CentredAffine& a,
                   const uint32_t* idx, double* recon) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return predictPointsAvx2(u, n, c, a, idx, recon);
#endif
  predictPointsPortable(u, n, c, a, idx, recon);
}

}  // namespace animc
