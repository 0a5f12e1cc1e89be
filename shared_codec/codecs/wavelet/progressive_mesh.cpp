// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/progressive_mesh.h"

#include <algorithm>
#include <cmath>
#include <memory_resource>
#include <numeric>
#include <string>
#include <tuple>

#include "codecs/wavelet/collapse_choice.h"

namespace animc {
namespace {

struct Candidate {
  double cost;
  uint32_t vertex;
  uint32_t target;
  CollapseKind kind;
};

double meanEdgeLength(const Topology& topology, const std::vector<double>& xyz) {
  double sum = 0;
  size_t count = 0;
  for (const Triangle& t : topology.triangles)
    for (int i = 0; i < 3; ++i) {
      const size_t a = 3 * size_t(t[i]), b = 3 * size_t(t[(i + 1) % 3]);
      sum += std::sqrt((xyz[a] - xyz[b]) * (xyz[a] - xyz[b]) + (xyz[a + 1] - xyz[b + 1]) * (xyz[a + 1] - xyz[b + 1]) +
                       (xyz[a + 2] - xyz[b + 2]) * (xyz[a + 2] - xyz[b + 2]));
      ++count;
    }
  return count ? sum / double(count) : 0.0;
}

// f(b) for each boundary edge (v, b), one held by exactly one live triangle: b is once among
// the corners of v's triangles (b > v only, when higher_only). times is all zeros, and left so.
template <class F>
void forEachBoundaryEdge(const LevelMesh& mesh, uint32_t v, bool higher_only, std::vector<uint32_t>& times,
                         std::vector<uint32_t>& corners, F f) {
  corners.clear();  // each once, in order of first appearance
  for (const uint32_t *t = mesh.trianglesBegin(v), *end = mesh.trianglesEnd(v); t != end; ++t)
    for (uint32_t b : mesh.triangle(*t))
      if ((higher_only ? b > v : b != v) && times[b]++ == 0) corners.push_back(b);
  for (uint32_t b : corners) {
    if (times[b] == 1) f(b);
    times[b] = 0;
  }
}

// The boundary loops (edges with one live triangle, joined at shared vertices) and how many
// vertices each still has, so that every loop keeps >= 3. Collapses that pass the link
// condition keep the topology, so loops neither split nor merge: built once, after the
// seams are welded, then only counted down.
struct BoundaryLoops {
  std::vector<uint32_t> loop_of;    // per vertex: a representative vertex of its loop
  std::vector<uint32_t> remaining;  // per representative: vertices on the loop

  BoundaryLoops(const LevelMesh& mesh, uint32_t vertex_count)
      : loop_of(vertex_count), remaining(vertex_count, 0) {
    std::iota(loop_of.begin(), loop_of.end(), 0u);
    const auto edges = boundaryEdges(mesh, vertex_count);
    for (const auto& [a, b] : edges) loop_of[find(a)] = find(b);
    for (uint32_t v = 0; v < vertex_count; ++v) loop_of[v] = find(v);
    std::vector<uint8_t> on_boundary(vertex_count, 0);
    for (const auto& [a, b] : edges) on_boundary[a] = on_boundary[b] = 1;
    for (uint32_t v = 0; v < vertex_count; ++v) remaining[loop_of[v]] += on_boundary[v];
  }

  bool canLose(uint32_t v) const { return remaining[loop_of[v]] > 3; }
  // One vertex less on v's loop, if the loop keeps at least 3.
  bool take(uint32_t v) {
    if (!canLose(v)) return false;
    --remaining[loop_of[v]];
    return true;
  }

 private:
  uint32_t find(uint32_t v) {
    while (loop_of[v] != v) v = loop_of[v] = loop_of[loop_of[v]];
    return v;
  }

