// SPDX-License-Identifier: Apache-2.0
#include "container/connectivity_coder.h"

#include <algorithm>
#include <string>

#include "entropy/bit_tree.h"
#include "entropy/integer_coder.h"

namespace animc {
namespace {

enum Choice : uint32_t { kCorner0 = 0, kCorner1, kCorner2, kNextNew, kDelta };

struct ConnectivityModels {
  BitTreeModel<3> choice[3];  // by corner position in the triangle
  IntegerModel<3> delta;
};

uint32_t chooseFor(uint32_t index, const Triangle& previous, uint32_t next_new) {
  for (uint32_t k = 0; k < 3; ++k)
    if (previous[k] == index) return k;
  return index == next_new ? kNextNew : kDelta;
}

}  // namespace

void encodeConnectivity(const Topology& topology, std::vector<uint8_t>& out) {
  ConnectivityModels m;
  RangeEncoder rc(out);
  Triangle previous = {~0u, ~0u, ~0u};
  uint32_t next_new = 0;
  int64_t last = 0;
  for (const Triangle& t : topology.triangles) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t choice = chooseFor(t[c], previous, next_new);
      encodeTree(rc, m.choice[c], choice);
      if (choice == kDelta) encodeInt(rc, m.delta, c, int64_t(t[c]) - last);
      last = t[c];
      if (t[c] >= next_new) next_new = t[c] + 1;
    }
    previous = t;
  }
  rc.finish();
}

Status decodeConnectivity(ByteReader in, uint32_t vertex_count, uint64_t triangle_count,
                          Topology& topology) {
  ConnectivityModels m;
  RangeDecoder rc(in.cursor(), in.remaining());
  topology.vertex_count = vertex_count;
  topology.triangles.clear();
  // A section cannot honestly hold more than ~100 triangles per byte; reserve no more.
  topology.triangles.reserve(size_t(std::min<uint64_t>(triangle_count, 100 * uint64_t(in.remaining()) + 16)));
  Triangle previous = {~0u, ~0u, ~0u};
  uint32_t next_new = 0;
  int64_t last = 0;
  for (uint64_t i = 0; i < triangle_count; ++i) {
    Triangle t;
    for (int c = 0; c < 3; ++c) {
      const uint32_t choice = decodeTree(rc, m.choice[c]);
      int64_t index;
      if (choice < 3) index = previous[choice];
      else if (choice == kNextNew) index = next_new;
      else if (choice == kDelta) index = last + decodeInt(rc, m.delta, c);
      else return corrupt("connectivity: unknown index code in triangle " + std::to_string(i));
      if (index < 0 || index >= int64_t(vertex_count))
        return corrupt("connectivity: triangle " + std::to_string(i) + " uses vertex " +
                       std::to_string(index) + " of " + std::to_string(vertex_count));
      t[c] = uint32_t(index);
      last = index;
      if (t[c] >= next_new) next_new = t[c] + 1;
    }
    if (rc.overran()) return corrupt("connectivity: coded data ends early");
    topology.triangles.push_back(t);
    previous = t;
  }
  return Status();
}

}  // namespace animc
