// SPDX-License-Identifier: Apache-2.0
// Animations for the unit tests: a small synthetic bumpy grid that deforms smoothly, moves
// rigidly, or both; and real sequences, from the data folders sequenceDir() searches.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/memory_sequence.h"
#include "metrics/sequence_metrics.h"
#include "seqio/sequence_io.h"

namespace animc::testing_support {

inline Topology gridTopology(int nx, int ny) {
  Topology t;
  t.vertex_count = uint32_t(nx * ny);
  for (int y = 0; y + 1 < ny; ++y)
    for (int x = 0; x + 1 < nx; ++x) {
      const uint32_t a = uint32_t(y * nx + x), b = a + 1, c = a + uint32_t(nx), d = c + 1;
      t.triangles.push_back({a, b, d});
      t.triangles.push_back({a, d, c});
    }
  return t;
}

// Frame f of a grid: a sine wave travelling over it (deform) and a rotation plus
// translation (rigid).
inline std::vector<float> gridFrame(int nx, int ny, int f, double deform, double rigid) {
  std::vector<float> xyz;
  const double angle = rigid * 0.05 * f;
  const double ca = std::cos(angle), sa = std::sin(angle);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const double px = double(x) / (nx - 1), py = double(y) / (ny - 1);
      const double pz = 0.2 * std::sin(7 * px + 3 * py) + deform * 0.1 * std::sin(6 * px - 0.3 * f);
      const double rx = ca * px - sa * pz + rigid * 0.02 * f;
      const double rz = sa * px + ca * pz;
      xyz.push_back(float(rx));
      xyz.push_back(float(py + rigid * 0.01 * f));
      xyz.push_back(float(rz));
    }
  return xyz;
}

inline MemorySequence gridSequence(int nx, int ny, int frames, double deform, double rigid) {
  std::vector<std::vector<float>> all;
  for (int f = 0; f < frames; ++f) all.push_back(gridFrame(nx, ny, f, deform, rigid));
  return MemorySequence(gridTopology(nx, ny), std::move(all), 25.0, "grid");
}

// The metrics library's figures of decoded against the original's frames; decoded must hold
// as many frames as the original.
inline SequenceMetrics decodedMetrics(const MemorySequence& original, const std::vector<std::vector<float>>& decoded) {
  EXPECT_EQ(decoded.size(), original.frames().size());
  MetricsAccumulator m(original.topology().vertex_count);
  for (size_t f = 0; f < decoded.size() && f < original.frames().size(); ++f)
    m.addFrame(original.frames()[f].data(), decoded[f].data());
  return m.finish();
}

// The KG error, percent.
inline double kgError(const MemorySequence& original, const std::vector<std::vector<float>>& decoded) {
  return decodedMetrics(original, decoded).kg_error;
}

// The folders searched for real sequences, in order: $ANIMC_DATA_DIR when set, the
// repository's tests/data (the sequences whose licences let it carry them), then the folder
// the build was configured with (ANIMC_EXTRA_DATA_DIR, by default ../shared/data).
inline std::vector<std::string> dataDirs() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("ANIMC_DATA_DIR"); env && *env) dirs.push_back(env);
  dirs.push_back(ANIMC_REPO_DATA_DIR);
  dirs.push_back(ANIMC_EXTRA_DATA_DIR);
  return dirs;
}

// The folder holding <name>/<name>.pc2.xz and <name>/<name>.ply, or "" when none does.
inline std::string sequenceDir(const std::string& name) {
  for (const std::string& dir : dataDirs()) {
    const std::string folder = dir + "/" + name + "/";
    if (std::ifstream(folder + name + ".pc2.xz") && std::ifstream(folder + name + ".ply")) return folder;
  }
  return "";
}

inline std::string missingSequenceMessage(const std::string& name) {
  std::string where;
  for (const std::string& dir : dataDirs()) where += (where.empty() ? "" : ", ") + dir;
  return "not run: sequence " + name + " not found (looked in " + where +
         "; set ANIMC_DATA_DIR to a folder holding it)";
}

// The first `frames` frames of a real sequence (all of them when frames <= 0). The test must
// have checked that the sequence is there (ANIMC_REQUIRE_SEQUENCE); a missing one fails it.
inline MemorySequence realSequence(const std::string& name, int frames) {
  const std::string dir = sequenceDir(name);
  if (dir.empty()) {
    ADD_FAILURE() << missingSequenceMessage(name);
    return MemorySequence(Topology(), {});
  }
  auto source = openSequence(dir + name + ".pc2.xz", dir + name + ".ply");
  EXPECT_TRUE(source.ok()) << source.status().message();
  if (!source.ok()) return MemorySequence(Topology(), {});
  auto read = readFrames(*source.value(), frames > 0 ? frames : std::numeric_limits<int64_t>::max());
  EXPECT_TRUE(read.ok()) << read.status().message();
  if (!read.ok()) return MemorySequence(Topology(), {});
  return MemorySequence(source.value()->topology(), std::move(read).value(), 25.0, name);
}

}  // namespace animc::testing_support

// Skips the test, with one line saying why, when a real sequence it needs is in no data folder
// (chickenCrossing's terms keep it out of the repository).
#define ANIMC_REQUIRE_SEQUENCE(name)                                                         \
  do {                                                                                       \
    if (::animc::testing_support::sequenceDir(name).empty())                                 \
      GTEST_SKIP() << ::animc::testing_support::missingSequenceMessage(name);                \
  } while (0)
