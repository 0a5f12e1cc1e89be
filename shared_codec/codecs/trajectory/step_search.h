// SPDX-License-Identifier: Apache-2.0
// The search for a rate mode's step (docs/trajectory.md, "Rate control"): the largest u =
// log2(step) in a range whose trial is acceptable, found with few trials. Each trial costs a
// quantisation and a decode of the group, so the search predicts where the boundary is
// (secant steps on the measured excess) and bisects only where the prediction fails.
#pragma once
#include <functional>

namespace animc {

struct StepSearch {
  double lowest = 0;   // taken when no trial is acceptable
  double highest = 0;  // taken when acceptable
  double guess = 0;    // the first trial
  double slope = 1;    // the expected growth of excess per unit of u, for the first steps
  // The result is within this of the boundary: a step half a percent finer than the exact
  // boundary's costs a few tenths of a percent more bits.
  double tolerance = 1.0 / 128;
};

// excess(u) is how far the trial at u misses its bound, in log2 units: <= 0 when acceptable,
// growing with u. Returns the largest acceptable u found (lowest when none is).
double searchStep(const StepSearch& search, const std::function<double(double u)>& excess);

}  // namespace animc
