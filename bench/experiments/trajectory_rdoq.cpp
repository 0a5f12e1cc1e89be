// SPDX-License-Identifier: Apache-2.0
// Design measurement for the trajectory codec's next version (issue 40): what rate-distortion
// quantisation of the coefficients would gain. For a trajectory-coded file of one group and
// its sequence, the group's leading K components are computed again as the encoder does (K and
// the coefficient step q from the file), and their coefficients c quantised three ways, each
// then coded as codec 3 codes them (its contexts and breadth-first prediction, through the
// codec's range coder and classed-integer models):
//   nearest  round(c / q);
//   today    the encoder's rule: towards zero below 0.6 of a step past an integer;
//   rdoq     vertex by vertex in coding order, each value the one of round(c / q), one step
//            nearer zero, and zero with the least squared error + lambda x its bits in the
//            models' state at that point, lambda the squared error a bit buys at a uniform
//            quantiser's slope (2 ln 2 / 12 q^2, the encoder's kBitSlope).
// Each variant's bytes and squared error (in the coefficient domain, which the orthonormal
// basis carries to the frames) are printed, and its bytes at today's error: the difference in
// error converted to bits at the slope today's rule has there, measured by coding the same
// coefficients with it at a 5 % coarser step (a uniform quantiser's 2 ln 2 / 12 q^2 does not
// hold at these rates: by it, plain rounding would beat today's rule, which real encodes at
// equal KG contradict, docs/trajectory.md).
// trajectory_variants.py builds it and runs it.
//   usage: trajectory_rdoq FILE.ams SEQUENCE MESH
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "entropy/classed_integer.h"
#include "trajectory_file.h"

namespace {

// The codec's own bands and prediction (group_coding.h).
constexpr int kBands = animc::kCoefficientBands;
using animc::coefficientBand;
using animc::roundedMean;
constexpr double kBitSlope = 2 * M_LN2 / 12;  // squared steps a bit buys

enum class Rule { kNearest, kToday, kRdoq };

struct Coded {
  double bytes = 0, error = 0;  // error squared, in the frames' units
};

Coded quantiseAndCode(const animc::Components& pc, const animc::CodingOrder& order, uint32_t K, double q, Rule rule) {
  const uint32_t n = uint32_t(order.vertex.size());
  std::vector<animc::ClassedIntegerModel> models(kBands * 3);
  std::vector<int64_t> value(size_t(n) * K, 0);
  std::vector<uint8_t> out;
  animc::RangeEncoder rc(out);
  animc::RawBitWriter raw;
  Coded c;
  for (uint32_t p = 0; p < n; ++p) {
    const uint32_t begin = order.first[p], end = order.first[p + 1];
    for (uint32_t k = 0; k < K; ++k) {
      int64_t prediction = 0;
      int kind = 0;
      if (begin != end) {
        int64_t sum = 0;
        for (uint32_t j = begin; j < end; ++j) sum += value[size_t(order.earlier[j]) * K + k];
        prediction = roundedMean(sum, int64_t(end - begin));
        kind = prediction == 0 ? 1 : 2;
      }
      animc::ClassedIntegerModel& model = models[size_t(coefficientBand(k) * 3 + kind)];
      const double x = double(pc.coefficients(Eigen::Index(p), Eigen::Index(k))) / q;  // in steps
      const double a = std::fabs(x);
      int64_t v = std::llround(x);
      if (rule == Rule::kToday) v = int64_t(std::copysign(std::floor(a + 1 - 0.6), x));
      if (rule == Rule::kRdoq) {
        const int64_t nearest = std::llround(x);
        const int64_t candidates[3] = {nearest, nearest - (nearest > 0) + (nearest < 0), 0};
        double best = HUGE_VAL;
        for (int64_t candidate : candidates) {
          const double cost = (x - double(candidate)) * (x - double(candidate)) +
                              kBitSlope * animc::classedCost(model, candidate - prediction);
          if (cost < best) best = cost, v = candidate;
        }
      }
      value[size_t(p) * K + k] = v;
      c.error += (x - double(v)) * (x - double(v)) * q * q;
      animc::encodeClassed(rc, raw, model, v - prediction);
    }
  }
  rc.finish();
  raw.appendTo(out);
  c.bytes = double(out.size());
  return c;
}

int measure(const OneGroup& one) {
  const animc::CodingOrder& order = *one.file.order;
  const animc::Components& pc = one.pc;
  const animc::TrajectoryGroup& g = one.group;
  const uint32_t K = std::min<uint32_t>(g.components, uint32_t(pc.sigma.size()));
  const char* names[3] = {"nearest", "today", "rdoq"};
  const double q = g.coefficient_step;
  Coded coded[3];
  for (int r = 0; r < 3; ++r) coded[r] = quantiseAndCode(pc, order, K, q, Rule(r));
  const Coded coarser = quantiseAndCode(pc, order, K, 1.05 * q, Rule::kToday);
  const double error_per_byte = (coarser.error - coded[1].error) / (coded[1].bytes - coarser.bytes);
  std::printf("{\"file\": \"%s\", \"components\": %u, \"bits_per_squared_step\": %.3f", one.path.c_str(), K,
              q * q / error_per_byte * 8);
  for (int r = 0; r < 3; ++r) {
    const double at_today = coded[r].bytes + (coded[r].error - coded[1].error) / error_per_byte;
    std::printf(", \"%s_bytes\": %.0f, \"%s_error\": %.6g, \"%s_at_today\": %.0f", names[r], coded[r].bytes,
                names[r], coded[r].error, names[r], at_today);
  }
  std::printf("}\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return measureOneGroup("trajectory_rdoq", argc, argv, measure); }
