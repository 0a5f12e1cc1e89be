// Context selection for the default profile's per-vertex residuals: the size of the same
// vertex's residual on the same axis in the previous frame (a vertex the affine missed
// once tends to be missed again). Both sides know it, so the context costs no bits.
// Measured on chickenCrossing: 2-7 % fewer bits than no context. Adding the already decoded
// mesh neighbours' residuals gained 1-2 % more but halved decoding speed, so it is not used.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace animc {

constexpr int kResidualContexts = 3;

class ResidualContexts {
 public:
  explicit ResidualContexts(uint32_t vertex_count)
      : now_(3 * size_t(vertex_count), 0), before_(3 * size_t(vertex_count), 0) {}

  // After an intra frame: no history.
  void restart() {
    std::fill(now_.begin(), now_.end(), 0);
    std::fill(before_.begin(), before_.end(), 0);
  }
  // The frame just coded becomes the history.
  void beginFrame() { before_.swap(now_); }

  int context(uint32_t v, int axis) const {
    const int previous = before_[3 * size_t(v) + axis];
    return previous == 0 ? 0 : (previous == 1 || previous == -1 ? 1 : 2);
  }
  void set(uint32_t v, const int64_t r[3]) {
    for (int a = 0; a < 3; ++a) now_[3 * size_t(v) + a] = int8_t(r[a] > 100 ? 100 : (r[a] < -100 ? -100 : r[a]));
  }

 private:
  std::vector<int8_t> now_, before_;
};

}  // namespace animc
