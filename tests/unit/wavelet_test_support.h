// SPDX-License-Identifier: Apache-2.0
// Helpers of the wavelet codec tests: frame and sequence errors.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/memory_sequence.h"
#include "test_sequences.h"  // decodedMetrics, kgError

namespace animc::testing_support {

inline std::vector<double> toDouble(const std::vector<float>& v) { return std::vector<double>(v.begin(), v.end()); }

// Root mean square of the vertex errors.
template <class A, class B>
double rmsError(const A& original, const B& decoded) {
  double sum = 0;
  for (size_t i = 0; i < original.size(); ++i) sum += (double(original[i]) - double(decoded[i])) * (double(original[i]) - double(decoded[i]));
  return std::sqrt(sum / double(original.size() / 3));
}

inline double bboxDiagonal(const std::vector<float>& xyz) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], double(xyz[i]));
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

}  // namespace animc::testing_support
