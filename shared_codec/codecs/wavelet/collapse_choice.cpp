#include "codecs/wavelet/collapse_choice.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }

// Triangles (v, ring[i], ring[i+1]) of v: k of them around a closed ring, k - 1 in an open fan.
size_t fanTriangleCount(const std::vector<uint32_t>& ring, bool closed) {
  return closed ? ring.size() : ring.size() - 1;
}

// The collapse keeps every surviving triangle of v non-degenerate, turned by less than
// acos(min_cos), and distinct from the triangles u already has.
bool keepsTrianglesSound(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v, uint32_t u,
                         const std::vector<uint32_t>& ring, bool closed, double min_cos) {
  const size_t k = ring.size();
  const Vec3 pv = at(xyz, v), pu = at(xyz, u);
  for (size_t i = 0; i < fanTriangleCount(ring, closed); ++i) {
    const uint32_t a = ring[i], b = ring[(i + 1) % k];
    if (a == u || b == u) continue;  // this triangle disappears
    if (mesh.hasTriangle(u, a, b)) return false;
    const Vec3 pa = at(xyz, a), pb = at(xyz, b);
    const Vec3 before = (pa - pv).cross(pb - pv), after = (pa - pu).cross(pb - pu);
    const double nb = before.norm(), na = after.norm();
    const double scale = (pa - pu).squaredNorm() + (pb - pu).squaredNorm();
    if (!(na > 1e-12 * scale) || !(nb > 0)) return false;
    if (before.dot(after) < min_cos * nb * na) return false;
  }
  return true;
}

// Link condition: v and u = ring[at_u] share exactly the neighbours flanking the edge (v, u)
// (two inside, one on a boundary edge, where the fan does not wrap around).
bool linkConditionHolds(const LevelMesh& mesh, const std::vector<uint32_t>& ring, size_t at_u, bool closed) {
  const size_t k = ring.size();
  const uint32_t u = ring[at_u];
  for (size_t i = 0; i < k; ++i) {
    const bool flanks = i == at_u || (closed || at_u + 1 < k ? i == (at_u + 1) % k : false) ||
                        (closed || at_u > 0 ? i == (at_u + k - 1) % k : false);
    if (!flanks && mesh.adjacent(u, ring[i])) return false;
  }
  return true;
}

// Memoryless quadric: squared distances of u's position to the planes of v's current
// triangles, area weighted, plus a small length term so that flat regions still prefer
// short edges.
double collapseCost(const std::vector<double>& xyz, uint32_t v, uint32_t u, const std::vector<uint32_t>& ring,
                    bool closed) {
  const size_t k = ring.size();
  const Vec3 pv = at(xyz, v), d = at(xyz, u) - pv;
  double quadric = 0, area = 0;
  for (size_t i = 0; i < fanTriangleCount(ring, closed); ++i) {
    const Vec3 n = (at(xyz, ring[i]) - pv).cross(at(xyz, ring[(i + 1) % k]) - pv);
    const double twice_area = n.norm();
    if (twice_area <= 0) continue;
    const double distance = n.dot(d) / twice_area;
    quadric += 0.5 * twice_area * distance * distance;
    area += 0.5 * twice_area;
  }
  return quadric + 1e-3 * area * d.squaredNorm();
}

// What the boundary curve loses when v leaves it: v's squared distance to the chord between
// its boundary neighbours a and b, times the chord's squared length (an area times a squared
// distance, like the quadric).
double boundaryCost(const std::vector<double>& xyz, uint32_t v, uint32_t a, uint32_t b) {
  const Vec3 pa = at(xyz, a), chord = at(xyz, b) - pa, d = at(xyz, v) - pa;
  const double length2 = chord.squaredNorm();
  if (!(length2 > 0)) return d.squaredNorm() * d.squaredNorm();
  const Vec3 off = d - (d.dot(chord) / length2) * chord;
  return off.squaredNorm() * length2;
}

void keepBetter(CollapseChoice& best, uint32_t u, double cost, bool fits) {
  const bool better = best.target == kNoVertex || (fits && !best.fits_length) ||
                      (fits == best.fits_length && cost < best.cost);
  if (better) best = CollapseChoice{u, cost, fits};
}

}  // namespace

CollapseChoice chooseCollapse(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                              const std::vector<uint32_t>& ring, double max_length,
                              double min_normal_cosine) {
  CollapseChoice best;
  const Vec3 pv = at(xyz, v);
  for (size_t i = 0; i < ring.size(); ++i) {
    const uint32_t u = ring[i];
    if (!linkConditionHolds(mesh, ring, i, true)) continue;
    if (!keepsTrianglesSound(mesh, xyz, v, u, ring, true, min_normal_cosine)) continue;
    keepBetter(best, u, collapseCost(xyz, v, u, ring, true), (at(xyz, u) - pv).norm() <= max_length);
  }
  return best;
}

CollapseChoice chooseBoundaryCollapse(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                                      const std::vector<uint32_t>& fan, double max_length,
                                      double min_normal_cosine) {
  CollapseChoice best;
  // An ear (one triangle) stays: its ring is a single edge, which spans no local frame, and
  // removing it turns an inner edge into boundary.
  if (fan.size() < 3) return best;
  const Vec3 pv = at(xyz, v);
  const double curve = boundaryCost(xyz, v, fan.front(), fan.back());
  for (size_t i : {size_t(0), fan.size() - 1}) {
    const uint32_t u = fan[i];
    if (!linkConditionHolds(mesh, fan, i, false)) continue;
    if (!keepsTrianglesSound(mesh, xyz, v, u, fan, false, min_normal_cosine)) continue;
    keepBetter(best, u, collapseCost(xyz, v, u, fan, false) + curve, (at(xyz, u) - pv).norm() <= max_length);
  }
  return best;
}

}  // namespace animc
