// SPDX-License-Identifier: Apache-2.0
#include "seqio/mesh_checks.h"

#include <cmath>
#include <cstdio>

namespace animc {
namespace {

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

}  // namespace

Status checkCoordinate(double value, uint64_t vertex) {
  if (!std::isfinite(value))
    return badInput("vertex " + std::to_string(vertex) + " has a non-finite coordinate (" +
                    formatNumber(value) + ")");
  if (std::fabs(value) > kMaxCoordinate)
    return badInput("vertex " + std::to_string(vertex) + ": coordinate too large (" +
                    formatNumber(value) + ")");
  return Status();
}

Status checkPositions(const float* xyz, uint32_t vertex_count) {
  for (uint64_t i = 0; i < uint64_t(vertex_count) * 3; ++i) {
    // One comparison catches NaN, Inf and huge values; the detailed check names which.
    if (!(std::fabs(xyz[i]) <= kMaxCoordinate)) return checkCoordinate(xyz[i], i / 3);
  }
  return Status();
}

Status checkTopology(const Topology& topology) {
  if (topology.vertex_count == 0) return badInput("empty mesh (0 vertices)");
  if (topology.triangles.empty()) return badInput("empty mesh (0 triangles)");
  for (size_t t = 0; t < topology.triangles.size(); ++t) {
    for (uint32_t index : topology.triangles[t]) {
      if (index >= topology.vertex_count)
        return badInput("triangle " + std::to_string(t) + ": vertex index " +
                        std::to_string(index) + " out of range (" +
                        std::to_string(topology.vertex_count) + " vertices)");
    }
  }
  return Status();
}

Status checkSameTopology(const Topology& actual, const Topology& expected, const std::string& other_name,
                         const std::function<std::string(size_t)>& origin) {
  if (actual.vertex_count != expected.vertex_count)
    return badInput("vertex count " + std::to_string(actual.vertex_count) + " differs from " +
                    other_name + " (" + std::to_string(expected.vertex_count) + ")");
  if (actual.triangles.size() != expected.triangles.size())
    return badInput("face list differs from " + other_name + " (" +
                    std::to_string(actual.triangles.size()) + " triangles instead of " +
                    std::to_string(expected.triangles.size()) + ")");
  for (size_t t = 0; t < actual.triangles.size(); ++t) {
    if (actual.triangles[t] != expected.triangles[t])
      return badInput("face list differs from " + other_name + " (first at " +
                      (origin ? origin(t) : "triangle " + std::to_string(t)) + ")");
  }
  return Status();
}

}  // namespace animc
