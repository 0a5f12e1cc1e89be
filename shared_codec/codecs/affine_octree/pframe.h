// What both P-frame coders (paper and default profile) get for one frame, all positions in the
// normalised units of the reference frame's root cube.
#pragma once
#include <cstdint>
#include <vector>

namespace animc {

struct PFrameInput {
  const std::vector<double>* reference = nullptr;  // u: reconstructed frame f-1
  const std::vector<double>* before = nullptr;     // reconstructed frame f-2, or null
  const std::vector<double>* target = nullptr;     // encoder only: the original frame f
  double max_error = 0.01;                         // ME, in root-cube units
  int max_depth = 10;
};

}  // namespace animc
