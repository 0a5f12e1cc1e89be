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
// A unit coordinate times kGridScale, clamped to [0, kGridTop], is its grid coordinate.
constexpr double kGridScale = double(1u << OctreePartition::kGridBits);
constexpr double kGridTop = double((1u << OctreePartition::kGridBits) - 1);

// Interleaved top kSpreadBits bits of the three coordinates, then (for trees deeper than
// kSpreadBits levels) the low bits.
uint64_t mortonKey(const uint32_t g[3], bool deep) {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a) key |= uint64_t(kSpread.bits[g[a] >> kLowBits]) << a;
  key <<= 3 * kLowBits;
  if (deep)
    for (int a = 0; a < 3; ++a) key |= uint64_t(kSpread.bits[g[a] & ((1u << kLowBits) - 1)]) << a;
  return key;
}

// floor(p·2^16) has, as its k-th bit from the top, whether p >= mid of its depth-k cell (cell
// bounds are dyadic, so both are exact); p = 1 clamps into the last cell, as does anything
// beyond, and anything below 0 (or NaN) into the first. x and y go through one Pair; the
// clamps are lane-wise std::max(0, g) and std::min(top, g).
void gridCoordinates(const double* p, uint32_t g[3]) {
  const Pair xy = minPair(splat(kGridTop), maxPair(splat(0.0), loadPair(p) * splat(kGridScale)));
  const double z = std::min(kGridTop, std::max(0.0, p[2] * kGridScale));
  g[0] = uint32_t(xy[0]);  // truncation = floor here
  g[1] = uint32_t(xy[1]);
  g[2] = uint32_t(z);
}

// The octant of depth d is bits s..s+2 of a key, s = octantShift(d): the top three bits for
// the root.
constexpr int kTopOctantShift = 3 * (OctreePartition::kGridBits - 1);
int octantShift(int depth) { return kTopOctantShift - 3 * depth; }
int octant(uint64_t key, int shift) { return int((key >> shift) & 7); }

// Splits run through the cell in blocks of at most kBlock vertices, so that eight 8-bit
// counters fit one register: counters in memory would make each increment wait for the
// previous one whenever neighbouring vertices share an octant, which they usually do.
constexpr uint32_t kBlock = 255;

uint32_t lane(uint64_t packed, int c) { return uint32_t(packed >> (8 * c)) & 0xFF; }

void mortonKeysPortable(const double* unit, size_t n, bool deep, uint64_t* keys) {
  for (size_t v = 0; v < n; ++v) {
    uint32_t g[3];
    gridCoordinates(&unit[3 * v], g);
    keys[v] = mortonKey(g, deep);
  }
}

#if ANIMC_AVX2_PATH
typedef int Int4 __attribute__((vector_size(16)));

