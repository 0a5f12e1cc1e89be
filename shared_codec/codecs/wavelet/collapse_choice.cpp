// SPDX-License-Identifier: Apache-2.0
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

// The first n elements of a scratch array that only grows.
template <class T>
T* firstOf(std::vector<T>& scratch, size_t n) {
  if (scratch.size() < n) scratch.resize(n);
  return scratch.data();
}

// The arithmetic below is Eigen's Vector3d dot, squaredNorm and cross (what this file used
// before: the hierarchy is the same bit for bit), written out by axis, on two vectors per
// Pair: dot (x0 y0 + x1 y1) + x2 y2, cross (a1 b2 - a2 b1, a2 b0 - a0 b2, a0 b1 - a1 b0).

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
// exist only when both flank u, that is in a ring of three. Two triangles at a time, one per
// lane.
bool keepsTrianglesSound(const LevelMesh& mesh, const VertexRing& ring, FanGeometry& fan,
                         const Flanks& flanks, double min_cos) {
  const uint32_t u = ring[flanks.at];
  const size_t after = flanks.after, before = flanks.before, triangles = fan.triangles;
  if (after != Flanks::kNone && after < triangles && (after + 1 == ring.size() ? 0 : after + 1) == before &&
      mesh.hasTriangle(u, ring[after], ring[before]))
    return false;
  const double *px = fan.position(0), *py = fan.position(1), *pz = fan.position(2);
  const Pair ux = splat(px[flanks.at]), uy = splat(py[flanks.at]), uz = splat(pz[flanks.at]);
  for (size_t i = 0; i < triangles; i += 2) {
    // a - u and b - u, the triangles' corners after the collapse
    const Pair ax = loadPair(px + i) - ux, ay = loadPair(py + i) - uy, az = loadPair(pz + i) - uz;
    const Pair bx = loadPair(px + i + 1) - ux, by = loadPair(py + i + 1) - uy, bz = loadPair(pz + i + 1) - uz;
    const Pair scale = ((ax * ax + ay * ay) + az * az) + ((bx * bx + by * by) + bz * bz);
    const Pair cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const Pair na = sqrtPair((cx * cx + cy * cy) + cz * cz), nb = loadPair(fan.twiceArea() + i);
    const Pair turn = (loadPair(fan.normal(0) + i) * cx + loadPair(fan.normal(1) + i) * cy) +
                      loadPair(fan.normal(2) + i) * cz;
    const auto unsound = ~(na > splat(1e-12) * scale) | ~(nb > splat(0.0)) | (turn < splat(min_cos) * nb * na);
    for (size_t lane = 0; lane < 2; ++lane) {
      const size_t t = i + lane;  // disappears when it has u as a corner
      if (unsound[lane] && t < triangles && t != flanks.at && t != before) return false;
    }
  }
  return true;
}

