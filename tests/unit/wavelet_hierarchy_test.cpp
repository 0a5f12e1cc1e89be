// SPDX-License-Identifier: Apache-2.0
// The progressive-mesh hierarchy and the anisotropic predictor of the wavelet codec.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "codecs/wavelet/anisotropic_predictor.h"
#include "codecs/wavelet/collapse_choice.h"
#include "codecs/wavelet/progressive_mesh.h"
#include "codecs/wavelet/wavelet_transform.h"
#include "core/parallel.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::gridFrame;
using testing_support::gridTopology;
using testing_support::realSequence;
using testing_support::toDouble;

// Every vertex is either in the base or removed exactly once, and whatever a removed vertex
// is predicted from (its ring, its flaps, its target) is still there one level coarser.
void expectValidHierarchy(const ProgressiveMesh& pm) {
  std::vector<int> removed_at(pm.vertex_count, -1);
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    ASSERT_LT(pm.collapses[i].vertex, pm.vertex_count);
    ASSERT_EQ(removed_at[pm.collapses[i].vertex], -1) << "vertex removed twice";
    removed_at[pm.collapses[i].vertex] = int(i);
  }
  for (uint32_t v : pm.base) EXPECT_EQ(removed_at[v], -1) << "base vertex " << v << " also removed";
  EXPECT_EQ(pm.base.size() + pm.collapses.size(), size_t(pm.vertex_count));
  EXPECT_TRUE(std::is_sorted(pm.base.begin(), pm.base.end()));
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    const Collapse& c = pm.collapses[i];
    if (i > 0) {
      EXPECT_GE(c.level, pm.collapses[i - 1].level);
    }
    auto later = [&](uint32_t w) { return removed_at[w] == -1 || removed_at[w] > int(i); };
    EXPECT_TRUE(later(c.target));
    const uint32_t* ring = &pm.ring[c.ring_begin];
    if (c.kind == CollapseKind::kBoundary) {
      EXPECT_GE(c.ring_size, 3) << "an ear was removed";
      EXPECT_TRUE(c.target == ring[0] || c.target == ring[c.ring_size - 1]) << "not along the boundary";
      EXPECT_EQ(pm.flap[c.ring_begin + c.ring_size - 1], kNoVertex);
    } else if (c.kind == CollapseKind::kSeam) {
      EXPECT_EQ(c.ring_size, 1);
      EXPECT_EQ(ring[0], c.target);
      EXPECT_EQ(c.level, 0);
    }
    for (uint32_t k = 0; k < c.ring_size; ++k) {
      EXPECT_TRUE(later(pm.ring[c.ring_begin + k]));
      const uint32_t f = pm.flap[c.ring_begin + k];
      if (f != kNoVertex) {
        EXPECT_TRUE(later(f));
      }
    }
  }
}

bool sameHierarchy(const ProgressiveMesh& a, const ProgressiveMesh& b) {
  if (a.base != b.base || a.ring != b.ring || a.flap != b.flap || a.collapses.size() != b.collapses.size())
    return false;
  for (size_t i = 0; i < a.collapses.size(); ++i) {
    const Collapse &x = a.collapses[i], &y = b.collapses[i];
    if (x.vertex != y.vertex || x.target != y.target || x.level != y.level || x.kind != y.kind) return false;
  }
  return a.base_triangles == b.base_triangles;
}

// Edges of a triangle list with how many triangles hold each.
std::map<std::pair<uint32_t, uint32_t>, int> edgeUse(const std::vector<Triangle>& triangles) {
  std::map<std::pair<uint32_t, uint32_t>, int> use;
  for (const Triangle& t : triangles)
    for (int i = 0; i < 3; ++i) ++use[std::minmax(t[i], t[(i + 1) % 3])];
  return use;
}

// Vertex count of every boundary loop (edges with one triangle, joined at shared vertices).
std::vector<int> boundaryLoopSizes(const std::vector<Triangle>& triangles, uint32_t vertex_count) {
  std::vector<uint32_t> parent(vertex_count);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<uint8_t> on_boundary(vertex_count, 0);
  for (const auto& [edge, count] : edgeUse(triangles))
    if (count == 1) {
      parent[find(edge.first)] = find(edge.second);
      on_boundary[edge.first] = on_boundary[edge.second] = 1;
    }
  std::map<uint32_t, int> size;
  for (uint32_t v = 0; v < vertex_count; ++v)
    if (on_boundary[v]) ++size[find(v)];
  std::vector<int> out;
  for (const auto& [root, n] : size) out.push_back(n);
  return out;
}