// Four vertices (twelve coordinates, three Quads) at a time through the grid conversion,
// whose clamps are the lane-wise forms of gridCoordinates()'.
ANIMC_TARGET_AVX2 void mortonKeysAvx2(const double* unit, size_t n, bool deep, uint64_t* keys) {
  const Quad scale = splatQuad(kGridScale), top = splatQuad(kGridTop), zero = splatQuad(0);
  size_t v = 0;
  for (; v + 4 <= n; v += 4) {
    uint32_t g[12];
    for (int k = 0; k < 3; ++k) {
      const Quad scaled = loadQuad(&unit[3 * v + 4 * k]) * scale;
      const Quad clamped = minQuad(top, maxQuad(zero, scaled));  // NaN to 0
      const Int4 grid = __builtin_convertvector(clamped, Int4);  // truncation = floor here
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
  for (int b = 0; b < 2; ++b) order_[b].resize(n);
#if ANIMC_AVX2_PATH
  if (cpuHasAvx2()) mortonKeysAvx2(unit_xyz.data(), n, deep, key_.data());
  else
#endif
    mortonKeysPortable(unit_xyz.data(), n, deep, key_.data());
  return restart();
}

Cell OctreePartition::restart() {
  const uint32_t n = uint32_t(key_.size());
  for (uint32_t i = 0; i < n; ++i) order_[0][i] = i;
  return Cell{0, n, 0};
}

void OctreePartition::split(const Cell& cell, Cell children[8]) {
  uint32_t count[8];
  countOctants(cell, count);
  uint32_t start[8];
  uint32_t at = 0;
  for (int c = 0; c < 8; ++c) {
    start[c] = at;
    children[c].begin = cell.begin + at;
    at += count[c];
    children[c].end = cell.begin + at;
    children[c].depth = cell.depth + 1;
  }
  scatter(cell, start);
}

namespace {

// The loops of a split, written once and compiled twice: for any x86-64 and for CPUs with
// AVX2 and BMI2, where the shifts by a variable amount (8 · octant) take one micro-operation
// instead of three. always_inline makes each wrapper below compile its own copy.
__attribute__((always_inline)) inline void countLoop(const uint64_t* key, const uint32_t* order, uint32_t n,
                                                     int shift, uint64_t* block_counts, uint32_t count[8]) {
  for (uint32_t i = 0, block = 0; i < n; ++block) {
    const uint32_t block_end = n - i > kBlock ? i + kBlock : n;
    uint64_t packed = 0;
    for (; i < block_end; ++i) packed += uint64_t(1) << (8 * octant(key[order[i]], shift));
    block_counts[block] = packed;
    for (int c = 0; c < 8; ++c) count[c] += lane(packed, c);
  }
}

// Stable counting-sort pass: each vertex to the next free slot of its octant. Within a block
// a vertex's slot is its block's base for the octant plus an 8-bit cursor held in one
// register; the bases only change between blocks.
__attribute__((always_inline)) inline void scatterLoop(const uint64_t* key, const uint32_t* order, uint32_t n,
                                                       int shift, const uint64_t* block_counts,
                                                       const uint32_t start[8], uint32_t* order_out) {
  uint32_t base[8];
  for (int c = 0; c < 8; ++c) base[c] = start[c];
  for (uint32_t i = 0, block = 0; i < n; ++block) {
    const uint32_t block_end = n - i > kBlock ? i + kBlock : n;
    uint64_t cursors = 0;
    for (; i < block_end; ++i) {
      const uint32_t v = order[i];
      const int o = octant(key[v], shift);
      const uint32_t slot = base[o] + lane(cursors, o);
      cursors += uint64_t(1) << (8 * o);
      order_out[slot] = v;
    }
    for (int c = 0; c < 8; ++c) base[c] += lane(block_counts[block], c);
  }
}

void countPortable(const uint64_t* key, const uint32_t* order, uint32_t n, int shift, uint64_t* block_counts,
                   uint32_t count[8]) {
  countLoop(key, order, n, shift, block_counts, count);
}
void scatterPortable(const uint64_t* key, const uint32_t* order, uint32_t n, int shift,
                     const uint64_t* block_counts, const uint32_t start[8], uint32_t* order_out) {
  scatterLoop(key, order, n, shift, block_counts, start, order_out);
}

#if ANIMC_AVX2_PATH
ANIMC_TARGET_AVX2 void countAvx2(const uint64_t* key, const uint32_t* order, uint32_t n, int shift,
                                 uint64_t* block_counts, uint32_t count[8]) {
  countLoop(key, order, n, shift, block_counts, count);
}
ANIMC_TARGET_AVX2 void scatterAvx2(const uint64_t* key, const uint32_t* order, uint32_t n, int shift,
                                   const uint64_t* block_counts, const uint32_t start[8], uint32_t* order_out) {
  scatterLoop(key, order, n, shift, block_counts, start, order_out);
}
#endif

}  // namespace

// Counts per block, kept for scatter(), and in total.
void OctreePartition::countOctants(const Cell& cell, uint32_t count[8]) {
  const uint32_t* order = vertices(cell);
  const uint32_t n = cell.end - cell.begin;
  const int shift = octantShift(cell.depth);
  block_counts_.resize(n / kBlock + 1);
  for (int c = 0; c < 8; ++c) count[c] = 0;
#if ANIMC_AVX2_PATH
  if (cpuHasAvx2()) return countAvx2(key_.data(), order, n, shift, block_counts_.data(), count);
#endif
  countPortable(key_.data(), order, n, shift, block_counts_.data(), count);
}

void OctreePartition::scatter(const Cell& cell, const uint32_t start[8]) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* order = vertices(cell);
  uint32_t* order_out = &order_[(cell.depth & 1) ^ 1][cell.begin];
  const int shift = octantShift(cell.depth);
#if ANIMC_AVX2_PATH
  if (cpuHasAvx2()) return scatterAvx2(key_.data(), order, n, shift, block_counts_.data(), start, order_out);
#endif
  scatterPortable(key_.data(), order, n, shift, block_counts_.data(), start, order_out);
}

}  // namespace animc
