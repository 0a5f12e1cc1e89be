#include "codecs/affine_octree/octree_shared.h"

#include <algorithm>
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

void splitCell(const Cell& cell, const std::vector<double>& unit_xyz, std::vector<uint32_t>& order,
               std::vector<uint32_t>& scratch, Cell children[8]) {
  const double half = cell.side * 0.5;
  const double mid[3] = {cell.corner[0] + half, cell.corner[1] + half, cell.corner[2] + half};
  const uint32_t n = cell.end - cell.begin;
  // scratch holds each vertex's octant first, then the reordered indices (counting sort).
  scratch.resize(2 * size_t(order.size()));
  uint32_t* octant = scratch.data();
  uint32_t* sorted = scratch.data() + order.size();
  uint32_t count[8] = {0};
  for (uint32_t i = 0; i < n; ++i) {
    const double* p = &unit_xyz[3 * size_t(order[cell.begin + i])];
    const uint32_t o = uint32_t(p[0] >= mid[0]) | uint32_t(p[1] >= mid[1]) << 1 | uint32_t(p[2] >= mid[2]) << 2;
    octant[i] = o;
    ++count[o];
  }
  uint32_t start[8];
  uint32_t at = cell.begin;
  for (int c = 0; c < 8; ++c) {
    start[c] = at - cell.begin;
    children[c].begin = at;
    at += count[c];
    children[c].end = at;
    children[c].side = half;
    children[c].depth = cell.depth + 1;
    for (int a = 0; a < 3; ++a) children[c].corner[a] = cell.corner[a] + (((c >> a) & 1) ? half : 0.0);
  }
  for (uint32_t i = 0; i < n; ++i) sorted[start[octant[i]]++] = order[cell.begin + i];
  std::memcpy(&order[cell.begin], sorted, n * sizeof(uint32_t));
}

}  // namespace animc
