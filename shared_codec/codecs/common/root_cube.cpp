// SPDX-License-Identifier: Apache-2.0
// The frame-wide passes of root_cube.h: bounding cube, normalisation into it and back,
// conversion to floats. They touch every coordinate of a frame or two per inter frame, so
// the busiest have an AVX2 version besides the portable one, working on whole Quads (for
// xyz-interleaved frames: blocks of four vertices, twelve doubles, three Quads whose lanes
// cycle through x, y, z); both compute each value with the same IEEE operations.
#include <algorithm>
#include <cmath>
#include <string>

#include "codecs/common/root_cube.h"
#include "core/large_memory.h"
#include "core/sequence.h"
#include "core/simd_math.h"

namespace animc {
namespace {

// The cube of a box: its min corner and its largest extent.
RootCube cubeOfBox(const double min[3], const double max[3]) {
  RootCube cube;
  double side = 0;
  for (int a = 0; a < 3; ++a) {
    cube.min[a] = min[a];
    side = std::max(side, max[a] - min[a]);
  }
  // A frame collapsed to one point still needs a scale; any positive one will do.
  cube.side = side > 0 ? side : 1.0;
  return cube;
}

// PointBox fed from xyz triples, ending in the root cube of the box.
struct BoxBuilder : PointBox {
  using PointBox::add;
  using PointBox::PointBox;
  void add(const double* p) { add(loadPair(p), p[2]); }
  RootCube cube() const {
    const double min[3] = {lo_xy[0], lo_xy[1], lo_z}, max[3] = {hi_xy[0], hi_xy[1], hi_z};
    return cubeOfBox(min, max);
  }
};

const double kOrigin[3] = {0, 0, 0};

typedef float FloatPair __attribute__((vector_size(8)));
typedef long long PairMask __attribute__((vector_size(16)));

bool toFloatsPortable(const double* frame, size_t size, float* out) {
  PairMask in_range = {-1, -1};
  size_t i = 0;
  for (; i + 2 <= size; i += 2) {
    const Pair x = loadPair(&frame[i]);
    in_range &= (x >= -kMaxCoordinate) & (x <= kMaxCoordinate);
    const FloatPair f = __builtin_convertvector(x, FloatPair);
    out[i] = f[0];
    out[i + 1] = f[1];
  }
  bool ok = in_range[0] && in_range[1];
  for (; i < size; ++i) {
    ok &= frame[i] >= -kMaxCoordinate && frame[i] <= kMaxCoordinate;
    out[i] = float(frame[i]);
  }
  return ok;
}

void normalisePortable(const RootCube& cube, const double* xyz, size_t size, double* out) {
  const PointNormaliser normaliser(cube);
  for (size_t i = 0; i < size; i += 3) normaliser.apply(&xyz[i], &out[i]);
}

// out[i..] = min + side · unit[i..] for the vertices from `from` on, adding them to box.
void denormaliseTail(const RootCube& cube, const double* unit, size_t from, size_t size, double* out,
                     BoxBuilder& box) {
  const Pair min_xy = loadPair(cube.min);
  const Pair side = splat(cube.side);
  for (size_t i = from; i < size; i += 3) {
    const Pair xy = min_xy + side * loadPair(&unit[i]);
    const double z = cube.min[2] + cube.side * unit[i + 2];
    storePair(&out[i], xy);
    out[i + 2] = z;
    box.add(xy, z);
  }
}

RootCube denormalisePortable(const RootCube& cube, const double* unit, size_t size, double* out) {
  if (size == 0) return cubeOfBox(kOrigin, kOrigin);
  BoxBuilder box(kOrigin);
  denormaliseTail(cube, unit, 0, 3, out, box);  // the first vertex, which the box starts from
  box = BoxBuilder(out);
  denormaliseTail(cube, unit, 3, size, out, box);
  return box.cube();
}

#if ANIMC_AVX2_PATH
constexpr size_t kBlock = 12;  // four vertices

// The three Quads of a block repeat a per-axis value v as (x y z x) (y z x y) (z x y z).
struct BlockPattern {
  Quad q[3];
  ANIMC_TARGET_AVX2 explicit BlockPattern(const double v[3])
      : q{{v[0], v[1], v[2], v[0]}, {v[1], v[2], v[0], v[1]}, {v[2], v[0], v[1], v[2]}} {}
};

// With the alignment of a float, to store four floats anywhere in a float array.
typedef float UnalignedFloatQuad __attribute__((vector_size(16), aligned(4)));

ANIMC_TARGET_AVX2 bool toFloatsAvx2(const double* frame, size_t size, float* out) {
  QuadMask in_range = {-1, -1, -1, -1};
  size_t i = 0;
  for (; i + 4 <= size; i += 4) {
    const Quad x = loadQuad(&frame[i]);
    in_range &= (x >= -kMaxCoordinate) & (x <= kMaxCoordinate);
    *reinterpret_cast<UnalignedFloatQuad*>(&out[i]) = __builtin_convertvector(x, UnalignedFloatQuad);
  }
  const bool tail_ok = toFloatsPortable(frame + i, size - i, out + i);  // first: it writes the tail
  return tail_ok && in_range[0] && in_range[1] && in_range[2] && in_range[3];
}

ANIMC_TARGET_AVX2 void normaliseAvx2(const RootCube& cube, const double* xyz, size_t size, double* out) {
  const double inv = 1.0 / cube.side;
  const Quad scale = splatQuad(inv);
  const BlockPattern min(cube.min);
  size_t i = 0;
  for (; i + kBlock <= size; i += kBlock)
    for (int k = 0; k < 3; ++k) storeQuad(&out[i + 4 * k], (loadQuad(&xyz[i + 4 * k]) - min.q[k]) * scale);
  normalisePortable(cube, xyz + i, size - i, out + i);
}

// Lane l of block Quad k holds axis (4k + l) % 3.
ANIMC_TARGET_AVX2 void foldBox(const Quad lo[3], const Quad hi[3], double min[3], double max[3]) {
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 4; ++l) {
      const int axis = (4 * k + l) % 3;
      min[axis] = std::min(min[axis], lo[k][l]);
      max[axis] = std::max(max[axis], hi[k][l]);
    }
}

ANIMC_TARGET_AVX2 RootCube denormaliseAvx2(const RootCube& cube, const double* unit, size_t size, double* out) {
  if (size < kBlock) return denormalisePortable(cube, unit, size, out);
  const BlockPattern min(cube.min);
  const Quad side = splatQuad(cube.side);
  Quad lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = hi[k] = min.q[k] + side * loadQuad(&unit[4 * k]);
    storeQuad(&out[4 * k], lo[k]);
  }
  size_t i = kBlock;
  for (; i + kBlock <= size; i += kBlock)
    for (int k = 0; k < 3; ++k) {
      const Quad p = min.q[k] + side * loadQuad(&unit[i + 4 * k]);
      storeQuad(&out[i + 4 * k], p);
      // Min and max are exact and, without NaN or -0.0 (neither comes out of a valid stream:
      // decoded frames are min + side · unit with min never -0.0), indifferent to the order
      // they see values in, so each lane keeps its own and they fold per axis at the end.
      lo[k] = minQuad(lo[k], p);
      hi[k] = maxQuad(hi[k], p);
    }
  double box_min[3] = {out[0], out[1], out[2]}, box_max[3] = {out[0], out[1], out[2]};
  foldBox(lo, hi, box_min, box_max);
  BoxBuilder box(box_min);
  box.add(box_max);
  denormaliseTail(cube, unit, i, size, out, box);
  return box.cube();
}
#endif

}  // namespace