  // The boundary edges (a, b), a < b. (Their order does not matter: the loops are the
  // connected components, whatever the order of the unions.)
  static std::vector<std::pair<uint32_t, uint32_t>> boundaryEdges(const LevelMesh& mesh, uint32_t vertex_count) {
    std::vector<std::pair<uint32_t, uint32_t>> out;
    std::vector<uint32_t> times(vertex_count, 0), corners;
    for (uint32_t a = 0; a < vertex_count; ++a)
      forEachBoundaryEdge(mesh, a, true, times, corners, [&](uint32_t b) { out.emplace_back(a, b); });
    return out;
  }
};

// Each vertex's collapse options on the current level. Its ring, costs and lengths depend on
// its own triangles, an option's validity also on the target's (link condition, duplicate
// triangles, fan size). A batch changes the triangles of its vertices and their rings only:
// those vertices are prepared again, and their neighbours' options onto them see from the
// batch count (changed_by) that their validity must be found again (a third of the vertices
// a batch reaches are such neighbours).
class CollapseOptionCache {
 public:
  struct Entry {
    explicit Entry(std::pmr::memory_resource* arena) : collapses(arena) {}
    bool stale = true;
    bool ring_found = false;   // by LevelMesh::orderedRing or openFan
    bool closed_ring = false;  // by orderedRing
    bool ring_kept = false;    // stale, but the ring is still v's (see keepRing)
    CollapseKind kind = CollapseKind::kInterior;
    VertexCollapses collapses;  // its ring is v's closed ring, or open fan on a boundary
  };

  explicit CollapseOptionCache(uint32_t vertex_count) : changed_by_(vertex_count, 0) {
    entries_.reserve(vertex_count);
    for (uint32_t v = 0; v < vertex_count; ++v) entries_.emplace_back(&arena_);
  }

  Entry& at(const LevelMesh& mesh, const std::vector<double>& xyz, uint32_t v, const HierarchySettings& settings) {
    Entry& e = entries_[v];
    if (!e.stale) return e;
    e.stale = false;
    VertexCollapses& c = e.collapses;
    if (e.ring_kept) {  // same fan shape, new geometry
      e.ring_kept = false;
      c.prepare(xyz, v, e.closed_ring, fan_);
      return e;
    }
    e.ring_found = e.closed_ring = false;
    e.kind = CollapseKind::kInterior;
    if (mesh.triangleCount(v) > kMaxCollapseTriangles) {
      c.clear();  // not removable; its ring is not even walked
    } else if (mesh.orderedRing(v, c.ring)) {
      e.ring_found = e.closed_ring = true;
      c.prepare(xyz, v, true, fan_);
    } else if (settings.collapse_boundaries && mesh.openFan(v, c.ring)) {
      e.ring_found = true;
      e.kind = CollapseKind::kBoundary;
      c.prepare(xyz, v, false, fan_);
    } else {
      c.clear();
    }
    return e;
  }

  // Before the batch is applied: v collapses onto u, and w is in v's ring without flanking the
  // edge (v, u). Then w's triangles that hold v become u's and none dies, and u is no neighbour
  // of w (the link condition), so w's steps stay the same with v replaced by u, from the same
  // first triangle: its new ring is its ring with v replaced by u, and needs no walk.
  void keepRing(uint32_t w, uint32_t v, uint32_t u) {
    Entry& e = entries_[w];
    if (e.stale || !e.ring_found) return;
    VertexRing& ring = e.collapses.ring;
    const auto at = std::find(ring.begin(), ring.end(), v);
    if (at == ring.end()) return;
    *at = u;
    e.ring_kept = true;
  }

  // After the batch is applied: v has collapsed onto u, and w, whose ring was closed, flanks
  // the edge (v, u). w's triangle with v and u died and its other one with v became u's, so
  // its steps are the same without v: its new ring is its ring without v, started (as a walk
  // would) at the corner after w in the first triangle of its list. A ring of three would
  // become two: walked again, and found not to be a ring.
  void keepFlankRing(const LevelMesh& mesh, uint32_t w, uint32_t v) {
    Entry& e = entries_[w];
    if (e.stale || !e.closed_ring || e.collapses.ring.size() < 4) return;
    VertexRing& ring = e.collapses.ring;
    const auto at = std::find(ring.begin(), ring.end(), v);
    if (at == ring.end()) return;
    ring.erase(at);
    const Triangle& first = mesh.triangle(*mesh.trianglesBegin(w));
    const uint32_t start = first[0] == w ? first[1] : (first[1] == w ? first[2] : first[0]);
    const auto from = std::find(ring.begin(), ring.end(), start);
    if (from == ring.end()) return;  // cannot happen; then the ring is walked again
    std::rotate(ring.begin(), from, ring.end());
    e.ring_kept = true;
  }
  // A vertex's entry as last prepared, and its ring: unchanged until the level's collapses are
  // applied (they mark every vertex whose ring they change stale).
  Entry& entry(uint32_t v) { return entries_[v]; }
  const VertexRing& ring(uint32_t v) const { return entries_[v].collapses.ring; }

