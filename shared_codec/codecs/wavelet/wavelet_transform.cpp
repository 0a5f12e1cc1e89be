// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/wavelet_transform.h"

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/local_frame.h"
#include "core/simd_math.h"

namespace animc {

// What the transform reads per collapse, as flat arrays. Positions are addressed by offsets
// (3 * vertex), as in stencil_offset_.
struct CollapseTables {
  const uint32_t* stencil_first;  // collapse i's stencil: [stencil_first[i], stencil_first[i + 1])
  const uint32_t* stencil_offset;
  const double* stencil_weight;
  const uint32_t* vertex_offset;  // of the vertex each collapse removes
  const uint8_t* near_end;        // whether the collapse reads the last vertex (stencil, ring or own)
  size_t collapse_count;
  // Local frames only: the collapses' rings (pm_.ring, 3 * pm_.ring) and tangent masks.
  const Collapse* collapses;
  const uint32_t* ring;
  const uint32_t* ring_offset;
  const double* cosines;
  const double* sines;
};

namespace {

constexpr double kPi = 3.14159265358979323846;
// Weights are clamped so that a sliver ring or a huge base face cannot dominate the rate.
constexpr double kMinWeight = 1.0, kMaxWeight = 100.0;

double triangleArea(const std::vector<double>& xyz, uint32_t a, uint32_t b, uint32_t c) {
  const Eigen::Vector3d pa(&xyz[3 * size_t(a)]), pb(&xyz[3 * size_t(b)]), pc(&xyz[3 * size_t(c)]);
  return 0.5 * (pb - pa).cross(pc - pa).norm();
}

// Sum of weight * position over a stencil, component by component in stencil order (the
// order Eigen's p += w * x used: encoder and decoder, old and new, round alike); x and y as
// the two lanes of a Pair, the same IEEE operations per lane.
inline void predict(const uint32_t* offsets, const double* weights, size_t size, const double* xyz, double p[3]) {
  Pair xy = splat(0.0);
  double z = 0.0;
  for (size_t s = 0; s < size; ++s) {
    const double* x = xyz + offsets[s];
    xy += splat(weights[s]) * loadPair(x);
    z += weights[s] * x[2];
  }
  p[0] = xy[0];
  p[1] = xy[1];
  p[2] = z;
}

// c[0] * normal + c[1] * tangent + c[2] * bitangent, summed in Eigen's order (as the code it
// replaced did), even for the world axes (0 * c and c * 1 are not no-ops for the sign of zero).
inline void toWorld(const LocalFrame& f, const double c[3], double out[3]) {
  for (int a = 0; a < 3; ++a) out[a] = (c[0] * f.normal[a] + c[1] * f.tangent[a]) + c[2] * f.bitangent[a];
}

inline void predictCollapse(const CollapseTables& t, size_t i, const double* xyz, double p[3]) {
  const uint32_t begin = t.stencil_first[i];
  predict(t.stencil_offset + begin, t.stencil_weight + begin, t.stencil_first[i + 1] - begin, xyz, p);
}

#if ANIMC_AVX2_PATH
// A point as lanes 0-2 of a Quad (lane 3: the next double), or by loadXyz when kNearEnd: the
// point may be the last one, whose next double does not exist.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad loadPoint(const double* p) { return kNearEnd ? loadXyz(p) : loadQuad(p); }

// A LocalFrame's axes as Quads (lanes 0-2).
struct FrameQuads {
  Quad normal, tangent, bitangent;
};

ANIMC_TARGET_AVX2 inline FrameQuads worldAxesQuads() {
  return {Quad{0, 0, 1, 0}, Quad{1, 0, 0, 0}, Quad{0, 1, 0, 0}};  // LocalFrame()
}

// Sum of lanes 0-2, in Eigen's order for 3-vectors (dot products, squared norms).
ANIMC_TARGET_AVX2 inline double sum3(Quad a) { return (a[0] + a[1]) + a[2]; }

// Eigen's cross product of lanes 0-2: (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).
ANIMC_TARGET_AVX2 inline Quad cross3(Quad a, Quad b) { return yzx(a) * zxy(b) - zxy(a) * yzx(b); }

// localFrame() (local_frame.h) on Quads, the same operations: Eigen's 3-vector expressions
// component by component, its sums of three in sum3's order. Lanes 3 hold whatever follows the
// ring's points, summed and multiplied; nothing reads them.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline FrameQuads localFrameQuads(const double* xyz, const uint32_t* ring_offsets,
                                                    const double* cosines, const double* sines, size_t k) {
  Quad t1 = splatQuad(0.0), t2 = splatQuad(0.0);
  for (size_t i = 0; i < k; ++i) {
    const Quad p = loadPoint<kNearEnd>(xyz + ring_offsets[i]);
    t1 += splatQuad(cosines[i]) * p;
    t2 += splatQuad(sines[i]) * p;
  }
  const Quad n = cross3(t1, t2);
  const double nn = std::sqrt(sum3(n * n)), scale = std::sqrt(sum3(t1 * t1)) * std::sqrt(sum3(t2 * t2));
  if (!(nn > 1e-9 * scale) || !(scale > 0) || !std::isfinite(nn)) return worldAxesQuads();
  FrameQuads f;
  f.normal = n / splatQuad(nn);
  const Quad u = t1 - splatQuad(sum3(t1 * f.normal)) * f.normal;
  const double z = sum3(u * u);  // Eigen's normalised(): u / |u|, u itself when |u| = 0
  f.tangent = z > 0 ? u / splatQuad(std::sqrt(z)) : u;
  f.bitangent = cross3(f.normal, f.tangent);
  return f;
}
#endif

// The frames of the details: collapse i's LocalFrame for the portable kernels
// (frames(i, xyz)), its FrameQuads for the AVX2 ones (frames.quads<kNearEnd>(i, xyz)).
// The world axes (local_frames = false) ...
struct WorldAxes {
  LocalFrame operator()(size_t, const double*) const { return LocalFrame(); }
#if ANIMC_AVX2_PATH
  template <bool kNearEnd>
  ANIMC_TARGET_AVX2 FrameQuads quads(size_t, const double*) const {
    return worldAxesQuads();
  }
#endif
};

// ... or the local frame of each collapse's ring on the positions in xyz.
struct RingFrames {
  const CollapseTables& t;
  LocalFrame operator()(size_t i, const double* xyz) const {
    const Collapse& c = t.collapses[i];
    return localFrame(xyz, t.ring + c.ring_begin, t.cosines + c.ring_begin, t.sines + c.ring_begin, c.ring_size);
  }
#if ANIMC_AVX2_PATH
  template <bool kNearEnd>
  ANIMC_TARGET_AVX2 FrameQuads quads(size_t i, const double* xyz) const {
    const Collapse& c = t.collapses[i];
    return localFrameQuads<kNearEnd>(xyz, t.ring_offset + c.ring_begin, t.cosines + c.ring_begin,
                                     t.sines + c.ring_begin, c.ring_size);
  }
#endif
};

// The forward loop: each removed vertex's detail = position - prediction, in its frame, x and
// y of the prediction through a Pair.
template <class Frames>
void forwardPortable(const CollapseTables& t, const double* xyz, double* coefficients, const Frames& frames) {
  for (size_t i = 0; i < t.collapse_count; ++i) {
    const uint32_t v = t.vertex_offset[i];
    double p[3];
    predictCollapse(t, i, xyz, p);
    const Eigen::Vector3d d = Eigen::Vector3d(xyz + v) - Eigen::Vector3d(p[0], p[1], p[2]);
    const Eigen::Vector3d local = frames(i, xyz).toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[v + a] = local[a];
  }
}

// The inverse loop: collapses finest last, each vertex = prediction + detail out of its frame.
template <class Frames>
void inversePortable(const CollapseTables& t, const double* coefficients, double* xyz, const Frames& frames) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    const uint32_t v = t.vertex_offset[i];
    double p[3], detail[3];
    predictCollapse(t, i, xyz, p);
    toWorld(frames(i, xyz), coefficients + v, detail);
    for (int a = 0; a < 3; ++a) xyz[v + a] = p[a] + detail[a];
  }
}

