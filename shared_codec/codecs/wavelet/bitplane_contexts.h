// SPDX-License-Identifier: Apache-2.0
// Internals of the bitplane coder (bitplane_coder.h): its adaptive models and the state both
// sides keep while walking the planes. One template walks a block for the encoder and the
// decoder alike, so the two cannot disagree on the order or the contexts of the decisions.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "codecs/wavelet/bitplane_coder.h"
#include "core/simd_math.h"
#include "entropy/range_coder.h"

namespace animc {

constexpr int kPlaneSlots = 32;
// What the same coefficient (vertex, block) did in the previous frame, against plane p:
// 0 = was zero, 1 = was below 2^p, 2 = became significant at p, 3 = was above.
constexpr int kTemporalContexts = 4;

inline int bitLength(uint32_t v) { return v == 0 ? 0 : 32 - __builtin_clz(v); }

// Every model of one frame (reset at the start of each frame, so a frame decodes on its
// own given the temporal context). Significance odds change sharply with the plane and the
// class, and rise with significant siblings, parents and last frame's magnitude.
struct BitplaneContexts {
  BitModel block[kPlaneSlots][kBitplaneClasses][kTemporalContexts];
  BitModel vertex[kPlaneSlots][kBitplaneClasses][kTemporalContexts][3];  // parent: none/zero/significant
  BitModel fresh[kBitplaneClasses][3][3][kTemporalContexts];  // component, significant ones before it
  BitModel component[kPlaneSlots][kBitplaneClasses][kTemporalContexts][2];  // 2+ siblings significant
  BitModel sign[kBitplaneClasses][3];    // last frame's sign: none / + / -

  // Before a frame whose walk starts at plane top - 1: the per-plane models above it are
  // never read, and skipping them saves most of the 50 KB a full reset writes per frame.
  void reset(int top) {
    fill(block, top);
    fill(vertex, top);
    fill(component, top);
    fill(fresh);
    fill(sign);
  }

 private:
  // The first `rows` rows of a table of models (all of them by default) back to the start.
  template <class Row, size_t kRows>
  static void fill(Row (&table)[kRows], int rows = int(kRows)) {
    BitModel* first = reinterpret_cast<BitModel*>(&table[0]);
    std::fill(first, first + size_t(rows) * (sizeof(Row) / sizeof(BitModel)), BitModel());
  }
};

// Reconstruction inside [known, known + 1) * 2^q steps: Laplacian residuals are denser near
// the interval's lower end, the more so right after significance (docs/wavelet.md).
constexpr double kFreshOffset = 0.25;
constexpr double kRefinedOffset = 0.5;

// The values of n coefficients known to k[i] units of 2^q steps (scale = step * 2^q):
// sign * (k == 0 ? 0 : (k + offset) * scale), the sign applied to zeros too; and, when
// bit_lengths is given, what they leave for the next frame's temporal contexts (the bit
// length of k plus q, 0 for k = 0, and the sign).
void reconstructCoefficients(SimdPath path, const uint32_t* k, const uint8_t* negative, size_t n, int q, double scale, double* out,
                             uint8_t* bit_lengths, uint8_t* was_negative);

template <class Io>
struct PlaneWalk;

class BitplaneState {
 public:
  void start(const BitplaneLayout& layout, const BitplaneHistory* context, SimdPath path) {
    path_ = path;
    classes_ = layout.classes;
    parents_ = layout.parents;
    vertices_ = layout.vertices;
    blocks_ = (vertices_ + kBlockVertices - 1) / kBlockVertices;
    const size_t count = 3 * vertices_;
    known_.assign(count, 0);
    negative_.assign(count, 0);
    vertex_mask_.assign(vertices_, 0);
    block_significant_.assign(blocks_, 0);
    // The history is read in place (the walk only reads it); no history reads as all zero.
    if (context && context->bits.size() == count && context->negative.size() == count) {
      previous_bits_ = context->bits.data();
      previous_negative_ = context->negative.data();
    } else {
      no_history_.assign(count, 0);
      previous_bits_ = previous_negative_ = no_history_.data();
    }
    summarise(previous_bits_, previous_vertex_bits_, previous_block_bits_);
  }