  // When a batch is applied: `changed` lists the vertices whose triangles it changes (the
  // removed ones and their rings).
  void markChanged(const std::vector<uint32_t>& changed) {
    ++batches_;
    for (uint32_t x : changed) {
      entries_[x].stale = true;
      changed_by_[x] = batches_;
    }
  }

  // LevelMesh::flapAcross(a, b, v) for an edge (a, b) of v's ring: when a's fresh entry holds
  // its closed ring, whose triangles (a, ring[m-1], ring[m]) and (a, ring[m], ring[m+1]) are
  // the two that hold b = ring[m], the flap is the one of ring[m-1], ring[m+1] that is not v,
  // found without walking a's triangles.
  uint32_t flapAcross(const LevelMesh& mesh, uint32_t a, uint32_t b, uint32_t v) const {
    const Entry& e = entries_[a];
    if (e.stale || !e.closed_ring) return mesh.flapAcross(a, b, v);
    const VertexRing& ring = e.collapses.ring;
    const size_t k = ring.size();
    for (size_t m = 0; m < k; ++m) {
      if (ring[m] != b) continue;
      const uint32_t previous = ring[m == 0 ? k - 1 : m - 1], next = ring[m + 1 == k ? 0 : m + 1];
      if (next == v) return previous;
      if (previous == v) return next;
      break;
    }
    return mesh.flapAcross(a, b, v);
  }

  CollapseChecks checks(const LevelMesh& mesh, const std::vector<double>& xyz, double min_normal_cosine) {
    return {mesh, xyz, min_normal_cosine, changed_by_, batches_, fan_};
  }

 private:
  // Every entry's ring and options: allocated as they grow, never freed one by one (a
  // vertex's arrays grow geometrically, and there are a few per vertex), all released with
  // the cache. Saves a malloc and a free per array.
  std::pmr::monotonic_buffer_resource arena_;
  std::vector<Entry> entries_;
  std::vector<uint32_t> changed_by_;  // CollapseChecks::changed_by
  uint32_t batches_ = 0;
  FanGeometry fan_;  // the fan of the vertex being prepared or checked, shared by every entry
};

Collapse recordCollapse(const LevelMesh& mesh, const CollapseOptionCache& cache, const Candidate& c,
                        const VertexRing& ring, int level, ProgressiveMesh& pm) {
  Collapse record;
  record.vertex = c.vertex;
  record.target = c.target;
  record.ring_begin = uint32_t(pm.ring.size());
  record.ring_size = uint16_t(ring.size());
  record.level = uint16_t(level);
  record.kind = c.kind;
  const size_t k = ring.size();
  for (size_t i = 0; i < k; ++i) {
    pm.ring.push_back(ring[i]);
    const bool wraps = c.kind != CollapseKind::kInterior && i + 1 == k;  // no edge from last to first
    pm.flap.push_back(wraps ? kNoVertex : cache.flapAcross(mesh, ring[i], ring[i + 1 == k ? 0 : i + 1], c.vertex));
  }
  return record;
}

// Whether v has a boundary edge. `times` is all zeros, and left so.
bool onBoundary(const LevelMesh& mesh, uint32_t v, std::vector<uint32_t>& times, std::vector<uint32_t>& corners) {
  bool any = false;
  forEachBoundaryEdge(mesh, v, false, times, corners, [&](uint32_t) { any = true; });
  return any;
}

// Seams: boundary vertices at exactly the same parametric position (texture seams, split
// normals) move together, so every copy but the lowest-numbered one is removed first,
// predicted by that one, and welded onto it, which also closes the seam for the levels
// above. Only non-adjacent boundary vertices are welded: coincident neighbours (a
// coarse parametric grid merging close vertices) are degenerate edges, not seams. Exact
// comparisons and index order keep it deterministic.
int weldSeams(LevelMesh& mesh, const std::vector<double>& xyz, const CollapseOptionCache& cache,
              std::vector<uint8_t>& removed, ProgressiveMesh& pm) {
  std::vector<uint32_t> order(removed.size());
  std::iota(order.begin(), order.end(), 0u);
  auto position = [&](uint32_t v) { return std::make_tuple(xyz[3 * size_t(v)], xyz[3 * size_t(v) + 1], xyz[3 * size_t(v) + 2]); };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return position(a) < position(b) || (position(a) == position(b) && a < b);
  });
  std::vector<uint32_t> times(removed.size(), 0), corners;
  int welded = 0;
  for (size_t first = 0, end = 0; first < order.size(); first = end) {
    const uint32_t original = order[first];
    for (end = first + 1; end < order.size() && position(order[end]) == position(original); ++end) {
      const uint32_t copy = order[end];
      if (!onBoundary(mesh, original, times, corners) || !onBoundary(mesh, copy, times, corners) ||
          mesh.adjacent(copy, original))
        continue;
      const Candidate seam{0.0, copy, original, CollapseKind::kSeam};
      pm.collapses.push_back(recordCollapse(mesh, cache, seam, {original}, 0, pm));
      removed[copy] = 1;
      ++welded;
    }
  }
  for (const Collapse& c : pm.collapses) mesh.weld(c.vertex, c.target);
  return welded;
}