#if ANIMC_AVX2_PATH
// Term s of a stencil: weight * position.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad stencilTerm(const uint32_t* offsets, const double* weights, ptrdiff_t s,
                                          const double* xyz) {
  return splatQuad(weights[s]) * loadPoint<kNearEnd>(xyz + offsets[s]);
}

// predict() with x, y and z as lanes of one Quad: the same operations per component. Lane 3
// sums whatever follows each point (the next point's x); nothing reads it. Two terms per
// iteration: the count of iterations, which varies from stencil to stencil, is then easier on
// the branch predictor (the inverse is faster than with one), and the order of the
// additions is the same.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad predictQuad(const uint32_t* offsets, const double* weights, size_t size,
                                          const double* xyz) {
  Quad p = splatQuad(0.0);
  // Indexed from the end (negative to 0): the loop's count is its index.
  const uint32_t* const offsets_end = offsets + size;
  const double* const weights_end = weights + size;
  ptrdiff_t s = -ptrdiff_t(size);
  if (size & 1) p += stencilTerm<kNearEnd>(offsets_end, weights_end, s++, xyz);
  for (; s != 0; s += 2) {
    p += stencilTerm<kNearEnd>(offsets_end, weights_end, s, xyz);
    p += stencilTerm<kNearEnd>(offsets_end, weights_end, s + 1, xyz);
  }
  return p;
}

