#include "codecs/wavelet/anisotropic_predictor.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }

// Second difference across edge (j, k) with opposite vertices l1 and l2 (the triangles
// (j, k, l1) and (k, j, l2) unfolded): the jump of the normal derivative of the piecewise
// linear interpolant, times the edge length so that it is scale free.
struct EdgeStencil {
  uint32_t vertex[4];
  double coefficient[4];
  double weight;
};

bool secondDifference(const std::vector<double>& xyz, uint32_t j, uint32_t k, uint32_t l1, uint32_t l2,
                      const AnisotropyParams& params, EdgeStencil& out) {
  // The four positions once, into locals: out's doubles could alias xyz, which would make
  // the compiler load them again after every store.
  const Vec3 pj = at(xyz, j), pk = at(xyz, k), pl[2] = {at(xyz, l1), at(xyz, l2)};
  const Vec3 e = pk - pj;
  const double length2 = e.squaredNorm();
  if (!(length2 > 0)) return false;
  const double length = std::sqrt(length2);
  double c[4] = {0, 0, 0, 0};
  for (int s = 0; s < 2; ++s) {
    const Vec3 d = pl[s] - pj;
    const double alpha = d.dot(e) / length2;
    const double height = (d - alpha * e).norm();
    if (!(height > 1e-9 * length)) return false;
    c[2 + s] = length / height;
    c[0] -= (1 - alpha) * length / height;
    c[1] -= alpha * length / height;
  }
  const Vec3 n1 = e.cross(pl[0] - pj), n2 = (pj - pk).cross(pl[1] - pk);
  const double norms = n1.norm() * n2.norm();
  out = {{j, k, l1, l2}, {c[0], c[1], c[2], c[3]}, edgeWeight(norms > 0 ? n1.dot(n2) / norms : 1.0, params)};
  return true;
}

// The terms a_{v,m} of one stencil by vertex m, in the order the vertices first appear (the
// order the weights are stored and summed in); slot_ finds a vertex's term without a search.
class StencilTerms {
 public:
  explicit StencilTerms(uint32_t vertex_count) : slot_(vertex_count, kNoSlot) {}

  void add(uint32_t vertex, double a) {
    uint32_t& slot = slot_[vertex];
    if (slot == kNoSlot) {
      slot = uint32_t(terms_.size());
      terms_.emplace_back(vertex, a);
    } else {
      terms_[slot].second += a;
    }
  }
  const std::vector<std::pair<uint32_t, double>>& terms() const { return terms_; }
  // Empties the list for the next stencil, resetting only the slots it used.
  void clear() {
    for (const auto& t : terms_) slot_[t.first] = kNoSlot;
    terms_.clear();
  }

 private:
  static constexpr uint32_t kNoSlot = UINT32_MAX;
  std::vector<uint32_t> slot_;
  std::vector<std::pair<uint32_t, double>> terms_;
};

// Accumulates -w_e c_{e,v} c_{e,m} into the stencil of v (a_{v,m} of the paper) and
// w_e c_{e,v}^2 into the normaliser A_v.
void accumulate(const EdgeStencil& e, uint32_t v, StencilTerms& terms, double& normaliser) {
  double cv = 0;
  for (int i = 0; i < 4; ++i)
    if (e.vertex[i] == v) cv += e.coefficient[i];
  normaliser += e.weight * cv * cv;
  for (int i = 0; i < 4; ++i)
    if (e.vertex[i] != v) terms.add(e.vertex[i], -e.weight * cv * e.coefficient[i]);
}

