#include "codecs/wavelet/wavelet_transform.h"

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/local_frame.h"

namespace animc {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Weights are clamped so that a sliver ring or a huge base face cannot dominate the rate.
constexpr double kMinWeight = 1.0, kMaxWeight = 100.0;

double triangleArea(const std::vector<double>& xyz, uint32_t a, uint32_t b, uint32_t c) {
  const Eigen::Vector3d pa(&xyz[3 * size_t(a)]), pb(&xyz[3 * size_t(b)]), pc(&xyz[3 * size_t(c)]);
  return 0.5 * (pb - pa).cross(pc - pa).norm();
}

Eigen::Vector3d predict(const PredictionStencils& s, size_t i, const double* xyz) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (uint32_t j = s.first[i]; j < s.first[i + 1]; ++j)
    p += s.weight[j] * Eigen::Vector3d(xyz + 3 * size_t(s.vertex[j]));
  return p;
}

}  // namespace

WaveletTransform::WaveletTransform(const Topology& topology, const std::vector<double>& parametric_xyz,
                                   bool local_frames, const HierarchySettings& settings)
    : local_frames_(local_frames), pm_(buildProgressiveMesh(topology, parametric_xyz, settings)),
      stencils_(buildPredictor(pm_, parametric_xyz)),
      level_of_(topology.vertex_count, -1) {
  cosines_.resize(pm_.ring.size());
  sines_.resize(pm_.ring.size());
  for (const Collapse& c : pm_.collapses) {
    for (uint32_t k = 0; k < c.ring_size; ++k) {
      cosines_[c.ring_begin + k] = std::cos(2 * kPi * k / c.ring_size);
      sines_[c.ring_begin + k] = std::sin(2 * kPi * k / c.ring_size);
    }
    level_of_[c.vertex] = c.level;
  }
  computeWeights(topology, parametric_xyz);
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
    const Eigen::Vector3d d = Eigen::Vector3d(xyz + 3 * size_t(c.vertex)) - predict(stencils_, i, xyz);
    const Eigen::Vector3d local = f.toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[3 * size_t(c.vertex) + a] = local[a];
  }
}

void WaveletTransform::inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const {
  xyz = coefficients;  // base vertices are their own coefficients
  for (size_t i = pm_.collapses.size(); i-- > 0;) {
    const Collapse& c = pm_.collapses[i];
    const LocalFrame f = frameOf(c, xyz.data());
    const Eigen::Vector3d p = predict(stencils_, i, xyz.data()) +
                              f.toWorld(Eigen::Vector3d(&coefficients[3 * size_t(c.vertex)]));
    for (int a = 0; a < 3; ++a) xyz[3 * size_t(c.vertex) + a] = p[a];
  }
}

}  // namespace animc