size_t countKind(const ProgressiveMesh& pm, CollapseKind kind) {
  return size_t(std::count_if(pm.collapses.begin(), pm.collapses.end(), [&](const Collapse& c) { return c.kind == kind; }));
}

// The base mesh is still a mesh: no degenerate or repeated triangle, no edge in more than two
// triangles, every boundary loop at least a triangle's worth of vertices.
void expectSoundBase(const ProgressiveMesh& pm) {
  std::vector<Triangle> sorted;
  for (Triangle t : pm.base_triangles) {
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) << "degenerate base triangle";
    std::sort(t.begin(), t.end());
    sorted.push_back(t);
  }
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "repeated base triangle";
  for (const auto& [edge, count] : edgeUse(pm.base_triangles)) EXPECT_LE(count, 2) << "non-manifold edge";
  for (int n : boundaryLoopSizes(pm.base_triangles, pm.vertex_count)) EXPECT_GE(n, 3);
}

// Forward then inverse transform gives the frame back (world axes and local frames).
void expectExactReconstruction(const Topology& topology, const std::vector<double>& parametric,
                               const std::vector<double>& frame) {
  for (bool local_frames : {false, true}) {
    const WaveletTransform transform(bestSimdPath(), topology, parametric, local_frames);
    std::vector<double> coefficients, back;
    transform.forward(frame.data(), coefficients);
    transform.inverse(coefficients, back);
    ASSERT_EQ(back.size(), frame.size());
    for (size_t i = 0; i < frame.size(); ++i) ASSERT_NEAR(back[i], frame[i], 1e-9) << "local frames " << local_frames;
  }
}

bool onGridBorder(uint32_t v, int nx, int ny) {
  const int x = int(v) % nx, y = int(v) / nx;
  return x == 0 || y == 0 || x == nx - 1 || y == ny - 1;
}

TEST(WaveletHierarchy, OpenGridLosesMostOfItsBorderAndReconstructsExactly) {
  const int nx = 20, ny = 16;
  const Topology topology = gridTopology(nx, ny);
  const auto xyz = toDouble(gridFrame(nx, ny, 0, 1.0, 0.0));
  const ProgressiveMesh pm = buildProgressiveMesh(topology, xyz);
  expectValidHierarchy(pm);
  expectSoundBase(pm);
  size_t border_in_base = 0;
  for (uint32_t v : pm.base) border_in_base += onGridBorder(v, nx, ny);
  const size_t border = 2 * nx + 2 * (ny - 2);
  EXPECT_LT(border_in_base * 4, border) << "most border vertices should go";
  EXPECT_GT(countKind(pm, CollapseKind::kBoundary), border / 2);
  EXPECT_LT(pm.base.size(), size_t(20));
  EXPECT_GT(pm.level_count, 2);
  expectExactReconstruction(topology, xyz, toDouble(gridFrame(nx, ny, 7, 1.0, 1.0)));
}

// A level's collapse options are prepared on threads, a block of vertices at a time, when the
// mesh holds several blocks: the hierarchy is the one a single thread builds.
TEST(WaveletHierarchy, IsTheSameOnAnyNumberOfThreads) {
  const int nx = 120, ny = 90;  // 10 800 vertices: three blocks of options
  const Topology topology = gridTopology(nx, ny);
  const auto xyz = toDouble(gridFrame(nx, ny, 3, 1.0, 1.0));
  ProgressiveMesh one;
  {
    ThreadBudget budget(1);
    one = buildProgressiveMesh(topology, xyz);
  }
  expectValidHierarchy(one);
  EXPECT_GT(one.level_count, 2);
  for (unsigned threads : {2u, 3u}) {
    ThreadBudget budget(threads);
    EXPECT_TRUE(sameHierarchy(one, buildProgressiveMesh(topology, xyz))) << threads << " threads";
  }
}

