// SPDX-License-Identifier: Apache-2.0
// Positions of one frame on their own, the intra frames of both codecs (the first frame of
// every group): positions on a uniform grid anchored at the frame's minimum corner, each vertex predicted from the already decoded neighbours with a
// lower index (the mesh is known to both sides), residuals through the range coder.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/adjacency.h"
#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

class StaticPositionCoder {
 public:
  // Keeps a reference to topology, which must outlive the coder.
  explicit StaticPositionCoder(const Topology& topology) : topology_(topology) {}

  // step: grid spacing in the frame's units (> 0). Appends the payload to out and leaves the
  // reconstruction (what the decoder will produce) in recon.
  void encode(const std::vector<double>& xyz, double step, std::vector<uint8_t>& out,
              std::vector<double>& recon) const;
  Status decode(ByteReader& in, std::vector<double>& recon) const;

 private:
  void predict(const VertexAdjacency& adjacency, const std::vector<int64_t>& q, uint32_t v, int64_t pred[3]) const;
  // Built when the first frame is coded: the decoder of an auto file holds a coder for each
  // candidate, most of which never see a frame, and a large mesh's rows take a while to build.
  const VertexAdjacency& adjacency() const;

  const Topology& topology_;
  mutable std::unique_ptr<const VertexAdjacency> adjacency_;
};

}  // namespace animc
