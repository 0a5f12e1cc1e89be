#include "codecs/wavelet/wavelet_transform.h"

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/local_frame.h"
#include "core/simd_math.h"

namespace animc {
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

// What the inverse reads per collapse, as flat arrays. Positions are addressed by offsets
// (3 * vertex), as in stencil_offset_.
struct InverseTables {
  const uint32_t* stencil_first;  // collapse i's stencil: [stencil_first[i], stencil_first[i + 1])
  const uint32_t* stencil_offset;
  const double* stencil_weight;
  const uint32_t* vertex_offset;  // of the vertex each collapse removes
  const uint8_t* reads_last;      // whether its stencil reads the last vertex
  size_t collapse_count;
};

// The inverse loop (collapses finest last, each vertex = prediction + detail in its frame),
// x and y through a Pair. frame_of(i, xyz) gives collapse i's LocalFrame.
template <class FrameOf>
void inversePortable(const InverseTables& t, const double* coefficients, double* xyz, FrameOf frame_of) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    const uint32_t begin = t.stencil_first[i], v = t.vertex_offset[i];
    double p[3], detail[3];
    predict(t.stencil_offset + begin, t.stencil_weight + begin, t.stencil_first[i + 1] - begin, xyz, p);
    toWorld(frame_of(i, xyz), coefficients + v, detail);
    for (int a = 0; a < 3; ++a) xyz[v + a] = p[a] + detail[a];
  }
}

#if ANIMC_AVX2_PATH
// A point as lanes 0-2 of a Quad, from three loads (lane 3 is 0), where the one load of
// loadQuad would read past the end of the array.
ANIMC_TARGET_AVX2 inline Quad loadPointQuad(const double* p) { return Quad{p[0], p[1], p[2], 0.0}; }
// Lanes 0-2 of a Quad as a point (lane 3 would overwrite the next point's x).
ANIMC_TARGET_AVX2 inline void storePointQuad(double* p, Quad v) {
  storePair(p, Pair{v[0], v[1]});
  p[2] = v[2];
}

// predict() with x, y and z as lanes of one Quad: the same operations per component. Lane 3
// sums whatever follows each point (the next point's x); nothing reads it. When
// kNearEnd, the stencil may hold the last point, whose fourth double does not exist.
template <bool kNearEnd>
ANIMC_TARGET_AVX2 inline Quad predictQuad(const uint32_t* offsets, const double* weights, size_t size,
                                          const double* xyz) {
  Quad p = splatQuad(0.0);
  // Indexed from the end (negative to 0): the loop's count is its index.
  const uint32_t* const offsets_end = offsets + size;
  const double* const weights_end = weights + size;
  for (ptrdiff_t s = -ptrdiff_t(size); s != 0; ++s) {
    const double* const x = xyz + offsets_end[s];
    p += splatQuad(weights_end[s]) * (kNearEnd ? loadPointQuad(x) : loadQuad(x));
  }
  return p;
}

// A frame axis as a Quad (lane 3: 0).
ANIMC_TARGET_AVX2 inline Quad axisQuad(const Eigen::Vector3d& axis) { return Quad{axis[0], axis[1], axis[2], 0.0}; }

// inversePortable with x, y and z as lanes of one Quad: the same operations per component.
template <class FrameOf>
ANIMC_TARGET_AVX2 void inverseAvx2(const InverseTables& t, const double* coefficients, double* xyz,
                                   FrameOf frame_of) {
  for (size_t i = t.collapse_count; i-- > 0;) {
    const uint32_t begin = t.stencil_first[i], size = t.stencil_first[i + 1] - begin, v = t.vertex_offset[i];
    const Quad p = t.reads_last[i] ? predictQuad<true>(t.stencil_offset + begin, t.stencil_weight + begin, size, xyz)
                                   : predictQuad<false>(t.stencil_offset + begin, t.stencil_weight + begin, size, xyz);
    const LocalFrame f = frame_of(i, xyz);
    const double* const c = coefficients + v;
    const Quad detail = (splatQuad(c[0]) * axisQuad(f.normal) + splatQuad(c[1]) * axisQuad(f.tangent)) +
                        splatQuad(c[2]) * axisQuad(f.bitangent);
    storePointQuad(xyz + v, p + detail);
  }
}
#endif

// The inverse loop on the fastest kernel this CPU runs (all give the same bits).
template <class FrameOf>
void runInverse(const InverseTables& t, const double* coefficients, double* xyz, FrameOf frame_of) {
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
  stencil_offset_.resize(stencils_.vertex.size());
  for (size_t s = 0; s < stencils_.vertex.size(); ++s) stencil_offset_[s] = 3 * stencils_.vertex[s];
  std::vector<bool> removed(pm_.vertex_count, false);
  collapse_offset_.clear();
  reads_last_.clear();
  for (size_t i = 0; i < pm_.collapses.size(); ++i) {
    removed[pm_.collapses[i].vertex] = true;
    collapse_offset_.push_back(3 * pm_.collapses[i].vertex);
    const auto first = stencils_.vertex.begin() + stencils_.first[i], end = stencils_.vertex.begin() + stencils_.first[i + 1];
    reads_last_.push_back(std::find(first, end, pm_.vertex_count - 1) != end);
  }
  kept_offset_.clear();
  for (uint32_t v = 0; v < pm_.vertex_count; ++v)
    if (!removed[v]) kept_offset_.push_back(3 * v);
}

void WaveletTransform::predictCollapse(size_t i, const double* xyz, double p[3]) const {
  const uint32_t begin = stencils_.first[i], end = stencils_.first[i + 1];
  predict(&stencil_offset_[begin], &stencils_.weight[begin], end - begin, xyz, p);
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
  coefficients.assign(xyz, xyz + 3 * size_t(pm_.vertex_count));
  for (size_t i = 0; i < pm_.collapses.size(); ++i) {
    const Collapse& c = pm_.collapses[i];
    const LocalFrame f = frameOf(c, xyz);
    double p[3];
    predictCollapse(i, xyz, p);
    const Eigen::Vector3d d = Eigen::Vector3d(xyz + 3 * size_t(c.vertex)) - Eigen::Vector3d(p[0], p[1], p[2]);
    const Eigen::Vector3d local = f.toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[3 * size_t(c.vertex) + a] = local[a];
  }
}

void WaveletTransform::inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const {
  // Base vertices are their own coefficients; the loop writes every other vertex (no copy of
  // all the coefficients first).
  xyz.resize(coefficients.size());
  double* const out = xyz.data();
  for (uint32_t v : kept_offset_)
    for (int a = 0; a < 3; ++a) out[v + a] = coefficients[v + a];
  const InverseTables tables{stencils_.first.data(), stencil_offset_.data(), stencils_.weight.data(),
                             collapse_offset_.data(), reads_last_.data(), pm_.collapses.size()};
  if (local_frames_)
    runInverse(tables, coefficients.data(), out,
               [this](size_t i, const double* positions) { return frameOf(pm_.collapses[i], positions); });
  else
    runInverse(tables, coefficients.data(), out, [](size_t, const double*) { return LocalFrame(); });
}

}  // namespace animc
