// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/level_mesh.h"

#include <algorithm>

namespace animc {

LevelMesh::LevelMesh(const Topology& topology)
    : vertex_count_(topology.vertex_count), triangles_(topology.triangles), alive_(topology.triangles.size(), 1),
      neighbours_(topology.vertex_count) {
  rebuildIncidence();
}

void VertexMarks::restart() {
  std::fill(token_.begin(), token_.end(), 0);
  current_ = 1;
}

void LevelMesh::rebuildIncidence() {
  dropDeadTrianglesAndCount();
  first_.resize(vertex_count_);
  uint32_t start = 0;
  for (uint32_t v = 0; v < vertex_count_; ++v) {
    first_[v] = start;
    start += count_[v];
  }
  incident_.resize(start);
  std::vector<uint32_t> fill(first_);
  for (size_t t = 0; t < triangles_.size(); ++t)
    for (uint32_t v : triangles_[t]) incident_[fill[v]++] = uint32_t(t);
  rebuilt_size_ = incident_.size();
}

// Dead triangles never come back: dropping them (in order, so every vertex still lists its
// triangles in the same order) keeps each rebuild proportional to what is left. The same
// pass counts each vertex's triangles.
void LevelMesh::dropDeadTrianglesAndCount() {
  count_.assign(vertex_count_, 0);
  size_t kept = 0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    if (!alive_[t]) continue;
    const Triangle tri = triangles_[t];
    triangles_[kept++] = tri;
    for (uint32_t v : tri) ++count_[v];
  }
  triangles_.resize(kept);
  alive_.assign(kept, 1);
}

void LevelMesh::reclaimSpace() {
  if (incident_.size() > 2 * rebuilt_size_) rebuildIncidence();
}

// Each query takes two tokens (leaving, passed); when they run out, all marks restart.
void FanQuery::nextStepToken() {
  if (step_token_ >= UINT32_MAX - 2) {
    std::fill(step_from_.begin(), step_from_.end(), StepMark());
    step_token_ = 0;
  }
  step_token_ += 2;
}

bool LevelMesh::fanSteps(uint32_t v, FanQuery& query) const {
  query.nextStepToken();
  const size_t triangles = triangleCount(v);
  if (query.steps_.size() < triangles) query.steps_.resize(triangles);
  // Locals, not members, in the loop: its stores could alias them for the compiler.
  const uint32_t token = query.step_token_;
  std::pair<uint32_t, uint32_t>* const steps = query.steps_.data();
  FanQuery::StepMark* const from_vertex = query.step_from_.data();
  size_t count = 0;
  for (const uint32_t *t = trianglesBegin(v), *end = trianglesEnd(v); t != end; ++t) {
    const Triangle& tri = triangles_[*t];
    uint32_t a, b;  // the corners after v, in the triangle's orientation
    if (tri[0] == v) {
      a = tri[1], b = tri[2];
    } else if (tri[1] == v) {
      a = tri[2], b = tri[0];
    } else {
      a = tri[0], b = tri[1];
    }
    if (a == v || b == v || a == b) return false;
    steps[count++] = {a, b};
    FanQuery::StepMark& from = from_vertex[a];
    from.to = from.token == token ? kNoVertex : b;
    from.token = token;
  }
  query.step_count_ = count;
  return true;
}

// Follows the steps from `start` through all of them and returns the vertex reached last;
// kNoVertex when some vertex has two ways out (non-manifold or inconsistent orientation) or
// none before the steps are used up, or is passed twice. ring (resized to `size`) receives
// the vertices passed, start first.
uint32_t LevelMesh::walkSteps(FanQuery& query, uint32_t start, VertexRing& ring, size_t size) const {
  const size_t count = query.step_count_;
  ring.resize(size);  // as a vertex's rings keep their size, usually no change
  const uint32_t token = query.step_token_, passed = token + 1;
  FanQuery::StepMark* const from_vertex = query.step_from_.data();
  uint32_t* const out = ring.data();
  uint32_t current = start;
  for (size_t i = 0; i < count; ++i) {
    FanQuery::StepMark& from = from_vertex[current];
    if (from.token != token || from.to == kNoVertex) return kNoVertex;  // a boundary, a flipped
    from.token = passed;                                                // or non-manifold neighbour
    out[i] = current;
    current = from.to;
  }
  return current;
}

bool LevelMesh::orderedRing(uint32_t v, VertexRing& ring, FanQuery& query) const {
  // A closed fan is one cycle through all the steps, back to where it started.
  if (!fanSteps(v, query) || query.step_count_ < 3) return false;
  const uint32_t start = query.steps_[0].first;
  return walkSteps(query, start, ring, query.step_count_) == start;
}

