// SPDX-License-Identifier: Apache-2.0
// What both P-frame coders (paper and default profile) get for one frame, positions in the
// normalised units of the reference frame's root cube (but for `before`).
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/affine_octree/octree_shared.h"

namespace animc {

struct PFrameInput {
  const std::vector<double>* reference = nullptr;  // u: reconstructed frame f-1
  // Reconstructed frame f-2, or null, in world units: the default profile normalises each
  // point into `cube` as it gathers it, which saves a pass over the frame.
  const std::vector<double>* before = nullptr;
  RootCube cube;  // the reference frame's root cube
  const std::vector<double>* target = nullptr;     // encoder only: the original frame f
  double max_error = 0.01;                         // ME, in root-cube units
  int max_depth = 10;
};

}  // namespace animc
