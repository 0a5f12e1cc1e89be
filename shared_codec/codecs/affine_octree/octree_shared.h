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

// A cell: its corner and side in normalised units, its depth, and the range [begin, end) of
// the partition's vertex order holding its vertices.
struct Cell {
  double corner[3];
  double side;
  uint32_t begin, end;
  int depth;
};

// The octree over a reference frame's normalised positions, as both sides walk it. Each
// vertex's cell at every depth comes from its 16-bit grid coordinates (computed once per
// frame), so a split tests bits instead of comparing doubles. A vertex on a split plane goes
// to the upper child, exactly as the comparison p >= mid would put it.
class OctreePartition {
 public:
  static constexpr int kGridBits = 16;  // >= the deepest allowed octree level

  // Takes a new reference frame and returns the root cell holding all its vertices.
  Cell reset(const std::vector<double>& unit_xyz);
  // Back to the root with the same reference (the encoder's second pass).
  Cell restart();
  // Reorders the cell's vertices by child octant (bit 0 = x upper half, bit 1 = y, bit 2 = z)
  // and fills the 8 children; children may be empty.
  void split(const Cell& cell, Cell children[8]);
  const uint32_t* vertices(const Cell& cell) const { return order_.data() + cell.begin; }
  uint32_t vertex(uint32_t position) const { return order_[position]; }

 private:
  std::vector<uint16_t> grid_;  // x y z per vertex
  std::vector<uint32_t> order_, scratch_;
  std::vector<uint8_t> octant_;
};

}  // namespace animc