// Link condition: v and u = ring[at_u] share exactly the neighbours flanking the edge (v, u)
// (two inside, one on a boundary edge, where the fan does not wrap around).
bool linkConditionHolds(const LevelMesh& mesh, const VertexRing& ring, const Flanks& flanks) {
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

void FanGeometry::reserve(size_t k) {
  if (k + 3 <= stride_) return;
  stride_ = std::max(k + 3, 2 * stride_);
  arrays_.resize(12 * stride_);
  order_.resize(stride_);
}

void VertexCollapses::computeFan(const std::vector<double>& xyz, FanGeometry& fan) const {
  const size_t k = ring.size(), triangles = closed_ ? k : k - 1;
  const double* pv = point(xyz, vertex_);
  fan.vertex = vertex_;
  fan.triangles = triangles;
  fan.reserve(k);
  double* const position[3] = {fan.position(0), fan.position(1), fan.position(2)};
  double* const spoke[3] = {fan.spoke(0), fan.spoke(1), fan.spoke(2)};
  double* const normal[3] = {fan.normal(0), fan.normal(1), fan.normal(2)};
  double* const twice_area = fan.twiceArea();
  for (size_t i = 0; i < k; ++i) {
    const double* p = point(xyz, ring[i]);
    for (int a = 0; a < 3; ++a) {
      position[a][i] = p[a];
      spoke[a][i] = p[a] - pv[a];
    }
  }
  for (int a = 0; a < 3; ++a) {  // ring[0] again at k
    position[a][k] = position[a][0];
    spoke[a][k] = spoke[a][0];
  }
  for (size_t i = 0; i < triangles; i += 2) {
    const Pair ax = loadPair(spoke[0] + i), ay = loadPair(spoke[1] + i), az = loadPair(spoke[2] + i);
    const Pair bx = loadPair(spoke[0] + i + 1), by = loadPair(spoke[1] + i + 1), bz = loadPair(spoke[2] + i + 1);
    const Pair nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
    storePair(normal[0] + i, nx);
    storePair(normal[1] + i, ny);
    storePair(normal[2] + i, nz);
    storePair(twice_area + i, sqrtPair((nx * nx + ny * ny) + nz * nz));
  }
}

void VertexCollapses::prepare(const std::vector<double>& xyz, uint32_t v, bool closed, FanGeometry& scratch) {
  vertex_ = v;
  closed_ = closed;
  has_nan_cost_ = false;
  if (scratch.vertex == v) scratch.vertex = kNoVertex;  // v's ring has changed
  // An ear (one triangle) stays: its ring is a single edge, which spans no local frame, and
  // removing it turns an inner edge into boundary.
  if (!closed && ring.size() < 3) return options_.clear();
  computeFan(xyz, scratch);
  const double curve = closed ? 0.0 : boundaryCost(xyz, v, ring.front(), ring.back());
  computeCosts(scratch, curve);
  addOptionsByCost(scratch);
}

// Memoryless quadric of each option's target u: squared distances of u to the planes of v's
// current triangles, area weighted, plus a small length term so that flat regions still
// prefer short edges, plus `curve`; and the length of the edge (v, u). Into the scratch's
// cost and length arrays, by option number; several targets at a time, one per lane: lane by
// lane the same IEEE operations as one target at a time.
void VertexCollapses::computeCosts(FanGeometry& fan, double curve) const {
#if ANIMC_AVX2_PATH
  if (useAvx2(fan.path)) return computeCostsAvx2(fan, curve);
#endif
  Pair* const planes = firstOf(fan.planes, 5 * fan.triangles);
  Pair* planes_end = planes;
  const double *nx = fan.normal(0), *ny = fan.normal(1), *nz = fan.normal(2);
  double area = 0;
  for (size_t i = 0; i < fan.triangles; ++i) {
    const double twice_area = fan.twiceArea()[i];
    if (twice_area <= 0) continue;  // no plane
    planes_end[0] = splat(nx[i]);
    planes_end[1] = splat(ny[i]);
    planes_end[2] = splat(nz[i]);
    planes_end[3] = splat(twice_area);
    planes_end[4] = splat(0.5 * twice_area);
    planes_end += 5;
    area += 0.5 * twice_area;
  }
  const Pair length_weight = splat(1e-3 * area);
  const double *sx = fan.spoke(0), *sy = fan.spoke(1), *sz = fan.spoke(2);
  for (size_t i = 0; i < optionCount(); i += 2) {  // lane 1 beyond the last option: not used
    const uint32_t p0 = ringPosition(i), p1 = ringPosition(i + 1);
    const Pair dx = {sx[p0], sx[p1]}, dy = {sy[p0], sy[p1]}, dz = {sz[p0], sz[p1]};
    Pair quadric = splat(0.0);
    for (const Pair* plane = planes; plane != planes_end; plane += 5) {
      const Pair distance = ((plane[0] * dx + plane[1] * dy) + plane[2] * dz) / plane[3];
      quadric += plane[4] * distance * distance;
    }
    const Pair squared_length = (dx * dx + dy * dy) + dz * dz;
    storePair(fan.cost() + i, (quadric + length_weight * squared_length) + splat(curve));
    storePair(fan.length() + i, sqrtPair(squared_length));
  }
}

#if ANIMC_AVX2_PATH
// Four targets at a time, one per lane of a Quad, each plane's values broadcast from the fan's
// arrays (no splatted copies). A closed ring's targets are ring positions i..i+3 in order, so
// their spokes load as Quads (lanes past the ring read its padding, and their results land in
// the arrays' spare room); an open fan's two ends are gathered.
ANIMC_TARGET_AVX2 void VertexCollapses::computeCostsAvx2(FanGeometry& fan, double curve) const {
  const double *nx = fan.normal(0), *ny = fan.normal(1), *nz = fan.normal(2), *twice_area = fan.twiceArea();
  double area = 0;
  for (size_t t = 0; t < fan.triangles; ++t)
    if (!(twice_area[t] <= 0)) area += 0.5 * twice_area[t];
  const Quad length_weight = splatQuad(1e-3 * area);
  const double *sx = fan.spoke(0), *sy = fan.spoke(1), *sz = fan.spoke(2);
  const size_t last = ring.size() - 1;
  for (size_t i = 0; i < optionCount(); i += 4) {
    const Quad dx = closed_ ? loadQuad(sx + i) : Quad{sx[0], sx[last], sx[last], sx[last]};
    const Quad dy = closed_ ? loadQuad(sy + i) : Quad{sy[0], sy[last], sy[last], sy[last]};
    const Quad dz = closed_ ? loadQuad(sz + i) : Quad{sz[0], sz[last], sz[last], sz[last]};
    Quad quadric = splatQuad(0.0);
    for (size_t t = 0; t < fan.triangles; ++t) {
      if (twice_area[t] <= 0) continue;  // no plane
      const Quad distance =
          ((splatQuad(nx[t]) * dx + splatQuad(ny[t]) * dy) + splatQuad(nz[t]) * dz) / splatQuad(twice_area[t]);
      quadric += splatQuad(0.5 * twice_area[t]) * distance * distance;
    }
    const Quad squared_length = (dx * dx + dy * dy) + dz * dz;
    storeQuad(fan.cost() + i, (quadric + length_weight * squared_length) + splatQuad(curve));
    storeQuad(fan.length() + i, __builtin_ia32_sqrtpd256(squared_length));
  }
}
#endif

// The options in (cost, ring position) order: an insertion sort of the option numbers (ring
// positions grow with them), the same comparisons as sorting the options themselves, so the
// same order even where a NaN cost leaves the order partial; then each option built once.
void VertexCollapses::addOptionsByCost(FanGeometry& fan) {
  const double* cost = fan.cost();
  uint32_t* order = fan.order();
  auto before = [cost](uint32_t a, uint32_t b) { return cost[a] < cost[b] || (cost[a] == cost[b] && a < b); };
  const size_t count = optionCount();
  bool nan = false;
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t j = i;
    for (; j > 0 && before(i, order[j - 1]); --j) order[j] = order[j - 1];
    order[j] = i;
    nan |= std::isnan(cost[i]);
  }
  has_nan_cost_ = nan;
  options_.resize(count);  // constructs only the options beyond the previous count
  Option* const out = options_.data();
  const double* length = fan.length();
  for (size_t k = 0; k < count; ++k) {
    const uint32_t i = order[k], position = ringPosition(i);
    out[k] = {{ring[position], position, cost[i], length[i]}, Validity::kUnknown, 0};
  }
}

