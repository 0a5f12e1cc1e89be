// SPDX-License-Identifier: Apache-2.0
// A stand-in for MeshLab's CMeshO with the element interface meshlab_adapter/layer_checks.h
// uses (vectors vert and face, IsD(), cP(), cV(k)), so that the adapter's checks run in tests
// and fuzzers built without MeshLab.
#pragma once
#include <array>
#include <vector>

namespace animc::testing {

struct StandInVertex {
  std::array<float, 3> p{};
  bool deleted = false;
  bool IsD() const { return deleted; }
  const float* cP() const { return p.data(); }
};

struct StandInFace {
  std::array<const StandInVertex*, 3> corner{};
  bool deleted = false;
  bool IsD() const { return deleted; }
  const StandInVertex* cV(int k) const { return corner[k]; }
};

struct StandInLayer {
  std::vector<StandInVertex> vert;
  std::vector<StandInFace> face;

  // A face on vertex slots a, b, c. Faces point into vert: add every vertex first.
  void addFace(size_t a, size_t b, size_t c, bool deleted = false) {
    face.push_back({{&vert[a], &vert[b], &vert[c]}, deleted});
  }
};

}  // namespace animc::testing
