// SPDX-License-Identifier: Apache-2.0
// Every on-wire identifier of the codecs, in one place (docs/format.md 6.1 and 10.1 mirror
// this file). Ids are never reused: a change to a codec's bytes takes a new id or profile.
#pragma once
#include <cstdint>

namespace animc {

enum class CodecId : uint8_t {
  kAffineOctree = 1,  // docs/affine_octree.md
  kWavelet = 2,       // Guskov & Khodakovsky 2004 (docs/wavelet.md)
  kTrajectory = 3,    // trajectory PCA over frame groups (docs/trajectory.md)
  kAuto = 4,          // per group, the smallest of the others (docs/auto.md)
  kTrajectory2 = 5,   // trajectory PCA per part of the mesh (docs/trajectory.md, "Parts")
};

// Profiles of the Affine-Octree codec (its Profile parameter).
enum class Profile : uint8_t {
  kPaper = 0,       // the Affine-Octree paper as published (docs/affine_octree.md, "paper")
  kPredictive = 1,  // our predictive variant of the same octree, the default (docs/affine_octree.md)
};

}  // namespace animc