  // Encoder only: magnitudes in steps (floor: a dead zone of twice the step) and signs.
  void quantise(const double* values, double step) {
    const size_t count = 3 * vertices_;
    magnitude_.resize(count);
    input_negative_.resize(count);
    bits_.resize(count);
    for (size_t j = 0; j < count; ++j) {
      const double q = std::floor(std::fabs(values[j]) / step);
      magnitude_[j] = q < double(kMaxBitplaneMagnitude) ? uint32_t(q) : kMaxBitplaneMagnitude;  // NaN -> 0
      input_negative_[j] = values[j] < 0;
      bits_[j] = uint8_t(bitLength(magnitude_[j]));
    }
    summarise(bits_.data(), vertex_bits_, block_bits_);
  }

  int topPlane() const {
    int top = 0;
    for (uint8_t b : block_bits_) top = std::max(top, int(b));
    return top;
  }
  size_t blockCount() const { return blocks_; }

  // Codes blocks [0, end) of plane p, or fewer: stop(b), asked before each block, may end the
  // plane early (the encoder's byte budget). Returns the number of blocks coded. Not inlined:
  // inside the decoder's whole-block function GCC 12 keeps fewer of the walk's pointers in
  // registers.
  template <class Io, class Stop>
  __attribute__((noinline)) size_t codePlane(Io& io, BitplaneContexts& m, int p, size_t end, Stop stop) {
    return walkPlane(io, m, p, end, stop);
  }
#if ANIMC_AVX2_PATH
  // codePlane for the AVX2 path (SimdPath::kAvx2, CPUs with AVX2 and BMI2): the
  // walk's shifts by a variable amount (contexts, model rates) then take one instruction and
  // no count register. The same decisions.
  template <class Io, class Stop>
  ANIMC_TARGET_AVX2 __attribute__((noinline)) size_t codePlaneAvx2(Io& io, BitplaneContexts& m, int p, size_t end,
                                                                  Stop stop) {
    return walkPlane(io, m, p, end, stop);
  }
#endif
  // The decoder's view after `planes` planes from `top`, the last one stopping before block
  // `stop`, and what it leaves for the next frame's temporal contexts.
  void finish(int top, int planes, size_t stop, double step, std::vector<double>& decoded,
              BitplaneHistory* history) const {
    reconstruct(cutRanges(top, planes, stop), step, known_.data(), decoded, history);
  }

  // Encoder only, after quantise(): what finish() would give had the walk been cut there.
  void preview(int planes, size_t stop, double step, std::vector<double>& decoded) {
    for (size_t j = 0; j < negative_.size(); ++j) negative_[j] = input_negative_[j];
    const CutRanges ranges = cutRanges(topPlane(), planes, stop);
    preview_known_.resize(magnitude_.size());
    for (const CutRange& r : ranges.range)  // the magnitudes down to each range's last plane
      for (size_t j = r.begin; j < r.end; ++j) preview_known_[j] = r.q >= 32 ? 0u : magnitude_[j] >> r.q;
    reconstruct(ranges, step, preview_known_.data(), decoded, nullptr);
  }

 private:
  template <class Io>
  friend struct PlaneWalk;

  template <class Io, class Stop>
  __attribute__((always_inline)) size_t walkPlane(Io& io, BitplaneContexts& m, int p, size_t end, Stop stop) {
    PlaneWalk<Io> walk{io, m, p, *this};
    size_t b = 0;
    for (; b < end && !stop(b); ++b) walk.codeBlock(b);
    io = walk.io;
    return b;
  }

  // A cut leaves the coefficients of the blocks before the stop known down to plane q, the
  // others one plane less (none received: every magnitude is below 2^top, so it reads 0).
  struct CutRange {
    size_t begin, end;
    int q;
  };
  struct CutRanges {
    CutRange range[2];
  };
  CutRanges cutRanges(int top, int planes, size_t stop) const {
    const size_t count = 3 * vertices_;
    const size_t complete_end = std::min(count, 3 * kBlockVertices * stop);
    const int full_q = top - planes;
    return {{{0, complete_end, full_q}, {complete_end, count, std::min(top, full_q + 1)}}};
  }

