// SPDX-License-Identifier: Apache-2.0
#include "codecs/affine_octree/octree_shared.h"

#include <algorithm>

#include "core/simd_math.h"

namespace animc {

namespace {

// Bit i of a 10-bit value moved to bit 3i, for interleaving three coordinates into a Morton
// key with one lookup each (4 KB, stays in cache).
constexpr int kSpreadBits = 10;
struct SpreadTable {
  uint32_t bits[1 << kSpreadBits];
  constexpr SpreadTable() : bits() {
    for (uint32_t x = 0; x < (1u << kSpreadBits); ++x)
      for (int i = 0; i < kSpreadBits; ++i) bits[x] |= ((x >> i) & 1u) << (3 * i);
  }
};
constexpr SpreadTable kSpread;

constexpr int kLowBits = OctreePartition::kGridBits - kSpreadBits;

// A unit coordinate times scale, clamped to [0, top], is its grid coordinate: on a grid of
// 2^16 for deep trees, else of 2^kSpreadBits, whose coordinates are the 16-bit ones shifted
// right by kLowBits (the scalings are exact, and the clamps agree) without the shift.
struct Grid {
  double scale, top;
  explicit Grid(bool deep) {
    const int bits = deep ? OctreePartition::kGridBits : kSpreadBits;
    scale = double(1u << bits);
    top = double((1u << bits) - 1);
  }
};

// Interleaved top kSpreadBits bits of the three coordinates, then (for trees deeper than
// kSpreadBits levels) the low bits.
uint64_t mortonKey(const uint32_t g[3], bool deep) {
  uint64_t key = 0;
  if (!deep) {
    for (int a = 0; a < 3; ++a) key |= uint64_t(kSpread.bits[g[a]]) << a;
    return key << (3 * kLowBits);
  }
  for (int a = 0; a < 3; ++a) key |= uint64_t(kSpread.bits[g[a] >> kLowBits]) << a;
  key <<= 3 * kLowBits;
  for (int a = 0; a < 3; ++a) key |= uint64_t(kSpread.bits[g[a] & ((1u << kLowBits) - 1)]) << a;
  return key;
}

// floor(p·2^16) has, as its k-th bit from the top, whether p >= mid of its depth-k cell (cell
// bounds are dyadic, so both are exact); p = 1 clamps into the last cell, as does anything
// beyond, and anything below 0 (or NaN) into the first. x and y go through one Pair; the
// clamps are lane-wise std::max(0, g) and std::min(top, g).
void gridCoordinates(const double* p, const Grid& grid, uint32_t g[3]) {
  const Pair xy = minPair(splat(grid.top), maxPair(splat(0.0), loadPair(p) * splat(grid.scale)));
  const double z = std::min(grid.top, std::max(0.0, p[2] * grid.scale));
  g[0] = uint32_t(xy[0]);  // truncation = floor here
  g[1] = uint32_t(xy[1]);
  g[2] = uint32_t(z);
}

// The octant of depth d is bits s..s+2 of a key, s = octantShift(d): the top three bits for
// the root.
constexpr int kTopOctantShift = 3 * (OctreePartition::kGridBits - 1);
int octantShift(int depth) { return kTopOctantShift - 3 * depth; }
uint32_t octant(uint64_t key, int shift) { return uint32_t(key >> shift) & 7; }

// Splits run through the cell in blocks of at most kBlock vertices, so that eight 8-bit
// cursors fit one register: cursors in memory would make each increment wait for the
// previous one whenever neighbouring vertices share an octant, which they usually do.
constexpr uint32_t kBlock = 255;

uint32_t lane(uint64_t packed, uint32_t c) { return uint32_t(packed >> (8 * c)) & 0xFF; }

void mortonKeysPortable(const double* unit, size_t n, bool deep, uint64_t* keys) {
  const Grid grid(deep);
  for (size_t v = 0; v < n; ++v) {
    uint32_t g[3];
    gridCoordinates(&unit[3 * v], grid, g);
    keys[v] = mortonKey(g, deep);
  }
}

#if ANIMC_AVX2_PATH

// Four vertices (twelve coordinates, three Quads) at a time through the grid conversion,
// whose clamps are the lane-wise forms of gridCoordinates()'.
ANIMC_TARGET_AVX2 void mortonKeysAvx2(const double* unit, size_t n, bool deep, uint64_t* keys) {
  const Grid grid(deep);
  const Quad scale = splatQuad(grid.scale), top = splatQuad(grid.top), zero = splatQuad(0);
  size_t v = 0;
  for (; v + 4 <= n; v += 4) {
    uint32_t g[12];
    for (int k = 0; k < 3; ++k) {
      const Quad scaled = loadQuad(&unit[3 * v + 4 * k]) * scale;
      const Quad clamped = minQuad(top, maxQuad(zero, scaled));  // NaN to 0
      const IntQuad grid = __builtin_convertvector(clamped, IntQuad);  // truncation = floor here
      for (int l = 0; l < 4; ++l) g[4 * k + l] = uint32_t(grid[l]);
    }
    for (int j = 0; j < 4; ++j) keys[v + j] = mortonKey(&g[3 * j], deep);
  }
  mortonKeysPortable(unit + 3 * v, n - v, deep, keys + v);
}
#endif

}  // namespace

Cell OctreePartition::reset(const std::vector<double>& unit_xyz, int levels) {
  const uint32_t n = uint32_t(unit_xyz.size() / 3);
  const bool deep = levels > kSpreadBits;
  key_.resize(n);
  for (int b = 0; b < 2; ++b) order_[b].resize(kPadding + size_t(n));
  buckets_.resize(kPadding + 8 * size_t(std::min(n, kBucketCell)));
#if ANIMC_AVX2_PATH
  if (useAvx2(path_)) mortonKeysAvx2(unit_xyz.data(), n, deep, key_.data());
  else
#endif
    mortonKeysPortable(unit_xyz.data(), n, deep, key_.data());
  return restart();
}

OctreePartition::OctreePartition(const OctreePartition& whole, const Cell& cell) : whole_(&whole), path_(whole.path_) {
  const uint32_t n = cell.end - cell.begin;
  for (int b = 0; b < 2; ++b) order_[b].resize(kPadding + size_t(n));
  buckets_.resize(kPadding + 8 * size_t(std::min(n, kBucketCell)));
  std::copy(whole.vertices(cell), whole.vertices(cell) + n, &order_[cell.depth & 1][kPadding]);
}

Cell OctreePartition::restart() {
  const uint32_t n = uint32_t(key_.size());
  uint32_t* order = &order_[0][kPadding];
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  return Cell{0, n, 0};
}

namespace {

// The loops of a split, written once and compiled twice: for any x86-64 and for CPUs with
// AVX2 and BMI2, where the shifts by a variable amount (8 · octant) take one micro-operation
// instead of three. always_inline makes each wrapper below compile its own copy.

// One pass through the cell: each vertex, in order, to the next free slot of its octant's
// bucket (bucket c begins at c·n, so none can overflow). Within a block a vertex's slot is
// its bucket's fill before the block plus an 8-bit cursor held in one register; the fills
// only change between blocks. The buckets' sizes go to count.
__attribute__((always_inline)) inline void fillBucketsLoop(const uint64_t* key, const uint32_t* order, uint32_t n,
                                                           int shift, uint32_t* buckets, uint32_t count[8]) {
  size_t base[8];
  for (int c = 0; c < 8; ++c) base[c] = size_t(c) * n;
  for (uint32_t i = 0; i < n;) {
    const uint32_t block_end = n - i > kBlock ? i + kBlock : n;
    uint64_t cursors = 0;
    for (; i < block_end; ++i) {
      const uint32_t v = order[i];
      const uint32_t o = octant(key[v], shift);
      buckets[base[o] + lane(cursors, o)] = v;
      cursors += uint64_t(1) << (8 * o);
    }
    for (int c = 0; c < 8; ++c) base[c] += lane(cursors, c);
  }
  for (int c = 0; c < 8; ++c) count[c] = uint32_t(base[c] - size_t(c) * n);
}

// noinline: see cell_kernels.cpp (portable versions).
__attribute__((noinline)) void fillBucketsPortable(const uint64_t* key, const uint32_t* order, uint32_t n, int shift, uint32_t* buckets,
                         uint32_t count[8]) {
  fillBucketsLoop(key, order, n, shift, buckets, count);
}

#if ANIMC_AVX2_PATH
ANIMC_TARGET_AVX2 void fillBucketsAvx2(const uint64_t* key, const uint32_t* order, uint32_t n, int shift,
                                       uint32_t* buckets, uint32_t count[8]) {
  fillBucketsLoop(key, order, n, shift, buckets, count);
}
#endif

// Cells of at most kSmallCell vertices (most splits: leaves hold a few vertices) skip the
// buckets, whose eight copies are a fixed cost per split: a count pass, then each
// vertex straight to its child's next slot, the slots of all eight children as the 8-bit
// lanes of one register (their starts are a prefix sum of the counts, one multiplication).
// This costs more per vertex than the buckets, so only small cells take it.
constexpr uint32_t kSmallCell = 32;
static_assert(kSmallCell <= kBlock, "counts and slots of a small cell fit 8-bit lanes");

// Lane c: the sum of the lanes below c (no sum exceeds 255 here, so no lane carries).
uint64_t lanesBelow(uint64_t packed) { return (packed << 8) * 0x0101010101010101u; }

// Returns the children's sizes, packed.
__attribute__((always_inline)) inline uint64_t splitSmallLoop(const uint64_t* key, const uint32_t* order, uint32_t n,
                                                              int shift, uint32_t* out) {
  uint64_t counts = 0;
  for (uint32_t i = 0; i < n; ++i) counts += uint64_t(1) << (8 * octant(key[order[i]], shift));
  uint64_t slots = lanesBelow(counts);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t v = order[i];
    const uint32_t o = octant(key[v], shift);
    out[lane(slots, o)] = v;
    slots += uint64_t(1) << (8 * o);
  }
  return counts;
}

__attribute__((noinline)) uint64_t splitSmallPortable(const uint64_t* key, const uint32_t* order, uint32_t n,
                                                      int shift, uint32_t* out) {
  return splitSmallLoop(key, order, n, shift, out);
}

#if ANIMC_AVX2_PATH
ANIMC_TARGET_AVX2 uint64_t splitSmallAvx2(const uint64_t* key, const uint32_t* order, uint32_t n, int shift,
                                          uint32_t* out) {
  return splitSmallLoop(key, order, n, shift, out);
}
#endif

// Copies n indices in chunks of kCopyChunk from the back, and always at least one chunk: the
// copy may begin up to kCopyChunk - 1 indices (a whole chunk when n = 0) before the ranges,
// in both arrays, but has no branch that depends on n when n <= kCopyChunk, the usual case
// (a library call or an exact loop costs more than the copy itself, through its call or its
// mispredicted exits).
constexpr int64_t kCopyChunk = 8;
typedef uint32_t IndexChunk __attribute__((vector_size(4 * kCopyChunk), aligned(4)));
void copyBackwards(const uint32_t* from, uint32_t n, uint32_t* to) {
  int64_t k = n;
  do {
    k -= kCopyChunk;
    *reinterpret_cast<IndexChunk*>(to + k) = *reinterpret_cast<const IndexChunk*>(from + k);
  } while (k > 0);
}

}  // namespace

