// SPDX-License-Identifier: Apache-2.0
// Design measurement for the trajectory codec's next version (issue 40): the basis vectors
// quantised in a DCT domain along time instead of the time domain. For a trajectory-coded
// file of one group and its sequence, the group's leading K principal components are computed
// again as the encoder does (TrajectoryDecomposition; K and the coefficient step q from the
// file), and each basis vector b_k (3G values: x over the G frames, then y, then z) is
// quantised at the encoder's step s_k = q / sigma_k two ways:
//   time  today's: round(b / s_k), coded as differences along each coordinate's run, one
//         classed-integer model per component band (group_coding.cpp's encodeRow);
//   dct   each coordinate's run through an orthonormal DCT-II of length G, round(d / s_k),
//         the integers coded as they are, one model per component band and frequency band
//         (0, 1, 2-3, 4-7, ...: high frequencies of smooth vectors are mostly zero).
// Both through the codec's range coder. The error a basis vector's quantisation adds to the
// frames is sigma_k^2 times its squared error (the DCT is orthonormal, so it is measured in
// either domain); the sums of both over the K vectors are printed.
// trajectory_variants.py builds it and runs it.
//   usage: trajectory_basis_dct FILE.ams SEQUENCE MESH
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

struct Coded {
  double bytes = 0, error = 0;  // error: sum of sigma_k^2 |b_k - quantised b_k|^2
};

// Orthonormal DCT-II matrix of size n (row f: frequency f).
std::vector<double> dctMatrix(uint32_t n) {
  std::vector<double> m(size_t(n) * n);
  for (uint32_t f = 0; f < n; ++f)
    for (uint32_t t = 0; t < n; ++t)
      m[size_t(f) * n + t] = std::cos(M_PI * (t + 0.5) * f / n) * std::sqrt((f == 0 ? 1.0 : 2.0) / n);
  return m;
}

Coded codeBasis(const animc::Components& pc, uint32_t K, uint32_t G, double q, bool dct) {
  const std::vector<double> m = dct ? dctMatrix(G) : std::vector<double>();
  std::vector<animc::ClassedIntegerModel> models(kBands * (dct ? 12 : 1));
  std::vector<uint8_t> out;
  animc::RangeEncoder rc(out);
  animc::RawBitWriter raw;
  Coded c;
  for (uint32_t k = 0; k < K; ++k) {
    const double sigma = pc.sigma[k], step = std::clamp(q / sigma, 1.0 / 2147483647.0, 2.0);
    for (uint32_t axis = 0; axis < 3; ++axis) {
      std::vector<double> run(G);
      for (uint32_t t = 0; t < G; ++t) run[t] = pc.basis(Eigen::Index(axis * G + t), Eigen::Index(k));
      if (dct) {
        for (uint32_t f = 0; f < G; ++f) {
          double d = 0;
          for (uint32_t t = 0; t < G; ++t) d += m[size_t(f) * G + t] * run[t];
          const int64_t v = std::llround(d / step);
          const double e = d - double(v) * step;
          c.error += sigma * sigma * e * e;
          const int frequency_band = std::min(f == 0 ? 0 : 32 - __builtin_clz(f), 11);
          animc::encodeClassed(rc, raw, models[size_t(coefficientBand(k)) * 12 + frequency_band], v);
        }
      } else {
        int64_t previous = 0;
        for (uint32_t t = 0; t < G; ++t) {
          const int64_t v = std::llround(run[t] / step);
          const double e = run[t] - double(v) * step;
          c.error += sigma * sigma * e * e;
          animc::encodeClassed(rc, raw, models[size_t(coefficientBand(k))], v - previous);
          previous = v;
        }
      }
    }
  }
  rc.finish();
  raw.appendTo(out);
  c.bytes = double(out.size());
  return c;
}

int measure(const OneGroup& one) {
  const animc::TrajectoryGroup& g = one.group;
  const animc::Components& pc = one.pc;
  const std::string& ams = one.path;
  const uint32_t G = g.frames;
  const uint32_t K = std::min<uint32_t>(g.components, uint32_t(pc.sigma.size()));
  const Coded time = codeBasis(pc, K, G, g.coefficient_step, false);
  const Coded dct = codeBasis(pc, K, G, g.coefficient_step, true);
  std::printf("{\"file\": \"%s\", \"components\": %u, \"time_bytes\": %.0f, \"time_error\": %.6g, "
              "\"dct_bytes\": %.0f, \"dct_error\": %.6g}\n",
              ams.c_str(), K, time.bytes, time.error, dct.bytes, dct.error);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return measureOneGroup("trajectory_basis_dct", argc, argv, measure); }