  // known: each coefficient's magnitude in units of 2^q steps, q its range's.
  void reconstruct(const CutRanges& ranges, double step, const uint32_t* known, std::vector<double>& decoded,
                   BitplaneHistory* history) const {
    const size_t count = 3 * vertices_;
    decoded.resize(count);
    if (history) {
      history->bits.resize(count);
      history->negative.resize(count);
    }
    for (const CutRange& r : ranges.range)
      reconstructCoefficients(path_, known + r.begin, negative_.data() + r.begin, r.end - r.begin, r.q, std::ldexp(step, r.q),
                              decoded.data() + r.begin, history ? history->bits.data() + r.begin : nullptr,
                              history ? history->negative.data() + r.begin : nullptr);
  }

  // Largest bit length per vertex and per block (raw pointers: the byte stores would make
  // the compiler reload a vector's data pointer after each one).
  void summarise(const uint8_t* bits, std::vector<uint8_t>& per_vertex, std::vector<uint8_t>& per_block) const {
    const size_t n = vertices_;  // a local: after a byte store vertices_ would be reloaded
    per_vertex.resize(n);
    per_block.resize(blocks_);
    uint8_t* const vertex = per_vertex.data();
    uint8_t* const block = per_block.data();
    for (size_t v = 0; v < n; ++v) vertex[v] = std::max({bits[3 * v], bits[3 * v + 1], bits[3 * v + 2]});
    for (size_t b = 0; b < blocks_; ++b) {
      uint8_t largest = 0;
      for (size_t v = b * kBlockVertices; v < std::min(n, (b + 1) * kBlockVertices); ++v) largest = std::max(largest, vertex[v]);
      block[b] = largest;
    }
  }

  const uint8_t* classes_ = nullptr;
  const uint32_t* parents_ = nullptr;
  size_t vertices_ = 0, blocks_ = 0;
  SimdPath path_ = SimdPath::kPortable;  // the reconstruction's kernels, set by start()
  std::vector<uint32_t> known_;          // magnitude >> (current plane), 0 while insignificant
  std::vector<uint8_t> negative_;
  std::vector<uint8_t> vertex_mask_;     // significant components of each vertex
  std::vector<uint8_t> block_significant_;
  const uint8_t* previous_bits_ = nullptr;      // the context's history, or no_history_
  const uint8_t* previous_negative_ = nullptr;
  std::vector<uint8_t> no_history_, previous_vertex_bits_, previous_block_bits_;
  // Encoder only.
  std::vector<uint32_t> magnitude_, preview_known_;
  std::vector<uint8_t> input_negative_, bits_, vertex_bits_, block_bits_;
};

// One plane of the walk, shared by the encoder and the decoder. It works on raw copies of the
// state's pointers and of the coder (Io) held as locals, not through BitplaneState: the walk
// stores bytes (masks, signs), and a byte store may alias any object in memory, which would
// make the compiler reload every pointer and the coder's range after each of them.
template <class Io>
struct PlaneWalk {
  PlaneWalk(const Io& coder, BitplaneContexts& models, int plane, BitplaneState& s)
      : io(coder), m(models), p(plane), vertices(s.vertices_), classes(s.classes_), parents(s.parents_),
        known(s.known_.data()), negative(s.negative_.data()), mask(s.vertex_mask_.data()),
        block_significant(s.block_significant_.data()), previous_bits(s.previous_bits_),
        previous_vertex_bits(s.previous_vertex_bits_.data()),
        previous_block_bits(s.previous_block_bits_.data()), previous_negative(s.previous_negative_),
        magnitude(s.magnitude_.data()), input_negative(s.input_negative_.data()),
        vertex_bits(s.vertex_bits_.data()), block_bits(s.block_bits_.data()) {}

  Io io;
  BitplaneContexts& m;
  const int p;
  const size_t vertices;
  const uint8_t* const classes;
  const uint32_t* const parents;
  uint32_t* const known;
  uint8_t* const negative;
  uint8_t* const mask;
  uint8_t* const block_significant;
  const uint8_t *const previous_bits, *const previous_vertex_bits, *const previous_block_bits,
      *const previous_negative;
  // Encoder only (empty on the decoder's side, never read there).
  const uint32_t* const magnitude;
  const uint8_t *const input_negative, *const vertex_bits, *const block_bits;

