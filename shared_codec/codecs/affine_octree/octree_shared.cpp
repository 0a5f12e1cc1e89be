#include "codecs/affine_octree/octree_shared.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace animc {

RootCube boundingCube(const std::vector<double>& xyz) {
  RootCube cube;
  double max[3];
  for (int a = 0; a < 3; ++a) cube.min[a] = max[a] = xyz.empty() ? 0.0 : xyz[a];
  for (size_t i = 0; i < xyz.size(); i += 3) {
    for (int a = 0; a < 3; ++a) {
      cube.min[a] = std::min(cube.min[a], xyz[i + a]);
      max[a] = std::max(max[a], xyz[i + a]);
    }
  }
  double side = 0;
  for (int a = 0; a < 3; ++a) side = std::max(side, max[a] - cube.min[a]);
  // A frame collapsed to one point still needs a scale; any positive one will do.
  cube.side = side > 0 ? side : 1.0;
  return cube;
}

void normalize(const RootCube& cube, const std::vector<double>& xyz, std::vector<double>& out) {
  out.resize(xyz.size());
  const double inv = 1.0 / cube.side;
  for (size_t i = 0; i < xyz.size(); i += 3)
    for (int a = 0; a < 3; ++a) out[i + a] = (xyz[i + a] - cube.min[a]) * inv;
}

Cell OctreePartition::reset(const std::vector<double>& unit_xyz) {
  const double scale = double(1u << kGridBits);
  const double top = double((1u << kGridBits) - 1);
  grid_.resize(unit_xyz.size());
  // floor(p·2^16) has, as its k-th bit from the top, whether p >= mid of its depth-k cell
  // (cell bounds are dyadic, so both are exact); p = 1 clamps into the last cell.
  for (size_t i = 0; i < unit_xyz.size(); ++i) {
    const double g = unit_xyz[i] * scale;
    grid_[i] = uint16_t(g > 0 ? (g < top ? g : top) : 0.0);  // truncation = floor here
  }
  return restart();
}

Cell OctreePartition::restart() {
  const uint32_t n = uint32_t(grid_.size() / 3);
  order_.resize(n);
  for (uint32_t i = 0; i < n; ++i) order_[i] = i;
  return Cell{{0, 0, 0}, 1.0, 0, n, 0};
}

void OctreePartition::split(const Cell& cell, Cell children[8]) {
  const int shift = kGridBits - 1 - cell.depth;
  const uint32_t n = cell.end - cell.begin;
  octant_.resize(order_.size());
  scratch_.resize(order_.size());
  uint32_t count[8] = {0};
  for (uint32_t i = 0; i < n; ++i) {
    const uint16_t* g = &grid_[3 * size_t(order_[cell.begin + i])];
    const uint8_t o = uint8_t(((g[0] >> shift) & 1) | ((g[1] >> shift) & 1) << 1 | ((g[2] >> shift) & 1) << 2);
    octant_[i] = o;
    ++count[o];
  }
  const double half = cell.side * 0.5;
  uint32_t start[8];
  uint32_t at = 0;
  for (int c = 0; c < 8; ++c) {
    start[c] = at;
    children[c].begin = cell.begin + at;
    at += count[c];
    children[c].end = cell.begin + at;
    children[c].side = half;
    children[c].depth = cell.depth + 1;
    for (int a = 0; a < 3; ++a) children[c].corner[a] = cell.corner[a] + (((c >> a) & 1) ? half : 0.0);
  }
  for (uint32_t i = 0; i < n; ++i) scratch_[start[octant_[i]]++] = order_[cell.begin + i];
  std::memcpy(&order_[cell.begin], scratch_.data(), n * sizeof(uint32_t));
}

}  // namespace animc