TEST(WaveletHierarchy, BoundaryCollapsesCanBeTurnedOff) {
  const int nx = 20, ny = 16;
  const Topology topology = gridTopology(nx, ny);
  const auto xyz = toDouble(gridFrame(nx, ny, 0, 1.0, 0.0));
  HierarchySettings settings;
  settings.collapse_boundaries = false;
  const ProgressiveMesh pm = buildProgressiveMesh(topology, xyz, settings);
  expectValidHierarchy(pm);
  for (uint32_t v = 0; v < topology.vertex_count; ++v)
    if (onGridBorder(v, nx, ny)) {
      EXPECT_TRUE(std::binary_search(pm.base.begin(), pm.base.end(), v)) << "border vertex " << v << " removed";
    }
  EXPECT_LT(pm.base.size(), size_t(2 * nx + 2 * (ny - 2) + 40));
}

// Two grids side by side whose touching columns are separate copies (a texture seam: same
// positions, different vertices, so two components), plus an isolated triangle.
struct SeamMesh {
  Topology topology;
  std::vector<double> xyz;
  std::vector<std::pair<uint32_t, uint32_t>> copies;  // (copy in the right grid, original)
};

SeamMesh seamMesh(int nx, int ny, double phase) {
  SeamMesh m;
  const Topology grid = gridTopology(nx, ny);
  auto height = [&](double x, double y) { return 0.3 * std::sin(2.0 * x + phase) * std::cos(1.5 * y); };
  for (int side = 0; side < 2; ++side) {
    const uint32_t offset = uint32_t(side * nx * ny);
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const double px = double(x + side * (nx - 1)) / (nx - 1), py = double(y) / (ny - 1);
        m.xyz.insert(m.xyz.end(), {px, py, height(px, py)});
      }
    for (Triangle t : grid.triangles) {
      for (uint32_t& v : t) v += offset;
      m.topology.triangles.push_back(t);
    }
  }
  for (int y = 0; y < ny; ++y) m.copies.emplace_back(uint32_t(nx * ny + y * nx), uint32_t(y * nx + nx - 1));
  const uint32_t lone = uint32_t(2 * nx * ny);
  m.xyz.insert(m.xyz.end(), {3.0, 0.0, 0.0, 3.5, 0.0, 0.0, 3.0, 0.5, 0.2});
  m.topology.triangles.push_back({lone, lone + 1, lone + 2});
  m.topology.vertex_count = lone + 3;
  return m;
}

TEST(WaveletHierarchy, SeamCopiesAreWeldedAndBothComponentsSimplified) {
  const SeamMesh mesh = seamMesh(12, 10, 0.0);
  const ProgressiveMesh pm = buildProgressiveMesh(mesh.topology, mesh.xyz);
  expectValidHierarchy(pm);
  expectSoundBase(pm);
  EXPECT_EQ(countKind(pm, CollapseKind::kSeam), mesh.copies.size());
  for (const auto& [copy, original] : mesh.copies) {
    const uint32_t seam_copy = copy;  // a structured binding cannot be captured before C++20
    const auto c = std::find_if(pm.collapses.begin(), pm.collapses.end(), [&](const Collapse& x) { return x.vertex == seam_copy; });
    ASSERT_NE(c, pm.collapses.end()) << "seam copy " << copy << " kept";
    EXPECT_EQ(c->kind, CollapseKind::kSeam);
    EXPECT_EQ(c->target, original);
  }
  const uint32_t lone = mesh.topology.vertex_count - 3;
  for (uint32_t v = lone; v < lone + 3; ++v) EXPECT_TRUE(std::binary_search(pm.base.begin(), pm.base.end(), v));
  EXPECT_LT(pm.base.size(), size_t(3 + 20));
  EXPECT_TRUE(sameHierarchy(pm, buildProgressiveMesh(mesh.topology, mesh.xyz))) << "not deterministic";

  // The copies move with their originals, so their details vanish; all is reconstructed.
  const SeamMesh moved = seamMesh(12, 10, 0.7);
  const WaveletTransform transform(bestSimdPath(), mesh.topology, mesh.xyz, false);
  std::vector<double> coefficients;
  transform.forward(moved.xyz.data(), coefficients);
  for (const auto& copy : mesh.copies)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(coefficients[3 * copy.first + a], 0.0);
  expectExactReconstruction(mesh.topology, mesh.xyz, moved.xyz);
}

