// Small synthetic animations for the unit tests: a bumpy grid that deforms smoothly, moves
// rigidly, or both. Real data comes from ANIMC_SHARED_DATA in the tests that need it.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "core/memory_sequence.h"

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

}  // namespace animc::testing_support
