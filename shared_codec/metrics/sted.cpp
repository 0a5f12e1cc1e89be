// SPDX-License-Identifier: Apache-2.0
// STED (docs/metrics.md): the spatial part compares edge lengths of each frame in local
// neighbourhoods, the temporal part the space-time length of each vertex's step between frames.
#include <algorithm>
#include <cmath>

#include "animc/animc.h"
#include "core/adjacency.h"

namespace animc {
namespace {

constexpr int kMaxRings = 3;  // a 3-ring holds about 90 edges on a regular mesh; wider costs O(r^2)

struct Edge {
  uint32_t a, b;
};

double length(const float* xyz, uint32_t a, uint32_t b) {
  const double dx = double(xyz[3 * a]) - xyz[3 * b], dy = double(xyz[3 * a + 1]) - xyz[3 * b + 1],
               dz = double(xyz[3 * a + 2]) - xyz[3 * b + 2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double bboxDiagonal(const float* xyz, uint32_t n) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t i = 0; i < 3 * n; ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], double(xyz[i]));
  }
  return n == 0 ? 0 : std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

}  // namespace

struct StedAccumulator::Impl {
  uint32_t n = 0;
  StedOptions options;
  std::vector<Edge> edges;
  // Rows of edge ids: the edges of vertex v's neighbourhood are
  // neighbourhood[first[v]] .. neighbourhood[first[v + 1] - 1].
  std::vector<uint32_t> first, neighbourhood;
  std::vector<double> change, weight;  // per edge, this frame: (l' - l) / l and l
  std::vector<float> previous_original, previous_reconstructed;
  double time_length = 0;  // the temporal edge's time component, fixed by frame 0
  double spatial_sum = 0, temporal_sum = 0;
  int64_t spatial_terms = 0, temporal_terms = 0;

  void build(const uint32_t* triangles, size_t triangle_count);
  void addSpatial(const float* original, const float* reconstructed);
  void addTemporal(const float* original, const float* reconstructed);
};

// The neighbourhood of v: the vertices within `rings` edges of v, and every edge joining two
// of them.
void StedAccumulator::Impl::build(const uint32_t* triangles, size_t triangle_count) {
  Topology topology;
  topology.vertex_count = n;
  for (size_t t = 0; t < triangle_count; ++t) {
    const uint32_t* c = triangles + 3 * t;
    if (c[0] < n && c[1] < n && c[2] < n) topology.triangles.push_back({c[0], c[1], c[2]});
  }
  const VertexAdjacency adjacency(topology);
  const uint32_t* slots = n ? adjacency.begin(0) : nullptr;
  std::vector<uint32_t> edge_at_slot(n ? size_t(adjacency.end(n - 1) - slots) : 0);
  for (uint32_t u = 0; u < n; ++u)
    for (const uint32_t* w = adjacency.begin(u); w != adjacency.end(u); ++w)
      if (*w > u) {
        edge_at_slot[w - slots] = uint32_t(edges.size());
        edges.push_back({u, *w});
      }
  auto edgeId = [&](uint32_t u, uint32_t w) {
    if (u > w) std::swap(u, w);
    return edge_at_slot[std::lower_bound(adjacency.begin(u), adjacency.end(u), w) - slots];
  };
  std::vector<uint32_t> stamp(n, UINT32_MAX), members;
  first.assign(1, 0);
  for (uint32_t v = 0; v < n; ++v) {
    members.assign(1, v);
    stamp[v] = v;
    for (size_t begin = 0, ring = 0; ring < size_t(options.rings); ++ring) {
      const size_t end = members.size();
      for (size_t i = begin; i < end; ++i)
        for (const uint32_t* w = adjacency.begin(members[i]); w != adjacency.end(members[i]); ++w)
          if (stamp[*w] != v) {
            stamp[*w] = v;
            members.push_back(*w);
          }
      begin = end;
    }
    for (uint32_t u : members)
      for (const uint32_t* w = adjacency.begin(u); w != adjacency.end(u); ++w)
        if (*w > u && stamp[*w] == v) neighbourhood.push_back(edgeId(u, *w));
    first.push_back(uint32_t(neighbourhood.size()));
  }
  change.resize(edges.size());
  weight.resize(edges.size());
}

