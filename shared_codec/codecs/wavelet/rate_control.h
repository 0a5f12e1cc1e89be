// SPDX-License-Identifier: Apache-2.0
// Rate control by target error (WaveletOptions::target_kg): per-frame error bounds whose sum
// over the frames bounds the sequence's KG error, and the search of the shortest bitplane
// prefix that meets a frame's bound.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

namespace animc {

// (target_kg / 100)^2 * sum over the frame's vertices of |x - centroid|^2: the KG
// denominator of this frame (DESIGN.md: E(A) is the per-frame centroid), scaled.
double frameErrorBound(const float* original, size_t vertices, double target_kg);

// Sum over vertices of |x - x~|^2, x~ the decoder's float output of reconstruction.
double floatOutputError(const float* original, const std::vector<double>& reconstruction);

// A prefix of a bitplane stream: `planes` planes, the last one after `blocks` blocks.
struct BitplaneCut {
  int planes = 0;
  size_t blocks = 0;
};

// The shortest cut with error(cut) <= bound, among 0 planes (nothing) and (n, b) for n in
// [1, planes], b in [1, blocks] on a grid of at most kCutGrid positions per plane, by
// bisection (the error falls, almost always, as the cut grows); the complete stream when
// nothing meets the bound. Only cuts that were evaluated and met the bound are returned, so
// the bound holds even where the error is not monotone. hint: a likely plane count (the
// previous frame's), tried first to save evaluations of the error.
constexpr size_t kCutGrid = 32;
BitplaneCut shortestCut(int planes, size_t blocks, double bound, int hint,
                        const std::function<double(const BitplaneCut&)>& error);

}  // namespace animc