TEST(WaveletHierarchy, SeamsStayApartWhenWeldingIsOff) {
  const SeamMesh mesh = seamMesh(12, 10, 0.0);
  HierarchySettings settings;
  settings.weld_seams = false;
  const ProgressiveMesh pm = buildProgressiveMesh(mesh.topology, mesh.xyz, settings);
  expectValidHierarchy(pm);
  expectSoundBase(pm);
  EXPECT_EQ(countKind(pm, CollapseKind::kSeam), 0u);
  // Each grid is a disc: its boundary loop keeps at least 3 vertices, so does the triangle.
  const std::vector<int> loops = boundaryLoopSizes(pm.base_triangles, pm.vertex_count);
  EXPECT_EQ(loops.size(), 3u);
}

// A disk whose rim of n vertices (alternately slightly up and down) is fanned by two hubs,
// each over half of it: both hubs are in n / 2 + 2 triangles.
struct TwoHubDisk {
  Topology topology;
  std::vector<double> xyz;
  uint32_t hub_a, hub_b;
};

TwoHubDisk twoHubDisk(uint32_t n) {
  TwoHubDisk d;
  d.hub_a = n;
  d.hub_b = n + 1;
  d.topology.vertex_count = n + 2;
  for (uint32_t i = 0; i < n; ++i) {
    const double a = M_PI / 2 + 2 * M_PI * i / n;
    d.xyz.insert(d.xyz.end(), {std::cos(a), std::sin(a), i % 2 ? 0.05 : -0.05});
  }
  d.xyz.insert(d.xyz.end(), {-1e-3, 0, 0, 1e-3, 0, 0});
  for (uint32_t i = 0; i < n / 2; ++i) d.topology.triangles.push_back({d.hub_a, i, i + 1});
  for (uint32_t i = n / 2; i < n; ++i) d.topology.triangles.push_back({d.hub_b, i, (i + 1) % n});
  d.topology.triangles.push_back({d.hub_a, n / 2, d.hub_b});
  d.topology.triangles.push_back({d.hub_b, 0, d.hub_a});
  return d;
}

TEST(WaveletHierarchy, NoCollapseLeavesAVertexInMoreTrianglesThanTheBound) {
  // Merging the hubs would leave one in 402 triangles: over the bound, so it is not done
  // (without the bound the hubs merged on level 0, and merges like it can double a vertex's
  // fan, and the square cost of walking it, on every level).
  const TwoHubDisk disk = twoHubDisk(400);
  const ProgressiveMesh pm = buildProgressiveMesh(disk.topology, disk.xyz);
  expectValidHierarchy(pm);
  for (const Collapse& c : pm.collapses) {
    EXPECT_FALSE((c.vertex == disk.hub_a || c.vertex == disk.hub_b) && (c.target == disk.hub_a || c.target == disk.hub_b))
        << "hubs merged on level " << c.level;
    EXPECT_LE(c.ring_size, kMaxCollapseTriangles + 1);
  }
}

// One test per real sequence (with its most base vertices), so that a sequence the data
// folders lack is listed as not run.
class WaveletHierarchyOnSequence : public ::testing::TestWithParam<std::pair<const char*, size_t>> {};

TEST_P(WaveletHierarchyOnSequence, IsCoveredAndRebuiltIdentically) {
  const auto [name, max_base] = GetParam();
  ANIMC_REQUIRE_SEQUENCE(name);
  {
    MemorySequence seq = realSequence(name, 1);
    ASSERT_EQ(seq.frames().size(), 1u);
    const auto xyz = toDouble(seq.frames()[0]);
    const ProgressiveMesh a = buildProgressiveMesh(seq.topology(), xyz);
    expectValidHierarchy(a);
    EXPECT_LE(a.base.size(), max_base);
    for (int n : boundaryLoopSizes(a.base_triangles, a.vertex_count)) EXPECT_GE(n, 3);
    EXPECT_TRUE(sameHierarchy(a, buildProgressiveMesh(seq.topology(), xyz))) << "not deterministic";
    for (SimdPath path : availableSimdPaths()) {  // the cost kernels of every path agree
      HierarchySettings settings;
      settings.path = path;
      EXPECT_TRUE(sameHierarchy(a, buildProgressiveMesh(seq.topology(), xyz, settings))) << int(path);
    }
  }
}

