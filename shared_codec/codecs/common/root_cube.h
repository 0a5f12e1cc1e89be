// SPDX-License-Identifier: Apache-2.0
// Frames in and out of their root cube, which every codec computes identically on both sides:
// the tight bounding cube of a frame, positions normalised into it and back, and a decoded
// frame as the floats a decoder returns. The frame-wide passes have an AVX2 version beside
// the portable one, computing each value with the same IEEE operations (root_cube.cpp).
#pragma once
#include <vector>

#include "core/simd_math.h"
#include "core/status.h"

namespace animc {

// The root cube of the paper: tight bounding cube of the reference frame, side S.
struct RootCube {
  double min[3] = {0, 0, 0};
  double side = 1;
};

// Positions are xyz-interleaved doubles.
RootCube boundingCube(const std::vector<double>& xyz);
// out = (xyz − cube.min) / cube.side, vertex by vertex; out may be xyz itself.
void normalise(SimdPath path, const RootCube& cube, const std::vector<double>& xyz, std::vector<double>& out);
// normalise()'s arithmetic for one point, (x − min) · (1 / side), x and y through a Pair: the
// portable normalise() and the passes that normalise points as they meet them share it.
struct PointNormaliser {
  Pair min_xy;
  double min_z, inv;
  explicit PointNormaliser(const RootCube& cube)
      : min_xy(loadPair(cube.min)), min_z(cube.min[2]), inv(1.0 / cube.side) {}
  void apply(const double* p, double out[3]) const {
    storePair(out, (loadPair(p) - min_xy) * splat(inv));
    out[2] = (p[2] - min_z) * inv;
  }
};
// out = cube.min + cube.side · unit, returning the bounding cube of out (what boundingCube(out)
// returns) found in the same pass.
RootCube denormalise(SimdPath path, const RootCube& cube, const std::vector<double>& unit,
                     std::vector<double>& out);
// A decoded frame as floats, what both codecs' decoders return; kCorrupt naming the first
// vertex with a coordinate that is NaN, infinite or beyond ±1e30, which no valid stream
// decodes to.
Status decodedFrameToFloats(SimdPath path, const std::vector<double>& frame, std::vector<float>& out);

}  // namespace animc
