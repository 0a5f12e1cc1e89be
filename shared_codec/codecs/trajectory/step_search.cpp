// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/step_search.h"

#include <algorithm>
#include <cmath>

namespace animc {
namespace {

// Excesses are clamped to this (an error of 0 is -infinity) so that the secant stays finite.
constexpr double kMaxExcess = 64;
// The most a prediction moves from a trial before a bracket is known.
constexpr double kMaxJump = 4;
constexpr int kMaxTrials = 64;
// Trials in a row that lower the excess by less than this fraction of what the slope predicts
// end a search that has found no acceptable step.
constexpr double kFlatFraction = 0.125;
constexpr int kFlatTrials = 2;
// ... and only trials this much finer than the last failure count (a step 16 % finer): closer
// ones see the noise of a largest error, which does not fall smoothly with the step.
constexpr double kFlatSpan = 0.25;

}  // namespace

double searchStep(const StepSearch& s, const std::function<double(double u)>& excess) {
  const double tol = s.tolerance;
  double pass = s.lowest, fail = s.highest;  // the bracket; its ends are assumed until tried
  double f_pass = NAN, f_fail = NAN;
  double u = std::clamp(s.guess, s.lowest, s.highest);
  double width_before = HUGE_VAL;  // the bracket two trials ago
  double width_last = HUGE_VAL;
  int flat_steps = 0;  // downward trials in a row, none acceptable, the excess hardly falling
  // Before a bracket, the slope the last two trials measured (the excess of a group often
  // grows slower than the model says, and steps by the model's slope would creep up on the
  // boundary), within a quarter of the model's and the model's.
  double slope = s.slope, u_before = NAN, f_before = NAN;
  for (int trial = 0; trial < kMaxTrials; ++trial) {
    const double f = std::clamp(excess(u), -kMaxExcess, kMaxExcess);
    if (!std::isnan(f_before) && u != u_before)
      slope = std::clamp((f - f_before) / (u - u_before), s.slope / 4, s.slope);
    u_before = u;
    f_before = f;
    if (f <= 0) {
      pass = u;
      f_pass = f;
    } else {
      // Finer steps that do not lower the error: what is left is not quantisation error (the
      // components computed do not carry enough), and no step will be acceptable.
      const bool flat = !std::isnan(f_fail) && std::isnan(f_pass) && fail - u >= kFlatSpan &&
                        f_fail - f < kFlatFraction * s.slope * (fail - u);
      flat_steps = flat ? flat_steps + 1 : 0;
      if (flat_steps == kFlatTrials) return s.lowest;
      fail = u;
      f_fail = f;
    }
    if (!std::isnan(f_pass) && pass >= s.highest) return s.highest;
    if (!std::isnan(f_fail) && fail <= s.lowest) return s.lowest;
    const double width = fail - pass;
    if (!std::isnan(f_pass) && !std::isnan(f_fail) && width <= tol) break;
    // The predicted boundary, aimed half a tolerance past it on the side not yet tried close
    // by, so that the next trial often closes the bracket.
    double next;
    if (!std::isnan(f_pass) && !std::isnan(f_fail)) {
      const double root = pass + width * (-f_pass) / (f_fail - f_pass);
      next = f <= 0 ? root + tol / 2 : root - tol / 2;
      // Bisect when the predictions stop halving the bracket.
      if (width > width_before / 2) next = (pass + fail) / 2;
    } else if (f <= 0) {
      next = u + std::clamp(-f / slope, tol, kMaxJump) + tol / 2;
    } else {
      next = u - std::clamp(f / slope, tol, kMaxJump) - tol / 2;
    }
    const double margin = std::min(tol / 4, width / 4);
    u = std::clamp(next, pass + margin, fail - margin);
    width_before = width_last;
    width_last = width;
  }
  return pass;
}

}  // namespace animc
