// SPDX-License-Identifier: Apache-2.0
// Context selection for the default profile's per-vertex residuals: the size of the same
// vertex's residual on the same axis in the previous frame (a vertex the affine missed
// once tends to be missed again). Both sides know it, so the context costs no bits.
// Adding the already decoded mesh neighbours' residuals saves a few more bits but halves the
// decoding speed, so it is not used (docs/notes/affine_octree_history.md).
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
  // The frame just coded becomes the history, and the new frame starts with no residual
  // anywhere: a leaf without residuals then has nothing to record, which is cheaper than
  // recording three zeros per vertex (most leaves have none).
  void beginFrame() {
    before_.swap(now_);
    std::fill(now_.begin(), now_.end(), 0);
  }

  // By coordinate index (3·v + axis): the context its residual is coded in this frame, and
  // its residual, recorded for the next (a zero needs no recording).
  int contextAt(size_t coordinate) const { return before_[coordinate]; }
  // By the vertex's first coordinate index: the largest of its three axes' contexts.
  int vertexContext(size_t coordinate) const {
    return std::max(std::max(before_[coordinate], before_[coordinate + 1]), before_[coordinate + 2]);
  }
  void setAt(size_t coordinate, int64_t r) { now_[coordinate] = contextOf(r); }

 private:
  // 0: the residual was zero, 1: it was ±1, 2: it was larger.
  static uint16_t contextOf(int64_t r) { return r == 0 ? 0 : (r == 1 || r == -1 ? 1 : 2); }

  // The context each residual gives the next frame, stored rather than the residual itself;
  // 16-bit because char-typed stores would alias the range coder's state.
  std::vector<uint16_t> now_, before_;
};

}  // namespace animc