bool LevelMesh::openFan(uint32_t v, VertexRing& ring, FanQuery& query) const {
  // An open fan is one chain through all the steps, from the one spoke no step enters.
  if (!fanSteps(v, query) || query.step_count_ == 0) return false;
  const size_t count = query.step_count_;
  const auto& steps = query.steps_;
  query.entered_.clearAll();
  for (size_t i = 0; i < count; ++i) query.entered_.mark(steps[i].second);
  uint32_t start = kNoVertex;
  for (size_t i = 0; i < count; ++i) {
    if (query.entered_.marked(steps[i].first)) continue;
    if (start != kNoVertex) return false;  // several fans meet at v
    start = steps[i].first;
  }
  if (start == kNoVertex) return false;
  const uint32_t end = walkSteps(query, start, ring, count + 1);
  if (end == kNoVertex || query.step_from_[end].token == query.step_token_ + 1) return false;  // the end was passed
  ring.back() = end;
  return true;
}

uint32_t LevelMesh::flapAcross(uint32_t a, uint32_t b, uint32_t v) const {
  uint32_t found = kNoVertex;
  for (const uint32_t *t = trianglesBegin(a), *end = trianglesEnd(a); t != end; ++t) {
    const Triangle& tri = triangles_[*t];
    if (tri[0] != b && tri[1] != b && tri[2] != b) continue;               // not on the edge
    if (v != b && (tri[0] == v || tri[1] == v || tri[2] == v)) continue;  // v's side
    uint32_t other = kNoVertex;  // the last corner that is neither a nor b
    for (uint32_t w : tri)
      if (w != a && w != b) other = w;
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
  for (const uint32_t *t = trianglesBegin(u), *end = trianglesEnd(u); t != end; ++t) neighbours_.mark(triangles_[*t]);
}

template <class Dies>
void LevelMesh::replaceVertex(uint32_t v, uint32_t u, Dies dies) {
  for (const uint32_t *t = trianglesBegin(v), *end = trianglesEnd(v); t != end; ++t) {
    Triangle& tri = triangles_[*t];
    if (tri[0] == u || tri[1] == u || tri[2] == u) {
      alive_[*t] = 0;
      dies(*t);
      continue;
    }
    for (uint32_t& w : tri)
      if (w == v) w = u;
  }
}

void LevelMesh::collapse(uint32_t v, uint32_t u) {
  replaceVertex(v, u, [&](uint32_t t) {
    for (uint32_t w : triangles_[t])
      if (w != u && w != v) dropFromList(w, t);  // u's list is merged below
  });
  mergeLists(u, v);
  count_[v] = 0;
}

void LevelMesh::weld(uint32_t v, uint32_t u) {
  replaceVertex(v, u, [](uint32_t) {});
}

// Removes triangle t (listed once) from v's list, keeping the order.
void LevelMesh::dropFromList(uint32_t v, uint32_t t) {
  uint32_t* list = incident_.data() + first_[v];
  const uint32_t n = count_[v];
  uint32_t i = 0;
  while (i < n && list[i] != t) ++i;
  if (i == n) return;
  for (; i + 1 < n; ++i) list[i] = list[i + 1];
  --count_[v];
}

// u's new list after the collapse of v onto it: the live triangles of both lists, in order,
// at the end of incident_.
void LevelMesh::mergeLists(uint32_t u, uint32_t v) {
  const size_t at = incident_.size();
  incident_.resize(at + count_[u] + count_[v]);  // before taking pointers: it may move
  const uint32_t *a = trianglesBegin(u), *a_end = trianglesEnd(u);
  const uint32_t *b = trianglesBegin(v), *b_end = trianglesEnd(v);
  uint32_t* out = incident_.data() + at;
  for (;;) {
    while (a != a_end && !alive_[*a]) ++a;
    while (b != b_end && !alive_[*b]) ++b;
    if (a == a_end && b == b_end) break;
    *out++ = b == b_end || (a != a_end && *a <= *b) ? *a++ : *b++;
  }
  first_[u] = uint32_t(at);
  count_[u] = uint32_t(out - (incident_.data() + at));
  incident_.resize(at + count_[u]);
}

std::vector<Triangle> LevelMesh::liveTriangles() const {
  std::vector<Triangle> out;
  for (size_t t = 0; t < triangles_.size(); ++t)
    if (alive_[t]) out.push_back(triangles_[t]);
  return out;
}

}  // namespace animc
