// SPDX-License-Identifier: Apache-2.0
// The trajectory encoder: principal components of a group's trajectories (Eigen), then the
// coarsest coefficient step that meets the target error, measured on the frames the decoder
// will produce.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/trajectory_codec.h"
#include "core/parallel.h"

namespace animc {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The trajectories of one group held in double: at most this many values (256 MB). Since
// the components are at most 3 x frames, the coefficients then stay within the decoders'
// kMaxTrajectoryCoefficients too.
constexpr uint64_t kMaxGroupValues = uint64_t(1) << 25;
static_assert(kMaxGroupValues <= kMaxTrajectoryCoefficients, "a group's coefficients must fit the format's limit");
// Integers of the payload stay below 2^30 in magnitude (their differences below 2^31).
constexpr double kMaxQuantised = double(1 << 29);

// The principal components of a group's trajectories: the mean trajectory, unit basis
// vectors by decreasing singular value, and every vertex's coefficients on them.
struct Components {
  Eigen::RowVectorXd mean;  // 3G
  Eigen::MatrixXd basis;    // 3G x K, columns
  Eigen::VectorXd sigma;    // K
  RowMatrix coefficients;   // N x K
};

// The products of a group's large matrices are cut into blocks of a fixed size that threads
// share: the blocks, never the thread count, decide what each product computes.
constexpr Eigen::Index kProductColumns = 64;
constexpr Eigen::Index kProductRows = 1024;

// The lower triangle of a^T a, all that the eigensolver reads (the rest is zero), a block of
// columns at a time.
template <class Matrix>
Eigen::MatrixXd lowerGram(const Matrix& a) {
  const Eigen::Index d = a.cols();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(d, d);
  const size_t blocks = size_t((d + kProductColumns - 1) / kProductColumns);
  parallelFor(blocks, double(a.rows()) * double(d) * double(kProductColumns) / 2, [&](size_t b) {
    const Eigen::Index j = Eigen::Index(b) * kProductColumns, w = std::min(kProductColumns, d - j);
    gram.block(j, j, d - j, w).noalias() = a.middleCols(j, d - j).transpose() * a.middleCols(j, w);
  });
  return gram;
}

// a * b, a block of rows of a at a time.
RowMatrix productByRows(const RowMatrix& a, const Eigen::MatrixXd& b) {
  RowMatrix out(a.rows(), b.cols());
  const size_t blocks = size_t((a.rows() + kProductRows - 1) / kProductRows);
  parallelFor(blocks, double(kProductRows) * double(a.cols()) * double(b.cols()), [&](size_t i) {
    const Eigen::Index r = Eigen::Index(i) * kProductRows, h = std::min(kProductRows, a.rows() - r);
    out.middleRows(r, h).noalias() = a.middleRows(r, h) * b;
  });
  return out;
}

// a^T * b, a block of columns of b at a time.
Eigen::MatrixXd transposedProductByColumns(const RowMatrix& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.cols(), b.cols());
  const size_t blocks = size_t((b.cols() + kProductColumns - 1) / kProductColumns);
  parallelFor(blocks, double(a.rows()) * double(a.cols()) * double(kProductColumns), [&](size_t i) {
    const Eigen::Index j = Eigen::Index(i) * kProductColumns, w = std::min(kProductColumns, b.cols() - j);
    out.middleCols(j, w).noalias() = a.transpose() * b.middleCols(j, w);
  });
  return out;
}

