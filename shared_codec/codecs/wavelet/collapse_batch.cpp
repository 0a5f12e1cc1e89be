// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/collapse_batch.h"

namespace animc {

Collapse recordCollapse(const LevelMesh& mesh, const CollapseOptionCache& cache, const Candidate& c,
                        const VertexRing& ring, int level, ProgressiveMesh& pm) {
  Collapse record;
  record.vertex = c.vertex;
  record.target = c.target;
  record.ring_begin = uint32_t(pm.ring.size());
  record.ring_size = uint16_t(ring.size());
  record.level = uint16_t(level);
  record.kind = c.kind;
  const size_t k = ring.size();
  for (size_t i = 0; i < k; ++i) {
    pm.ring.push_back(ring[i]);
    const bool wraps = c.kind != CollapseKind::kInterior && i + 1 == k;  // no edge from last to first
    pm.flap.push_back(wraps ? kNoVertex : cache.flapAcross(mesh, ring[i], ring[i + 1 == k ? 0 : i + 1], c.vertex));
  }
  return record;
}

}  // namespace animc
