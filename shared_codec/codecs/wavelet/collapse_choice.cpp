#include "codecs/wavelet/collapse_choice.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }

// The collapse keeps every surviving triangle of v non-degenerate, turned by less than
// acos(min_cos), and distinct from the triangles u already has.
bool keepsTrianglesSound(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v, uint32_t u,
                         const std::vector<uint32_t>& ring, double min_cos) {
  const size_t k = ring.size();
  const Vec3 pv = at(xyz, v), pu = at(xyz, u);
  for (size_t i = 0; i < k; ++i) {
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

// Link condition: v and u share exactly the two neighbours flanking the edge (v, u).
bool linkConditionHolds(const LevelMesh& mesh, const std::vector<uint32_t>& ring, size_t at_u) {
  const size_t k = ring.size();
  const uint32_t u = ring[at_u];
  for (size_t i = 0; i < k; ++i) {
    if (i == at_u || i == (at_u + 1) % k || i == (at_u + k - 1) % k) continue;
    if (mesh.adjacent(u, ring[i])) return false;
  }
  return true;
}

// Memoryless quadric: squared distances of u's position to the planes of v's current
// triangles, area weighted, plus a small length term so that flat regions still prefer
// short edges.
double collapseCost(const std::vector<double>& xyz, uint32_t v, uint32_t u, const std::vector<uint32_t>& ring) {
  const size_t k = ring.size();
  const Vec3 pv = at(xyz, v), d = at(xyz, u) - pv;
  double quadric = 0, area = 0;
  for (size_t i = 0; i < k; ++i) {
    const Vec3 n = (at(xyz, ring[i]) - pv).cross(at(xyz, ring[(i + 1) % k]) - pv);
    const double twice_area = n.norm();
    if (twice_area <= 0) continue;
    const double distance = n.dot(d) / twice_area;
    quadric += 0.5 * twice_area * distance * distance;
    area += 0.5 * twice_area;
  }
  return quadric + 1e-3 * area * d.squaredNorm();
}

}  // namespace

CollapseChoice chooseCollapse(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v,
                              const std::vector<uint32_t>& ring, double max_length,
                              double min_normal_cosine) {
  CollapseChoice best;
  const Vec3 pv = at(xyz, v);
  for (size_t i = 0; i < ring.size(); ++i) {
    const uint32_t u = ring[i];
    if (!linkConditionHolds(mesh, ring, i)) continue;
    if (!keepsTrianglesSound(mesh, xyz, v, u, ring, min_normal_cosine)) continue;
    const bool fits = (at(xyz, u) - pv).norm() <= max_length;
    const double cost = collapseCost(xyz, v, u, ring);
    const bool better = best.target == kNoVertex || (fits && !best.fits_length) ||
                        (fits == best.fits_length && cost < best.cost);
    if (better) best = CollapseChoice{u, cost, fits};
  }
  return best;
}

}  // namespace animc