RootCube boundingCube(const std::vector<double>& xyz) {
  BoxBuilder box(xyz.empty() ? kOrigin : xyz.data());
  for (size_t i = 0; i < xyz.size(); i += 3) box.add(&xyz[i]);
  return box.cube();
}

void normalise([[maybe_unused]] SimdPath path, const RootCube& cube, const std::vector<double>& xyz, std::vector<double>& out) {
  out.resize(xyz.size());
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return normaliseAvx2(cube, xyz.data(), xyz.size(), out.data());
#endif
  normalisePortable(cube, xyz.data(), xyz.size(), out.data());
}

Status decodedFrameToFloats([[maybe_unused]] SimdPath path, const std::vector<double>& frame, std::vector<float>& out) {
  out.resize(frame.size());
#if ANIMC_AVX2_PATH
  const bool in_range = useAvx2(path) ? toFloatsAvx2(frame.data(), frame.size(), out.data())
                                       : toFloatsPortable(frame.data(), frame.size(), out.data());
#else
  const bool in_range = toFloatsPortable(frame.data(), frame.size(), out.data());
#endif
  if (in_range) return Status();
  for (size_t i = 0;; ++i)
    if (!(std::fabs(frame[i]) <= kMaxCoordinate))  // false for NaN and infinities too
      return corrupt("decoded vertex " + std::to_string(i / 3) + " is out of range");
}

RootCube denormalise([[maybe_unused]] SimdPath path, const RootCube& cube, const std::vector<double>& unit,
                     std::vector<double>& out) {
  resizeWithHugePages(out, unit.size());
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return denormaliseAvx2(cube, unit.data(), unit.size(), out.data());
#endif
  return denormalisePortable(cube, unit.data(), unit.size(), out.data());
}

}  // namespace animc
