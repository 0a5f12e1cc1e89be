// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/rate_control.h"

#include <algorithm>

namespace animc {

double frameErrorBound(const float* original, size_t vertices, double target_kg) {
  if (vertices == 0) return 0;
  double centroid[3] = {0, 0, 0};
  for (size_t i = 0; i < 3 * vertices; ++i) centroid[i % 3] += original[i];
  for (double& c : centroid) c /= double(vertices);
  double sum = 0;
  for (size_t i = 0; i < 3 * vertices; ++i) sum += (original[i] - centroid[i % 3]) * (original[i] - centroid[i % 3]);
  // A hair below the exact bound: the metric sums in another order.
  return (target_kg / 100) * (target_kg / 100) * sum * (1 - 1e-9);
}

double floatOutputError(const float* original, const std::vector<double>& reconstruction) {
  double sum = 0;
  for (size_t i = 0; i < reconstruction.size(); ++i) {
    const double d = double(float(reconstruction[i])) - double(original[i]);
    sum += d * d;
  }
  return sum;
}

namespace {

// Smallest n in [1, planes] with error(n complete planes) <= bound; planes + 1 if none.
int fewestPlanes(int planes, size_t blocks, double bound, int hint,
                 const std::function<double(const BitplaneCut&)>& error) {
  int low = 1, high = planes + 1;  // the answer is in [low, high]
  if (hint >= 1 && hint <= planes) {
    if (error(BitplaneCut{hint, blocks}) <= bound) {
      high = hint;
      if (hint == 1 || error(BitplaneCut{hint - 1, blocks}) > bound) return hint;
      high = hint - 1;
    } else {
      low = hint + 1;
    }
  }
  while (low < high) {
    const int mid = low + (high - low) / 2;
    if (error(BitplaneCut{mid, blocks}) <= bound) high = mid;
    else low = mid + 1;
  }
  return low;  // every high <= planes was a tested success; planes + 1 = none
}

}  // namespace

BitplaneCut shortestCut(int planes, size_t blocks, double bound, int hint,
                        const std::function<double(const BitplaneCut&)>& error) {
  const BitplaneCut complete{planes, blocks};
  if (planes <= 0 || blocks == 0 || error(BitplaneCut{0, 0}) <= bound) return BitplaneCut{0, 0};
  const int n = fewestPlanes(planes, blocks, bound, hint, error);
  if (n > planes) return complete;
  // Within plane n, the fewest grid steps of blocks (the last grid point is all blocks).
  const size_t grid = std::min(blocks, kCutGrid);
  auto blocksAt = [&](size_t g) { return (blocks * g + grid - 1) / grid; };
  size_t first = 1, last = grid;
  while (first < last) {
    const size_t mid = first + (last - first) / 2;
    if (error(BitplaneCut{n, blocksAt(mid)}) <= bound) last = mid;
    else first = mid + 1;
  }
  return BitplaneCut{n, blocksAt(last)};
}

}  // namespace animc