template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad predictCollapseQuad(const CollapseTables& t, size_t i, const double* xyz) {
  const uint32_t begin = t.stencil_first[i];
  return predictQuad<kNearEnd>(t.stencil_offset + begin, t.stencil_weight + begin, t.stencil_first[i + 1] - begin, xyz);
}

// toWorld() with the world components as lanes: the same operations.
ANIMC_TARGET_AVX2 inline Quad toWorldQuad(const FrameQuads& f, const double c[3]) {
  return (splatQuad(c[0]) * f.normal + splatQuad(c[1]) * f.tangent) + splatQuad(c[2]) * f.bitangent;
}

// LocalFrame::toLocal() with the three dot products as lanes: lane k = (axis_k[0] * d[0] +
// axis_k[1] * d[1]) + axis_k[2] * d[2], Eigen's order for the dot product of 3-vectors.
ANIMC_TARGET_AVX2 inline Quad toLocalQuad(const FrameQuads& f, Quad d) {
  Quad column[3];  // column[a]: the a-th components of the normal, tangent and bitangent
  transposeColumns(f.normal, f.tangent, f.bitangent, splatQuad(0.0), column);
  return (column[0] * splatQuad(d[0]) + column[1] * splatQuad(d[1])) + column[2] * splatQuad(d[2]);
}

// The portable kernels' collapse i with x, y and z as lanes of one Quad: the same operations
// per component.
template <bool kNearEnd, class Frames>
ANIMC_TARGET_AVX2 inline void forwardCollapseAvx2(const CollapseTables& t, size_t i, const double* xyz,
                                                  double* coefficients, const Frames& frames) {
  const uint32_t v = t.vertex_offset[i];
  const Quad d = loadPoint<kNearEnd>(xyz + v) - predictCollapseQuad<kNearEnd>(t, i, xyz);
  storeXyz(coefficients + v, toLocalQuad(frames.template quads<kNearEnd>(i, xyz), d));
}

template <bool kNearEnd, class Frames>
ANIMC_TARGET_AVX2 inline void inverseCollapseAvx2(const CollapseTables& t, size_t i, const double* coefficients,
                                                  double* xyz, const Frames& frames) {
  const uint32_t v = t.vertex_offset[i];
  const Quad p = predictCollapseQuad<kNearEnd>(t, i, xyz);
  storeXyz(xyz + v, p + toWorldQuad(frames.template quads<kNearEnd>(i, xyz), coefficients + v));
}

template <class Frames>
ANIMC_TARGET_AVX2 void forwardAvx2(const CollapseTables& t, const double* xyz, double* coefficients,
                                   const Frames& frames) {
  for (size_t i = 0; i < t.collapse_count; ++i) {
    if (t.near_end[i])
      forwardCollapseAvx2<true>(t, i, xyz, coefficients, frames);
    else
      forwardCollapseAvx2<false>(t, i, xyz, coefficients, frames);
  }
}

template <class Frames>
ANIMC_TARGET_AVX2 void inverseAvx2(const CollapseTables& t, const double* coefficients, double* xyz,
                                   const Frames& frames) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    if (t.near_end[i])
      inverseCollapseAvx2<true>(t, i, coefficients, xyz, frames);
    else
      inverseCollapseAvx2<false>(t, i, coefficients, xyz, frames);
  }
}
#endif

// The loops on the kernels of `path` (all give the same bits).
template <class Frames>
void runForward([[maybe_unused]] SimdPath path, const CollapseTables& t, const double* xyz, double* coefficients,
                const Frames& frames) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return forwardAvx2(t, xyz, coefficients, frames);
#endif
  forwardPortable(t, xyz, coefficients, frames);
}

template <class Frames>
void runInverse([[maybe_unused]] SimdPath path, const CollapseTables& t, const double* coefficients, double* xyz,
                const Frames& frames) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return inverseAvx2(t, coefficients, xyz, frames);
#endif
  inversePortable(t, coefficients, xyz, frames);
}

}  // namespace

