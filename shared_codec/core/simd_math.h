// SPDX-License-Identifier: Apache-2.0
// Small fixed-width vectors for the per-vertex loops (GCC/Clang vector extensions).
//  - Pair: two doubles (a point's x and y; z goes alone), the SIMD width every x86-64 and
//    ARM64 CPU has.
//  - Quad: four doubles (x, y, z and an unused lane), for the AVX2 versions of the hottest
//    loops, chosen at run time on x86-64 CPUs that have AVX2 (SimdPath below).
// Every operation is the IEEE operation of each lane, so results are bit-identical to the
// scalar formulas they replace (no reassociation, no fused multiply-add: the library is built
// with -ffp-contract=off), whichever version runs.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace animc {

typedef double Pair __attribute__((vector_size(16)));
// The same with the alignment of a double, to load and store pairs anywhere in a double array.
// (Not memcpy: GCC treats a copied block as possibly aliasing anything, which forces
// reloads of unrelated pointers in the loops around it.)
typedef double UnalignedPair __attribute__((vector_size(16), aligned(8)));

inline Pair loadPair(const double* p) { return *reinterpret_cast<const UnalignedPair*>(p); }
inline void storePair(double* p, Pair v) { *reinterpret_cast<UnalignedPair*>(p) = v; }
inline Pair splat(double x) { return Pair{x, x}; }
// Lane-wise std::min / std::max (first argument kept on ties and unordered values).
inline Pair minPair(Pair a, Pair b) { return b < a ? b : a; }
inline Pair maxPair(Pair a, Pair b) { return a < b ? b : a; }
// Lane by lane the correctly rounded square root, as std::sqrt, without its errno test.
inline Pair sqrtPair(Pair x) {
#if defined(__SSE2__)
  return __builtin_ia32_sqrtpd(x);
#else
  return Pair{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}

// The running bounding box of points, x and y through a Pair, z alone.
struct PointBox {
  Pair lo_xy, hi_xy;
  double lo_z, hi_z;
  explicit PointBox(const double* first) : lo_xy(loadPair(first)), hi_xy(lo_xy), lo_z(first[2]), hi_z(first[2]) {}
  void add(Pair xy, double z) {
    lo_xy = minPair(lo_xy, xy);
    hi_xy = maxPair(hi_xy, xy);
    lo_z = std::min(lo_z, z);
    hi_z = std::max(hi_z, z);
  }
};

}  // namespace animc

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ANIMC_NO_AVX2)
#define ANIMC_AVX2_PATH 1
// For the functions that make up the AVX2 versions; everything they inline follows. Every
// CPU with AVX2 also has BMI2 (shifts by a variable amount in one micro-operation).
#define ANIMC_TARGET_AVX2 __attribute__((target("avx2,bmi2")))
// For the few kernels that also have a version in 512-bit vectors (SimdPath::kAvx512).
#define ANIMC_TARGET_AVX512 __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,avx2,bmi2")))

