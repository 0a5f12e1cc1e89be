// SPDX-License-Identifier: Apache-2.0
// The progressive-mesh hierarchy of the wavelet codec (paper section 3.2): half-edge
// collapses in batches, one independent set per level, chosen by a memoryless quadric cost
// under an edge-length bound that is relaxed level by level. Built from the connectivity and
// the parametric mesh only, deterministically, so encoder and decoder build the same one.
// Vertices are never renumbered: the hierarchy only lists which vertex goes when.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/wavelet/level_mesh.h"
#include "core/sequence.h"
#include "core/simd_math.h"
#include "core/status.h"

namespace animc {

enum class CollapseKind : uint8_t {
  kInterior,  // closed ring; anisotropic prediction
  kBoundary,  // open fan, collapsed along a boundary edge; predicted along the boundary
  kSeam,      // a copy of `target` (same parametric position, e.g. a texture seam); welded
};

// One half-edge collapse: `vertex` is removed onto its neighbour `target`. Its one ring at
// that moment is ring[ring_begin .. ring_begin + ring_size) of the ProgressiveMesh, cyclic,
// with flap[k] the vertex across the link edge (ring[k], ring[k+1]) or kNoVertex.
// kBoundary: the ring is an open fan, v's triangles are (vertex, ring[k], ring[k+1]) for
// k < ring_size - 1 only; ring's first and last vertices are its boundary neighbours, one of
// them the target; the last flap is kNoVertex.
// kSeam: the ring is the target alone, its flap kNoVertex.
struct Collapse {
  uint32_t vertex = 0;
  uint32_t target = 0;
  uint32_t ring_begin = 0;
  uint16_t ring_size = 0;
  uint16_t level = 0;  // batch number; 0 = the first (finest) batch
  CollapseKind kind = CollapseKind::kInterior;
};

struct ProgressiveMesh {
  uint32_t vertex_count = 0;
  int level_count = 0;
  std::vector<Collapse> collapses;  // in removal order, finest batch first
  std::vector<uint32_t> ring;
  std::vector<uint32_t> flap;
  std::vector<uint32_t> base;       // vertices never removed, ascending (each boundary loop
                                    // keeps at least 3)
  std::vector<Triangle> base_triangles;
};

struct HierarchySettings {
  int max_levels = 64;
  double first_length_factor = 1.0;  // bound of level 0, times the mean edge length
  double length_growth = 1.25;       // the bound grows by this factor every level
  double min_normal_cosine = 0.3;    // a collapse may not turn a triangle by more than ~72 deg
  bool collapse_boundaries = true;   // false keeps every boundary vertex in the base
  bool weld_seams = true;            // false keeps coincident vertices apart
  SimdPath path = SimdPath::kPortable;  // the collapse costs' kernels (same hierarchy either way)
};

// The hierarchy's cost grew with the square of each vertex's triangle count (its ring is
// walked and checked once per neighbour, at every level that touches it). Real meshes sum
// a few tens of such squares per triangle, but a fan of k triangles around one vertex, which
// a few bytes of connectivity can declare, would cost k^2: the build leaves fans of more than
// kMaxCollapseTriangles alone (collapse_choice.h). Encoder and decoder still refuse meshes whose sum exceeds
// this many per triangle plus a fixed allowance (about one vertex in 1000 triangles), and
// vertices in more triangles than Collapse::ring_size can count (an open fan's ring has one
// vertex more than its triangles): a second guard.
constexpr uint64_t kMaxRingCostPerTriangle = 64;
constexpr uint64_t kRingCostAllowance = uint64_t(1) << 20;
constexpr uint32_t kMaxTrianglesAtVertex = UINT16_MAX - 1;
Status checkHierarchyCost(const Topology& topology);

// parametric_xyz: 3 * vertex_count coordinates (the parametric mesh).
ProgressiveMesh buildProgressiveMesh(const Topology& topology, const std::vector<double>& parametric_xyz,
                                     const HierarchySettings& settings = {});

}  // namespace animc
