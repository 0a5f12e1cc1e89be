// SPDX-License-Identifier: Apache-2.0
// Design measurement for the trajectory codec's next version (issue 40): what other contexts
// and predictions would make of the coefficients of today's files. Each group payload is read
// back (readTrajectoryGroup) and its quantised coefficients, unchanged (so at the file's own
// error), coded again by each variant below through the codec's own range coder and classed
// integer models (entropy/classed_integer.h); the bytes of each are printed.
//   today       codec 3: the component's band x the prediction's kind (no coded neighbour,
//               zero, non-zero), the rounded mean of the coded neighbours' values;
//   previous    today's contexts x the class of the vertex's own residual in the component
//               before (0, 1, 2-3, 4 and more);
//   activity    today's contexts x the class of the mean magnitude of the coded neighbours'
//               residuals in this component (0, below 1, below 3, 3 and more);
//   both        previous and activity together;
//   components  today's contexts with one band per component up to 16, then today's bands;
//   shrunk      today's contexts, the prediction scaled by a factor per band (the least-squares
//               one over the group, 8 floats a group, counted);
//   hierarchy   an interpolating prediction instead of the breadth-first one: the vertices are
//               split into levels, each level a maximal independent set of the graph that
//               remains (whose edges join the neighbours of every vertex taken out before it);
//               the last, coarsest vertices are coded as today among themselves, then the
//               levels from coarse to fine, each vertex predicted by the rounded mean of all
//               its neighbours in its level's graph, every one of them coded already. Contexts:
//               today's x the level (the four finest, then one for the rest);
//   one level   hierarchy with one level: a maximal independent set predicted by all its
//               neighbours, the rest coded as today among themselves first;
//   unpredicted today's bands with no prediction (what the prediction is worth).
// trajectory_variants.py builds it and runs it.
//   usage: trajectory_contexts FILE.ams...
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <algorithm>
#include <cstdint>
#include <set>

#include "core/adjacency.h"
#include "entropy/classed_integer.h"
#include "trajectory_file.h"

