#include "codecs/wavelet/level_mesh.h"

#include <algorithm>

namespace animc {

LevelMesh::LevelMesh(const Topology& topology)
    : vertex_count_(topology.vertex_count), triangles_(topology.triangles),
      alive_(topology.triangles.size(), 1), mark_(topology.vertex_count, 0) {
  rebuildIncidence();
}

void LevelMesh::rebuildIncidence() {
  dropDeadTriangles();
  first_.assign(vertex_count_ + 1, 0);
  for (const Triangle& tri : triangles_)
    for (uint32_t v : tri) ++first_[v + 1];
  for (uint32_t v = 0; v < vertex_count_; ++v) first_[v + 1] += first_[v];
  incident_.resize(first_.back() + 1);  // +1 keeps &incident_[first_[v]] valid when empty
  fill_.assign(first_.begin(), first_.end() - 1);
  for (size_t t = 0; t < triangles_.size(); ++t)
    for (uint32_t v : triangles_[t]) incident_[fill_[v]++] = uint32_t(t);
}

// Dead triangles never come back: dropping them (in order, so every vertex still lists its
// triangles in the same order) keeps each level's rebuild proportional to what is left.
void LevelMesh::dropDeadTriangles() {
  size_t kept = 0;
  for (size_t t = 0; t < triangles_.size(); ++t)
    if (alive_[t]) triangles_[kept++] = triangles_[t];
  triangles_.resize(kept);
  alive_.assign(kept, 1);
}

namespace {

using Steps = std::vector<std::pair<uint32_t, uint32_t>>;

// Follows the steps from `start` through all of them; false when some vertex has two ways
// out (non-manifold or inconsistent orientation) or none before the steps are used up.
// ring receives the vertices visited, start first, then the vertex reached last.
bool walkSteps(const Steps& steps, uint32_t start, std::vector<uint32_t>& ring) {
  ring.clear();
  ring.reserve(steps.size() + 1);
  uint32_t current = start;
  for (size_t i = 0; i < steps.size(); ++i) {
    uint32_t next = kNoVertex;
    for (const auto& s : steps) {
      if (s.first != current) continue;
      if (next != kNoVertex) return false;  // two triangles leave the same spoke
      next = s.second;
    }
    if (next == kNoVertex) return false;  // a boundary or a flipped neighbour
    ring.push_back(current);
    current = next;
  }
  ring.push_back(current);
  return true;
}

// Quadratic, without a copy: rings are short.
bool allDistinct(const std::vector<uint32_t>& vertices) {
  for (size_t i = 0; i < vertices.size(); ++i)
    for (size_t j = i + 1; j < vertices.size(); ++j)
      if (vertices[i] == vertices[j]) return false;
  return true;
}

}  // namespace

bool LevelMesh::fanSteps(uint32_t v, std::vector<std::pair<uint32_t, uint32_t>>& steps) const {
  steps.clear();
  for (const uint32_t* t = trianglesBegin(v); t != trianglesEnd(v); ++t) {
    const Triangle& tri = triangles_[*t];
    const int at = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    const uint32_t a = tri[(at + 1) % 3], b = tri[(at + 2) % 3];
    if (a == v || b == v || a == b) return false;
    steps.emplace_back(a, b);
  }
  return true;
}

bool LevelMesh::orderedRing(uint32_t v, std::vector<uint32_t>& ring) const {
  // A closed fan is one cycle through all the steps.
  Steps& steps = steps_;
  if (!fanSteps(v, steps) || steps.size() < 3) return false;
  if (!walkSteps(steps, steps[0].first, ring) || ring.back() != ring.front()) return false;
  ring.pop_back();
  return allDistinct(ring);
}

bool LevelMesh::openFan(uint32_t v, std::vector<uint32_t>& ring) const {
  // An open fan is one chain through all the steps, from the one spoke no step enters.
  Steps& steps = steps_;
  if (!fanSteps(v, steps) || steps.empty()) return false;
  uint32_t start = kNoVertex;
  for (const auto& s : steps) {
    bool entered = false;
    for (const auto& r : steps) entered = entered || r.second == s.first;
    if (entered) continue;
    if (start != kNoVertex) return false;  // several fans meet at v
    start = s.first;
  }
  if (start == kNoVertex || !walkSteps(steps, start, ring)) return false;
  return allDistinct(ring);
}

uint32_t LevelMesh::flapAcross(uint32_t a, uint32_t b, uint32_t v) const {
  uint32_t found = kNoVertex;
  for (const uint32_t* t = trianglesBegin(a); t != trianglesEnd(a); ++t) {
    const Triangle& tri = triangles_[*t];
    bool has_b = false, has_v = false;
    uint32_t other = kNoVertex;
    for (uint32_t w : tri) {
      if (w == b) has_b = true;
      else if (w == v) has_v = true;
      else if (w != a) other = w;
    }
    if (!has_b || has_v) continue;
    if (found != kNoVertex || other == kNoVertex) return kNoVertex;
    found = other;
  }
  return found;
}

bool LevelMesh::hasTriangle(uint32_t a, uint32_t b, uint32_t c) const {
  for (const uint32_t* t = trianglesBegin(a); t != trianglesEnd(a); ++t) {
    const Triangle& tri = triangles_[*t];
    const bool has_b = tri[0] == b || tri[1] == b || tri[2] == b;
    const bool has_c = tri[0] == c || tri[1] == c || tri[2] == c;
    if (has_b && has_c) return true;
  }
  return false;
}

bool LevelMesh::adjacent(uint32_t u, uint32_t w) const {
  for (const uint32_t* t = trianglesBegin(u); t != trianglesEnd(u); ++t) {
    const Triangle& tri = triangles_[*t];
    if (tri[0] == w || tri[1] == w || tri[2] == w) return true;
  }
  return false;
}

void LevelMesh::markNeighbours(uint32_t u) const {
  if (++mark_token_ == 0) {  // wrapped: old marks could match again
    std::fill(mark_.begin(), mark_.end(), 0);
    mark_token_ = 1;
  }
  for (const uint32_t* t = trianglesBegin(u); t != trianglesEnd(u); ++t)
    for (uint32_t w : triangles_[*t]) mark_[w] = mark_token_;
}

void LevelMesh::collapse(uint32_t v, uint32_t u) {
  for (const uint32_t* t = trianglesBegin(v); t != trianglesEnd(v); ++t) {
    Triangle& tri = triangles_[*t];
    if (tri[0] == u || tri[1] == u || tri[2] == u) {
      alive_[*t] = 0;
      continue;
    }
    for (uint32_t& w : tri)
      if (w == v) w = u;
  }
}

std::vector<Triangle> LevelMesh::liveTriangles() const {
  std::vector<Triangle> out;
  for (size_t t = 0; t < triangles_.size(); ++t)
    if (alive_[t]) out.push_back(triangles_[t]);
  return out;
}

}  // namespace animc
