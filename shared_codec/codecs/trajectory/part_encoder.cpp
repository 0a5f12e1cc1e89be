// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/part_encoder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "codecs/trajectory/group_frames.h"
#include "core/large_memory.h"
#include "core/parallel.h"

namespace animc {
namespace {

// The fewest components computed more at a time.
constexpr Eigen::Index kMinMoreComponents = 16;
// The most vertices of a part whose basis and coefficients are refined (refine()): its
// products run on one thread and hold the part's coefficients in double three times over,
// which on a 727 395-vertex group took 2.4 times the rest of the encoder's time and half as
// much memory again (docs/trajectory.md, "Quantisation").
constexpr uint32_t kMostRefinedVertices = 1 << 16;
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

// Coefficients are rounded towards zero a little (a value within 0.6 of a step of zero
// becomes 0, and so on): a zero costs far fewer bits than a 1, and the step the target then
// needs is only a little finer. 0.6 beat 0.5 and 0.7 on the shared sequences (trajectory.md).
constexpr double kRoundingThreshold = 0.6;
int32_t quantiseCoefficient(double value, double step) {
  const double magnitude = std::min(std::floor(std::fabs(value) / step + 1 - kRoundingThreshold), kMaxQuantised);
  return int32_t(std::copysign(magnitude, value));
}

// Bits of a value through an adaptive classed model, roughly: zeros are the common case.
double estimatedBits(int64_t v) {
  static const std::array<double, 1024> small = [] {
    std::array<double, 1024> bits{};
    for (size_t i = 1; i < bits.size(); ++i) bits[i] = 2 + 2 * std::log2(double(i));
    bits[0] = 0.3;
    return bits;
  }();
  const uint64_t magnitude = uint64_t(v < 0 ? -v : v);
  return magnitude < small.size() ? small[magnitude] : 2 + 2 * std::log2(double(magnitude));
}

// Quantised values as the decoders make them, a column a vector.
Eigen::MatrixXd dequantisedColumns(const std::vector<std::vector<int32_t>>& values, const std::vector<float>& steps) {
  Eigen::MatrixXd out(Eigen::Index(values.empty() ? 0 : values[0].size()), Eigen::Index(values.size()));
  for (Eigen::Index k = 0; k < out.cols(); ++k)
    for (Eigen::Index j = 0; j < out.rows(); ++j)
      out(j, k) = dequantised(values[size_t(k)][size_t(j)], steps[size_t(k)]);
  return out;
}

// A coefficient quantised at step q (a float's value, as the file holds it) and dequantised
// as the decoders do.
float decodedCoefficient(double value, double q) { return dequantised(quantiseCoefficient(value, q), float(q)); }

// The same for a matrix of them.
Eigen::MatrixXd dequantisedCoefficients(const Eigen::MatrixXd& values, double q) {
  Eigen::MatrixXd out(values.rows(), values.cols());
  for (Eigen::Index j = 0; j < out.rows(); ++j)
    for (Eigen::Index k = 0; k < out.cols(); ++k) out(j, k) = decodedCoefficient(values(j, k), q);
  return out;
}

}  // namespace

double GroupContext::allowance(double share) const {
  const double value = options.rate_value;
  if (options.rate == TrajectoryRate::kTargetKg) return (value / 100) * (value / 100) * spread;
  double allowed = 0;
  for (double side : cube_sides) allowed += mesh_vertices * (share * value * side) * (share * value * side);
  return allowed;
}

// What quantising the coefficients of component k at step q does to them, summed over
// the part's vertices.
struct PartEncoder::ColumnStats {
  double error = 0;   // squared, of the quantised coefficients
  double energy = 0;  // squared, of the quantised coefficients
  double bits = 0;    // estimated
  bool any = false;   // a coefficient is not zero
};

// The components of [first, K) worth sending at coefficient step q, with their basis
// vectors quantised.
struct PartEncoder::Selection {
  std::vector<Eigen::Index> sent;
  std::vector<std::vector<int32_t>> basis;  // of each sent
  std::vector<float> basis_step;
  RowMatrixF refined;  // N x sent, the coefficients refine() fitted to the basis; empty: the components'

