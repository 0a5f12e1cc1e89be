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
  xyz = coefficients;  // base vertices are their own coefficients
  double* const out = xyz.data();
  for (size_t i = pm_.collapses.size(); i-- > 0;) {
    const Collapse& c = pm_.collapses[i];
    double p[3], detail[3];
    predictCollapse(i, out, p);
    toWorld(frameOf(c, out), &coefficients[3 * size_t(c.vertex)], detail);
    for (int a = 0; a < 3; ++a) out[3 * size_t(c.vertex) + a] = p[a] + detail[a];
  }
}

}  // namespace animc
