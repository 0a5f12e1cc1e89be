// SPDX-License-Identifier: Apache-2.0
// One level of the hierarchy build (progressive_mesh.cpp): the batch of collapses chosen as a
// greedy independent set, applied to the LevelMesh and recorded in the ProgressiveMesh.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "codecs/wavelet/boundary_loops.h"
#include "codecs/wavelet/collapse_option_cache.h"
#include "codecs/wavelet/progressive_mesh.h"

namespace animc {

struct Candidate {
  double cost;
  uint32_t vertex;
  uint32_t target;
  CollapseKind kind;
};

// The record of collapse c, whose vertex's ring is `ring`, on `level`: appends its ring and
// flaps to pm.
Collapse recordCollapse(const LevelMesh& mesh, const CollapseOptionCache& cache, const Candidate& c,
                        const VertexRing& ring, int level, ProgressiveMesh& pm);

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
    cache_.prepareStale(mesh_, xyz_, vertices_.live, settings_);
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

}  // namespace animc