// Each vertex adds the length-weighted standard deviation of its neighbourhood's relative edge
// changes; edges of length 0 in the original carry no weight.
void StedAccumulator::Impl::addSpatial(const float* original, const float* reconstructed) {
  for (size_t e = 0; e < edges.size(); ++e) {
    const double l = length(original, edges[e].a, edges[e].b);
    weight[e] = l;
    change[e] = l > 0 ? (length(reconstructed, edges[e].a, edges[e].b) - l) / l : 0;
  }
  for (uint32_t v = 0; v < n; ++v) {
    double w = 0, mean = 0;
    for (uint32_t i = first[v]; i < first[v + 1]; ++i) {
      w += weight[neighbourhood[i]];
      mean += weight[neighbourhood[i]] * change[neighbourhood[i]];
    }
    if (!(w > 0)) continue;
    mean /= w;
    double variance = 0;
    for (uint32_t i = first[v]; i < first[v + 1]; ++i) {
      const double d = change[neighbourhood[i]] - mean;
      variance += weight[neighbourhood[i]] * d * d;
    }
    spatial_sum += std::sqrt(variance / w);
    ++spatial_terms;
  }
}

// The temporal edge of v from frame f-1 to f has length sqrt(|p_f - p_{f-1}|^2 + T^2), T the
// time component; each adds |L' - L| / L.
void StedAccumulator::Impl::addTemporal(const float* original, const float* reconstructed) {
  const double t2 = time_length * time_length;
  for (uint32_t v = 0; v < 3 * n; v += 3) {
    double d2 = 0, r2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = double(original[v + k]) - previous_original[v + k];
      const double r = double(reconstructed[v + k]) - previous_reconstructed[v + k];
      d2 += d * d;
      r2 += r * r;
    }
    const double l = std::sqrt(d2 + t2);
    if (!(l > 0)) continue;
    temporal_sum += std::fabs(std::sqrt(r2 + t2) - l) / l;
    ++temporal_terms;
  }
}

StedAccumulator::StedAccumulator(uint32_t vertex_count, const uint32_t* triangles, size_t triangle_count,
                                 const StedOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->n = vertex_count;
  impl_->options = options;
  impl_->options.rings = std::clamp(options.rings, 1, kMaxRings);
  impl_->build(triangles, triangle_count);
}

StedAccumulator::~StedAccumulator() = default;
StedAccumulator::StedAccumulator(StedAccumulator&&) noexcept = default;
StedAccumulator& StedAccumulator::operator=(StedAccumulator&&) noexcept = default;

void StedAccumulator::addFrame(const float* original, const float* reconstructed) {
  Impl& s = *impl_;
  s.addSpatial(original, reconstructed);
  if (s.previous_original.empty()) {
    s.time_length = s.options.time_step * bboxDiagonal(original, s.n);
  } else {
    s.addTemporal(original, reconstructed);
  }
  s.previous_original.assign(original, original + 3 * size_t(s.n));
  s.previous_reconstructed.assign(reconstructed, reconstructed + 3 * size_t(s.n));
}

StedFigures StedAccumulator::finish() const {
  const Impl& s = *impl_;
  StedFigures f;
  if (s.spatial_terms) f.spatial = s.spatial_sum / double(s.spatial_terms);
  if (s.temporal_terms) f.temporal = s.temporal_sum / double(s.temporal_terms);
  const double c = s.options.temporal_weight;
  f.sted = std::sqrt(f.spatial * f.spatial + c * c * f.temporal * f.temporal);
  return f;
}

}  // namespace animc
