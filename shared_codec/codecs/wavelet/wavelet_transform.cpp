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
  const uint8_t* near_end;        // whether the collapse reads the last vertex (stencil or own)
  size_t collapse_count;
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

// The forward loop: each removed vertex's detail = position - prediction, in its frame
// (frame_of(i, xyz): collapse i's LocalFrame), x and y of the prediction through a Pair.
template <class FrameOf>
void forwardPortable(const CollapseTables& t, const double* xyz, double* coefficients, FrameOf frame_of) {
  for (size_t i = 0; i < t.collapse_count; ++i) {
    const uint32_t v = t.vertex_offset[i];
    double p[3];
    predictCollapse(t, i, xyz, p);
    const Eigen::Vector3d d = Eigen::Vector3d(xyz + v) - Eigen::Vector3d(p[0], p[1], p[2]);
    const Eigen::Vector3d local = frame_of(i, xyz).toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[v + a] = local[a];
  }
}

// The inverse loop: collapses finest last, each vertex = prediction + detail out of its frame.
template <class FrameOf>
void inversePortable(const CollapseTables& t, const double* coefficients, double* xyz, FrameOf frame_of) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    const uint32_t v = t.vertex_offset[i];
    double p[3], detail[3];
    predictCollapse(t, i, xyz, p);
    toWorld(frame_of(i, xyz), coefficients + v, detail);
    for (int a = 0; a < 3; ++a) xyz[v + a] = p[a] + detail[a];
  }
}

#if ANIMC_AVX2_PATH
// A point as lanes 0-2 of a Quad (lane 3: the next double), or by loadXyz when kNearEnd: the
// point may be the last one, whose next double does not exist.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad loadPoint(const double* p) { return kNearEnd ? loadXyz(p) : loadQuad(p); }

// Term s of a stencil: weight * position.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad stencilTerm(const uint32_t* offsets, const double* weights, ptrdiff_t s,
                                          const double* xyz) {
  return splatQuad(weights[s]) * loadPoint<kNearEnd>(xyz + offsets[s]);
}

// predict() with x, y and z as lanes of one Quad: the same operations per component. Lane 3
// sums whatever follows each point (the next point's x); nothing reads it. When kNearEnd,
// the stencil may hold the last point, whose fourth double does not exist. Two terms per
// iteration: the count of iterations, which varies from stencil to stencil, is then easier on
// the branch predictor (the inverse is 20 % faster than with one), and the order of the
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

// The frame's axes as Quads (lane 3: 0): normal, tangent, bitangent; and its columns, the
// a-th components of the three.
ANIMC_TARGET_AVX2 inline Quad axisQuad(const Eigen::Vector3d& axis) { return Quad{axis[0], axis[1], axis[2], 0.0}; }
ANIMC_TARGET_AVX2 inline Quad frameColumn(const LocalFrame& f, int a) {
  return Quad{f.normal[a], f.tangent[a], f.bitangent[a], 0.0};
}

// toWorld() with the world components as lanes: the same operations.
ANIMC_TARGET_AVX2 inline Quad toWorldQuad(const LocalFrame& f, const double c[3]) {
  return (splatQuad(c[0]) * axisQuad(f.normal) + splatQuad(c[1]) * axisQuad(f.tangent)) +
         splatQuad(c[2]) * axisQuad(f.bitangent);
}

// LocalFrame::toLocal() with the three dot products as lanes: lane k = (axis_k[0] * d[0] +
// axis_k[1] * d[1]) + axis_k[2] * d[2], Eigen's order for the dot product of 3-vectors.
ANIMC_TARGET_AVX2 inline Quad toLocalQuad(const LocalFrame& f, Quad d) {
  return (frameColumn(f, 0) * splatQuad(d[0]) + frameColumn(f, 1) * splatQuad(d[1])) +
         frameColumn(f, 2) * splatQuad(d[2]);
}

// forwardPortable with x, y and z as lanes of one Quad: the same operations per component.
template <bool kNearEnd, class FrameOf>
ANIMC_TARGET_AVX2 inline void forwardCollapseAvx2(const CollapseTables& t, size_t i, const double* xyz,
                                                  double* coefficients, FrameOf frame_of) {
  const uint32_t v = t.vertex_offset[i];
  const Quad d = loadPoint<kNearEnd>(xyz + v) - predictCollapseQuad<kNearEnd>(t, i, xyz);
  storeXyz(coefficients + v, toLocalQuad(frame_of(i, xyz), d));
}

template <class FrameOf>
ANIMC_TARGET_AVX2 void forwardAvx2(const CollapseTables& t, const double* xyz, double* coefficients,
                                   FrameOf frame_of) {
  for (size_t i = 0; i < t.collapse_count; ++i) {
    if (t.near_end[i])
      forwardCollapseAvx2<true>(t, i, xyz, coefficients, frame_of);
    else
      forwardCollapseAvx2<false>(t, i, xyz, coefficients, frame_of);
  }
}