// Base vertices before boundary collapses and seam welding: 413, 1241, 613, 22.
INSTANTIATE_TEST_SUITE_P(Real, WaveletHierarchyOnSequence,
                         ::testing::Values(std::pair<const char*, size_t>{"chickenCrossing", 260},
                                           std::pair<const char*, size_t>{"oa_angelyss_lower", 250},
                                           std::pair<const char*, size_t>{"oa_gargoyle_upper", 130},
                                           std::pair<const char*, size_t>{"sydney_md2", 25}),
                         [](const auto& info) { return std::string(info.param.first); });

// A torus of nx * ny vertices (every vertex interior), slightly perturbed.
Topology torusTopology(uint32_t nx, uint32_t ny) {
  Topology t;
  t.vertex_count = nx * ny;
  for (uint32_t y = 0; y < ny; ++y)
    for (uint32_t x = 0; x < nx; ++x) {
      const uint32_t a = y * nx + x, b = y * nx + (x + 1) % nx, c = ((y + 1) % ny) * nx + x,
                     d = ((y + 1) % ny) * nx + (x + 1) % nx;
      t.triangles.push_back({a, b, d});
      t.triangles.push_back({a, d, c});
    }
  return t;
}

// Each vertex's triangles, as vertex triples, in the order its incidence list holds them.
std::vector<std::vector<Triangle>> incidence(const LevelMesh& mesh, uint32_t vertex_count) {
  std::vector<std::vector<Triangle>> out(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v)
    for (const uint32_t* t = mesh.trianglesBegin(v); t != mesh.trianglesEnd(v); ++t)
      out[v].push_back(mesh.triangle(*t));
  return out;
}

std::vector<uint32_t> closedRing(const LevelMesh& mesh, uint32_t v, FanQuery& query) {
  VertexRing ring;
  if (!mesh.orderedRing(v, ring, query)) return {};
  return std::vector<uint32_t>(ring.begin(), ring.end());
}

// Whether a and b hold the same cyclic sequence.
bool sameCycle(std::vector<uint32_t> a, const std::vector<uint32_t>& b) {
  if (a.size() != b.size()) return false;
  for (size_t turn = 0; turn < a.size(); ++turn) {
    if (a == b) return true;
    std::rotate(a.begin(), a.begin() + 1, a.end());
  }
  return a.empty();
}

// LevelMesh::collapse updates the incidence lists in place of a full rebuild, and the
// hierarchy keeps the rings of a collapse's neighbours instead of walking them again: a
// neighbour that does not flank the collapsed edge has its ring with v replaced by u, one that
// flanks it its ring without v. Random collapses that pass the link condition, on a torus and
// on an open grid, checked against a rebuild and fresh ring walks.
TEST(WaveletLevelMesh, CollapsesUpdateListsAndNeighbourRingsAsARebuildWould) {
  for (const Topology& topology : {torusTopology(9, 7), gridTopology(9, 8)}) {
    LevelMesh mesh(topology);
    FanQuery query(topology.vertex_count);
    std::vector<uint8_t> removed(topology.vertex_count, 0);
    std::mt19937 random(5);
    int collapses = 0;
    for (int attempt = 0; attempt < 400 && collapses < 30; ++attempt) {
      const uint32_t v = uint32_t(random() % topology.vertex_count);
      const std::vector<uint32_t> ring = closedRing(mesh, v, query);
      if (removed[v] || ring.empty()) continue;
      const size_t at = random() % ring.size();
      const uint32_t u = ring[at];
      const uint32_t before = ring[(at + ring.size() - 1) % ring.size()], after = ring[(at + 1) % ring.size()];
      mesh.markNeighbours(u);  // link condition: only the flanks are common neighbours
      if (std::any_of(ring.begin(), ring.end(),
                      [&](uint32_t w) { return w != u && w != before && w != after && mesh.markedNeighbour(w); }))
        continue;
      std::map<uint32_t, std::vector<uint32_t>> rings_before;
      for (uint32_t w : ring) rings_before[w] = closedRing(mesh, w, query);
      mesh.collapse(v, u);
      removed[v] = 1;
      ++collapses;
      LevelMesh rebuilt = mesh;
      rebuilt.rebuildIncidence();
      ASSERT_EQ(incidence(mesh, topology.vertex_count), incidence(rebuilt, topology.vertex_count))
          << "after collapsing " << v << " onto " << u;
      for (const auto& [w, old_ring] : rings_before) {
        if (w == u || old_ring.empty()) continue;
        std::vector<uint32_t> expected = old_ring;
        if (w == before || w == after) {
          if (old_ring.size() < 4) continue;  // becomes two: no ring
          expected.erase(std::find(expected.begin(), expected.end(), v));
          EXPECT_TRUE(sameCycle(expected, closedRing(rebuilt, w, query))) << "flank " << w;
        } else {
          std::replace(expected.begin(), expected.end(), v, u);
          EXPECT_EQ(closedRing(rebuilt, w, query), expected) << "neighbour " << w;
        }
      }
    }
    EXPECT_GE(collapses, 20);
  }
}

