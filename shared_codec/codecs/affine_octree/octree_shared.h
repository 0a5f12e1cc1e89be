// What the Affine-Octree encoder and decoder compute identically from the reference frame:
// its bounding cube, the normalised positions, and the vertex lists of the octree cells.
#pragma once
#include <cstdint>
#include <vector>

namespace animc {

// The root cube of the paper: tight bounding cube of the reference frame, side S.
struct RootCube {
  double min[3] = {0, 0, 0};
  double side = 1;
};

// Positions are xyz-interleaved doubles.
RootCube boundingCube(const std::vector<double>& xyz);
void normalize(const RootCube& cube, const std::vector<double>& xyz, std::vector<double>& out);

// A cell: its corner and side in normalised units and the range [begin, end) of `order`
// holding its vertices.
struct Cell {
  double corner[3];
  double side;
  uint32_t begin, end;
  int depth;
};

// Reorders order[cell.begin, cell.end) by child octant (bit 0 = x upper half, bit 1 = y,
// bit 2 = z) and fills the 8 children; children may be empty.
void splitCell(const Cell& cell, const std::vector<double>& unit_xyz, std::vector<uint32_t>& order,
               std::vector<uint32_t>& scratch, Cell children[8]);

}  // namespace animc
