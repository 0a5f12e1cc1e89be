#include "codecs/wavelet/anisotropic_predictor.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "core/simd_math.h"

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }
const double* point(const std::vector<double>& xyz, uint32_t v) { return &xyz[3 * size_t(v)]; }

// Second difference across edge (j, k) with opposite vertices l1 and l2 (the triangles
// (j, k, l1) and (k, j, l2) unfolded): the jump of the normal derivative of the piecewise
// linear interpolant, times the edge length so that it is scale free.
struct EdgeStencil {
  uint32_t vertex[4];
  double coefficient[4];
  double weight;
};

// The two flaps' terms are computed at once, one per lane, and so are the two normals; the
// arithmetic is Eigen's Vector3d (what this function used before: the same bits), written out
// by axis: dot (x0 y0 + x1 y1) + x2 y2, cross (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).
bool secondDifference(const std::vector<double>& xyz, uint32_t j, uint32_t k, uint32_t l1, uint32_t l2,
                      const AnisotropyParams& params, EdgeStencil& out) {
  const double *pj = point(xyz, j), *pk = point(xyz, k), *p1 = point(xyz, l1), *p2 = point(xyz, l2);
  const double ex = pk[0] - pj[0], ey = pk[1] - pj[1], ez = pk[2] - pj[2];
  const double length2 = (ex * ex + ey * ey) + ez * ez;
  if (!(length2 > 0)) return false;
  const double length = std::sqrt(length2);
  // Lane s: flap l(s+1) - j, its foot's parameter alpha on the edge and its height over it.
  const Pair dx = Pair{p1[0], p2[0]} - splat(pj[0]), dy = Pair{p1[1], p2[1]} - splat(pj[1]),
             dz = Pair{p1[2], p2[2]} - splat(pj[2]);
  const Pair alpha = ((dx * ex + dy * ey) + dz * ez) / splat(length2);
  const Pair hx = dx - alpha * ex, hy = dy - alpha * ey, hz = dz - alpha * ez;
  const Pair height = sqrtPair((hx * hx + hy * hy) + hz * hz);
  if (!(height[0] > 1e-9 * length) || !(height[1] > 1e-9 * length)) return false;
  const Pair flap = splat(length) / height;
  const Pair to_j = (splat(1.0) - alpha) * length / height, to_k = alpha * length / height;
  // Lane 0: the normal of (j, k, l1), e x (l1 - j); lane 1: that of (k, j, l2), (j - k) x (l2 - k).
  const Pair ax = {ex, pj[0] - pk[0]}, ay = {ey, pj[1] - pk[1]}, az = {ez, pj[2] - pk[2]};
  const Pair bx = Pair{p1[0], p2[0]} - Pair{pj[0], pk[0]}, by = Pair{p1[1], p2[1]} - Pair{pj[1], pk[1]},
             bz = Pair{p1[2], p2[2]} - Pair{pj[2], pk[2]};
  const Pair nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
  const Pair norm = sqrtPair((nx * nx + ny * ny) + nz * nz);
  const double norms = norm[0] * norm[1];
  const double normal_dot = (nx[0] * nx[1] + ny[0] * ny[1]) + nz[0] * nz[1];
  out = {{j, k, l1, l2},
         {(0.0 - to_j[0]) - to_j[1], (0.0 - to_k[0]) - to_k[1], flap[0], flap[1]},
         edgeWeight(norms > 0 ? normal_dot / norms : 1.0, params)};
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
  out.vertex.reserve(2 * pm.ring.size());  // about a ring and its flaps per stencil
  out.weight.reserve(2 * pm.ring.size());
  out.first.push_back(0);
  StencilTerms stencil(pm.vertex_count);
  for (const Collapse& c : pm.collapses) appendStencil(pm, c, parametric_xyz, params, stencil, out);
  return out;
}

}  // namespace animc
