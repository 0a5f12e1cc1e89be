#include "codecs/wavelet/progressive_mesh.h"

#include <algorithm>
#include <cmath>

#include "codecs/wavelet/collapse_choice.h"

namespace animc {
namespace {

struct Candidate {
  double cost;
  uint32_t vertex;
  uint32_t target;
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

// Every removable vertex's best collapse; any_valid tells whether relaxing the length bound
// could still find work.
std::vector<Candidate> levelCandidates(const LevelMesh& mesh, const std::vector<double>& xyz,
                                       const std::vector<uint8_t>& removed, double max_length,
                                       const HierarchySettings& settings, bool& any_valid) {
  std::vector<Candidate> out;
  std::vector<uint32_t> ring;
  any_valid = false;
  for (uint32_t v = 0; v < removed.size(); ++v) {
    if (removed[v] || !mesh.orderedRing(v, ring)) continue;
    const CollapseChoice c = chooseCollapse(mesh, xyz, v, ring, max_length, settings.min_normal_cosine);
    if (c.target == kNoVertex) continue;
    any_valid = true;
    if (c.fits_length) out.push_back({c.cost, v, c.target});
  }
  // Cost, then vertex index: a total order, so both sides pick the same batch.
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return a.cost < b.cost || (a.cost == b.cost && a.vertex < b.vertex);
  });
  return out;
}

// Greedy independent set: closed one rings of the batch are vertex-disjoint, so the batch's
// collapses touch disjoint triangles and no removed vertex is in another's predictor stencil.
int applyBatch(LevelMesh& mesh, const std::vector<Candidate>& candidates, int level,
               std::vector<uint8_t>& removed, ProgressiveMesh& pm) {
  std::vector<uint8_t> marked(removed.size(), 0);
  std::vector<uint32_t> ring;
  int applied = 0;
  for (const Candidate& c : candidates) {
    if (!mesh.orderedRing(c.vertex, ring)) continue;
    bool free = !marked[c.vertex];
    for (uint32_t w : ring) free = free && !marked[w];
    if (!free) continue;
    marked[c.vertex] = 1;
    for (uint32_t w : ring) marked[w] = 1;
    Collapse record;
    record.vertex = c.vertex;
    record.target = c.target;
    record.ring_begin = uint32_t(pm.ring.size());
    record.ring_size = uint16_t(ring.size());
    record.level = uint16_t(level);
    for (size_t k = 0; k < ring.size(); ++k) {
      pm.ring.push_back(ring[k]);
      pm.flap.push_back(mesh.flapAcross(ring[k], ring[(k + 1) % ring.size()], c.vertex));
    }
    pm.collapses.push_back(record);
    removed[c.vertex] = 1;
    ++applied;
  }
  // Apply after choosing, so every record above saw the level as it started.
  for (size_t i = pm.collapses.size() - size_t(applied); i < pm.collapses.size(); ++i)
    mesh.collapse(pm.collapses[i].vertex, pm.collapses[i].target);
  return applied;
}

}  // namespace

ProgressiveMesh buildProgressiveMesh(const Topology& topology, const std::vector<double>& parametric_xyz,
                                     const HierarchySettings& settings) {
  ProgressiveMesh pm;
  pm.vertex_count = topology.vertex_count;
  LevelMesh mesh(topology);
  std::vector<uint8_t> removed(topology.vertex_count, 0);
  double max_length = settings.first_length_factor * meanEdgeLength(topology, parametric_xyz);
  for (int level = 0; level < settings.max_levels; ++level, max_length *= settings.length_growth) {
    bool any_valid = false;
    const std::vector<Candidate> candidates =
        levelCandidates(mesh, parametric_xyz, removed, max_length, settings, any_valid);
    if (!any_valid) break;
    if (applyBatch(mesh, candidates, pm.level_count, removed, pm) == 0) continue;
    ++pm.level_count;
    mesh.rebuildIncidence();
  }
  for (uint32_t v = 0; v < topology.vertex_count; ++v)
    if (!removed[v]) pm.base.push_back(v);
  pm.base_triangles = mesh.liveTriangles();
  return pm;
}

}  // namespace animc
