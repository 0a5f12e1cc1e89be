#include "codecs/wavelet/wavelet_transform.h"

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/local_frame.h"

namespace animc {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Weights are clamped so that a sliver ring or a huge base face cannot dominate the rate.
constexpr double kMinWeight = 0.05, kMaxWeight = 100.0;

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
                                   const HierarchySettings& settings)
    : pm_(buildProgressiveMesh(topology, parametric_xyz, settings)),
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
  std::vector<double> area(topology.vertex_count, 0.0);
  double total = 0;
  for (const Triangle& t : topology.triangles) total += triangleArea(xyz, t[0], t[1], t[2]);
  for (const Triangle& t : pm_.base_triangles) {
    const double a = triangleArea(xyz, t[0], t[1], t[2]);
    for (uint32_t v : t) area[v] += a;
  }
  for (const Collapse& c : pm_.collapses)
    for (uint32_t k = 0; k < c.ring_size; ++k)
      area[c.vertex] += triangleArea(xyz, c.vertex, pm_.ring[c.ring_begin + k],
                                     pm_.ring[c.ring_begin + (k + 1) % c.ring_size]);
  const double mean = topology.vertex_count ? 3.0 * total / topology.vertex_count : 0.0;
  weights_.assign(topology.vertex_count, 1.0);
  if (!(mean > 0)) return;
  for (uint32_t v = 0; v < topology.vertex_count; ++v)
    if (area[v] > 0) weights_[v] = std::clamp(std::sqrt(area[v] / mean), kMinWeight, kMaxWeight);
}

void WaveletTransform::forward(const double* xyz, std::vector<double>& coefficients) const {
  coefficients.assign(xyz, xyz + 3 * size_t(pm_.vertex_count));
  for (size_t i = 0; i < pm_.collapses.size(); ++i) {
    const Collapse& c = pm_.collapses[i];
    const LocalFrame f = localFrame(xyz, &pm_.ring[c.ring_begin], &cosines_[c.ring_begin],
                                    &sines_[c.ring_begin], c.ring_size);
    const Eigen::Vector3d d = Eigen::Vector3d(xyz + 3 * size_t(c.vertex)) - predict(stencils_, i, xyz);
    const Eigen::Vector3d local = f.toLocal(d);
    for (int a = 0; a < 3; ++a) coefficients[3 * size_t(c.vertex) + a] = local[a];
  }
}

void WaveletTransform::inverse(const std::vector<double>& coefficients, std::vector<double>& xyz) const {
  xyz = coefficients;  // base vertices are their own coefficients
  for (size_t i = pm_.collapses.size(); i-- > 0;) {
    const Collapse& c = pm_.collapses[i];
    const LocalFrame f = localFrame(xyz.data(), &pm_.ring[c.ring_begin], &cosines_[c.ring_begin],
                                    &sines_[c.ring_begin], c.ring_size);
    const Eigen::Vector3d p = predict(stencils_, i, xyz.data()) +
                              f.toWorld(Eigen::Vector3d(&coefficients[3 * size_t(c.vertex)]));
    for (int a = 0; a < 3; ++a) xyz[3 * size_t(c.vertex) + a] = p[a];
  }
}

}  // namespace animc
