// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/clusters.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace animc {
namespace {

// Frames the distances are measured on: at most this many, evenly spaced. Parts differ in
// their slow motion, which a subsample keeps, and the cost stays O(vertices x parts).
constexpr uint32_t kMaxClusterFrames = 64;
// Rounds of k-means at most: labels hardly change after a dozen.
constexpr int kIterations = 12;
constexpr uint32_t kVerticesPerTask = 1024;
// The most parts clusterTrajectories() makes (labels are bytes).
constexpr uint32_t kMaxParts = 256;

struct Features {
  uint32_t dims = 0;
  std::vector<float> values;  // vertices x dims
  const float* row(uint32_t v) const { return values.data() + size_t(v) * dims; }
};

Features sampled(const float* frames, uint32_t vertices, uint32_t frame_count) {
  const uint32_t stride = (frame_count + kMaxClusterFrames - 1) / kMaxClusterFrames;
  const uint32_t used = (frame_count + stride - 1) / stride;
  Features f;
  f.dims = 3 * used;
  f.values.resize(size_t(vertices) * f.dims);
  for (uint32_t v = 0; v < vertices; ++v)
    for (uint32_t i = 0; i < used; ++i)
      for (uint32_t c = 0; c < 3; ++c)
        f.values[size_t(v) * f.dims + 3 * i + c] = frames[(size_t(i) * stride * vertices + v) * 3 + c];
  return f;
}

double squaredDistance(const float* a, const double* b, uint32_t dims) {
  double sum = 0;
  for (uint32_t d = 0; d < dims; ++d) sum += (a[d] - b[d]) * (a[d] - b[d]);
  return sum;
}

// Farthest-point seeds from vertex 0: spread over the motions, and deterministic.
std::vector<double> seeds(const Features& f, uint32_t vertices, uint32_t parts) {
  std::vector<double> centres(size_t(parts) * f.dims);
  std::vector<double> nearest(vertices, HUGE_VAL);
  uint32_t next = 0;
  for (uint32_t c = 0; c < parts; ++c) {
    std::copy(f.row(next), f.row(next) + f.dims, centres.begin() + size_t(c) * f.dims);
    uint32_t farthest = 0;
    for (uint32_t v = 0; v < vertices; ++v) {
      nearest[v] = std::min(nearest[v], squaredDistance(f.row(v), &centres[size_t(c) * f.dims], f.dims));
      if (nearest[v] > nearest[farthest]) farthest = v;
    }
    next = farthest;
  }
  return centres;
}

// Each vertex to its nearest centre (the first of equal ones). The distances to all centres
// are summed side by side, a feature at a time, from the centres laid out feature-major: each
// sum still adds its terms in feature order, as squaredDistance() does, so the labels are the
// same, and the vertex's features are read once instead of once a centre.
void assign(const Features& f, const std::vector<double>& centres, uint32_t parts, std::vector<uint8_t>& labels) {
  std::vector<double> by_feature(centres.size());
  for (uint32_t c = 0; c < parts; ++c)
    for (uint32_t d = 0; d < f.dims; ++d) by_feature[size_t(d) * parts + c] = centres[size_t(c) * f.dims + d];
  parallelForBlocks(labels.size(), kVerticesPerTask, double(parts) * f.dims, [&](size_t, size_t begin, size_t end) {
    double sums[kMaxParts];
    for (size_t v = begin; v < end; ++v) {
      std::fill(sums, sums + parts, 0.0);
      const float* row = f.row(uint32_t(v));
      for (uint32_t d = 0; d < f.dims; ++d) {
        const double x = row[d];
        const double* centre = &by_feature[size_t(d) * parts];
        for (uint32_t c = 0; c < parts; ++c) sums[c] += (x - centre[c]) * (x - centre[c]);
      }
      labels[v] = uint8_t(std::min_element(sums, sums + parts) - sums);
    }
  });
}

// Each centre the mean of its vertices (one left alone when it has none).
void update(const Features& f, const std::vector<uint8_t>& labels, uint32_t parts, std::vector<double>& centres) {
  std::vector<double> sums(centres.size(), 0);
  std::vector<uint32_t> counts(parts, 0);
  for (uint32_t v = 0; v < labels.size(); ++v) {
    ++counts[labels[v]];
    for (uint32_t d = 0; d < f.dims; ++d) sums[size_t(labels[v]) * f.dims + d] += f.row(v)[d];
  }
  for (uint32_t c = 0; c < parts; ++c)
    for (uint32_t d = 0; counts[c] > 0 && d < f.dims; ++d)
      centres[size_t(c) * f.dims + d] = sums[size_t(c) * f.dims + d] / counts[c];
}

// Labels renumbered by lowest vertex, empty parts dropped; returns their number.
uint32_t numberByLowestVertex(std::vector<uint8_t>& labels, uint32_t parts) {
  std::vector<int> number(parts, -1);
  uint32_t count = 0;
  for (uint8_t& label : labels) {
    if (number[label] < 0) number[label] = int(count++);
    label = uint8_t(number[label]);
  }
  return count;
}

// Weighted k-means of a few points (rows of `points`): the group of each.
std::vector<uint32_t> groupPoints(const Features& points, const std::vector<uint32_t>& weights, uint32_t groups) {
  const uint32_t n = uint32_t(weights.size());
  std::vector<double> centres = seeds(points, n, groups);
  std::vector<uint32_t> group(n, 0);
  for (int i = 0; i < kIterations; ++i) {
    for (uint32_t p = 0; p < n; ++p) {
      double nearest = HUGE_VAL;
      for (uint32_t g = 0; g < groups; ++g) {
        const double d = squaredDistance(points.row(p), &centres[size_t(g) * points.dims], points.dims);
        if (d < nearest) nearest = d, group[p] = g;
      }
    }
    std::vector<double> sums(centres.size(), 0);
    std::vector<double> totals(groups, 0);
    for (uint32_t p = 0; p < n; ++p) {
      totals[group[p]] += weights[p];
      for (uint32_t d = 0; d < points.dims; ++d)
        sums[size_t(group[p]) * points.dims + d] += weights[p] * points.row(p)[d];
    }
    for (uint32_t g = 0; g < groups; ++g)
      for (uint32_t d = 0; totals[g] > 0 && d < points.dims; ++d)
        centres[size_t(g) * points.dims + d] = sums[size_t(g) * points.dims + d] / totals[g];
  }
  return group;
}

}  // namespace

