// SPDX-License-Identifier: Apache-2.0
// The trajectory encoder: principal components of a group's trajectories (Eigen), then the
// coarsest coefficient step that meets the target error, measured on the frames the decoder
// will produce.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "codecs/trajectory/components.h"
#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/group_frames.h"
#include "codecs/trajectory/step_search.h"
#include "codecs/trajectory/trajectory_codec.h"
#include "core/large_memory.h"
#include "core/parallel.h"

namespace animc {
namespace {

// The trajectories of one group: at most this many values (128 MB in float). Since
// the components are at most 3 x frames, the coefficients then stay within the decoders'
// kMaxTrajectoryCoefficients too.
constexpr uint64_t kMaxGroupValues = uint64_t(1) << 25;
static_assert(kMaxGroupValues <= kMaxTrajectoryCoefficients, "a group's coefficients must fit the format's limit");
// Integers of the payload stay below 2^30 in magnitude (their differences below 2^31).
constexpr double kMaxQuantised = double(1 << 29);
// The components computed first, and the fewest computed more at a time.
constexpr Eigen::Index kFirstComponents = 64;
constexpr Eigen::Index kMinMoreComponents = 16;
// Vertices the rate search quantises and measures at a time, on one thread: a block's
// coefficients and frames stay in cache.
constexpr uint32_t kVertexBlock = 2048;

size_t vertexBlocks(uint32_t vertices) { return (vertices + kVertexBlock - 1) / kVertexBlock; }

// block(b, begin, end) for the vertex blocks of `vertices`, on any thread. The blocks are
// fixed, so what each one sums never depends on the thread count; vertex_cost is parallelFor's
// cost of one vertex.
void forVertexBlocks(uint32_t vertices, double vertex_cost,
                     const std::function<void(size_t b, uint32_t begin, uint32_t end)>& block) {
  parallelForBlocks(vertices, kVertexBlock, vertex_cost,
                    [&](size_t b, size_t begin, size_t end) { block(b, uint32_t(begin), uint32_t(end)); });
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
      : options_(options), order_(topology), vertices_(topology.vertex_count), path_(path), position_(vertices_) {
    for (uint32_t p = 0; p < vertices_; ++p) position_[order_.vertex[p]] = p;
  }

  uint32_t maxGroupFrames() const override {
    const uint64_t by_memory = std::max<uint64_t>(1, kMaxGroupValues / (uint64_t(3) * vertices_));
    return uint32_t(std::min<uint64_t>(options_.group_frames, by_memory));
  }

  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    frames_ = GroupFrames();  // the last group's, no longer asked for
    original_ = frames;
    frame_count_ = frame_count;
    cube_sides_.clear();  // measure() compares with them at every step the search tries
    if (options_.rate == TrajectoryRate::kMaxError) {
      cube_sides_.resize(frame_count);
      parallelFor(frame_count, 6.0 * vertices_, [&](size_t t) { cube_sides_[t] = cubeSide(uint32_t(t)); });
    }
    spread_ = options_.rate == TrajectoryRate::kTargetKg ? spread() : 0;
    TrajectoryDecomposition decomposition(trajectories());
    // The leading components only, as many as the step chosen might send: more while the
    // weakest of them could still be worth its bits.
    Components pc = decomposition.none();
    Eigen::Index more = kFirstComponents;
    double step = 0;
    for (;;) {
      decomposition.extend(pc, more, negligibleEnergy());
      // The model's step can be off by half: pc is judged at twice it before any search.
      const double optimistic = 2 * predictedStep(pc);
      if (!pc.complete && clearlyTooFew(pc, optimistic)) {
        more = moreComponents(pc, optimistic);
        continue;
      }
      step = chooseStep(pc);
      if (pc.complete || carriesEnough(pc, step) || sendsNoneOfTheWeakest(pc, float(step))) break;
      more = moreComponents(pc, step);
    }
    TrajectoryGroup group;
    quantiseGroup(pc, step, group);
    pc = Components();  // before the decoded frames take as much memory
    trial_group_ = TrajectoryGroup();
    payloads.assign(frame_count, std::vector<uint8_t>{kTrajectoryNextFrame});
    payloads[0].clear();
    writeTrajectoryGroup(group, order_, payloads[0]);
    frames_.reset(group, order_, path_);
    original_ = nullptr;
  }