  // The coefficient of the part's row p on the k-th component sent.
  float coefficient(const Components& pc, Eigen::Index p, size_t k) const {
    return refined.size() ? refined(p, Eigen::Index(k)) : pc.coefficients(p, sent[k]);
  }
};

PartEncoder::PartEncoder(const GroupContext& group, const CodingOrder& order, const std::vector<uint32_t>& members)
    : PartEncoder(group, order, members, Components()) {
  decomposition_ = std::make_unique<TrajectoryDecomposition>(trajectories());
  pc_ = decomposition_->none();
}

PartEncoder::PartEncoder(const GroupContext& group, const CodingOrder& order, const std::vector<uint32_t>& members,
                         Components pc)
    : group_(group), order_(order), members_(members), vertices_(uint32_t(order.vertex.size())), position_(vertices_) {
  for (uint32_t p = 0; p < vertices_; ++p) position_[order_.vertex[p]] = p;
  pc_ = std::move(pc);
  pc_.complete = true;
}

// A row a vertex, in coding order (so are the coefficients then), of 3G values: x over the
// frames, then y, then z.
RowMatrixF PartEncoder::trajectories() const {
  const uint32_t g = group_.frames;
  RowMatrixF x(vertices_, 3 * g);
  adviseHugePages(x.data(), size_t(x.size()) * sizeof(float));  // the encoder's largest buffer
  forVertexBlocks(vertices_, 3.0 * g, [&](size_t, uint32_t begin, uint32_t end) {
    for (uint32_t p = begin; p < end; ++p)
      for (uint32_t t = 0; t < g; ++t)
        for (uint32_t c = 0; c < 3; ++c) x(p, c * g + t) = vertexOf(t, order_.vertex[p])[c];
  });
  return x;
}

void PartEncoder::extend(Eigen::Index count) {
  if (decomposition_) decomposition_->extend(pc_, count, negligibleEnergy());
}

void PartEncoder::release() {
  decomposition_.reset();
  pc_ = Components();
}

bool PartEncoder::refinable() const { return vertices_ <= kMostRefinedVertices; }

bool PartEncoder::carriesEnough(double q) const {
  if (pc_.sigma.size() == 0) return pc_.complete;
  const double weakest = pc_.sigma[pc_.sigma.size() - 1];
  return weakest * weakest <= leastWorthSending(q);
}

// Too few when the energy left out is more than the part's share of the error allowed, or
// step q would send the weakest of the components.
bool PartEncoder::clearlyTooFew(double q) const {
  const double left_out = pc_.energy - pc_.sigma.squaredNorm();
  const TrajectoryRate rate = group_.options.rate;
  if (rate == TrajectoryRate::kTargetKg || rate == TrajectoryRate::kMaxError) {
    if (left_out > group_.allowedAtMost() * share()) return true;
    if (left_out >= group_.modelledAllowance() * share()) return false;  // the model cannot tell
  }
  return !carriesEnough(q) && !sendsNoneOfTheWeakest(float(q));
}

// The components after the weakest eighth, weaker still, would not be sent either. (The
// bound of carriesEnough() is safe but can ask for many more components that are not sent in
// the end.)
bool PartEncoder::sendsNoneOfTheWeakest(float q) const {
  const Eigen::Index k = pc_.sigma.size(), tail = std::max<Eigen::Index>(kMinMoreComponents / 2, k / 8);
  return selection(q, std::max<Eigen::Index>(0, k - tail)).sent.empty();
}

// A component would remove at most its energy, and cost at least the bits of a zero for each
// of its coefficients and basis values.
double leastWorthSending(double q, uint32_t vertices, uint32_t frames) {
  return kBitSlope * q * q * estimatedBits(0) * (vertices + 3.0 * frames);
}

double PartEncoder::leastWorthSending(double q) const { return animc::leastWorthSending(q, vertices_, group_.frames); }

// From the decay of the last half of the singular values: a quarter more than where they
// fall below what is worth sending.
Eigen::Index PartEncoder::moreComponents(double q) const {
  const Eigen::Index k = pc_.sigma.size();
  const double weakest = pc_.sigma[k - 1], middle = pc_.sigma[k / 2];
  const double decay = std::log(weakest / middle) / double(k - 1 - k / 2);  // per component
  const double needed = std::log(std::sqrt(leastWorthSending(q)) / weakest) / decay;
  if (!(decay < 0) || !(needed < double(k))) return k;
  return std::max<Eigen::Index>(std::max(kMinMoreComponents, k / 2), Eigen::Index(1.25 * needed) + 1);
}

double PartEncoder::largestCoefficient() const {
  return pc_.coefficients.size() ? double(pc_.coefficients.cwiseAbs().maxCoeff()) : 0.0;
}

// Energy whose loss hardly changes the step chosen: a hundredth of the part's share of the
// error allowed.
double PartEncoder::negligibleEnergy() const {
  switch (group_.options.rate) {
    case TrajectoryRate::kTargetKg:
    case TrajectoryRate::kMaxError: return group_.modelledAllowance() * share() / 100;
    case TrajectoryRate::kStep: {
      const double q = group_.options.rate_value * group_.diagonal;
      return 3.0 * vertices_ * group_.frames * q * q / 12 / 100;
    }
    case TrajectoryRate::kBitsPerVertexFrame: return 0;
  }
  return 0;
}

// A step of the mean or of a basis vector moves the part's vertices by `weight` times its
// square: the part's vertex count, or the energy of the component's quantised coefficients.
// A bit is worth the error it buys at coefficient step q, kBitSlope q^2. The rows are priced
// where the refinement is (the chosen cut's last search: the cuts are compared without it,
// which it changes little, for less time), and always in a part too large to refine, whose
// rows cost little next to its vertices. A max error is not priced: the prices trade the
// squared error for bits and moved the largest error either way.
RowPrices PartEncoder::rowPrices(double q, double weight, double row_step) const {
  if (group_.options.rate == TrajectoryRate::kMaxError || (group_.refinement_rounds == 0 && refinable())) return {};
  return {weight * row_step * row_step, kBitSlope * q * q};
}

// A vertex block at a time (rows of the coefficients, on any thread), the blocks' sums added
// in order.
std::vector<PartEncoder::ColumnStats> PartEncoder::columnStats(double q, Eigen::Index first) const {
  const Eigen::Index count = pc_.coefficients.cols() - first;
  std::vector<std::vector<ColumnStats>> partial(vertexBlocks(vertices_));
  forVertexBlocks(vertices_, 20.0 * double(count), [&](size_t b, uint32_t begin, uint32_t end) {
    // Summed in a block's own vector, stored once: the blocks' vectors may share cache lines.
    std::vector<ColumnStats> block(static_cast<size_t>(count));
    for (uint32_t p = begin; p < end; ++p)
      for (Eigen::Index k = 0; k < count; ++k) {
        const double c = pc_.coefficients(p, first + k);
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

PartEncoder::Selection PartEncoder::selection(double q, Eigen::Index first) const {
  const std::vector<ColumnStats> stats = columnStats(q, first);
  std::vector<std::vector<int32_t>> basis(stats.size());
  std::vector<float> steps(stats.size());
  std::vector<char> sent(stats.size(), 0);
  parallelFor(stats.size(), 20.0 * group_.frames, [&](size_t i) {
    if (!stats[i].any) return;
    const Eigen::Index k = first + Eigen::Index(i);
    // An error d in basis vector k moves the vertices by their coefficients times d, sigma_k
    // in total, and one in the mean moves all the part's vertices by d: these steps make each
    // cost the squared error of one coefficient's step.
    steps[i] = float(std::clamp(q / pc_.sigma[k], 1.0 / kMaxQuantised, 2.0));
    basis[i].resize(size_t(3) * group_.frames);
    // Whether it is sent is judged with its basis vector rounded to nearest; then the
    // vector is quantised for its bits too.
    quantiseRow(pc_.basis.col(k).data(), group_.frames, steps[i], RowPrices{}, basis[i].data());
    sent[i] = worthSending(k, q, stats[i], basis[i], steps[i]);
    const RowPrices prices = rowPrices(q, stats[i].energy, steps[i]);
    if (sent[i] && prices.error_per_bit > 0)
      quantiseRow(pc_.basis.col(k).data(), group_.frames, steps[i], prices, basis[i].data());
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

// The part as quantised at step, all but its coefficients; and the components sent, whose
// coefficients are quantised at g.coefficient_step.
PartEncoder::Selection PartEncoder::quantiseHeader(double step, TrajectoryGroup& g) const {
  g.frames = group_.frames;
  g.coefficient_step = float(step);
  const double q = g.coefficient_step;
  Selection chosen = selection(q);
  if (group_.refinement_rounds > 0 && refinable() && !chosen.sent.empty()) refine(q, chosen);
  const size_t row = size_t(3) * group_.frames;
  const uint32_t used = uint32_t(chosen.sent.size());
  g.components = used;
  g.basis_step = chosen.basis_step;
  g.basis.resize(used * row);
  for (uint32_t k = 0; k < used; ++k)
    std::copy(chosen.basis[k].begin(), chosen.basis[k].end(), g.basis.begin() + k * row);
  const double mean_reach = pc_.mean.cwiseAbs().maxCoeff();
  g.mean_step = float(std::max(q / std::sqrt(double(vertices_)), mean_reach / kMaxQuantised + 1e-30));
  g.mean.resize(row);
  quantiseRow(pc_.mean.data(), group_.frames, g.mean_step, rowPrices(q, vertices_, g.mean_step), g.mean.data());
  return chosen;
}

// The basis vectors sent and their coefficients fitted to each other as quantised, by
// alternating least squares (a Lloyd iteration over the two factors): the basis vectors that
// best carry the part's trajectories given the coefficients as quantised at step q, quantised
// at their steps, then the coefficients that best carry the trajectories on that basis as
// dequantised. Either fit takes back part of the other's quantisation error, so a coarser
// step meets the same error. The trajectories are taken as the part's components carry them
// (C B^T, B orthonormal), so each fit, and the error the fits are judged by, is a small solve
// or product in the components' space, with no pass over the trajectories. Only the
// components up to the last one sent take part: the weaker ones are the least converged, and
// at the noise floor of a mesh of few motions their vectors are not orthogonal, so they would
// not carry the trajectories. Quantisation can undo a fit (an ill-conditioned one most of
// all): the refinement stops at the first round that does not lower the error, keeping the
// best.
void PartEncoder::refine(double q, Selection& chosen) const {
  const Eigen::Index n = pc_.coefficients.rows(), sent = Eigen::Index(chosen.sent.size());
  const Eigen::Index leading = chosen.sent.back() + 1;
  const Eigen::MatrixXd c = pc_.coefficients.leftCols(leading).cast<double>();  // N x K
  const auto components = pc_.basis.leftCols(leading);                          // 3G x K
  // The coefficients to quantise: the components' at first, then fitted to the basis.
  Eigen::MatrixXd fitted(n, sent);
  for (Eigen::Index k = 0; k < sent; ++k) fitted.col(k) = c.col(chosen.sent[size_t(k)]);
  std::vector<std::vector<int32_t>> values = chosen.basis;
  Eigen::MatrixXd basis = dequantisedColumns(values, chosen.basis_step);  // 3G x sent
  Eigen::MatrixXd basis_gram = basis.transpose() * basis;
  Eigen::MatrixXd basis_on_components = basis.transpose() * components;  // sent x K
  double best = HUGE_VAL;
  for (int round = 0;; ++round) {
    const Eigen::MatrixXd quantised = dequantisedCoefficients(fitted, q);  // N x sent
    const Eigen::MatrixXd gram = quantised.transpose() * quantised;
    const Eigen::MatrixXd on_components = quantised.transpose() * c;  // sent x K
    // |C B^T - Q B'^T|^2 less |C|^2, with B^T B = I.
    const double error =
        gram.cwiseProduct(basis_gram).sum() - 2 * on_components.cwiseProduct(basis_on_components).sum();
    if (!(error < best)) return;
    best = error;
    if (round > 0) {
      chosen.basis = values;
      chosen.refined = fitted.cast<float>();
    }
    if (round == group_.refinement_rounds) return;
    // B' = B C^T Q (Q^T Q)^-1, quantised; then C' = C B^T B' (B'^T B')^-1.
    const Eigen::MatrixXd fit = components * gram.ldlt().solve(on_components).transpose();
    if (!fit.allFinite()) return;
    for (Eigen::Index k = 0; k < sent; ++k) {
      const double step = chosen.basis_step[size_t(k)];
      quantiseRow(fit.col(k).data(), group_.frames, step, rowPrices(q, gram(k, k), step), values[size_t(k)].data());
    }
    basis = dequantisedColumns(values, chosen.basis_step);
    basis_gram = basis.transpose() * basis;
    basis_on_components = basis.transpose() * components;
    fitted = c * basis_gram.ldlt().solve(basis_on_components).transpose();
    if (!fitted.allFinite()) return;
  }
}

// Into g, whose buffers the search's trials reuse (a large group's would otherwise be new
// pages at every trial).
void PartEncoder::quantise(double step, TrajectoryGroup& g) const {
  const Selection chosen = quantiseHeader(step, g);
  const double q = g.coefficient_step;
  const size_t used = chosen.sent.size();
  g.coefficients.resize(size_t(vertices_) * used);
  forVertexBlocks(vertices_, 10.0 * double(used), [&](size_t, uint32_t begin, uint32_t end) {
    for (uint32_t p = begin; p < end; ++p)
      for (size_t k = 0; k < used; ++k)
        g.coefficients[p * used + k] = quantiseCoefficient(chosen.coefficient(pc_, p, k), q);
  });
}

// Rate-distortion choice of a component: sent when the squared error it removes (its
// energy, less the error of its quantised coefficients and basis vector) is worth its
// estimated bits at the slope of a uniform quantiser, 2 ln 2 q^2 / 12 per bit. Weak
// components otherwise cost a whole basis vector for a few coefficients.
bool PartEncoder::worthSending(Eigen::Index k, double q, const ColumnStats& column, const std::vector<int32_t>& basis,
                               float basis_step) const {
  double bits = column.bits, basis_error = 0;
  int64_t previous = 0;
  for (size_t i = 0; i < basis.size(); ++i) {
    const double b = pc_.basis(Eigen::Index(i), k), bhat = basis[i] * double(basis_step);
    basis_error += (b - bhat) * (b - bhat);
    if (i % group_.frames == 0) previous = 0;
    bits += estimatedBits(basis[i] - previous);
    previous = basis[i];
  }
  const double coded_error = column.error + column.energy * basis_error;
  const double removed = pc_.sigma[k] * pc_.sigma[k] - coded_error;
  return removed > kBitSlope * q * q * bits;
}

// A block of vertices at a time (on any thread; the blocks' sums added in order): their
// coefficients quantised into panels, and their frames computed as the decoders do, without
// the whole part's coefficients ever quantised at once.
PartError PartEncoder::measure(double step, bool frame_worst) const {
  TrajectoryGroup header;
  const Selection chosen = quantiseHeader(step, header);
  const GroupBasis basis = dequantisedBasis(header);
  const uint32_t used = header.components, frames = group_.frames;
  const double q = header.coefficient_step;
  const size_t blocks = vertexBlocks(vertices_);
  std::vector<double> squared(blocks, 0);
  std::vector<std::vector<double>> worst(blocks);
  forVertexBlocks(vertices_, 3.0 * (used + 4) * frames, [&](size_t b, uint32_t v0, uint32_t end) {
    const uint32_t count = end - v0;
    // Summed in the block's own variables, stored once: neighbouring blocks' slots share
    // cache lines, and threads writing them at every vertex would pass those lines back and forth.
    double block_squared = 0;
    std::vector<double> block_worst(frames, 0);
    std::vector<float> panels(FrameKernel::panelFloats(count, used), 0.0f);
    for (uint32_t i = 0; i < count && used > 0; ++i) {
      float* panel = panels.data() + FrameKernel::panelOffset(i, used);
      const Eigen::Index p = position_[v0 + i];
      for (uint32_t k = 0; k < used; ++k)
        panel[size_t(k) * FrameKernel::kLanes] = decodedCoefficient(chosen.coefficient(pc_, p, k), q);
    }
    std::vector<float> xyz(size_t(FrameKernel::kBatch) * 3 * count);
    for (uint32_t first = 0; first < frames; first += FrameKernel::kBatch) {
      FrameKernel::run(group_.path, basis, panels.data(), count, 0, count, first, xyz.data());
      for (uint32_t t = first; t < std::min(frames, first + FrameKernel::kBatch); ++t) {
        const float* decoded = xyz.data() + size_t(t - first) * 3 * count;
        for (uint32_t i = 0; i < count; ++i) {
          const float* original = vertexOf(t, v0 + i);
          double sq = 0;
          for (int c = 0; c < 3; ++c)
            sq += (double(decoded[3 * i + c]) - original[c]) * (double(decoded[3 * i + c]) - original[c]);
          block_squared += sq;
          block_worst[t] = std::max(block_worst[t], sq);
        }
      }
    }
    squared[b] = block_squared;
    worst[b] = std::move(block_worst);
  });
  PartError e;
  for (size_t b = 0; b < blocks; ++b) e.squared += squared[b];
  if (frame_worst) {
    e.frame_worst.assign(frames, 0);
    for (uint32_t t = 0; t < frames; ++t)
      for (size_t b = 0; b < blocks; ++b) e.frame_worst[t] = std::max(e.frame_worst[t], worst[b][t]);
  }
  return e;
}

}  // namespace animc