namespace {

using animc::ClassedIntegerModel;
using animc::CodingOrder;
using animc::TrajectoryGroup;

// The codec's own bands and prediction (group_coding.h).
constexpr int kBands = animc::kCoefficientBands;
using animc::coefficientBand;
using animc::roundedMean;
int componentBandOf(uint32_t k) { return k < 16 ? int(k) : 16 + std::min(31 - __builtin_clz(k + 1), 11) - 4; }
constexpr int kComponentBands = 24;

int magnitudeContext(int64_t v) {
  const int64_t m = v < 0 ? -v : v;
  return m == 0 ? 0 : m == 1 ? 1 : m < 4 ? 2 : 3;
}

// 4 x the mean magnitude of the coded neighbours' residuals: 0, below 1, below 3, more.
int activityContext(int64_t sum_abs, int64_t n) {
  if (n == 0 || sum_abs == 0) return 0;
  return sum_abs < n ? 1 : sum_abs < 3 * n ? 2 : 3;
}

struct Variant {
  std::string name;
  int contexts;
  bool shrunk = false;
  // The context of a value from its component, prediction kind, previous residual, activity.
  std::function<int(uint32_t k, int kind, int previous, int activity)> context;
  bool predicted = true;
};

std::vector<Variant> variants() {
  return {
      {"today", kBands * 3, false, [](uint32_t k, int kind, int, int) { return coefficientBand(k) * 3 + kind; }},
      {"previous", kBands * 12, false,
       [](uint32_t k, int kind, int previous, int) { return (coefficientBand(k) * 3 + kind) * 4 + previous; }},
      {"activity", kBands * 12, false,
       [](uint32_t k, int kind, int, int activity) { return (coefficientBand(k) * 3 + kind) * 4 + activity; }},
      {"both", kBands * 48, false,
       [](uint32_t k, int kind, int previous, int activity) {
         return ((coefficientBand(k) * 3 + kind) * 4 + previous) * 4 + activity;
       }},
      {"components", kComponentBands * 3, false,
       [](uint32_t k, int kind, int, int) { return componentBandOf(k) * 3 + kind; }},
      {"shrunk", kBands * 3, true, [](uint32_t k, int kind, int, int) { return coefficientBand(k) * 3 + kind; }},
      {"unpredicted", kBands * 3, false, [](uint32_t k, int, int, int) { return coefficientBand(k) * 3; }, false},
  };
}

// The neighbours' mean of each value (in double), for the shrinking factors and the coder.
struct Neighbourhood {
  std::vector<double> mean;  // per value; NaN without a coded neighbour
};

Neighbourhood neighbourMeans(const TrajectoryGroup& g, const CodingOrder& order) {
  const uint32_t n = uint32_t(order.vertex.size()), K = g.components;
  Neighbourhood h;
  h.mean.assign(size_t(n) * K, NAN);
  for (uint32_t p = 0; p < n; ++p) {
    const uint32_t begin = order.first[p], end = order.first[p + 1];
    if (begin == end) continue;
    for (uint32_t k = 0; k < K; ++k) {
      int64_t sum = 0;
      for (uint32_t i = begin; i < end; ++i) sum += g.coefficients[size_t(order.earlier[i]) * K + k];
      h.mean[size_t(p) * K + k] = double(sum) / double(end - begin);
    }
  }
  return h;
}

// Least-squares factor per band of value ~ factor x neighbours' mean, as a float.
std::vector<float> shrinkFactors(const TrajectoryGroup& g, const Neighbourhood& h) {
  std::vector<double> xy(kBands, 0), xx(kBands, 0);
  const size_t K = g.components;
  for (size_t i = 0; i < h.mean.size(); ++i) {
    if (std::isnan(h.mean[i])) continue;
    const int b = coefficientBand(uint32_t(i % K));
    xy[b] += h.mean[i] * g.coefficients[i];
    xx[b] += h.mean[i] * h.mean[i];
  }
  std::vector<float> f(kBands, 1.0f);
  for (int b = 0; b < kBands; ++b)
    if (xx[b] > 0) f[b] = float(xy[b] / xx[b]);
  return f;
}

// The order and predictors of the hierarchy variant, over coding positions: values are coded
// vertex by vertex in `sequence`; predictors[first[i] .. first[i + 1]) are the positions whose
// mean predicts sequence[i], and level[i] its level (0 = finest, the coarsest set last).
struct Hierarchy {
  std::vector<uint32_t> sequence, first, predictors;
  std::vector<int> level;
};

constexpr uint32_t kCoarsest = 64;  // vertices left when the levels stop
constexpr int kLevelContexts = 5;

Hierarchy buildHierarchy(const animc::Topology& topology, const CodingOrder& order, int max_levels) {
  const uint32_t n = topology.vertex_count;
  std::vector<uint32_t> position(n);
  for (uint32_t p = 0; p < n; ++p) position[order.vertex[p]] = p;
  // The graph over positions, as sets (the levels add edges).
  std::vector<std::set<uint32_t>> graph(n);
  const animc::VertexAdjacency adjacency(topology);
  for (uint32_t v = 0; v < n; ++v)
    for (const uint32_t* w = adjacency.begin(v); w != adjacency.end(v); ++w) graph[position[v]].insert(position[*w]);
  std::vector<bool> removed(n, false);
  uint32_t remaining = n;
  std::vector<std::vector<uint32_t>> levels;  // finest first
  std::vector<std::vector<std::vector<uint32_t>>> level_predictors;
  while (remaining > kCoarsest && int(levels.size()) < max_levels) {
    std::vector<bool> blocked(n, false);
    std::vector<uint32_t> fine;
    for (uint32_t p = 0; p < n; ++p) {  // greedy, in today's coding order
      if (removed[p] || blocked[p] || graph[p].empty()) continue;
      fine.push_back(p);
      for (uint32_t q : graph[p]) blocked[q] = true;
    }
    if (fine.empty() || remaining - fine.size() < 1) break;
    std::vector<std::vector<uint32_t>> predictors;
    for (uint32_t p : fine) {
      predictors.emplace_back(graph[p].begin(), graph[p].end());
      removed[p] = true;
    }
    for (uint32_t p : fine) {  // the neighbours of a vertex taken out become neighbours
      for (uint32_t a : graph[p]) {
        graph[a].erase(p);
        for (uint32_t b : graph[p])
          if (a != b) graph[a].insert(b);
      }
      graph[p].clear();
    }
    remaining -= uint32_t(fine.size());
    levels.push_back(std::move(fine));
    level_predictors.push_back(std::move(predictors));
  }
  Hierarchy h;
  h.first.push_back(0);
  // The coarsest vertices in today's order, each from its coded neighbours in the last graph.
  std::vector<bool> coded(n, false);
  for (uint32_t p = 0; p < n; ++p) {
    if (removed[p]) continue;
    h.sequence.push_back(p);
    h.level.push_back(kLevelContexts - 1);
    for (uint32_t q : graph[p])
      if (coded[q]) h.predictors.push_back(q);
    h.first.push_back(uint32_t(h.predictors.size()));
    coded[p] = true;
  }
  for (size_t l = levels.size(); l-- > 0;) {
    for (size_t i = 0; i < levels[l].size(); ++i) {
      h.sequence.push_back(levels[l][i]);
      h.level.push_back(std::min<int>(int(l), kLevelContexts - 2));
      for (uint32_t q : level_predictors[l][i]) h.predictors.push_back(q);
      h.first.push_back(uint32_t(h.predictors.size()));
    }
  }
  return h;
}

size_t hierarchyBytes(const TrajectoryGroup& g, const Hierarchy& hierarchy) {
  const uint32_t K = g.components;
  const int per_level = kBands * 3;
  std::vector<ClassedIntegerModel> models(size_t(per_level) * kLevelContexts);
  std::vector<uint8_t> out;
  animc::RangeEncoder rc(out);
  animc::RawBitWriter raw;
  for (size_t i = 0; i < hierarchy.sequence.size(); ++i) {
    const uint32_t p = hierarchy.sequence[i], begin = hierarchy.first[i], end = hierarchy.first[i + 1];
    for (uint32_t k = 0; k < K; ++k) {
      int64_t sum = 0, prediction = 0;
      int kind = 0;
      for (uint32_t j = begin; j < end; ++j) sum += g.coefficients[size_t(hierarchy.predictors[j]) * K + k];
      if (begin != end) {
        prediction = roundedMean(sum, int64_t(end - begin));
        kind = prediction == 0 ? 1 : 2;
      }
      const int64_t residual = g.coefficients[size_t(p) * K + k] - prediction;
      const int context = coefficientBand(k) * 3 + kind + per_level * hierarchy.level[i];
      animc::encodeClassed(rc, raw, models[size_t(context)], residual);
    }
  }
  rc.finish();
  raw.appendTo(out);
  return out.size();
}

size_t codedBytes(const TrajectoryGroup& g, const CodingOrder& order, const Neighbourhood& h, const Variant& v) {
  const uint32_t n = uint32_t(order.vertex.size()), K = g.components;
  const std::vector<float> factor = v.shrunk ? shrinkFactors(g, h) : std::vector<float>(kBands, 1.0f);
  std::vector<ClassedIntegerModel> models(size_t(v.contexts));
  std::vector<int64_t> residual(size_t(n) * K, 0);
  std::vector<uint8_t> out;
  animc::RangeEncoder rc(out);
  animc::RawBitWriter raw;
  for (uint32_t p = 0; p < n; ++p) {
    const uint32_t begin = order.first[p], end = order.first[p + 1];
    int64_t previous = 0;
    for (uint32_t k = 0; k < K; ++k) {
      const size_t i = size_t(p) * K + k;
      int64_t prediction = 0, sum_abs = 0;
      int kind = 0;
      if (begin != end && v.predicted) {
        int64_t sum = 0;
        for (uint32_t j = begin; j < end; ++j) {
          sum += g.coefficients[size_t(order.earlier[j]) * K + k];
          const int64_t r = residual[size_t(order.earlier[j]) * K + k];
          sum_abs += r < 0 ? -r : r;
        }
        prediction = v.shrunk ? int64_t(std::floor(double(factor[coefficientBand(k)]) * h.mean[i] + 0.5))
                              : roundedMean(sum, int64_t(end - begin));
        kind = prediction == 0 ? 1 : 2;
      }
      residual[i] = g.coefficients[i] - prediction;
      const int context =
          v.context(k, kind, magnitudeContext(previous), activityContext(sum_abs, int64_t(end - begin)));
      animc::encodeClassed(rc, raw, models[size_t(context)], residual[i]);
      previous = residual[i];
    }
  }
  rc.finish();
  raw.appendTo(out);
  return out.size() + (v.shrunk ? 4 * kBands : 0);
}

int measure(const std::string& path) {
  TrajectoryFile file;
  if (!file.open("trajectory_contexts", path)) return 1;
  const CodingOrder& order = *file.order;
  const animc::Topology& topology = file.source->topology();
  const Hierarchy levels[2] = {buildHierarchy(topology, order, INT32_MAX), buildHierarchy(topology, order, 1)};
  const std::vector<Variant> all = variants();
  std::vector<double> bytes(all.size(), 0), hierarchy_bytes(2, 0);
  std::vector<uint8_t> payload;
  for (size_t group = 0; group < file.groups(); ++group) {
    TrajectoryGroup g;
    if (!file.read(group, payload, g)) return 1;
    const Neighbourhood h = neighbourMeans(g, order);
    for (size_t v = 0; v < all.size(); ++v) bytes[v] += double(codedBytes(g, order, h, all[v]));
    for (int a = 0; a < 2; ++a) hierarchy_bytes[a] += double(hierarchyBytes(g, levels[a]));
  }
  std::printf("{\"file\": \"%s\", \"vertices\": %u, \"frames\": %lld", path.c_str(), unsigned(order.vertex.size()),
              (long long)file.source->frameCount());
  for (size_t v = 0; v < all.size(); ++v) std::printf(", \"%s\": %.0f", all[v].name.c_str(), bytes[v]);
  std::printf(", \"hierarchy\": %.0f, \"one level\": %.0f}\n", hierarchy_bytes[0], hierarchy_bytes[1]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return measureEach(argc, argv, measure); }
