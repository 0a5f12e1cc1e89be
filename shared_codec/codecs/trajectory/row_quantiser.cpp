// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/row_quantiser.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "entropy/classed_integer.h"

namespace animc {
namespace {

int64_t rounded(double value_in_steps) {
  return int64_t(std::clamp(std::nearbyint(value_in_steps), -kMaxQuantised, kMaxQuantised));
}

// Bits of a difference by its magnitude class: the class's share among the differences of
// the row rounded to nearest (and half a count for each class, as Krichevsky and Trofimov's
// estimator has), then its sign and low bits. Small differences, the common ones, are looked
// up directly.
class DifferenceBits {
 public:
  DifferenceBits(const double* values, uint32_t frames, double inverse_step) {
    std::array<uint32_t, kClasses> count{};
    for (uint32_t c = 0; c < 3; ++c) {
      int64_t previous = 0;
      for (uint32_t t = 0; t < frames; ++t) {
        const int64_t value = rounded(values[size_t(c) * frames + t] * inverse_step);
        ++count[classOf(value - previous)];
        previous = value;
      }
    }
    const double total = 3.0 * frames + 0.5 * kClasses;
    const double unseen = std::log2(total / 0.5);
    for (uint32_t c = 0; c < kClasses; ++c)
      by_class_[c] = (count[c] ? std::log2(total / (count[c] + 0.5)) : unseen) + (c > 0 ? rawBitsOfClass(c) : 0);
    for (int64_t d = -kSmall; d <= kSmall; ++d) small_[size_t(d + kSmall)] = by_class_[classOf(d)];
  }
  double operator()(int64_t d) const {
    return d >= -kSmall && d <= kSmall ? small_[size_t(d + kSmall)] : by_class_[classOf(d)];
  }

 private:
  static constexpr uint32_t kClasses = kMaxMagnitudeClass + 1;
  static constexpr int64_t kSmall = 64;
  static uint32_t classOf(int64_t d) { return std::min(magnitudeClass(uint64_t(d < 0 ? -d : d)), kMaxMagnitudeClass); }
  std::array<double, kClasses> by_class_;
  std::array<double, 2 * kSmall + 1> small_;
};

}  // namespace

void quantiseRow(const double* values, uint32_t frames, double step, const RowPrices& prices, int32_t* out) {
  if (!(prices.error_per_bit > 0)) {
    for (size_t i = 0; i < size_t(3) * frames; ++i) out[i] = int32_t(rounded(values[i] / step));
    return;
  }
  const double inverse_step = 1 / step;
  const DifferenceBits bits(values, frames, inverse_step);
  std::vector<std::array<uint8_t, 2>> came_from(frames);  // each state's best state before it
  for (uint32_t c = 0; c < 3; ++c) {
    const double* x = values + size_t(c) * frames;
    int32_t* v = out + size_t(c) * frames;
    // State 0 rounds down, state 1 up. The run starts from 0: in state 0, from a value of 0.
    int64_t previous_down = 0;
    std::array<double, 2> cost = {0, HUGE_VAL};
    for (uint32_t t = 0; t < frames; ++t) {
      const double u = x[t] * inverse_step;
      const int64_t down = int64_t(std::clamp(std::floor(u), -kMaxQuantised, kMaxQuantised - 1));
      // From state p to state s the difference is d + s - p.
      const int64_t d = down - previous_down;
      const double same = prices.error_per_bit * bits(d), fewer = prices.error_per_bit * bits(d - 1),
                   more = prices.error_per_bit * bits(d + 1);
      const double to_down[2] = {cost[0] + same, cost[1] + fewer};
      const double to_up[2] = {cost[0] + more, cost[1] + same};
      const double miss_down = u - double(down), miss_up = 1 - miss_down;
      came_from[t] = {uint8_t(to_down[1] < to_down[0]), uint8_t(to_up[1] < to_up[0])};
      cost = {std::min(to_down[0], to_down[1]) + prices.error_of_a_step * miss_down * miss_down,
              std::min(to_up[0], to_up[1]) + prices.error_of_a_step * miss_up * miss_up};
      previous_down = down;
      v[t] = int32_t(down);
    }
    int state = cost[1] < cost[0] ? 1 : 0;
    for (uint32_t t = frames; t-- > 0;) {
      v[t] += state;
      state = came_from[t][size_t(state)];
    }
  }
}

}  // namespace animc