// The cell's vertices are sorted into eight buckets, one per octant, in one pass, then copied
// out to the children (a count pass and then a scatter pass straight to the children costs
// more per vertex than the copy). Children are filled from the
// last one down, so that whatever a copy writes before its child's range lies either in a
// child still to be filled or before the cell, where every cell has been walked already
// (the walk is depth first, and a cell's list is dead once it is split); the buffers have
// kPadding slots in front for that.
void OctreePartition::split(const Cell& cell, Cell children[8]) {
  const uint32_t n = cell.end - cell.begin;
  if (n <= kSmallCell) return splitSmall(cell, children);
  if (n > kBucketCell) return splitLarge(cell, children);
  const uint32_t* order = vertices(cell);
  const int shift = octantShift(cell.depth);
  static_assert(kCopyChunk <= kPadding, "a copy may reach kCopyChunk slots before its range");
  uint32_t count[8];
#if ANIMC_AVX2_PATH
  if (useAvx2(path_))
    fillBucketsAvx2(keys(), order, n, shift, &buckets_[kPadding], count);
  else
#endif
    fillBucketsPortable(keys(), order, n, shift, &buckets_[kPadding], count);
  uint32_t* out = &order_[(cell.depth & 1) ^ 1][kPadding + cell.begin];
  const uint32_t* buckets = &buckets_[kPadding];
  uint32_t end = n;
  for (int c = 7; c >= 0; --c) {
    end -= count[c];
    children[c] = Cell{cell.begin + end, cell.begin + end + count[c], cell.depth + 1};
    copyBackwards(buckets + size_t(c) * n, count[c], out + end);
  }
}