// A vertex's proposal while a batch is chosen: its option `option` (in cost order), the
// cheapest within the length bound not known to be invalid.
struct Proposal {
  double cost;
  uint32_t vertex;
  uint32_t option;
};

// (cost, vertex): a total order when no cost is NaN, so both sides pick the same batch.
struct Before {
  bool operator()(const Proposal& a, const Proposal& b) const {
    return a.cost < b.cost || (a.cost == b.cost && a.vertex < b.vertex);
  }
};
struct After {
  bool operator()(const Proposal& a, const Proposal& b) const { return Before()(b, a); }
};

// One level's batch, a greedy independent set: the candidates (each vertex's cheapest valid
// collapse within the length bound) are taken in (cost, vertex) order and accepted when the
// closed one ring of their vertex shares no vertex with an accepted one. Closed rings of a
// batch are vertex-disjoint, so its collapses touch disjoint triangles and no removed vertex
// is in another's predictor stencil (stencils reach at most one step beyond the ring: flaps,
// and on a boundary the next boundary vertices, which a disjoint ring cannot remove).
class Batch {
 public:
  // Which vertices are gone, and the marks every batch uses.
  struct Vertices {
    explicit Vertices(const std::vector<uint8_t>& removed_first) : removed(removed_first), marked(removed.size(), 0) {
      for (uint32_t v = 0; v < removed.size(); ++v)
        if (!removed[v]) live.push_back(v);
    }
    std::vector<uint8_t> removed;
    std::vector<uint32_t> live;   // the others, ascending
    std::vector<uint8_t> marked;  // the closed rings of a batch's collapses; clear between batches
  };

  Batch(LevelMesh& mesh, const std::vector<double>& xyz, double max_length, const HierarchySettings& settings,
        BoundaryLoops& loops, Vertices& vertices, CollapseOptionCache& cache, ProgressiveMesh& pm)
      : mesh_(mesh), xyz_(xyz), max_length_(max_length), settings_(settings), loops_(loops), vertices_(vertices),
        removed_(vertices.removed), marked_(vertices.marked), cache_(cache), pm_(pm),
        checks_(cache.checks(mesh, xyz, settings.min_normal_cosine)) {}

  // Chooses and applies the batch; returns the number of collapses. any_valid tells whether,
  // should there be none, relaxing the bound could still find work.
  int apply(bool& any_valid) {
    bool nan_cost = false;
    std::vector<Proposal> proposals = propose(nan_cost);
    if (nan_cost)
      acceptExactOrder(proposals);
    else
      acceptLazily(proposals);
    any_valid = applied_ > 0 || anyValidOption();
    // Apply after choosing, so every record saw the level as it started.
    const size_t first = pm_.collapses.size() - size_t(applied_);
    for (size_t i = first; i < pm_.collapses.size(); ++i) keepRings(pm_.collapses[i], false);
    for (size_t i = first; i < pm_.collapses.size(); ++i)
      mesh_.collapse(pm_.collapses[i].vertex, pm_.collapses[i].target);
    for (size_t i = first; i < pm_.collapses.size(); ++i) keepRings(pm_.collapses[i], true);
    cache_.markChanged(changed_);
    for (uint32_t x : changed_) marked_[x] = 0;
    std::vector<uint32_t>& live = vertices_.live;
    live.erase(std::remove_if(live.begin(), live.end(), [&](uint32_t v) { return removed_[v] != 0; }), live.end());
    return applied_;
  }