// The fan size first (the checks would walk a big fan), then the link condition, which needs
// no normals, then the triangles.
bool VertexCollapses::keepsMeshSound(const CollapseOption& option, const CollapseChecks& checks) const {
  const LevelMesh& mesh = checks.mesh;
  if (mesh.triangleCount(option.target) + mesh.triangleCount(vertex_) > kMaxCollapseTriangles + 2) return false;
  const Flanks flanks(ring.size(), closed_, option.ring_position);
  if (!linkConditionHolds(mesh, ring, flanks)) return false;
  if (checks.fan.vertex != vertex_) computeFan(checks.xyz, checks.fan);
  return keepsTrianglesSound(mesh, ring, checks.fan, flanks, checks.min_normal_cosine);
}

bool VertexCollapses::valid(size_t i, const CollapseChecks& checks) {
  Option& o = options_[i];
  if (o.validity == Validity::kUnknown || checks.changed_by[o.choice.target] > o.checked_after) {
    o.validity = keepsMeshSound(o.choice, checks) ? Validity::kValid : Validity::kInvalid;
    o.checked_after = checks.batches;
  }
  return o.validity == Validity::kValid;
}

size_t VertexCollapses::nextWithin(double max_length, size_t from) const {
  for (size_t i = from; i < options_.size(); ++i)
    if (options_[i].choice.length <= max_length) return i;
  return kNone;
}

size_t VertexCollapses::nextValidWithin(const CollapseChecks& checks, double max_length, size_t from) {
  for (size_t i = nextWithin(max_length, from); i != kNone; i = nextWithin(max_length, i + 1))
    if (valid(i, checks)) return i;
  return kNone;
}

bool VertexCollapses::anyValid(const CollapseChecks& checks) {
  for (size_t i = 0; i < options_.size(); ++i)
    if (valid(i, checks)) return true;
  return false;
}

}  // namespace animc