// inversePortable with x, y and z as lanes of one Quad: the same operations per component.
template <class FrameOf>
ANIMC_TARGET_AVX2 void inverseAvx2(const CollapseTables& t, const double* coefficients, double* xyz,
                                   FrameOf frame_of) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    const uint32_t v = t.vertex_offset[i];
    const Quad p = t.near_end[i] ? predictCollapseQuad<true>(t, i, xyz) : predictCollapseQuad<false>(t, i, xyz);
    storeXyz(xyz + v, p + toWorldQuad(frame_of(i, xyz), coefficients + v));
  }
}
#endif

// The loops on the fastest kernel this CPU runs (all give the same bits).
template <class FrameOf>
void runForward(const CollapseTables& t, const double* xyz, double* coefficients, FrameOf frame_of) {
#if ANIMC_AVX2_PATH
  if (cpuHasAvx2()) return forwardAvx2(t, xyz, coefficients, frame_of);
#endif
  forwardPortable(t, xyz, coefficients, frame_of);
}

template <class FrameOf>
void runInverse(const CollapseTables& t, const double* coefficients, double* xyz, FrameOf frame_of) {
#if ANIMC_AVX2_PATH
  if (cpuHasAvx2()) return inverseAvx2(t, coefficients, xyz, frame_of);
#endif
  inversePortable(t, coefficients, xyz, frame_of);
}

}  // namespace

WaveletTransform::WaveletTransform(const Topology& topology, const std::vector<double>& parametric_xyz,
                                   bool local_frames, const HierarchySettings& settings)
    : local_frames_(local_frames), pm_(buildProgressiveMesh(topology, parametric_xyz, settings)),
      stencils_(buildPredictor(pm_, parametric_xyz)),
      level_of_(topology.vertex_count, -1) {
  flattenStencils();
  if (local_frames_) {  // the tangent masks of frameOf; world axes need none
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

void WaveletTransform::flattenStencils() {
  const uint32_t last = pm_.vertex_count - 1;
  stencil_offset_.resize(stencils_.vertex.size());
  for (size_t s = 0; s < stencils_.vertex.size(); ++s) stencil_offset_[s] = 3 * stencils_.vertex[s];
  std::vector<bool> removed(pm_.vertex_count, false);
  collapse_offset_.clear();
  near_end_.clear();
  for (size_t i = 0; i < pm_.collapses.size(); ++i) {
    const uint32_t v = pm_.collapses[i].vertex;
    removed[v] = true;
    collapse_offset_.push_back(3 * v);
    const auto begin = stencils_.vertex.begin() + stencils_.first[i];
    const auto end = stencils_.vertex.begin() + stencils_.first[i + 1];
    near_end_.push_back(v == last || std::find(begin, end, last) != end);
  }
  kept_offset_.clear();
  for (uint32_t v = 0; v < pm_.vertex_count; ++v)
    if (!removed[v]) kept_offset_.push_back(3 * v);
}

CollapseTables WaveletTransform::tables() const {
  return {stencils_.first.data(), stencil_offset_.data(), stencils_.weight.data(),
          collapse_offset_.data(), near_end_.data(), pm_.collapses.size()};
}

void WaveletTransform::copyKept(const double* from, double* to) const {
  for (uint32_t v : kept_offset_)
    for (int a = 0; a < 3; ++a) to[v + a] = from[v + a];
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

LocalFrame WaveletTransform::frameOf(const Collapse& c, const double* xyz) const {
  if (!local_frames_) return LocalFrame();
  return localFrame(xyz, &pm_.ring[c.ring_begin], &cosines_[c.ring_begin], &sines_[c.ring_begin], c.ring_size);
}

void WaveletTransform::forward(const double* xyz, std::vector<double>& coefficients) const {
  // Base vertices are their own coefficients; the loop writes every other vertex.
  coefficients.resize(3 * size_t(pm_.vertex_count));
  copyKept(xyz, coefficients.data());
  if (local_frames_)
    runForward(tables(), xyz, coefficients.data(),
               [this](size_t i, const double* positions) { return frameOf(pm_.collapses[i], positions); });
  else
    runForward(tables(), xyz, coefficients.data(), [](size_t, const double*) { return LocalFrame(); });
}

void WaveletTransform::inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const {
  // As in forward(): no copy of all the coefficients first.
  xyz.resize(coefficients.size());
  copyKept(coefficients.data(), xyz.data());
  if (local_frames_)
    runInverse(tables(), coefficients.data(), xyz.data(),
               [this](size_t i, const double* positions) { return frameOf(pm_.collapses[i], positions); });
  else
    runInverse(tables(), coefficients.data(), xyz.data(), [](size_t, const double*) { return LocalFrame(); });
}

}  // namespace animc