 private:
  // Prepares every removable vertex and proposes its cheapest option within the bound.
  std::vector<Proposal> propose(bool& nan_cost) {
    std::vector<Proposal> out(vertices_.live.size());  // at most one per live vertex
    size_t count = 0;
    for (uint32_t v : vertices_.live) {
      const VertexCollapses* c = removable(v);
      const size_t first = c ? c->nextWithin(max_length_) : VertexCollapses::kNone;
      if (first == VertexCollapses::kNone) continue;
      out[count++] = {c->option(first).cost, v, uint32_t(first)};
      nan_cost = nan_cost || c->hasNanCost();
    }
    out.resize(count);
    return out;
  }

  // The options of v, which is live, when v may be removed on this level (prepared if its
  // triangles changed).
  VertexCollapses* removable(uint32_t v) {
    CollapseOptionCache::Entry& e = cache_.at(mesh_, xyz_, v, settings_);
    if (e.kind == CollapseKind::kBoundary && !loops_.canLose(v)) return nullptr;
    return &e.collapses;
  }

  // Proposals in (cost, vertex) order, a proposal's cost being a lower bound of its vertex's
  // candidate cost until its validity is known: the least proposal is the next candidate once
  // found valid, else its vertex proposes its next option (into a heap merged with the sorted
  // first proposals). A vertex whose ring an accepted collapse has reached by then is out at
  // any cost, so its validity is not needed: most proposals never have theirs found. Same
  // batch as sorting the candidates, when the order is total.
  void acceptLazily(std::vector<Proposal>& proposals) {
    std::sort(proposals.begin(), proposals.end(), Before());
    std::vector<Proposal> retries;  // a heap, least first
    for (size_t i = 0; i < proposals.size() || !retries.empty();) {
      Proposal p;
      if (retries.empty() || (i < proposals.size() && Before()(proposals[i], retries.front()))) {
        p = proposals[i++];
      } else {
        std::pop_heap(retries.begin(), retries.end(), After());
        p = retries.back();
        retries.pop_back();
      }
      if (blocked(p.vertex)) continue;
      VertexCollapses& c = cache_.entry(p.vertex).collapses;
      if (c.valid(p.option, checks_)) {
        accept(p);
        continue;
      }
      const size_t next = c.nextWithin(max_length_, p.option + 1);
      if (next == VertexCollapses::kNone) continue;
      retries.push_back({c.option(next).cost, p.vertex, uint32_t(next)});
      std::push_heap(retries.begin(), retries.end(), After());
    }
  }

  // With a NaN cost the order is not total: the exact candidates are sorted, as they always
  // were, so that the batch is the same on both sides whatever the sort makes of NaN.
  void acceptExactOrder(std::vector<Proposal>& proposals) {
    std::vector<Proposal> candidates;
    for (const Proposal& p : proposals) {
      VertexCollapses& c = cache_.entry(p.vertex).collapses;
      const size_t best = c.nextValidWithin(checks_, max_length_, p.option);
      if (best != VertexCollapses::kNone) candidates.push_back({c.option(best).cost, p.vertex, uint32_t(best)});
    }
    std::sort(candidates.begin(), candidates.end(), Before());
    for (const Proposal& p : candidates)
      if (!blocked(p.vertex)) accept(p);
  }

  bool blocked(uint32_t v) const {
    if (marked_[v]) return true;
    for (uint32_t w : cache_.ring(v))
      if (marked_[w]) return true;
    return false;
  }

  void accept(const Proposal& p) {
    const CollapseOptionCache::Entry& e = cache_.entry(p.vertex);
    if (e.kind == CollapseKind::kBoundary && !loops_.take(p.vertex)) return;
    const VertexRing& ring = e.collapses.ring;
    marked_[p.vertex] = 1;
    for (uint32_t w : ring) marked_[w] = 1;
    changed_.push_back(p.vertex);
    changed_.insert(changed_.end(), ring.begin(), ring.end());
    const Candidate c{p.cost, p.vertex, e.collapses.option(p.option).target, e.kind};
    pm_.collapses.push_back(recordCollapse(mesh_, cache_, c, ring, pm_.level_count, pm_));
    removed_[p.vertex] = 1;
    ++applied_;
  }

