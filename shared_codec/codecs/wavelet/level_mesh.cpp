#include "codecs/wavelet/level_mesh.h"

#include <algorithm>

namespace animc {

LevelMesh::LevelMesh(const Topology& topology)
    : vertex_count_(topology.vertex_count), triangles_(topology.triangles),
      alive_(topology.triangles.size(), 1), step_to_(topology.vertex_count, kNoVertex),
      leaves_(topology.vertex_count), entered_(topology.vertex_count), seen_(topology.vertex_count),
      neighbours_(topology.vertex_count) {
  rebuildIncidence();
}

void VertexMarks::clearAll() {
  if (++current_ == 0) {  // wrapped: old tokens could match again
    std::fill(token_.begin(), token_.end(), 0);
    current_ = 1;
  }
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

bool LevelMesh::fanSteps(uint32_t v) const {
  steps_.clear();
  leaves_.clearAll();
  for (const uint32_t* t = trianglesBegin(v); t != trianglesEnd(v); ++t) {
    const Triangle& tri = triangles_[*t];
    const int at = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    const uint32_t a = tri[(at + 1) % 3], b = tri[(at + 2) % 3];
    if (a == v || b == v || a == b) return false;
    steps_.emplace_back(a, b);
    step_to_[a] = leaves_.marked(a) ? kNoVertex : b;
    leaves_.mark(a);
  }
  return true;
}

// Follows the steps from `start` through all of them; false when some vertex has two ways
// out (non-manifold or inconsistent orientation) or none before the steps are used up.
// ring receives the vertices visited, start first, then the vertex reached last.
bool LevelMesh::walkSteps(uint32_t start, std::vector<uint32_t>& ring) const {
  const size_t count = steps_.size();
  ring.resize(count + 1);
  uint32_t current = start;
  for (size_t i = 0; i < count; ++i) {
    if (!leaves_.marked(current)) return false;  // a boundary or a flipped neighbour
    if (step_to_[current] == kNoVertex) return false;  // two triangles leave the same spoke
    ring[i] = current;
    current = step_to_[current];
  }
  ring[count] = current;
  return true;
}

bool LevelMesh::allDistinct(const std::vector<uint32_t>& vertices) const {
  seen_.clearAll();
  for (uint32_t w : vertices) {
    if (seen_.marked(w)) return false;
    seen_.mark(w);
  }
  return true;
}

bool LevelMesh::orderedRing(uint32_t v, std::vector<uint32_t>& ring) const {
  // A closed fan is one cycle through all the steps.
  if (!fanSteps(v) || steps_.size() < 3) return false;
  if (!walkSteps(steps_[0].first, ring) || ring.back() != ring.front()) return false;
  ring.pop_back();
  return allDistinct(ring);
}

bool LevelMesh::openFan(uint32_t v, std::vector<uint32_t>& ring) const {
  // An open fan is one chain through all the steps, from the one spoke no step enters.
  if (!fanSteps(v) || steps_.empty()) return false;
  entered_.clearAll();
  for (const auto& s : steps_) entered_.mark(s.second);
  uint32_t start = kNoVertex;
  for (const auto& s : steps_) {
    if (entered_.marked(s.first)) continue;
    if (start != kNoVertex) return false;  // several fans meet at v
    start = s.first;
  }
  if (start == kNoVertex || !walkSteps(start, ring)) return false;
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
  neighbours_.clearAll();
  for (const uint32_t* t = trianglesBegin(u); t != trianglesEnd(u); ++t)
    for (uint32_t w : triangles_[*t]) neighbours_.mark(w);
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