// A huge coordinate overflows some collapse costs to NaN, which leaves them unordered: the
// batches then sort their candidates as they always did. The hierarchy is still valid and the
// same every time.
TEST(WaveletHierarchy, NanCostsStillGiveAValidDeterministicHierarchy) {
  const Topology topology = gridTopology(12, 10);
  std::vector<double> xyz = toDouble(gridFrame(12, 10, 0, 0.0, 0.0));
  xyz[3 * 40 + 2] = 1e300;
  const ProgressiveMesh pm = buildProgressiveMesh(topology, xyz);
  expectValidHierarchy(pm);
  EXPECT_GT(pm.collapses.size(), 60u);
  EXPECT_TRUE(sameHierarchy(pm, buildProgressiveMesh(topology, xyz))) << "not deterministic";
}

TEST(WaveletPredictor, EdgeWeightFavoursFlatEdges) {
  const AnisotropyParams p;
  EXPECT_NEAR(edgeWeight(1.0, p), 1.1, 1e-12);
  EXPECT_NEAR(edgeWeight(0.0, p), 0.1 + std::exp(-1.0 / 0.18), 1e-12);
  EXPECT_GT(edgeWeight(0.9, p), edgeWeight(0.5, p));
}

// Second differences vanish on linear functions, so on a flat parametric mesh the predictor
// reproduces every interior vertex exactly (linear precision), except where it falls back to
// the ring average. Boundary vertices are interpolated along their coarser boundary edge by
// chord length: exact where the coarser border is still straight, i.e. away from the corners.
TEST(WaveletPredictor, StencilsAreAffineAndHaveLinearPrecision) {
  const Topology topology = gridTopology(16, 16);
  std::vector<double> flat;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool border = x == 0 || y == 0 || x == 15 || y == 15;  // straight, unevenly spaced
      const double px = std::pow(x, 1.3) + (border ? 0.0 : 0.3 * std::sin(y));
      const double py = std::pow(y, 1.2) + (border ? 0.0 : 0.2 * std::cos(3.0 * x));
      flat.insert(flat.end(), {px, py, 0.5 * px - 0.25 * py});
    }
  const ProgressiveMesh pm = buildProgressiveMesh(topology, flat);
  const PredictionStencils s = buildPredictor(pm, flat);
  ASSERT_EQ(s.first.size(), pm.collapses.size() + 1);
  size_t interior = 0, interior_exact = 0, boundary = 0, boundary_exact = 0;
  for (size_t i = 0; i < pm.collapses.size(); ++i) {
    double sum = 0, predicted[3] = {0, 0, 0};
    for (uint32_t j = s.first[i]; j < s.first[i + 1]; ++j) {
      sum += s.weight[j];
      for (int a = 0; a < 3; ++a) predicted[a] += s.weight[j] * flat[3 * s.vertex[j] + a];
    }
    EXPECT_NEAR(sum, 1.0, 1e-9);
    const uint32_t v = pm.collapses[i].vertex;
    const double miss = std::hypot(predicted[0] - flat[3 * v], predicted[1] - flat[3 * v + 1], predicted[2] - flat[3 * v + 2]);
    const bool on_boundary = pm.collapses[i].kind == CollapseKind::kBoundary;
    (on_boundary ? boundary : interior) += 1;
    (on_boundary ? boundary_exact : interior_exact) += miss < 1e-9;
  }
  EXPECT_GE(interior_exact * 10, interior * 9);
  EXPECT_GT(boundary, 30u);
  EXPECT_GE(boundary_exact * 10, boundary * 8);
}

}  // namespace
}  // namespace animc