  // CollapseOptionCache::keepRing for the ring vertices of c that do not flank its edge
  // (before the collapse is applied), or keepFlankRing for those that do (after).
  void keepRings(const Collapse& c, bool flanks) {
    const uint32_t* ring = &pm_.ring[c.ring_begin];
    const size_t k = c.ring_size;
    const size_t at = size_t(std::find(ring, ring + k, c.target) - ring);
    const bool closed = c.kind == CollapseKind::kInterior;
    for (size_t i = 0; i < k; ++i) {
      if (i == at) continue;
      const bool flank = i + 1 == at || at + 1 == i || (closed && (i + 1 == at + k || at + 1 == i + k));
      if (flank && flanks)
        cache_.keepFlankRing(mesh_, ring[i], c.vertex);
      else if (!flank && !flanks)
        cache_.keepRing(ring[i], c.vertex, c.target);
    }
  }

  // Whether some removable vertex has a valid option at any length (needed only when no
  // candidate was found within the bound).
  bool anyValidOption() {
    for (uint32_t v : vertices_.live) {
      VertexCollapses* c = removable(v);
      if (c && c->anyValid(checks_)) return true;
    }
    return false;
  }

  LevelMesh& mesh_;
  const std::vector<double>& xyz_;
  double max_length_;
  const HierarchySettings& settings_;
  BoundaryLoops& loops_;
  Vertices& vertices_;
  std::vector<uint8_t>& removed_;
  std::vector<uint8_t>& marked_;  // the closed rings of accepted collapses
  CollapseOptionCache& cache_;
  ProgressiveMesh& pm_;
  const CollapseChecks checks_;
  std::vector<uint32_t> changed_;  // the marked vertices
  int applied_ = 0;
};

}  // namespace

Status checkHierarchyCost(const Topology& topology) {
  if (topology.vertex_count == 0) return Status();  // nothing to build
  std::vector<uint32_t> triangles_at(topology.vertex_count, 0);
  for (const Triangle& t : topology.triangles)
    for (uint32_t v : t) ++triangles_at[v];
  uint64_t cost = 0;
  uint32_t busiest = 0;
  for (uint32_t v = 0; v < topology.vertex_count; ++v) {
    cost += uint64_t(triangles_at[v]) * triangles_at[v];
    if (triangles_at[v] > triangles_at[busiest]) busiest = v;
  }
  auto culprit = [&] {
    return "vertex " + std::to_string(busiest) + " is in " + std::to_string(triangles_at[busiest]) + " triangles";
  };
  if (triangles_at[busiest] > kMaxTrianglesAtVertex)
    return limitExceeded("the wavelet codec's hierarchy takes at most " + std::to_string(kMaxTrianglesAtVertex) +
                         " triangles at a vertex: " + culprit());
  const uint64_t limit = kMaxRingCostPerTriangle * topology.triangles.size() + kRingCostAllowance;
  if (cost > limit)
    return limitExceeded("the wavelet codec's hierarchy would take too long on this mesh: " + culprit() +
                         " (sum over vertices of their triangle count squared " + std::to_string(cost) +
                         ", limit " + std::to_string(limit) + " for " + std::to_string(topology.triangles.size()) +
                         " triangles)");
  return Status();
}

ProgressiveMesh buildProgressiveMesh(const Topology& topology, const std::vector<double>& parametric_xyz,
                                     const HierarchySettings& settings) {
  ProgressiveMesh pm;
  pm.vertex_count = topology.vertex_count;
  LevelMesh mesh(topology);
  std::vector<uint8_t> removed(topology.vertex_count, 0);
  double max_length = settings.first_length_factor * meanEdgeLength(topology, parametric_xyz);
  CollapseOptionCache cache(topology.vertex_count);
  if (settings.weld_seams && weldSeams(mesh, parametric_xyz, cache, removed, pm) > 0) {
    pm.level_count = 1;
    mesh.rebuildIncidence();
  }
  BoundaryLoops loops(mesh, topology.vertex_count);  // the welded seams are no longer boundary
  Batch::Vertices vertices(removed);
  for (int level = 0; level < settings.max_levels; ++level, max_length *= settings.length_growth) {
    bool any_valid = false;
    const int applied = Batch(mesh, parametric_xyz, max_length, settings, loops, vertices, cache, pm).apply(any_valid);
    if (!any_valid) break;
    if (applied == 0) continue;
    ++pm.level_count;
    mesh.reclaimSpace();
  }
  pm.base = vertices.live;
  pm.base_triangles = mesh.liveTriangles();
  return pm;
}

}  // namespace animc
