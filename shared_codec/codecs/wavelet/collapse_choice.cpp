#include "codecs/wavelet/collapse_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }
const double* point(const std::vector<double>& xyz, uint32_t v) { return &xyz[3 * size_t(v)]; }

// Vector3d's dot, squaredNorm and cross on plain arrays, with Eigen's operations in Eigen's
// order (what this file used before, so the hierarchy is the same bit for bit).
double dot3(const double* a, const double* b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
double squaredNorm3(const double* a) { return dot3(a, a); }
void difference3(const double* a, const double* b, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = a[i] - b[i];
}
void cross3(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// The first n elements of a scratch array that only grows.
template <class T>
T* firstOf(std::vector<T>& scratch, size_t n) {
  if (scratch.size() < n) scratch.resize(n);
  return scratch.data();
}

// Whether ring[i] is u = ring[at_u] or next to it along the fan (no wrap-around in an open
// one). Positions worked out once per target: the checks ask for every ring vertex.
struct Flanks {
  static constexpr size_t kNone = SIZE_MAX;
  size_t at, before, after;
  Flanks(size_t ring_size, bool closed, size_t at_u) : at(at_u) {
    after = closed || at_u + 1 < ring_size ? (at_u + 1 == ring_size ? 0 : at_u + 1) : kNone;
    before = closed || at_u > 0 ? (at_u == 0 ? ring_size - 1 : at_u - 1) : kNone;
  }
  bool operator()(size_t i) const { return i == at || i == after || i == before; }
};

// The collapse keeps every surviving triangle (v, a, b) of v non-degenerate, turned by less
// than acos(min_cos), and distinct from the triangles u already has. Called once the link
// condition holds: u's triangle {u, a, b} would make a and b neighbours of u, so it can
// exist only when both flank u. The offsets of a and b from u carry over from one triangle
// to the next.
bool keepsTrianglesSound(const LevelMesh& mesh, const std::vector<double>& xyz, const std::vector<uint32_t>& ring,
                         const FanGeometry& fan, const Flanks& flanks, double min_cos) {
  const size_t k = ring.size(), triangles = fan.triangles;
  const uint32_t u = ring[flanks.at];
  const double* pu = point(xyz, u);
  double from_a[3], from_b[3];  // a - u, b - u
  difference3(point(xyz, ring[0]), pu, from_a);
  double a_squared = squaredNorm3(from_a);
  for (size_t i = 0; i < triangles; ++i) {
    const size_t next = i + 1 == k ? 0 : i + 1;
    const uint32_t a = ring[i], b = ring[next];
    difference3(point(xyz, b), pu, from_b);
    const double b_squared = squaredNorm3(from_b);
    if (a != u && b != u) {  // otherwise the triangle disappears
      if (flanks(i) && flanks(next) && mesh.hasTriangle(u, a, b)) return false;
      double after[3];
      cross3(from_a, from_b, after);
      const double nb = fan.twice_area[i], na = std::sqrt(squaredNorm3(after));
      if (!(na > 1e-12 * (a_squared + b_squared)) || !(nb > 0)) return false;
      if (dot3(&fan.normal[3 * i], after) < min_cos * nb * na) return false;
    }
    std::copy(from_b, from_b + 3, from_a);
    a_squared = b_squared;
  }
  return true;
}

// Link condition: v and u = ring[at_u] share exactly the neighbours flanking the edge (v, u)
// (two inside, one on a boundary edge, where the fan does not wrap around).
bool linkConditionHolds(const LevelMesh& mesh, const std::vector<uint32_t>& ring, const Flanks& flanks) {
  mesh.markNeighbours(ring[flanks.at]);
  for (size_t i = 0; i < ring.size(); ++i)
    if (mesh.markedNeighbour(ring[i]) && !flanks(i)) return false;
  return true;
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

}  // namespace

void VertexCollapses::computeFan(const std::vector<double>& xyz, FanGeometry& fan) const {
  const size_t k = ring.size(), triangles = closed_ ? k : k - 1;
  const double* pv = point(xyz, vertex_);
  fan.vertex = vertex_;
  fan.triangles = triangles;
  double* const spoke = firstOf(fan.spoke, 3 * k);
  double* const normal = firstOf(fan.normal, 3 * triangles);
  double* const twice_area = firstOf(fan.twice_area, triangles);
  for (size_t i = 0; i < k; ++i) difference3(point(xyz, ring[i]), pv, spoke + 3 * i);
  for (size_t i = 0; i < triangles; ++i) {
    cross3(spoke + 3 * i, spoke + 3 * (i + 1 == k ? 0 : i + 1), normal + 3 * i);
    twice_area[i] = std::sqrt(squaredNorm3(normal + 3 * i));
  }
}

void VertexCollapses::prepare(const std::vector<double>& xyz, uint32_t v, bool closed, FanGeometry& scratch) {
  vertex_ = v;
  closed_ = closed;
  options_.clear();
  if (scratch.vertex == v) scratch.vertex = kNoVertex;  // v's ring has changed
  // An ear (one triangle) stays: its ring is a single edge, which spans no local frame, and
  // removing it turns an inner edge into boundary.
  if (!closed && ring.size() < 3) return;
  computeFan(xyz, scratch);
  const double curve = closed ? 0.0 : boundaryCost(xyz, v, ring.front(), ring.back());
  // Targets: all of a closed ring, the two ends of an open fan.
  const size_t count = closed ? ring.size() : 2;
  options_.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t position = uint32_t(closed || i == 0 ? i : ring.size() - 1);
    options_[i] = {{ring[position], position, 0.0, 0.0}, Validity::kUnknown};
  }
  computeCosts(scratch, curve);
  sortByCost();
}

// Memoryless quadric of each option's target u: squared distances of u to the planes of v's
// current triangles, area weighted, plus a small length term so that flat regions still
// prefer short edges, plus `curve`; and the length of the edge (v, u). Two targets at a time,
// one per lane: lane by lane the same IEEE operations as one target at a time.
void VertexCollapses::computeCosts(FanGeometry& fan, double curve) {
  Pair* const planes = firstOf(fan.planes, 5 * fan.triangles);
  Pair* planes_end = planes;
  double area = 0;
  for (size_t i = 0; i < fan.triangles; ++i) {
    const double twice_area = fan.twice_area[i];
    if (twice_area <= 0) continue;  // no plane
    const double* n = &fan.normal[3 * i];
    planes_end[0] = splat(n[0]);
    planes_end[1] = splat(n[1]);
    planes_end[2] = splat(n[2]);
    planes_end[3] = splat(twice_area);
    planes_end[4] = splat(0.5 * twice_area);
    planes_end += 5;
    area += 0.5 * twice_area;
  }
  const Pair length_weight = splat(1e-3 * area);
  for (size_t i = 0; i < options_.size(); i += 2) {
    const size_t j = i + 1 < options_.size() ? i + 1 : i;  // an odd last option takes both lanes
    const double* d0 = &fan.spoke[3 * options_[i].choice.ring_position];
    const double* d1 = &fan.spoke[3 * options_[j].choice.ring_position];
    const Pair dx = {d0[0], d1[0]}, dy = {d0[1], d1[1]}, dz = {d0[2], d1[2]};
    Pair quadric = splat(0.0);
    for (const Pair* plane = planes; plane != planes_end; plane += 5) {
      const Pair distance = ((plane[0] * dx + plane[1] * dy) + plane[2] * dz) / plane[3];
      quadric += plane[4] * distance * distance;
    }
    const Pair squared_length = (dx * dx + dy * dy) + dz * dz;
    const Pair cost = (quadric + length_weight * squared_length) + splat(curve);
    options_[i].choice.cost = cost[0];
    options_[i].choice.length = std::sqrt(squared_length[0]);
    options_[j].choice.cost = cost[1];
    options_[j].choice.length = std::sqrt(squared_length[1]);
  }
}

// Insertion sort: a few options, and a total order (positions are distinct), so the result
// does not depend on the algorithm.
void VertexCollapses::sortByCost() {
  auto before = [](const Option& x, const Option& y) {
    const CollapseOption &a = x.choice, &b = y.choice;
    return a.cost < b.cost || (a.cost == b.cost && a.ring_position < b.ring_position);
  };
  for (size_t i = 1; i < options_.size(); ++i) {
    const Option moving = options_[i];
    size_t j = i;
    for (; j > 0 && before(moving, options_[j - 1]); --j) options_[j] = options_[j - 1];
    options_[j] = moving;
  }
}

void VertexCollapses::forgetValidity(uint32_t target) {
  for (size_t i = 0; i < options_.size(); ++i)
    if (options_[i].choice.target == target) {
      options_[i].validity = Validity::kUnknown;
      return;  // targets are distinct ring vertices
    }
}

// The fan size first (the checks would walk a big fan), then the link condition, which needs
// no normals, then the triangles.
bool VertexCollapses::keepsMeshSound(const CollapseOption& option, const LevelMesh& mesh,
                                     const std::vector<double>& xyz, double min_normal_cosine,
                                     FanGeometry& scratch) const {
  if (mesh.triangleCount(option.target) + mesh.triangleCount(vertex_) > kMaxCollapseTriangles + 2) return false;
  const Flanks flanks(ring.size(), closed_, option.ring_position);
  if (!linkConditionHolds(mesh, ring, flanks)) return false;
  if (scratch.vertex != vertex_) computeFan(xyz, scratch);
  return keepsTrianglesSound(mesh, xyz, ring, scratch, flanks, min_normal_cosine);
}

bool VertexCollapses::valid(size_t option, const LevelMesh& mesh, const std::vector<double>& xyz,
                            double min_normal_cosine, FanGeometry& scratch) {
  Option& o = options_[option];
  if (o.validity == Validity::kUnknown)
    o.validity = keepsMeshSound(o.choice, mesh, xyz, min_normal_cosine, scratch) ? Validity::kValid : Validity::kInvalid;
  return o.validity == Validity::kValid;
}

// The options are in (cost, ring position) order: the first valid one within the bound is the
// answer, and the options after it need no validity.
const CollapseOption* VertexCollapses::cheapestWithin(const LevelMesh& mesh, const std::vector<double>& xyz,
                                                      double max_length, double min_normal_cosine,
                                                      FanGeometry& scratch) {
  for (size_t i = 0; i < options_.size(); ++i)
    if (options_[i].choice.length <= max_length && valid(i, mesh, xyz, min_normal_cosine, scratch))
      return &options_[i].choice;
  return nullptr;
}

bool VertexCollapses::anyValid(const LevelMesh& mesh, const std::vector<double>& xyz, double min_normal_cosine,
                               FanGeometry& scratch) {
  for (size_t i = 0; i < options_.size(); ++i)
    if (valid(i, mesh, xyz, min_normal_cosine, scratch)) return true;
  return false;
}

}  // namespace animc
