// SPDX-License-Identifier: Apache-2.0
// What the Affine-Octree encoder and decoder compute identically from the reference frame's
// normalised positions (codecs/common/root_cube.h): the vertex lists of the octree cells.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/common/root_cube.h"

namespace animc {

// A cell: its depth and the range [begin, end) of the partition's vertex order holding its
// vertices. (Its corner and side follow from the path to it; nothing needs them.)
struct Cell {
  uint32_t begin, end;
  int depth;
};

// The octree over a reference frame's normalised positions, as both sides walk it. Each
// vertex's cell at every depth comes from its 16-bit grid coordinates (computed once per
// frame) interleaved into one Morton key, so a split reads three bits of the vertex's key
// instead of comparing doubles. A vertex on a split plane goes to the upper child, exactly as
// the comparison p >= mid would put it. A split is stable, so every cell lists its vertices
// in increasing index order (the order both sides sum and code them in).
class OctreePartition {
 public:
  static constexpr int kGridBits = 16;  // >= the deepest allowed octree level

  explicit OctreePartition(SimdPath path) : path_(path) {}
  // A partition of one cell of `whole` alone, with lists of its own, so that the cell's subtree
  // can be walked on another thread: its root is rebased(cell). It reads whole's keys, which
  // must stay as they are while it is used.
  OctreePartition(const OctreePartition& whole, const Cell& cell);
  static Cell rebased(const Cell& cell) { return Cell{0, cell.end - cell.begin, cell.depth}; }

  // Takes a new reference frame and returns the root cell holding all its vertices. Cells
  // split down to depth `levels` at most (the tree's depth limit).
  Cell reset(const std::vector<double>& unit_xyz, int levels);
  // Back to the root of the last reset (the encoder's second pass).
  Cell restart();
  // Reorders the cell's vertices by child octant (bit 0 = x upper half, bit 1 = y, bit 2 = z)
  // and fills the 8 children; children may be empty.
  void split(const Cell& cell, Cell children[8]);
  const uint32_t* vertices(const Cell& cell) const { return order_[cell.depth & 1].data() + kPadding + cell.begin; }

 private:
  // By vertex index, never reordered: a split reads its keys through the vertex order, whose
  // indices increase within a cell, so the reads stream forward through this array, and a
  // split moves 4 bytes per vertex instead of 12.
  std::vector<uint64_t> key_;
  const OctreePartition* whole_ = nullptr;  // a branch's: the partition whose keys it reads
  const uint64_t* keys() const { return whole_ ? whole_->keys() : key_.data(); }
  // The vertices in partition order. A cell at depth d holds its range of buffer d % 2 and
  // its children are written to the other buffer: the parent's copy is dead once split, so
  // nothing is copied back.
  std::vector<uint32_t> order_[2];
  // split() of a cell of a few vertices, and of one too large for the buckets.
  void splitSmall(const Cell& cell, Cell children[8]);
  void splitLarge(const Cell& cell, Cell children[8]);

  // Scratch of split(): eight buckets of kBucketCell slots, for the cells no larger. Buckets as
  // large as the root would take 8 indices a vertex, more than all else the partition holds.
  static constexpr uint32_t kBucketCell = 1u << 16;
  std::vector<uint32_t> buckets_;
  // Slots in front of the vertex lists and the buckets, which split() may overwrite.
  static constexpr uint32_t kPadding = 8;
  SimdPath path_;
};

}  // namespace animc
