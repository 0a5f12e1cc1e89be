#include "codecs/wavelet/collapse_choice.h"

#include <algorithm>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace animc {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 at(const std::vector<double>& xyz, uint32_t v) { return Vec3(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); }

// v's triangles (v, ring[i], ring[i+1]): k of them around a closed ring, k - 1 in an open
// fan, with their normals (twice their area long) from the FanGeometry scratch.
struct Fan {
  const std::vector<uint32_t>& ring;
  bool closed;
  Vec3 pv;
  const double* normals;
  const double* twice_area;

  size_t triangleCount() const { return closed ? ring.size() : ring.size() - 1; }
  // The ring position after i (the fan's triangles are (v, ring[i], ring[next(i)])).
  size_t next(size_t i) const { return i + 1 == ring.size() ? 0 : i + 1; }
  Eigen::Map<const Vec3> normal(size_t i) const { return Eigen::Map<const Vec3>(normals + 3 * i); }
};

// Whether ring[i] is u = ring[at_u] or next to it along the fan (no wrap-around in an open
// one). Positions worked out once per target: the checks ask for every ring vertex.
struct Flanks {
  static constexpr size_t kNone = SIZE_MAX;
  size_t at, before, after;
  Flanks(const Fan& fan, size_t at_u) : at(at_u) {
    const size_t k = fan.ring.size();
    after = fan.closed || at_u + 1 < k ? fan.next(at_u) : kNone;
    before = fan.closed || at_u > 0 ? (at_u == 0 ? k - 1 : at_u - 1) : kNone;
  }
  bool operator()(size_t i) const { return i == at || i == after || i == before; }
};

// The collapse keeps every surviving triangle of v non-degenerate, turned by less than
// acos(min_cos), and distinct from the triangles u already has. Called once the link
// condition holds: u's triangle {u, a, b} would make a and b neighbours of u, so it can
// exist only when both flank u.
bool keepsTrianglesSound(const LevelMesh& mesh, const std::vector<double>& xyz, const Fan& fan,
                         const Flanks& flanks, double min_cos) {
  const std::vector<uint32_t>& ring = fan.ring;
  const uint32_t u = ring[flanks.at];
  const Vec3 pu = at(xyz, u);
  for (size_t i = 0; i < fan.triangleCount(); ++i) {
    const uint32_t a = ring[i], b = ring[fan.next(i)];
    if (a == u || b == u) continue;  // this triangle disappears
    if (flanks(i) && flanks(fan.next(i)) && mesh.hasTriangle(u, a, b)) return false;
    const Vec3 pa = at(xyz, a), pb = at(xyz, b);
    const Vec3 before = fan.normal(i);
    const Vec3 after = (pa - pu).cross(pb - pu);
    const double nb = fan.twice_area[i], na = after.norm();
    const double scale = (pa - pu).squaredNorm() + (pb - pu).squaredNorm();
    if (!(na > 1e-12 * scale) || !(nb > 0)) return false;
    if (before.dot(after) < min_cos * nb * na) return false;
  }
  return true;
}

// Link condition: v and u = ring[at_u] share exactly the neighbours flanking the edge (v, u)
// (two inside, one on a boundary edge, where the fan does not wrap around).
bool linkConditionHolds(const LevelMesh& mesh, const Fan& fan, const Flanks& flanks) {
  mesh.markNeighbours(fan.ring[flanks.at]);
  for (size_t i = 0; i < fan.ring.size(); ++i)
    if (!flanks(i) && mesh.markedNeighbour(fan.ring[i])) return false;
  return true;
}

// Memoryless quadric: squared distances of u's position to the planes of v's current
// triangles, area weighted, plus a small length term so that flat regions still prefer
// short edges.
double collapseCost(const std::vector<double>& xyz, const Fan& fan, uint32_t u) {
  const Vec3 d = at(xyz, u) - fan.pv;
  double quadric = 0, area = 0;
  for (size_t i = 0; i < fan.triangleCount(); ++i) {
    const double twice_area = fan.twice_area[i];
    if (twice_area <= 0) continue;
    const double distance = fan.normal(i).dot(d) / twice_area;
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

}  // namespace

void VertexCollapses::computeFan(const std::vector<double>& xyz, FanGeometry& scratch) const {
  const Vec3 pv = at(xyz, vertex_);
  const Fan shape{ring, closed_, pv, nullptr, nullptr};
  scratch.vertex = vertex_;
  scratch.normal.resize(3 * shape.triangleCount());
  scratch.twice_area.resize(shape.triangleCount());
  for (size_t i = 0; i < shape.triangleCount(); ++i) {
    const Vec3 normal = (at(xyz, ring[i]) - pv).cross(at(xyz, ring[shape.next(i)]) - pv);
    std::copy(normal.data(), normal.data() + 3, &scratch.normal[3 * i]);
    scratch.twice_area[i] = normal.norm();
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
  const Vec3 pv = at(xyz, v);
  const Fan fan{ring, closed, pv, scratch.normal.data(), scratch.twice_area.data()};
  const double curve = closed ? 0.0 : boundaryCost(xyz, v, ring.front(), ring.back());
  // Targets: all of a closed ring, the two ends of an open fan.
  const size_t count = closed ? ring.size() : 2;
  options_.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t position = uint32_t(closed || i == 0 ? i : ring.size() - 1);
    const uint32_t u = ring[position];
    options_.push_back({{u, position, collapseCost(xyz, fan, u) + curve, (at(xyz, u) - pv).norm()}});
  }
  sortByCost();
}

// Insertion sort: a few options, and a total order (positions are distinct), so the result
// does not depend on the algorithm.
void VertexCollapses::sortByCost() {
  auto before = [](const Option& x, const Option& y) {
    const CollapseOption &a = x.choice, &b = y.choice;
    return a.cost < b.cost || (a.cost == b.cost && a.ring_position < b.ring_position);
  };
  for (size_t i = 1; i < options_.size(); ++i)
    for (size_t j = i; j > 0 && before(options_[j], options_[j - 1]); --j) std::swap(options_[j], options_[j - 1]);
}

void VertexCollapses::forgetValidity(uint32_t target) {
  for (size_t i = 0; i < options_.size(); ++i)
    if (options_[i].choice.target == target) {
      options_[i].validity = Validity::kUnknown;
      return;  // targets are distinct ring vertices
    }
}

bool VertexCollapses::valid(size_t option, const LevelMesh& mesh, const std::vector<double>& xyz,
                            double min_normal_cosine, FanGeometry& scratch) {
  Option& o = options_[option];
  if (o.validity == Validity::kUnknown &&
      mesh.triangleCount(o.choice.target) + mesh.triangleCount(vertex_) > kMaxCollapseTriangles + 2)
    o.validity = Validity::kInvalid;  // before the checks, which would walk the big fan
  if (o.validity == Validity::kUnknown) {
    const Fan shape{ring, closed_, at(xyz, vertex_), nullptr, nullptr};
    const Flanks flanks(shape, o.choice.ring_position);
    bool ok = linkConditionHolds(mesh, shape, flanks);
    if (ok) {  // only the triangle checks need the fan's normals
      if (scratch.vertex != vertex_) computeFan(xyz, scratch);
      const Fan fan{ring, closed_, shape.pv, scratch.normal.data(), scratch.twice_area.data()};
      ok = keepsTrianglesSound(mesh, xyz, fan, flanks, min_normal_cosine);
    }
    o.validity = ok ? Validity::kValid : Validity::kInvalid;
  }
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