  // The temporal context of a coefficient (or vertex, block) whose last-frame bit length was
  // `previous` (<= kMaxBitplanes): (previous != 0) + (previous > p) + (previous > p + 1),
  // looked up in 2-bit fields of one word, since every significance decision needs one.
  int temporal(uint8_t previous) const { return int((temporal_fields >> (2 * (previous & 31))) & 3); }
  static uint64_t temporalFields(int plane) {
    uint64_t fields = 0;
    for (int b = 0; b <= kMaxBitplanes; ++b)
      fields |= uint64_t((b != 0) + (b > plane) + (b > plane + 1)) << (2 * b);
    return fields;
  }
  const uint64_t temporal_fields = temporalFields(p);
  int magnitudeBit(size_t j) const { return Io::kEncodes ? int((magnitude[j] >> p) & 1) : 0; }
  int newlySignificant(const uint8_t* bits, size_t i) const { return Io::kEncodes ? bits[i] == p + 1 : 0; }

  __attribute__((always_inline)) void codeBlock(size_t b) {  // inlined in each codePlane version
    const size_t first = b * kBlockVertices, last = std::min(first + kBlockVertices, vertices);
    if (!block_significant[b]) {
      BitModel& model = m.block[p][classes[first]][temporal(previous_block_bits[b])];
      if (!io.code(model, newlySignificant(block_bits, b))) return;
      block_significant[b] = 1;
      bool any = false;  // one vertex at least becomes significant: the last may be inferred
      for (size_t v = first; v < last; ++v) any |= codeFreshVertex(v, !any && v + 1 == last);
      return;
    }
    for (size_t v = first; v < last; ++v) {
      if (mask[v] == 7) codeRefinements(v);
      else if (mask[v]) codeSignificantVertex(v);
      else codeFreshVertex(v, false);
    }
  }

  bool codeFreshVertex(size_t v, bool inferred) {
    const int cls = classes[v];
    if (!inferred) {
      const uint32_t parent = parents[v];
      const int parent_state = parent == kNoParent ? 0 : mask[parent] ? 2 : 1;
      BitModel& model = m.vertex[p][cls][temporal(previous_vertex_bits[v])][parent_state];
      if (!io.code(model, newlySignificant(vertex_bits, v))) return false;
    }
    uint8_t vertex_mask = 0;
    int significant = 0;  // one component at least: the last may be inferred
    for (int a = 0; a < 3; ++a) {
      const size_t j = 3 * v + a;
      const int bit = a == 2 && significant == 0
                          ? 1
                          : io.code(m.fresh[cls][a][significant][temporal(previous_bits[j])], magnitudeBit(j));
      if (bit) {
        becomeSignificant(j, cls);
        vertex_mask |= uint8_t(1 << a);
        ++significant;
      }
    }
    mask[v] = vertex_mask;
    return true;
  }

  // The common case of the low planes: all three components known, three refinement bits.
  void codeRefinements(size_t v) {
    for (size_t j = 3 * v; j < 3 * v + 3; ++j) refine(j);
  }

  void codeSignificantVertex(size_t v) {
    const int cls = classes[v];
    uint8_t vertex_mask = mask[v];
    for (int a = 0; a < 3; ++a) {
      const size_t j = 3 * v + a;
      if (vertex_mask & (1 << a)) {
        refine(j);
        continue;
      }
      const int siblings = (0xE8 >> vertex_mask) & 1;  // 2+ of the 3 bits set: masks 3, 5, 6, 7
      if (io.code(m.component[p][cls][temporal(previous_bits[j])][siblings], magnitudeBit(j))) {
        becomeSignificant(j, cls);
        vertex_mask |= uint8_t(1 << a);
      }
    }
    mask[v] = vertex_mask;
  }

  // Refinement bits go raw, as in the paper. Only the first one after significance is
  // skewed (residuals are roughly Laplacian); an adaptive model for it saved a fraction of a
  // percent of the bits but slowed decoding: a model load, update and store, and a range
  // that depends on the bit, where a raw bit just halves it
  // (docs/notes/wavelet_history.md, "Decode speed, fourth pass").
  void refine(size_t j) { known[j] = (known[j] << 1) | uint32_t(io.raw(magnitudeBit(j))); }

  void becomeSignificant(size_t j, int cls) {
    known[j] = 1;
    const int previous_sign = previous_bits[j] == 0 ? 0 : 1 + (previous_negative[j] != 0);  // none/+/-
    negative[j] = uint8_t(io.code(m.sign[cls][previous_sign], Io::kEncodes ? input_negative[j] : 0));
  }
};

}  // namespace animc
