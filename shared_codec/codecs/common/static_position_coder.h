// SPDX-License-Identifier: Apache-2.0
// Positions of one frame on their own, the intra frames of both codecs (the first frame of
// every group): positions on a uniform grid anchored at the frame's minimum corner, each vertex predicted from the already decoded neighbours with a
// lower index (the mesh is known to both sides), residuals through the range coder.
#pragma once
#include <cstdint>
#include <vector>

#include "core/adjacency.h"
#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

class StaticPositionCoder {
 public:
  explicit StaticPositionCoder(const Topology& topology);

  // step: grid spacing in the frame's units (> 0). Appends the payload to out and leaves the
  // reconstruction (what the decoder will produce) in recon.
  void encode(const std::vector<double>& xyz, double step, std::vector<uint8_t>& out,
              std::vector<double>& recon) const;
  Status decode(ByteReader& in, std::vector<double>& recon) const;

 private:
  void predict(const std::vector<int64_t>& q, uint32_t v, int64_t pred[3]) const;

  uint32_t vertex_count_;
  VertexAdjacency adjacency_;
};

}  // namespace animc