WaveletTransform::WaveletTransform(SimdPath path, const Topology& topology, const std::vector<double>& parametric_xyz,
                                   bool local_frames, HierarchySettings settings)
    : path_(path), local_frames_(local_frames),
      pm_(buildProgressiveMesh(topology, parametric_xyz, (settings.path = path, settings))),
      stencils_(buildPredictor(pm_, parametric_xyz)),
      level_of_(topology.vertex_count, -1) {
  buildCollapseTables();
  if (local_frames_) {  // the tangent masks of the local frames; world axes need none
    cosines_.resize(pm_.ring.size());
    sines_.resize(pm_.ring.size());
  }
  for (const Collapse& c : pm_.collapses) {
    for (uint32_t k = 0; local_frames_ && k < c.ring_size; ++k) {
      cosines_[c.ring_begin + k] = std::cos(2 * kPi * k / c.ring_size);
      sines_[c.ring_begin + k] = std::sin(2 * kPi * k / c.ring_size);
    }
    level_of_[c.vertex] = c.level;
  }
  computeWeights(topology, parametric_xyz);
}

void WaveletTransform::buildCollapseTables() {
  const uint32_t last = pm_.vertex_count - 1;
  stencil_offset_.resize(stencils_.vertex.size());
  for (size_t s = 0; s < stencils_.vertex.size(); ++s) stencil_offset_[s] = 3 * stencils_.vertex[s];
  ring_offset_.resize(local_frames_ ? pm_.ring.size() : 0);  // what the local frames read
  for (size_t r = 0; r < ring_offset_.size(); ++r) ring_offset_[r] = 3 * pm_.ring[r];
  collapse_offset_.clear();
  near_end_.clear();
  for (size_t i = 0; i < pm_.collapses.size(); ++i) {
    const Collapse& c = pm_.collapses[i];
    collapse_offset_.push_back(3 * c.vertex);
    const auto stencil = stencils_.vertex.begin() + stencils_.first[i];
    const auto stencil_end = stencils_.vertex.begin() + stencils_.first[i + 1];
    const auto ring = pm_.ring.begin() + c.ring_begin, ring_end = ring + c.ring_size;
    near_end_.push_back(c.vertex == last || std::find(stencil, stencil_end, last) != stencil_end ||
                        std::find(ring, ring_end, last) != ring_end);
  }
}

CollapseTables WaveletTransform::tables() const {
  return {stencils_.first.data(), stencil_offset_.data(), stencils_.weight.data(),
          collapse_offset_.data(), near_end_.data(), pm_.collapses.size(),
          pm_.collapses.data(), pm_.ring.data(), ring_offset_.data(), cosines_.data(), sines_.data()};
}

void WaveletTransform::copyKept(const double* from, double* to) const {
  for (uint32_t v : pm_.base)
    for (size_t o = 3 * size_t(v); o < 3 * size_t(v) + 3; ++o) to[o] = from[o];
}

void WaveletTransform::computeWeights(const Topology& topology, const std::vector<double>& xyz) {
  // Support of each basis function in units of the vertex's own finest one ring: roughly the
  // number of finest vertices a unit error in its coefficient moves.
  std::vector<double> fine(topology.vertex_count, 0.0), coarse(topology.vertex_count, 0.0);
  for (const Triangle& t : topology.triangles) {
    const double a = triangleArea(xyz, t[0], t[1], t[2]);
    for (uint32_t v : t) fine[v] += a;
  }
  for (const Triangle& t : pm_.base_triangles) {
    const double a = triangleArea(xyz, t[0], t[1], t[2]);
    for (uint32_t v : t) coarse[v] += a;
  }
  for (const Collapse& c : pm_.collapses)
    for (uint32_t k = 0; k < c.ring_size; ++k)
      coarse[c.vertex] += triangleArea(xyz, c.vertex, pm_.ring[c.ring_begin + k],
                                       pm_.ring[c.ring_begin + (k + 1) % c.ring_size]);
  weights_.assign(topology.vertex_count, 1.0);
  for (uint32_t v = 0; v < topology.vertex_count; ++v)
    if (fine[v] > 0 && coarse[v] > 0) weights_[v] = std::clamp(std::sqrt(coarse[v] / fine[v]), kMinWeight, kMaxWeight);
}

void WaveletTransform::forward(const double* xyz, std::vector<double>& coefficients) const {
  // Base vertices are their own coefficients; the loop writes every other vertex.
  coefficients.resize(3 * size_t(pm_.vertex_count));
  copyKept(xyz, coefficients.data());
  const CollapseTables t = tables();
  if (local_frames_)
    runForward(path_, t, xyz, coefficients.data(), RingFrames{t});
  else
    runForward(path_, t, xyz, coefficients.data(), WorldAxes());
}

void WaveletTransform::inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const {
  // As in forward(): no copy of all the coefficients first.
  xyz.resize(coefficients.size());
  copyKept(coefficients.data(), xyz.data());
  const CollapseTables t = tables();
  if (local_frames_)
    runInverse(path_, t, coefficients.data(), xyz.data(), RingFrames{t});
  else
    runInverse(path_, t, coefficients.data(), xyz.data(), WorldAxes());
}

}  // namespace animc