// The few cells above kBucketCell vertices (the top levels of a large mesh's tree) take a
// count pass and then each vertex straight to its child's next slot.
void OctreePartition::splitLarge(const Cell& cell, Cell children[8]) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* order = vertices(cell);
  const int shift = octantShift(cell.depth);
  uint32_t* out = &order_[(cell.depth & 1) ^ 1][kPadding + cell.begin];
  uint32_t count[8] = {}, slot[8];
  const uint64_t* key = keys();
  for (uint32_t i = 0; i < n; ++i) ++count[octant(key[order[i]], shift)];
  uint32_t begin = 0;
  for (int c = 0; c < 8; ++c) {
    slot[c] = begin;
    children[c] = Cell{cell.begin + begin, cell.begin + begin + count[c], cell.depth + 1};
    begin += count[c];
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t v = order[i];
    out[slot[octant(key[v], shift)]++] = v;
  }
}

void OctreePartition::splitSmall(const Cell& cell, Cell children[8]) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* order = vertices(cell);
  const int shift = octantShift(cell.depth);
  uint32_t* out = &order_[(cell.depth & 1) ^ 1][kPadding + cell.begin];
#if ANIMC_AVX2_PATH
  const uint64_t counts =
      useAvx2(path_) ? splitSmallAvx2(keys(), order, n, shift, out) : splitSmallPortable(keys(), order, n, shift, out);
#else
  const uint64_t counts = splitSmallPortable(keys(), order, n, shift, out);
#endif
  const uint64_t starts = lanesBelow(counts);
  for (int c = 0; c < 8; ++c) {
    const uint32_t begin = cell.begin + lane(starts, c);
    children[c] = Cell{begin, begin + lane(counts, c), cell.depth + 1};
  }
}

}  // namespace animc
