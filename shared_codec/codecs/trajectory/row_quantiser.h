// SPDX-License-Identifier: Apache-2.0
// A trajectory row (a group's mean, or a basis vector: x over the G frames, then y, then z)
// quantised for its bits as well as its error. The decoders take each coordinate's run as
// differences along time (group_coding.cpp), so rounding every value to the nearest integer
// is not the cheapest choice at its error: a value rounded the other way can make two
// differences smaller. Each value is rounded down or up, whichever choices along the run cost
// least in squared error plus bits at a price (a Viterbi pass, two states a value).
#pragma once
#include <cstdint>

namespace animc {

// Integers of the payload stay below 2^30 in magnitude (their differences below 2^31).
constexpr double kMaxQuantised = double(1 << 29);

// What a row's error and bits cost: error_of_a_step x (value - integer)^2, the value in
// steps, plus error_per_bit x the bits of the differences. Bits at no price: each value is
// rounded to nearest.
struct RowPrices {
  double error_of_a_step = 1;
  double error_per_bit = 0;
};

// The 3 x frames values at `step` into `out`, each rounded down or up (within
// +-kMaxQuantised), at the least price. The bits of a difference are those of its magnitude
// class (entropy/classed_integer.h), as an adaptive model would learn them from the
// differences of the values rounded to nearest, plus its sign and low bits.
void quantiseRow(const double* values, uint32_t frames, double step, const RowPrices& prices, int32_t* out);

}  // namespace animc
