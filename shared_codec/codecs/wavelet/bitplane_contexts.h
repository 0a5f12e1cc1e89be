// Internals of the bitplane coder (bitplane_coder.h): its adaptive models and the state both
// sides keep while walking the planes. One template walks a block for the encoder and the
// decoder alike, so the two cannot disagree on the order or the contexts of the decisions.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "codecs/wavelet/bitplane_coder.h"
#include "entropy/range_coder.h"

namespace animc {

constexpr int kPlaneSlots = 32;
// What the same coefficient (vertex, block) did in the previous frame, against plane p:
// 0 = was zero, 1 = was below 2^p, 2 = became significant at p, 3 = was above.
constexpr int kTemporalContexts = 4;

inline int temporalContext(uint8_t previous_bits, int plane) {
  if (previous_bits == 0) return 0;
  return previous_bits <= plane ? 1 : previous_bits == plane + 1 ? 2 : 3;
}

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
  BitModel refine[kBitplaneClasses][3];  // known magnitude 1, 2-3, 4+

  void reset() {
    BitModel* first = &block[0][0][0];
    std::fill(first, first + sizeof(*this) / sizeof(BitModel), BitModel());
  }
};

// Reconstruction inside [known, known + 1) * 2^q steps: Laplacian residuals are denser near
// the interval's lower end, the more so right after significance (docs/wavelet.md).
constexpr double kFreshOffset = 0.25;
constexpr double kRefinedOffset = 0.5;

class BitplaneState {
 public:
  void start(const BitplaneLayout& layout, const BitplaneHistory* context) {
    classes_ = layout.classes;
    parents_ = layout.parents;
    vertices_ = layout.vertices;
    blocks_ = (vertices_ + kBlockVertices - 1) / kBlockVertices;
    const size_t count = 3 * vertices_;
    known_.assign(count, 0);
    negative_.assign(count, 0);
    vertex_mask_.assign(vertices_, 0);
    block_significant_.assign(blocks_, 0);
    previous_bits_.assign(count, 0);
    previous_sign_.assign(count, 0);
    if (context && context->bits.size() == count && context->negative.size() == count)
      for (size_t j = 0; j < count; ++j) {
        previous_bits_[j] = context->bits[j];
        previous_sign_[j] = context->bits[j] == 0 ? 0 : context->negative[j] ? 2 : 1;
      }
    summarise(previous_bits_, previous_vertex_bits_, previous_block_bits_);
  }

  // Encoder only: magnitudes in steps (floor: a dead zone of twice the step) and signs.
  void quantise(const double* values, double step) {
    const size_t count = 3 * vertices_;
    constexpr uint32_t kMaxMagnitude = (1u << kMaxBitplanes) - 1;
    magnitude_.resize(count);
    input_negative_.resize(count);
    bits_.resize(count);
    for (size_t j = 0; j < count; ++j) {
      const double q = std::floor(std::fabs(values[j]) / step);
      magnitude_[j] = q < double(kMaxMagnitude) ? uint32_t(q) : kMaxMagnitude;  // NaN -> 0
      input_negative_[j] = values[j] < 0;
      bits_[j] = uint8_t(bitLength(magnitude_[j]));
    }
    summarise(bits_, vertex_bits_, block_bits_);
  }

  int topPlane() const {
    int top = 0;
    for (uint8_t b : block_bits_) top = std::max(top, int(b));
    return top;
  }
  size_t blockCount() const { return blocks_; }

  template <class Io>
  void codeBlock(Io& io, BitplaneContexts& m, int p, size_t b) {
    const size_t first = b * kBlockVertices, last = std::min(first + kBlockVertices, vertices_);
    if (!block_significant_[b]) {
      BitModel& model = m.block[p][classes_[first]][temporalContext(previous_block_bits_[b], p)];
      if (!io.code(model, Io::kEncodes ? block_bits_[b] == p + 1 : 0)) return;
      block_significant_[b] = 1;
      bool any = false;  // one vertex at least becomes significant: the last may be inferred
      for (size_t v = first; v < last; ++v) any |= codeFreshVertex(io, m, p, v, !any && v + 1 == last);
      return;
    }
    for (size_t v = first; v < last; ++v) {
      if (vertex_mask_[v]) codeSignificantVertex(io, m, p, v);
      else codeFreshVertex(io, m, p, v, false);
    }
  }

  // The decoder's view after `planes` planes from `top`, the last one stopping before block
  // `stop`, and what it leaves for the next frame's temporal contexts.
  void finish(int top, int planes, size_t stop, double step, std::vector<double>& decoded,
              BitplaneHistory* history) const {
    reconstruct(top, planes, stop, step, decoded, history, [this](size_t j, int) { return known_[j]; });
  }

  // Encoder only, after quantise(): what finish() would give had the walk been cut there.
  void preview(int planes, size_t stop, double step, std::vector<double>& decoded) {
    for (size_t j = 0; j < negative_.size(); ++j) negative_[j] = input_negative_[j];
    reconstruct(topPlane(), planes, stop, step, decoded, nullptr,
                [this](size_t j, int q) { return q >= 32 ? 0u : magnitude_[j] >> q; });
  }