namespace animc {

typedef double Quad __attribute__((vector_size(32)));
typedef double UnalignedQuad __attribute__((vector_size(32), aligned(8)));
// The 64-bit integer lanes of a Quad (comparison results, masks, bit patterns), and four
// 32-bit integers (one per lane, converted to or from a Quad).
typedef long long QuadMask __attribute__((vector_size(32)));
typedef int32_t IntQuad __attribute__((vector_size(16)));

// Four consecutive doubles anywhere in a double array (as loadPair and storePair).
ANIMC_TARGET_AVX2 inline Quad loadQuad(const double* p) { return *reinterpret_cast<const UnalignedQuad*>(p); }
ANIMC_TARGET_AVX2 inline void storeQuad(double* p, Quad v) { *reinterpret_cast<UnalignedQuad*>(p) = v; }
ANIMC_TARGET_AVX2 inline Quad splatQuad(double x) { return Quad{x, x, x, x}; }
// Lane-wise std::min / std::max, as minPair and maxPair.
ANIMC_TARGET_AVX2 inline Quad minQuad(Quad a, Quad b) { return b < a ? b : a; }
ANIMC_TARGET_AVX2 inline Quad maxQuad(Quad a, Quad b) { return a < b ? b : a; }
// A point's x, y, z as lanes 0-2 of a Quad and back, touching those three doubles only:
// loadQuad would read the double after the point (past the end of an array, for its last
// point) and storeQuad would overwrite it. loadXyz leaves lane 3 at 0. It joins two loads
// (x y, then z and a zero): GCC builds Quad{p[0], p[1], p[2], 0.0} from scalar loads instead,
// sometimes with a register-to-register vmovq that valgrind 3.19 cannot decode.
ANIMC_TARGET_AVX2 inline Quad loadXyz(const double* p) {
  return __builtin_shufflevector(loadPair(p), Pair{p[2], 0.0}, 0, 1, 2, 3);
}
ANIMC_TARGET_AVX2 inline void storeXyz(double* p, Quad v) {
  storePair(p, Pair{v[0], v[1]});
  p[2] = v[2];
}
// Lanes 0-2 rotated: (v1, v2, v0) and (v2, v0, v1), lane 3 kept (cross products).
ANIMC_TARGET_AVX2 inline Quad yzx(Quad v) { return __builtin_shufflevector(v, v, 1, 2, 0, 3); }
ANIMC_TARGET_AVX2 inline Quad zxy(Quad v) { return __builtin_shufflevector(v, v, 2, 0, 1, 3); }
// Columns 0, 1 and 2 of the 4 x 4 matrix with rows a, b, c, e: (a[j], b[j], c[j], e[j]).
ANIMC_TARGET_AVX2 inline void transposeColumns(Quad a, Quad b, Quad c, Quad e, Quad columns[3]) {
  const Quad ab_even = __builtin_shufflevector(a, b, 0, 4, 2, 6), ab_odd = __builtin_shufflevector(a, b, 1, 5, 3, 7);
  const Quad ce_even = __builtin_shufflevector(c, e, 0, 4, 2, 6), ce_odd = __builtin_shufflevector(c, e, 1, 5, 3, 7);
  columns[0] = __builtin_shufflevector(ab_even, ce_even, 0, 1, 4, 5);
  columns[1] = __builtin_shufflevector(ab_odd, ce_odd, 0, 1, 4, 5);
  columns[2] = __builtin_shufflevector(ab_even, ce_even, 2, 3, 6, 7);
}

// Whether this CPU runs the AVX2 versions: found once, at load time, rather than through a
// function-local static, whose guard is tested on every call and whose slow path (a call)
// made each dispatching function save and restore its registers. Read before its initialisation (from another static
// initialiser) it is false, which selects the portable versions: same results.
inline const bool kCpuHasAvx2 =
    (__builtin_cpu_init(), __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2"));
// F, DQ, VL and BW together, as every CPU with AVX-512 since the first server ones has them.
inline const bool kCpuHasAvx512 = [] {
  __builtin_cpu_init();
  return kCpuHasAvx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
}();

}  // namespace animc
#else
#define ANIMC_AVX2_PATH 0
#endif

namespace animc {

// Which version of the kernels an encoder or decoder runs. It is chosen once, where the
// coder is made (the codec table's factories, from bestSimdPath()), and handed down to every
// kernel, so that all of one coder's kernels agree and a test can run every version in one
// build: they must give the same bytes and frames.
// kAvx512 is kAvx2 with the kernels that have a 512-bit version running that version (the
// trajectory codec's frame kernel); every other kernel runs its AVX2 version.
enum class SimdPath : uint8_t { kPortable, kAvx2, kAvx512 };

// ANIMC_SIMD=portable in the environment runs the portable versions on any CPU: what CPUs
// without AVX2 run, for the fuzzers (CI fuzzes both), or to rule the AVX2 versions out when a
// result looks wrong; ANIMC_SIMD=avx2 runs the AVX2 versions on a CPU with AVX-512, to compare
// them. Read once, at load time, like kCpuHasAvx2.
inline bool simdAsked(std::string_view name) {
  const char* value = std::getenv("ANIMC_SIMD");
  return value != nullptr && std::string_view(value) == name;
}
inline const bool kPortableForced = simdAsked("portable");
inline const bool kAvx2Forced = simdAsked("avx2");

// kAvx512 when this build has the AVX2 versions and this CPU has AVX-512 (F, DQ, VL, BW) as well
// as AVX2 and BMI2, kAvx2 when it has only those two, unless ANIMC_SIMD asks for the portable
// or the AVX2 ones.
inline SimdPath bestSimdPath() {
#if ANIMC_AVX2_PATH
  if (kCpuHasAvx512 && !kPortableForced && !kAvx2Forced) return SimdPath::kAvx512;
  if (kCpuHasAvx2 && !kPortableForced) return SimdPath::kAvx2;
#endif
  return SimdPath::kPortable;
}

// Every path this build and CPU can run, portable first (for tests that compare them): each
// path up to the best, in the enum's order, which is that of the instructions each adds.
inline std::vector<SimdPath> availableSimdPaths() {
  std::vector<SimdPath> paths = {SimdPath::kPortable};
  for (SimdPath path : {SimdPath::kAvx2, SimdPath::kAvx512})
    if (path <= bestSimdPath()) paths.push_back(path);
  return paths;
}

// Whether `path` runs the AVX2 versions (never in a build without them).
inline bool useAvx2(SimdPath path) { return ANIMC_AVX2_PATH && path != SimdPath::kPortable; }

}  // namespace animc
