// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/anisotropic_predictor.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>

#include "core/simd_math.h"

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

// Positions of one stencil vertex for each of two edges, by axis, one edge per lane.
struct LanePoints {
  Pair x, y, z;
};

LanePoints lanePoints(const double* const axis[3], size_t i) {
  return {loadPair(axis[0] + i), loadPair(axis[1] + i), loadPair(axis[2] + i)};
}

// The second differences of two edges at once, one per lane: edge (j, k) with opposite
// vertices l1 and l2. Lane by lane the operations of one edge, which are Eigen's Vector3d
// arithmetic (what this code used before: the same bits) written out by axis: dot
// (x0 y0 + x1 y1) + x2 y2, cross (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0). Fills the
// coefficients and the weight of out[lane] where valid[lane] is true on entry, and leaves it
// true where neither the edge nor a flap's height over it is degenerate (otherwise out[lane]
// is not used).
void secondDifferences(const LanePoints& j, const LanePoints& k, const LanePoints& l1, const LanePoints& l2,
                       const AnisotropyParams& params, EdgeStencil out[2], bool valid[2]) {
  const Pair ex = k.x - j.x, ey = k.y - j.y, ez = k.z - j.z;
  const Pair length2 = (ex * ex + ey * ey) + ez * ez;
  const Pair length = sqrtPair(length2);
  // Each flap l - j, its foot's parameter alpha on the edge and its height over it.
  const Pair d1x = l1.x - j.x, d1y = l1.y - j.y, d1z = l1.z - j.z;
  const Pair alpha1 = ((d1x * ex + d1y * ey) + d1z * ez) / length2;
  const Pair h1x = d1x - alpha1 * ex, h1y = d1y - alpha1 * ey, h1z = d1z - alpha1 * ez;
  const Pair height1 = sqrtPair((h1x * h1x + h1y * h1y) + h1z * h1z);
  const Pair d2x = l2.x - j.x, d2y = l2.y - j.y, d2z = l2.z - j.z;
  const Pair alpha2 = ((d2x * ex + d2y * ey) + d2z * ez) / length2;
  const Pair h2x = d2x - alpha2 * ex, h2y = d2y - alpha2 * ey, h2z = d2z - alpha2 * ez;
  const Pair height2 = sqrtPair((h2x * h2x + h2y * h2y) + h2z * h2z);
  const Pair c0 = (splat(0.0) - (splat(1.0) - alpha1) * length / height1) - (splat(1.0) - alpha2) * length / height2;
  const Pair c1 = (splat(0.0) - alpha1 * length / height1) - alpha2 * length / height2;
  const Pair c2 = length / height1, c3 = length / height2;
  // The normals of (j, k, l1), e x (l1 - j), and of (k, j, l2), (j - k) x (l2 - k).
  const Pair n1x = ey * d1z - ez * d1y, n1y = ez * d1x - ex * d1z, n1z = ex * d1y - ey * d1x;
  const Pair ax = j.x - k.x, ay = j.y - k.y, az = j.z - k.z;
  const Pair bx = l2.x - k.x, by = l2.y - k.y, bz = l2.z - k.z;
  const Pair n2x = ay * bz - az * by, n2y = az * bx - ax * bz, n2z = ax * by - ay * bx;
  const Pair norms = sqrtPair((n1x * n1x + n1y * n1y) + n1z * n1z) * sqrtPair((n2x * n2x + n2y * n2y) + n2z * n2z);
  const Pair normal_dot = (n1x * n2x + n1y * n2y) + n1z * n2z;
  for (int lane = 0; lane < 2; ++lane) {
    valid[lane] = valid[lane] && length2[lane] > 0 && height1[lane] > 1e-9 * length[lane] &&
                  height2[lane] > 1e-9 * length[lane];
    if (!valid[lane]) continue;
    EdgeStencil& e = out[lane];
    e.coefficient[0] = c0[lane];
    e.coefficient[1] = c1[lane];
    e.coefficient[2] = c2[lane];
    e.coefficient[3] = c3[lane];
    e.weight = edgeWeight(norms[lane] > 0 ? normal_dot[lane] / norms[lane] : 1.0, params);
  }
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
// parameters) was measured: barely fewer bits on smooth meshes and more on the game meshes,
// whose coarse boundaries are polygons with corners (docs/notes/wavelet_history.md).
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

// An interior collapse's edges: spoke i is (v, ring[i]) between the triangles (v, ring[i],
// next) and (v, previous, ring[i]); link edge i is (ring[i], next), between (v, ring[i], next)
// and the flap triangle beyond it. Their positions by axis (structure of arrays), so that
// edges i and i + 1 load as Pairs; reused from collapse to collapse, growing only.
class RingEdges {
 public:
  // Fills the arrays for c; then the edges' stencils.
  void compute(const ProgressiveMesh& pm, const Collapse& c, const std::vector<double>& xyz,
               const AnisotropyParams& params) {
    const uint32_t* ring = &pm.ring[c.ring_begin];
    const uint32_t* flap = &pm.flap[c.ring_begin];
    const size_t k = c.ring_size;
    if (stride_ < k + 3) grow(k + 3);
    // around[i + 1] is ring[i]; around[0] and around[k + 1..k + 2] wrap around, so that
    // previous, ring[i] and next are around[i], around[i + 1] and around[i + 2] for every i,
    // even the lane past the last edge.
    setPoint(around_, 0, xyz, ring[k - 1]);
    for (size_t i = 0; i < k; ++i) setPoint(around_, i + 1, xyz, ring[i]);
    setPoint(around_, k + 1, xyz, ring[0]);
    setPoint(around_, k + 2, xyz, ring[k > 1 ? 1 : 0]);
    for (size_t i = 0; i < k; ++i) {
      const bool has_flap = flap[i] != kNoVertex;
      setPoint(beyond_, i, xyz, has_flap ? flap[i] : c.vertex);
      spoke_valid_[i] = true;
      link_valid_[i] = has_flap;  // else no second difference (nor its exp) is wanted
    }
    setPoint(beyond_, k, xyz, c.vertex);
    spoke_valid_[k] = link_valid_[k] = false;  // the lane past the last edge
    const double* v = &xyz[3 * size_t(c.vertex)];
    const LanePoints pv = {splat(v[0]), splat(v[1]), splat(v[2])};
    for (size_t i = 0; i < k; i += 2) {
      const LanePoints previous = lanePoints(around_, i), here = lanePoints(around_, i + 1),
                       next = lanePoints(around_, i + 2);
      secondDifferences(pv, here, next, previous, params, &spoke_[i], &spoke_valid_[i]);
      secondDifferences(here, next, pv, lanePoints(beyond_, i), params, &link_[i], &link_valid_[i]);
    }
    for (size_t i = 0; i < k; ++i) {
      const uint32_t next = ring[i + 1 == k ? 0 : i + 1], previous = ring[i == 0 ? k - 1 : i - 1];
      uint32_t* s = spoke_[i].vertex;
      s[0] = c.vertex, s[1] = ring[i], s[2] = next, s[3] = previous;
      uint32_t* l = link_[i].vertex;
      l[0] = ring[i], l[1] = next, l[2] = c.vertex, l[3] = flap[i];
    }
  }
  // Edge i's stencil, null when it contributes nothing.
  const EdgeStencil* spoke(size_t i) const { return spoke_valid_[i] ? &spoke_[i] : nullptr; }
  const EdgeStencil* link(size_t i) const { return link_valid_[i] ? &link_[i] : nullptr; }

 private:
  void grow(size_t stride) {
    stride_ = std::max(stride, 2 * stride_);
    storage_.resize(6 * stride_);
    for (int a = 0; a < 3; ++a) {
      around_[a] = storage_.data() + a * stride_;
      beyond_[a] = storage_.data() + (3 + a) * stride_;
    }
    spoke_.resize(stride_);
    link_.resize(stride_);
    spoke_valid_.reset(new bool[stride_]);
    link_valid_.reset(new bool[stride_]);
  }
  static void setPoint(double* const axis[3], size_t i, const std::vector<double>& xyz, uint32_t w) {
    for (int a = 0; a < 3; ++a) axis[a][i] = xyz[3 * size_t(w) + a];
  }

  size_t stride_ = 0;
  std::vector<double> storage_;
  double* around_[3] = {};  // the ring, shifted by one and wrapped
  double* beyond_[3] = {};  // the flaps (v where there is none)
  std::vector<EdgeStencil> spoke_, link_;
  std::unique_ptr<bool[]> spoke_valid_, link_valid_;
};

void appendStencil(const ProgressiveMesh& pm, const Collapse& c, const std::vector<double>& xyz,
                   const AnisotropyParams& params, RingEdges& edges, StencilTerms& stencil, PredictionStencils& out) {
  if (c.kind == CollapseKind::kBoundary) return appendBoundaryStencil(pm, c, xyz, out);
  if (c.kind == CollapseKind::kSeam) return appendSeamStencil(c, out);
  const uint32_t* ring = &pm.ring[c.ring_begin];
  const size_t k = c.ring_size;
  edges.compute(pm, c, xyz, params);
  stencil.clear();
  double normaliser = 0;
  for (size_t i = 0; i < k; ++i) {
    if (const EdgeStencil* e = edges.spoke(i)) accumulate(*e, c.vertex, stencil, normaliser);
    if (const EdgeStencil* e = edges.link(i)) accumulate(*e, c.vertex, stencil, normaliser);
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
    const size_t at = out.vertex.size();
    out.vertex.resize(at + terms.size());
    out.weight.resize(at + terms.size());
    for (size_t j = 0; j < terms.size(); ++j) {
      out.vertex[at + j] = terms[j].first;
      out.weight[at + j] = terms[j].second / normaliser;
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
  RingEdges edges;
  for (const Collapse& c : pm.collapses) appendStencil(pm, c, parametric_xyz, params, edges, stencil, out);
  return out;
}

}  // namespace animc