Components principalComponents(RowMatrix x, uint64_t max_components) {
  Components pc;
  pc.mean = x.colwise().mean();
  x.rowwise() -= pc.mean;
  const Eigen::Index n = x.rows(), row = x.cols();
  // The smaller of the two Gram matrices: trajectories (row x row) or vertices (n x n).
  const bool by_trajectory = row <= n;
  const Eigen::MatrixXd gram = by_trajectory ? lowerGram(x) : lowerGram(x.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(gram);
  const Eigen::Index dim = gram.rows();
  const Eigen::Index k_count = std::min<Eigen::Index>(dim, Eigen::Index(max_components));
  pc.sigma.resize(k_count);
  Eigen::MatrixXd vectors(dim, k_count);
  for (Eigen::Index k = 0; k < k_count; ++k) {  // the solver sorts ascending
    pc.sigma[k] = std::sqrt(std::max(0.0, solver.eigenvalues()[dim - 1 - k]));
    vectors.col(k) = solver.eigenvectors().col(dim - 1 - k);
  }
  if (by_trajectory) {
    pc.basis = vectors;
    pc.coefficients = productByRows(x, pc.basis);
  } else {
    pc.basis = transposedProductByColumns(x, vectors);
    for (Eigen::Index k = 0; k < k_count; ++k) {
      if (pc.sigma[k] > 0) pc.basis.col(k) /= pc.sigma[k];
      vectors.col(k) *= pc.sigma[k];
    }
    pc.coefficients = vectors;
  }
  return pc;
}

int32_t quantise(double value, double step) {
  return int32_t(std::clamp(std::nearbyint(value / step), -kMaxQuantised, kMaxQuantised));
}

// Coefficients are rounded towards zero a little (a value within 0.6 of a step of zero
// becomes 0, and so on): a zero costs far fewer bits than a 1, and the step the target then
// needs is only a little finer. 0.6 beat 0.5 and 0.7 on the shared sequences (trajectory.md).
constexpr double kRoundingThreshold = 0.6;
// The squared error a bit buys at a uniform quantiser's slope, per squared step: 2 ln 2 / 12.
constexpr double kBitSlope = 0.1155;
int32_t quantiseCoefficient(double value, double step) {
  const double magnitude = std::min(std::floor(std::fabs(value) / step + 1 - kRoundingThreshold), kMaxQuantised);
  return int32_t(std::copysign(magnitude, value));
}

class TrajectoryEncoder final : public GroupEncoder {
 public:
  TrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology, SimdPath path)
      : options_(options), order_(topology), vertices_(topology.vertex_count), path_(path) {}

  uint32_t maxGroupFrames() const override {
    const uint64_t by_memory = std::max<uint64_t>(1, kMaxGroupValues / (uint64_t(3) * vertices_));
    return uint32_t(std::min<uint64_t>(options_.group_frames, by_memory));
  }

  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    original_ = frames;
    frame_count_ = frame_count;
    cube_sides_.clear();  // measure() compares with them at every step the bisection tries
    if (options_.rate == TrajectoryRate::kMaxError)
      for (uint32_t t = 0; t < frame_count; ++t) cube_sides_.push_back(cubeSide(t));
    const Components pc = principalComponents(trajectories(), kMaxTrajectoryCoefficients / vertices_);
    const TrajectoryGroup group = quantised(pc, chooseStep(pc));
    payloads.assign(frame_count, std::vector<uint8_t>{kTrajectoryNextFrame});
    payloads[0].clear();
    writeTrajectoryGroup(group, order_, payloads[0]);
    frames_.reset(group, order_, path_);
    original_ = nullptr;
  }

  void reconstruction(uint32_t k, float* xyz) const override { frames_.frame(k, xyz); }

 private:
  const float* vertexOf(uint32_t t, uint32_t v) const { return original_ + (size_t(t) * vertices_ + v) * 3; }

  RowMatrix trajectories() const {
    const uint32_t g = frame_count_;
    RowMatrix x(vertices_, 3 * g);
    for (uint32_t t = 0; t < g; ++t)
      for (uint32_t v = 0; v < vertices_; ++v)
        for (uint32_t c = 0; c < 3; ++c) x(v, c * g + t) = vertexOf(t, v)[c];
    return x;
  }

  // The sides of frame t's bounding box.
  std::array<double, 3> boxSides(uint32_t t) const {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (uint32_t v = 0; v < vertices_; ++v)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], double(vertexOf(t, v)[c]));
        hi[c] = std::max(hi[c], double(vertexOf(t, v)[c]));
      }
    return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  }

  double firstFrameDiagonal() const {
    const std::array<double, 3> s = boxSides(0);
    return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  }

  // The largest side of frame t's bounding box, 1 for a point (the affine-octree's cube).
  double cubeSide(uint32_t t) const {
    const std::array<double, 3> s = boxSides(t);
    const double side = std::max({s[0], s[1], s[2]});
    return side > 0 ? side : 1;
  }

  // Sum over the group's frames of |x - centroid of its frame|^2: the KG error's denominator.
  double spread() const {
    double sum = 0;
    for (uint32_t t = 0; t < frame_count_; ++t) {
      double centroid[3] = {0, 0, 0};
      for (uint32_t v = 0; v < vertices_; ++v)
        for (int c = 0; c < 3; ++c) centroid[c] += vertexOf(t, v)[c];
      for (double& c : centroid) c /= vertices_;
      for (uint32_t v = 0; v < vertices_; ++v)
        for (int c = 0; c < 3; ++c) sum += (vertexOf(t, v)[c] - centroid[c]) * (vertexOf(t, v)[c] - centroid[c]);
    }
    return sum;
  }

  // The coefficient step of the rate mode: fixed, or found by bisection on its logarithm
  // (the error grows and the size falls with the step).
  double chooseStep(const Components& pc) const {
    const double largest = pc.coefficients.size() ? pc.coefficients.cwiseAbs().maxCoeff() : 0.0;
    const double scale = std::max({largest, firstFrameDiagonal(), 1e-30});
    const double finest = std::max(largest / kMaxQuantised, scale * 1e-12);
    const double value = options_.rate_value;
    std::function<bool(double)> acceptable;  // of a step; true for the steps below some bound
    bool larger_is_acceptable = false;
    switch (options_.rate) {
      case TrajectoryRate::kStep: return std::max(value * firstFrameDiagonal(), finest);
      case TrajectoryRate::kTargetKg: {
        const double allowed = (value / 100) * (value / 100) * spread();
        acceptable = [&, allowed](double q) { return measure(quantised(pc, q)).squared <= allowed; };
        break;
      }
      case TrajectoryRate::kMaxError:
        acceptable = [&](double q) { return measure(quantised(pc, q)).within_max_error; };
        break;
      case TrajectoryRate::kBitsPerVertexFrame: {
        const double budget = value * vertices_ * frame_count_ / 8;
        acceptable = [&, budget](double q) {
          std::vector<uint8_t> payload;
          writeTrajectoryGroup(quantised(pc, q), order_, payload);
          return double(payload.size()) <= budget;
        };
        larger_is_acceptable = true;
        break;
      }
    }
    // pass: the end of the range known to be acceptable (assumed for the finest step with an
    // error bound, which meets any bound but float rounding; for a budget, the coarsest).
    double pass = larger_is_acceptable ? std::log2(2 * scale) : std::log2(finest);
    double fail = larger_is_acceptable ? std::log2(finest) : std::log2(2 * scale);
    if (acceptable(std::exp2(fail))) return std::exp2(fail);
    for (int i = 0; i < 24; ++i) {
      const double mid = (pass + fail) / 2;
      (acceptable(std::exp2(mid)) ? pass : fail) = mid;
    }
    return std::exp2(pass);
  }

  TrajectoryGroup quantised(const Components& pc, double step) const {
    TrajectoryGroup g;
    g.frames = frame_count_;
    g.coefficient_step = float(step);
    const double q = g.coefficient_step;
    const size_t row = size_t(3) * frame_count_;
    // Each component is quantised and judged on its own, on any thread; the ones sent are
    // then taken in order.
    const Eigen::Index k_all = pc.coefficients.cols();
    struct Quantised {
      std::vector<int32_t> column, basis;
      float basis_step = 0;
    };
    std::vector<Quantised> parts(static_cast<size_t>(k_all));
    parallelFor(parts.size(), 20.0 * vertices_ + 10.0 * row, [&](size_t i) {
      const Eigen::Index k = Eigen::Index(i);
      Quantised& part = parts[i];
      std::vector<int32_t> column(vertices_);
      bool any = false;
      for (uint32_t p = 0; p < vertices_; ++p) {
        column[p] = quantiseCoefficient(pc.coefficients(order_.vertex[p], k), q);
        any |= column[p] != 0;
      }
      if (!any) return;
      // An error d in basis vector k moves the vertices by their coefficients times d, sigma_k
      // in total, and one in the mean moves all N vertices by d: these steps make each cost
      // the squared error of one coefficient's step.
      const float basis_step = float(std::clamp(q / pc.sigma[k], 1.0 / kMaxQuantised, 2.0));
      std::vector<int32_t> basis(row);
      for (size_t j = 0; j < row; ++j) basis[j] = quantise(pc.basis(Eigen::Index(j), k), basis_step);
      if (!worthSending(pc, k, q, column, basis, basis_step)) return;
      part.column = std::move(column);
      part.basis = std::move(basis);
      part.basis_step = basis_step;
    });
    std::vector<std::vector<int32_t>> columns, rows;
    std::vector<float> steps;
    for (Quantised& part : parts) {
      if (part.column.empty()) continue;
      columns.push_back(std::move(part.column));
      rows.push_back(std::move(part.basis));
      steps.push_back(part.basis_step);
    }
    const uint32_t used = uint32_t(columns.size());
    g.components = used;
    g.coefficients.resize(size_t(vertices_) * used);
    for (uint32_t p = 0; p < vertices_; ++p)
      for (uint32_t k = 0; k < used; ++k) g.coefficients[size_t(p) * used + k] = columns[k][p];
    g.basis_step = steps;
    g.basis.resize(used * row);
    for (uint32_t k = 0; k < used; ++k) std::copy(rows[k].begin(), rows[k].end(), g.basis.begin() + k * row);
    const double mean_reach = pc.mean.cwiseAbs().maxCoeff();
    g.mean_step = float(std::max(q / std::sqrt(double(vertices_)), mean_reach / kMaxQuantised + 1e-30));
    g.mean.resize(row);
    for (size_t i = 0; i < row; ++i) g.mean[i] = quantise(pc.mean[Eigen::Index(i)], g.mean_step);
    return g;
  }

  // Rate-distortion choice of a component: sent when the squared error it removes (its
  // energy, less the error of its quantised coefficients and basis vector) is worth its
  // estimated bits at the slope of a uniform quantiser, 2 ln 2 q^2 / 12 per bit. Weak
  // components otherwise cost a whole basis vector for a few coefficients.
  bool worthSending(const Components& pc, Eigen::Index k, double q, const std::vector<int32_t>& column,
                    const std::vector<int32_t>& basis, float basis_step) const {
    double coded_error = 0, coded_energy = 0, bits = 0;
    for (uint32_t p = 0; p < vertices_; ++p) {
      const double c = pc.coefficients(order_.vertex[p], k), chat = column[p] * q;
      coded_error += (c - chat) * (c - chat);
      coded_energy += chat * chat;
      bits += estimatedBits(column[p]);
    }
    double basis_error = 0;
    int64_t previous = 0;
    for (size_t i = 0; i < basis.size(); ++i) {
      const double b = pc.basis(Eigen::Index(i), k), bhat = basis[i] * double(basis_step);
      basis_error += (b - bhat) * (b - bhat);
      if (i % frame_count_ == 0) previous = 0;
      bits += estimatedBits(basis[i] - previous);
      previous = basis[i];
    }
    coded_error += coded_energy * basis_error;
    const double removed = pc.sigma[k] * pc.sigma[k] - coded_error;
    return removed > kBitSlope * q * q * bits;
  }

  // Bits of a value through an adaptive classed model, roughly: zeros are the common case.
  static double estimatedBits(int64_t v) {
    if (v == 0) return 0.3;
    return 2 + 2 * std::log2(double(v < 0 ? -v : v));
  }

  struct GroupError {
    double squared = 0;            // summed over the group's vertices and frames
    bool within_max_error = true;  // every vertex within the max error (kMaxError)
  };

  // The error of the frames the decoder will make of `group`.
  GroupError measure(const TrajectoryGroup& group) const {
    GroupFrames decoded;
    decoded.reset(group, order_, path_);
    std::vector<float> xyz(size_t(3) * vertices_);
    GroupError e;
    for (uint32_t t = 0; t < frame_count_; ++t) {
      decoded.frame(t, xyz.data());
      const float* original = vertexOf(t, 0);
      double worst = 0;
      for (size_t v = 0; v < xyz.size(); v += 3) {
        double sq = 0;
        for (int c = 0; c < 3; ++c)
          sq += (double(xyz[v + c]) - original[v + c]) * (double(xyz[v + c]) - original[v + c]);
        e.squared += sq;
        worst = std::max(worst, sq);
      }
      if (options_.rate == TrajectoryRate::kMaxError) {
        const double bound = options_.rate_value * cube_sides_[t];
        e.within_max_error &= worst <= bound * bound;
      }
    }
    return e;
  }

  TrajectoryOptions options_;
  CodingOrder order_;
  uint32_t vertices_;
  SimdPath path_;
  const float* original_ = nullptr;  // the group being coded
  uint32_t frame_count_ = 0;
  std::vector<double> cube_sides_;  // of the group's frames (kMaxError)
  GroupFrames frames_;              // the last group as decoded
};

}  // namespace

std::unique_ptr<GroupEncoder> makeTrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryEncoder>(options, topology, path);
}

}  // namespace animc