std::vector<uint8_t> mergeParts(const float* frames, uint32_t vertices, uint32_t frame_count,
                                const std::vector<uint8_t>& labels, uint32_t count, uint32_t parts, uint32_t& merged) {
  std::vector<uint8_t> out(vertices, 0);
  if (parts > 1 && count > parts) {
    const Features f = sampled(frames, vertices, frame_count);
    std::vector<double> centres(size_t(count) * f.dims, 0);
    update(f, labels, count, centres);
    Features points;
    points.dims = f.dims;
    points.values.assign(centres.begin(), centres.end());
    std::vector<uint32_t> weights(count, 0);
    for (uint8_t label : labels) ++weights[label];
    const std::vector<uint32_t> group = groupPoints(points, weights, parts);
    for (uint32_t v = 0; v < vertices; ++v) out[v] = uint8_t(group[labels[v]]);
  } else if (parts > 1) {
    out = labels;
  }
  merged = numberByLowestVertex(out, std::max(parts, count));
  return out;
}

std::vector<uint8_t> clusterTrajectories(const float* frames, uint32_t vertices, uint32_t frame_count, uint32_t parts,
                                         uint32_t& count) {
  parts = std::max(1u, std::min({parts, vertices, kMaxParts}));
  std::vector<uint8_t> labels(vertices, 0);
  if (parts > 1) {
    const Features f = sampled(frames, vertices, frame_count);
    std::vector<double> centres = seeds(f, vertices, parts);
    std::vector<uint8_t> before;
    for (int i = 0; i < kIterations; ++i) {
      assign(f, centres, parts, labels);
      if (labels == before) break;  // settled: the rounds left would change nothing
      update(f, labels, parts, centres);
      before = labels;
    }
  }
  count = numberByLowestVertex(labels, parts);
  return labels;
}

}  // namespace animc