  bool reconstruction(uint32_t k, float* xyz) const override {
    frames_.frame(k, xyz);
    return true;
  }

 private:
  const float* vertexOf(uint32_t t, uint32_t v) const { return original_ + (size_t(t) * vertices_ + v) * 3; }

  // A row a vertex, in coding order (so are the coefficients then), of 3G values: x over the
  // frames, then y, then z.
  RowMatrixF trajectories() const {
    const uint32_t g = frame_count_;
    RowMatrixF x(vertices_, 3 * g);
    adviseHugePages(x.data(), size_t(x.size()) * sizeof(float));  // the encoder's largest buffer
    forVertexBlocks(vertices_, 3.0 * g, [&](size_t, uint32_t begin, uint32_t end) {
      for (uint32_t p = begin; p < end; ++p)
        for (uint32_t t = 0; t < g; ++t)
          for (uint32_t c = 0; c < 3; ++c) x(p, c * g + t) = vertexOf(t, order_.vertex[p])[c];
    });
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

  // Whether a component weaker than all of pc's would never be worth sending at step q: it
  // would remove at most its energy, and cost at least the bits of a zero for each of its
  // coefficients and basis values.
  bool carriesEnough(const Components& pc, double q) const {
    if (pc.sigma.size() == 0) return pc.complete;
    const double weakest = pc.sigma[pc.sigma.size() - 1];
    return weakest * weakest <= leastWorthSending(q);
  }

  // Whether pc cannot do, before any search: the energy it leaves out is more than the error
  // allowed, or step q (the model's, doubled) would send the weakest of pc's components.
  bool clearlyTooFew(const Components& pc, double q) const {
    const double left_out = pc.energy - pc.sigma.squaredNorm();
    if (options_.rate == TrajectoryRate::kTargetKg || options_.rate == TrajectoryRate::kMaxError) {
      if (left_out > allowedAtMost()) return true;
      if (left_out >= modelledAllowance()) return false;  // the model cannot tell
    }
    return !carriesEnough(pc, q) && !sendsNoneOfTheWeakest(pc, float(q));
  }

  // Whether none of the weakest eighth of pc's components is sent at step q: the components
  // after them, weaker still, would not be either. (The bound above is safe but can ask for
  // many more components that are not sent in the end.)
  bool sendsNoneOfTheWeakest(const Components& pc, float q) const {
    const Eigen::Index k = pc.sigma.size(), tail = std::max<Eigen::Index>(kMinMoreComponents / 2, k / 8);
    return selection(pc, q, std::max<Eigen::Index>(0, k - tail)).sent.empty();
  }

  double leastWorthSending(double q) const {
    return kBitSlope * q * q * estimatedBits(0) * (vertices_ + 3.0 * frame_count_);
  }

  // How many more components step q probably needs, from the decay of the last half of
  // pc's singular values: a quarter more than where they fall below what is worth sending.
  Eigen::Index moreComponents(const Components& pc, double q) const {
    const Eigen::Index k = pc.sigma.size();
    const double weakest = pc.sigma[k - 1], middle = pc.sigma[k / 2];
    const double decay = std::log(weakest / middle) / double(k - 1 - k / 2);  // per component
    const double needed = std::log(std::sqrt(leastWorthSending(q)) / weakest) / decay;
    if (!(decay < 0) || !(needed < double(k))) return k;
    return std::max<Eigen::Index>(std::max(kMinMoreComponents, k / 2), Eigen::Index(1.25 * needed) + 1);
  }

  // The step the search will probably choose (a model's), or the fixed step; infinity for a
  // budget (no prediction).
  double predictedStep(const Components& pc) const {
    switch (options_.rate) {
      case TrajectoryRate::kTargetKg:
      case TrajectoryRate::kMaxError: return std::exp2(modelledStep(pc, stepRange(pc)));
      case TrajectoryRate::kStep: return chooseStep(pc);
      case TrajectoryRate::kBitsPerVertexFrame: return HUGE_VAL;
    }
    return HUGE_VAL;
  }

  // The coefficient step of the rate mode: fixed, or searched on its logarithm (the error
  // grows and the size falls with the step), starting from a model's prediction.
  double chooseStep(const Components& pc) const {
    const double value = options_.rate_value;
    StepSearch search = stepRange(pc);
    if (options_.rate == TrajectoryRate::kStep) return std::max(value * firstFrameDiagonal(), std::exp2(search.lowest));
    std::function<double(double)> excess;
    switch (options_.rate) {
      case TrajectoryRate::kTargetKg: {
        search.guess = modelledStep(pc, search);
        search.slope = 2;  // a squared error
        const double allowed = allowedAtMost();
        excess = [&, allowed](double u) { return log2Ratio(measure(pc, std::exp2(u)).squared, allowed); };
        break;
      }
      case TrajectoryRate::kMaxError:
        search.guess = modelledStep(pc, search);
        excess = [&](double u) { return log2Ratio(measure(pc, std::exp2(u)).worst, 1) / 2; };
        break;
      case TrajectoryRate::kBitsPerVertexFrame: {
        // The size falls as the step grows: the search runs on -u.
        const double budget = value * vertices_ * frame_count_ / 8;
        search = {-search.highest, -search.lowest, 8 - search.highest};
        search.slope = 0.5;
        excess = [&, budget](double v) {
          std::vector<uint8_t> payload;
          writeTrajectoryGroup(trial(pc, std::exp2(-v)), order_, payload);
          return log2Ratio(double(payload.size()), budget);
        };
        return std::exp2(-searchStep(search, excess));
      }
      case TrajectoryRate::kStep: break;
    }
    return std::exp2(searchStep(search, excess));
  }

  // log2 of the finest step the payload allows, and of a step past any error.
  StepSearch stepRange(const Components& pc) const {
    const double largest = pc.coefficients.size() ? double(pc.coefficients.cwiseAbs().maxCoeff()) : 0.0;
    const double scale = std::max({largest, firstFrameDiagonal(), 1e-30});
    StepSearch search;
    search.lowest = std::log2(std::max(largest / kMaxQuantised, scale * 1e-12));
    search.highest = std::log2(2 * scale);
    return search;
  }

  static double log2Ratio(double value, double bound) {
    if (value <= 0) return -HUGE_VAL;
    return bound > 0 ? std::log2(value / bound) : HUGE_VAL;
  }

  // Energy whose loss hardly changes the step chosen: a hundredth of the error allowed.
  double negligibleEnergy() const {
    switch (options_.rate) {
      case TrajectoryRate::kTargetKg:
      case TrajectoryRate::kMaxError: return modelledAllowance() / 100;
      case TrajectoryRate::kStep: {
        const double q = options_.rate_value * firstFrameDiagonal();
        return 3.0 * vertices_ * frame_count_ * q * q / 12 / 100;
      }
      case TrajectoryRate::kBitsPerVertexFrame: return 0;
    }
    return 0;
  }

  // The squared error over the group that a rate mode allows: the KG target's, or for a max
  // error, every vertex at `share` of the bound.
  double allowance(double share) const {
    const double value = options_.rate_value;
    if (options_.rate == TrajectoryRate::kTargetKg) return (value / 100) * (value / 100) * spread_;
    double allowed = 0;
    for (double side : cube_sides_) allowed += vertices_ * (share * value * side) * (share * value * side);
    return allowed;
  }
  double allowedAtMost() const { return allowance(1); }
  // For the model below, a guess the trials correct: on the shared sequences the largest error
  // was 5 to 20 times the root mean square (docs/trajectory.md, "Rate control").
  double modelledAllowance() const { return allowance(0.1); }

  // log2 of the step at which a model of the squared error meets `allowed`: every component
  // costs its energy or a uniform quantiser's error on each vertex, whichever is smaller
  // (reverse water-filling), plus what the components computed leave out.
  double modelledStep(const Components& pc, const StepSearch& range) const {
    const double allowed = modelledAllowance();
    const double left_out = std::max(0.0, pc.energy - pc.sigma.squaredNorm());
    auto model = [&](double u) {
      const double per_component = vertices_ * std::exp2(2 * u) / 12;
      double e = left_out;
      for (Eigen::Index k = 0; k < pc.sigma.size(); ++k) e += std::min(pc.sigma[k] * pc.sigma[k], per_component);
      return e;
    };
    double lo = range.lowest, hi = range.highest;
    for (int i = 0; i < 50; ++i) {
      const double mid = (lo + hi) / 2;
      (model(mid) <= allowed ? lo : hi) = mid;
    }
    return lo;
  }

  // What quantising the coefficients of component k at step q does to them, summed over
  // the vertices.
  struct ColumnStats {
    double error = 0;   // squared, of the quantised coefficients
    double energy = 0;  // squared, of the quantised coefficients
    double bits = 0;    // estimated
    bool any = false;   // a coefficient is not zero
  };

  // The ColumnStats of components [first, K) at step q: a vertex block at a time (rows of
  // pc.coefficients, on any thread), the blocks' sums added in order.
  std::vector<ColumnStats> columnStats(const Components& pc, double q, Eigen::Index first) const {
    const Eigen::Index count = pc.coefficients.cols() - first;
    std::vector<std::vector<ColumnStats>> partial(vertexBlocks(vertices_));
    forVertexBlocks(vertices_, 20.0 * double(count), [&](size_t b, uint32_t begin, uint32_t end) {
      // Summed in a block's own vector, stored once: the blocks' vectors may share cache lines.
      std::vector<ColumnStats> block(static_cast<size_t>(count));
      for (uint32_t p = begin; p < end; ++p)
        for (Eigen::Index k = 0; k < count; ++k) {
          const double c = pc.coefficients(p, first + k);
          const int32_t value = quantiseCoefficient(c, q);
          const double chat = value * q;
          ColumnStats& s = block[size_t(k)];
          s.error += (c - chat) * (c - chat);
          s.energy += chat * chat;
          s.bits += estimatedBits(value);
          s.any |= value != 0;
        }
      partial[b] = std::move(block);
    });
    std::vector<ColumnStats> total(static_cast<size_t>(count));
    for (const auto& block : partial)
      for (size_t k = 0; k < total.size(); ++k) {
        total[k].error += block[k].error;
        total[k].energy += block[k].energy;
        total[k].bits += block[k].bits;
        total[k].any |= block[k].any;
      }
    return total;
  }

  // The components of [first, K) worth sending at coefficient step q, with their basis
  // vectors quantised.
  struct Selection {
    std::vector<Eigen::Index> sent;
    std::vector<std::vector<int32_t>> basis;  // of each sent
    std::vector<float> basis_step;
  };
  Selection selection(const Components& pc, double q, Eigen::Index first = 0) const {
    const std::vector<ColumnStats> stats = columnStats(pc, q, first);
    std::vector<std::vector<int32_t>> basis(stats.size());
    std::vector<float> steps(stats.size());
    std::vector<char> sent(stats.size(), 0);
    parallelFor(stats.size(), 20.0 * frame_count_, [&](size_t i) {
      if (!stats[i].any) return;
      const Eigen::Index k = first + Eigen::Index(i);
      // An error d in basis vector k moves the vertices by their coefficients times d, sigma_k
      // in total, and one in the mean moves all N vertices by d: these steps make each cost
      // the squared error of one coefficient's step.
      steps[i] = float(std::clamp(q / pc.sigma[k], 1.0 / kMaxQuantised, 2.0));
      basis[i].resize(size_t(3) * frame_count_);
      for (size_t j = 0; j < basis[i].size(); ++j) basis[i][j] = quantise(pc.basis(Eigen::Index(j), k), steps[i]);
      sent[i] = worthSending(pc, k, q, stats[i], basis[i], steps[i]);
    });
    Selection out;
    for (size_t i = 0; i < stats.size(); ++i) {
      if (!sent[i]) continue;
      out.sent.push_back(first + Eigen::Index(i));
      out.basis.push_back(std::move(basis[i]));
      out.basis_step.push_back(steps[i]);
    }
    return out;
  }

  // The group as quantised at step, all but its coefficients; and the components sent, whose
  // coefficients are quantised at g.coefficient_step.
  Selection quantiseHeader(const Components& pc, double step, TrajectoryGroup& g) const {
    g.frames = frame_count_;
    g.coefficient_step = float(step);
    const double q = g.coefficient_step;
    Selection chosen = selection(pc, q);
    const size_t row = size_t(3) * frame_count_;
    const uint32_t used = uint32_t(chosen.sent.size());
    g.components = used;
    g.basis_step = chosen.basis_step;
    g.basis.resize(used * row);
    for (uint32_t k = 0; k < used; ++k)
      std::copy(chosen.basis[k].begin(), chosen.basis[k].end(), g.basis.begin() + k * row);
    const double mean_reach = pc.mean.cwiseAbs().maxCoeff();
    g.mean_step = float(std::max(q / std::sqrt(double(vertices_)), mean_reach / kMaxQuantised + 1e-30));
    g.mean.resize(row);
    for (size_t i = 0; i < row; ++i) g.mean[i] = quantise(pc.mean[Eigen::Index(i)], g.mean_step);
    return chosen;
  }

  // The group as quantised at step: into g, whose buffers the search's trials reuse (a large
  // group's would otherwise be new pages at every trial).
  void quantiseGroup(const Components& pc, double step, TrajectoryGroup& g) const {
    const Selection chosen = quantiseHeader(pc, step, g);
    const double q = g.coefficient_step;
    const size_t used = chosen.sent.size();
    g.coefficients.resize(size_t(vertices_) * used);
    forVertexBlocks(vertices_, 10.0 * double(used), [&](size_t, uint32_t begin, uint32_t end) {
      for (uint32_t p = begin; p < end; ++p)
        for (size_t k = 0; k < used; ++k)
          g.coefficients[p * used + k] = quantiseCoefficient(pc.coefficients(p, chosen.sent[k]), q);
    });
  }

  // A trial of the search: the group at step q in trial_group_.
  const TrajectoryGroup& trial(const Components& pc, double q) const {
    quantiseGroup(pc, q, trial_group_);
    return trial_group_;
  }

  // Rate-distortion choice of a component: sent when the squared error it removes (its
  // energy, less the error of its quantised coefficients and basis vector) is worth its
  // estimated bits at the slope of a uniform quantiser, 2 ln 2 q^2 / 12 per bit. Weak
  // components otherwise cost a whole basis vector for a few coefficients.
  bool worthSending(const Components& pc, Eigen::Index k, double q, const ColumnStats& column,
                    const std::vector<int32_t>& basis, float basis_step) const {
    double bits = column.bits, basis_error = 0;
    int64_t previous = 0;
    for (size_t i = 0; i < basis.size(); ++i) {
      const double b = pc.basis(Eigen::Index(i), k), bhat = basis[i] * double(basis_step);
      basis_error += (b - bhat) * (b - bhat);
      if (i % frame_count_ == 0) previous = 0;
      bits += estimatedBits(basis[i] - previous);
      previous = basis[i];
    }
    const double coded_error = column.error + column.energy * basis_error;
    const double removed = pc.sigma[k] * pc.sigma[k] - coded_error;
    return removed > kBitSlope * q * q * bits;
  }

  // Bits of a value through an adaptive classed model, roughly: zeros are the common case.
  static double estimatedBits(int64_t v) {
    static const std::array<double, 1024> small = [] {
      std::array<double, 1024> bits{};
      for (size_t i = 1; i < bits.size(); ++i) bits[i] = 2 + 2 * std::log2(double(i));
      bits[0] = 0.3;
      return bits;
    }();
    const uint64_t magnitude = uint64_t(v < 0 ? -v : v);
    return magnitude < small.size() ? small[magnitude] : 2 + 2 * std::log2(double(magnitude));
  }

  struct GroupError {
    double squared = 0;  // summed over the group's vertices and frames
    double worst = 0;    // the largest squared distance over the max error's (kMaxError)
  };

  // The error of the frames the decoder will make of the group at step `step`, a block of
  // vertices at a time (on any thread; the blocks' sums added in order): their coefficients
  // quantised into panels, and their frames computed as the decoders do, without the
  // whole group's coefficients ever quantised at once.
  GroupError measure(const Components& pc, double step) const {
    TrajectoryGroup header;
    const Selection chosen = quantiseHeader(pc, step, header);
    const GroupBasis basis = dequantisedBasis(header);
    const uint32_t used = header.components;
    const double q = header.coefficient_step;
    const size_t blocks = vertexBlocks(vertices_);
    std::vector<double> squared(blocks, 0);
    std::vector<std::vector<double>> worst(blocks);
    forVertexBlocks(vertices_, 3.0 * (used + 4) * frame_count_, [&](size_t b, uint32_t v0, uint32_t end) {
      const uint32_t count = end - v0;
      // Summed in the block's own variables, stored once: neighbouring blocks' slots share
      // cache lines, and threads writing them at every vertex would pass those lines back and forth.
      double block_squared = 0;
      std::vector<double> block_worst(frame_count_, 0);
      std::vector<float> panels(FrameKernel::panelFloats(count, used), 0.0f);
      for (uint32_t i = 0; i < count && used > 0; ++i) {
        float* panel = panels.data() + FrameKernel::panelOffset(i, used);
        const Eigen::Index p = position_[v0 + i];
        for (uint32_t k = 0; k < used; ++k)
          panel[size_t(k) * FrameKernel::kLanes] = dequantisedCoefficient(
              quantiseCoefficient(pc.coefficients(p, chosen.sent[k]), q), header.coefficient_step);
      }
      std::vector<float> xyz(size_t(FrameKernel::kBatch) * 3 * count);
      for (uint32_t first = 0; first < frame_count_; first += FrameKernel::kBatch) {
        FrameKernel::run(path_, basis, panels.data(), count, 0, count, first, xyz.data());
        for (uint32_t t = first; t < std::min(frame_count_, first + FrameKernel::kBatch); ++t) {
          const float* decoded = xyz.data() + size_t(t - first) * 3 * count;
          const float* original = vertexOf(t, v0);
          for (size_t v = 0; v < size_t(3) * count; v += 3) {
            double sq = 0;
            for (int c = 0; c < 3; ++c)
              sq += (double(decoded[v + c]) - original[v + c]) * (double(decoded[v + c]) - original[v + c]);
            block_squared += sq;
            block_worst[t] = std::max(block_worst[t], sq);
          }
        }
      }
      squared[b] = block_squared;
      worst[b] = std::move(block_worst);
    });
    GroupError e;
    for (size_t b = 0; b < blocks; ++b) e.squared += squared[b];
    if (options_.rate == TrajectoryRate::kMaxError)
      for (uint32_t t = 0; t < frame_count_; ++t) {
        double frame_worst = 0;
        for (size_t b = 0; b < blocks; ++b) frame_worst = std::max(frame_worst, worst[b][t]);
        const double bound = options_.rate_value * cube_sides_[t];
        e.worst = std::max(e.worst, frame_worst / (bound * bound));
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
  double spread_ = 0;               // of the group (kTargetKg)
  GroupFrames frames_;              // the last group as decoded
  std::vector<uint32_t> position_;  // in coding order, of each vertex
  // The bits-per-vertex-frame search's trials, their buffers kept from one trial to the next.
  mutable TrajectoryGroup trial_group_;
};

}  // namespace

std::unique_ptr<GroupEncoder> makeTrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryEncoder>(options, topology, path);
}

}  // namespace animc