 private:
  template <class Known>
  void reconstruct(int top, int planes, size_t stop, double step, std::vector<double>& decoded,
                   BitplaneHistory* history, Known known) const {
    const size_t count = 3 * vertices_;
    decoded.resize(count);
    if (history) {
      history->bits.resize(count);
      history->negative.resize(count);
    }
    const int full_q = top - planes, short_q = std::min(top, full_q + 1);
    const double full_scale = std::ldexp(step, full_q), short_scale = std::ldexp(step, short_q);
    for (size_t v = 0; v < vertices_; ++v) {
      const bool complete = v / kBlockVertices < stop;
      const int q = complete ? full_q : short_q;
      const double scale = complete ? full_scale : short_scale;
      for (size_t j = 3 * v; j < 3 * v + 3; ++j) {
        const uint32_t k = planes == 0 ? 0 : known(j, q);
        const double magnitude = k == 0 ? 0.0 : (double(k) + (k == 1 ? kFreshOffset : kRefinedOffset)) * scale;
        decoded[j] = negative_[j] ? -magnitude : magnitude;
        if (history) {
          history->bits[j] = uint8_t(k == 0 ? 0 : bitLength(k) + q);
          history->negative[j] = negative_[j];
        }
      }
    }
  }

  template <class Io>
  int magnitudeBit(size_t j, int p) const {
    return Io::kEncodes ? int((magnitude_[j] >> p) & 1) : 0;
  }

  template <class Io>
  bool codeFreshVertex(Io& io, BitplaneContexts& m, int p, size_t v, bool inferred) {
    const int cls = classes_[v];
    if (!inferred) {
      const uint32_t parent = parents_[v];
      const int parent_state = parent == kNoParent ? 0 : vertex_mask_[parent] ? 2 : 1;
      BitModel& model = m.vertex[p][cls][temporalContext(previous_vertex_bits_[v], p)][parent_state];
      if (!io.code(model, Io::kEncodes ? vertex_bits_[v] == p + 1 : 0)) return false;
    }
    int significant = 0;  // one component at least: the last may be inferred
    for (int a = 0; a < 3; ++a) {
      const size_t j = 3 * v + a;
      const int bit = a == 2 && significant == 0
                          ? 1
                          : io.code(m.fresh[cls][a][significant][temporalContext(previous_bits_[j], p)],
                                    magnitudeBit<Io>(j, p));
      if (bit) {
        becomeSignificant(io, m, v, a, cls);
        ++significant;
      }
    }
    return true;
  }

  template <class Io>
  void codeSignificantVertex(Io& io, BitplaneContexts& m, int p, size_t v) {
    const int cls = classes_[v];
    for (int a = 0; a < 3; ++a) {
      const size_t j = 3 * v + a;
      if (vertex_mask_[v] & (1 << a)) {
        const uint32_t k = known_[j];
        known_[j] = (k << 1) | uint32_t(io.code(m.refine[cls][k == 1 ? 0 : k <= 3 ? 1 : 2], magnitudeBit<Io>(j, p)));
        continue;
      }
      const int siblings = __builtin_popcount(vertex_mask_[v]) >= 2;
      if (io.code(m.component[p][cls][temporalContext(previous_bits_[j], p)][siblings], magnitudeBit<Io>(j, p)))
        becomeSignificant(io, m, v, a, cls);
    }
  }

  template <class Io>
  void becomeSignificant(Io& io, BitplaneContexts& m, size_t v, int a, int cls) {
    const size_t j = 3 * v + a;
    known_[j] = 1;
    vertex_mask_[v] |= uint8_t(1 << a);
    negative_[j] = uint8_t(io.code(m.sign[cls][previous_sign_[j]], Io::kEncodes ? input_negative_[j] : 0));
  }

  // Largest bit length per vertex and per block.
  void summarise(const std::vector<uint8_t>& bits, std::vector<uint8_t>& per_vertex,
                 std::vector<uint8_t>& per_block) const {
    per_vertex.resize(vertices_);
    per_block.assign(blocks_, 0);
    for (size_t v = 0; v < vertices_; ++v) {
      per_vertex[v] = std::max({bits[3 * v], bits[3 * v + 1], bits[3 * v + 2]});
      uint8_t& b = per_block[v / kBlockVertices];
      b = std::max(b, per_vertex[v]);
    }
  }

  const uint8_t* classes_ = nullptr;
  const uint32_t* parents_ = nullptr;
  size_t vertices_ = 0, blocks_ = 0;
  std::vector<uint32_t> known_;          // magnitude >> (current plane), 0 while insignificant
  std::vector<uint8_t> negative_;
  std::vector<uint8_t> vertex_mask_;     // significant components of each vertex
  std::vector<uint8_t> block_significant_;
  std::vector<uint8_t> previous_bits_, previous_vertex_bits_, previous_block_bits_, previous_sign_;
  // Encoder only.
  std::vector<uint32_t> magnitude_;
  std::vector<uint8_t> input_negative_, bits_, vertex_bits_, block_bits_;
};

}  // namespace animc