// Boundary vertex v between its boundary neighbours a and b (ring.back(), ring.front()):
// the point of the coarser boundary edge (a, b) at v's chord-length place between them on
// the parametric mesh. A cubic through the next boundary vertices as well (Lagrange, chord
// parameters) was measured: -1 % bits on chickenCrossing, +2..6 % on the game meshes, whose
// coarse boundaries are polygons with corners (docs/wavelet.md).
void appendBoundaryStencil(const ProgressiveMesh& pm, const Collapse& c, const std::vector<double>& xyz,
                           PredictionStencils& out) {
  const uint32_t a = pm.ring[c.ring_begin + c.ring_size - 1], b = pm.ring[c.ring_begin];
  const Vec3 pv = at(xyz, c.vertex);
  const double to_a = (pv - at(xyz, a)).norm(), to_b = (at(xyz, b) - pv).norm();
  const double s = to_a + to_b > 0 ? to_a / (to_a + to_b) : 0.5;
  out.vertex.insert(out.vertex.end(), {a, b});
  out.weight.insert(out.weight.end(), {1 - s, s});
  out.first.push_back(uint32_t(out.vertex.size()));
}

// A seam copy is predicted by the vertex it duplicates.
void appendSeamStencil(const Collapse& c, PredictionStencils& out) {
  out.vertex.push_back(c.target);
  out.weight.push_back(1.0);
  out.first.push_back(uint32_t(out.vertex.size()));
}

void appendStencil(const ProgressiveMesh& pm, const Collapse& c, const std::vector<double>& xyz,
                   const AnisotropyParams& params, StencilTerms& stencil, PredictionStencils& out) {
  if (c.kind == CollapseKind::kBoundary) return appendBoundaryStencil(pm, c, xyz, out);
  if (c.kind == CollapseKind::kSeam) return appendSeamStencil(c, out);
  const uint32_t* ring = &pm.ring[c.ring_begin];
  const uint32_t* flap = &pm.flap[c.ring_begin];
  const size_t k = c.ring_size;
  stencil.clear();
  double normaliser = 0;
  EdgeStencil e;
  for (size_t i = 0; i < k; ++i) {
    const uint32_t next = ring[(i + 1) % k], previous = ring[(i + k - 1) % k];
    // Spoke (v, ring[i]) between triangles (v, ring[i], next) and (v, previous, ring[i]).
    if (secondDifference(xyz, c.vertex, ring[i], next, previous, params, e)) accumulate(e, c.vertex, stencil, normaliser);
    // Link edge (ring[i], next) between (v, ring[i], next) and the flap triangle beyond it.
    if (flap[i] != kNoVertex && secondDifference(xyz, ring[i], next, c.vertex, flap[i], params, e))
      accumulate(e, c.vertex, stencil, normaliser);
  }
  const std::vector<std::pair<uint32_t, double>>& terms = stencil.terms();
  double sum = 0, l1 = 0;
  for (const auto& t : terms) {
    sum += t.second;
    l1 += std::fabs(t.second);
  }
  const bool usable = normaliser > 0 && std::isfinite(normaliser) &&
                      std::fabs(sum - normaliser) <= 1e-6 * normaliser && l1 <= params.max_stencil_l1 * normaliser;
  if (usable) {
    for (const auto& t : terms) {
      out.vertex.push_back(t.first);
      out.weight.push_back(t.second / normaliser);
    }
  } else {  // degenerate geometry: the plain average of the ring
    for (size_t i = 0; i < k; ++i) {
      out.vertex.push_back(ring[i]);
      out.weight.push_back(1.0 / double(k));
    }
  }
  out.first.push_back(uint32_t(out.vertex.size()));
}

}  // namespace

double edgeWeight(double normal_dot, const AnisotropyParams& params) {
  return params.epsilon + std::exp((normal_dot - 1.0) / (2.0 * params.sigma * params.sigma));
}

PredictionStencils buildPredictor(const ProgressiveMesh& pm, const std::vector<double>& parametric_xyz,
                                  const AnisotropyParams& params) {
  PredictionStencils out;
  out.first.reserve(pm.collapses.size() + 1);
  out.first.push_back(0);
  StencilTerms stencil(pm.vertex_count);
  for (const Collapse& c : pm.collapses) appendStencil(pm, c, parametric_xyz, params, stencil, out);
  return out;
}

}  // namespace animc
