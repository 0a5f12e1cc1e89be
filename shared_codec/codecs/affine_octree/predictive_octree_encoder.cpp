// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/predictive_octree.h"
#include "core/parallel.h"

namespace animc {
namespace {

// Of the nearest value, one step nearer zero and zero, the one of least rate + distortion
// (bits); adds its rate to `bits`.
template <class Rate, class Distortion>
int64_t cheapest(int64_t nearest, const Rate& rate, const Distortion& distortion, double& bits) {
  int64_t best = nearest;
  double best_rate = rate(nearest);
  if (nearest != 0) {
    double best_cost = best_rate + distortion(nearest);
    const int64_t nearer_zero = nearest - (nearest > 0) + (nearest < 0);
    const auto consider = [&](int64_t c) {
      const double c_rate = rate(c), c_cost = c_rate + distortion(c);
      if (c_cost < best_cost) best = c, best_rate = c_rate, best_cost = c_cost;
    };
    consider(nearer_zero);
    if (nearer_zero != 0) consider(0);
  }
  bits += best_rate;
  return best;
}

// A value in steps (a correction or a residual), rounded half away from zero; beyond ±2^40
// (NaN included) it is clamped, which the callers' overflow tests then catch. (Inline
// arithmetic: std::llround and std::nearbyint are library calls in this hot loop.)
int64_t nearestSteps(double x) {
  constexpr double kLimit = 0x1p40;
  if (!(x > -kLimit)) return -int64_t(kLimit);
  if (x > kLimit) return int64_t(kLimit);
  return int64_t(x + std::copysign(0.5, x));  // no branch on the sign: it is random
}

// Cells of fewer vertices search their children on the caller's thread: below this, a
// subtree's search costs less than starting a thread and copying its vertex list.
constexpr uint32_t kMinThreadedSearch = 1u << 15;

}  // namespace

double quantiseCorrections(const PredictiveModels& pm, const CentredAffine& fit, const CentredAffine& prior,
                           const CorrectionSteps& steps, size_t n, const double normal[9], double weight,
                           int64_t coded[12]) {
  double bits = 0;
  const double translation_weight = weight * double(n) * steps.translation * steps.translation;
  for (int r = 0; r < 3; ++r) {
    const double x = (fit.t[r] - prior.t[r]) / steps.translation;
    coded[r] = cheapest(
        nearestSteps(x), [&](int64_t c) { return classedCost(pm.translation[r], c); },
        [&](int64_t c) { return translation_weight * (double(c) - x) * (double(c) - x); }, bits);
  }
  const bool linear = n >= kMinLinearVertices;
  const double linear_weight = weight * steps.linear * steps.linear;
  for (int r = 0; r < 3; ++r) {
    double x[3], e[3];  // the row's corrections, and the chosen ones' rounding errors
    int64_t* row = &coded[3 + 3 * r];
    for (int k = 0; k < 3; ++k) {
      x[k] = (fit.L[3 * r + k] - prior.L[3 * r + k]) / steps.linear;
      row[k] = linear ? nearestSteps(x[k]) : 0;
      e[k] = double(row[k]) - x[k];
    }
    if (!linear) continue;
    for (int k = 0; k < 3; ++k) {
      const double* a = &normal[3 * k];
      // The part of eᵀ·A·e that depends on e[k].
      const double others = 2.0 * (a[(k + 1) % 3] * e[(k + 1) % 3] + a[(k + 2) % 3] * e[(k + 2) % 3]);
      row[k] = cheapest(
          row[k], [&](int64_t c) { return classedCost(pm.linear, c); },
          [&](int64_t c) {
            const double ek = double(c) - x[k];
            return linear_weight * ek * (a[k] * ek + others);
          },
          bits);
      e[k] = double(row[k]) - x[k];
    }
  }
  return bits;
}

struct PredictiveOctreeEncoder::Walk {
  const PFrameInput& in;
  double step;
  // Lagrangian weight: squared error is converted to bits at the slope of a uniform
  // quantiser of this step (dD/dR = -2·ln2·D with D = step²/12), scaled by kRateDistortion.
  double bits_per_squared_error;
  bool overflow = false;
  size_t cursor = 0;  // next plan node while coding
  RangeEncoder* rc = nullptr;
  RawBitWriter* raw = nullptr;
  std::vector<double>* recon = nullptr;
  PredictiveFrameStats* stats = nullptr;
};

bool PredictiveOctreeEncoder::encode(const PFrameInput& in, std::vector<uint8_t>& out,
                                     std::vector<double>& recon, PredictiveFrameStats& stats) {
  const double step = residualStep(in.max_error);
  Walk w{in, step, 1.0 / (kRateDistortion * 2.0 * std::log(2.0) * step * step / 12.0)};
  contexts_.beginFrame();
  // Pass 1: choose the tree by estimated cost (the search reorders the partition freely).
  plan_.clear();
  Search whole{partition_, points_, plan_};
  search(w, whole, partition_.reset(*in.reference, in.max_depth));
  if (w.overflow) return false;
  // Pass 2: code the chosen tree exactly as the decoder will walk it.
  const Cell root = partition_.restart();
  RangeEncoder rc(out);
  RawBitWriter raw;
  recon.resize(in.reference->size());
  w.rc = &rc;
  w.raw = &raw;
  w.recon = &recon;
  w.stats = &stats;
  codeCell(w, root);
  rc.finish();
  raw.appendTo(out);
  return true;
}

double PredictiveOctreeEncoder::search(Walk& w, Search& s, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  if (n == 0) return 0;
  const size_t mark = s.plan.size();
  s.plan.push_back(Node{false, {}});
  LeafCost leaf_eval;
  const double leaf_bits = evaluateLeaf(w, s, cell, s.plan[mark], leaf_eval);
  const bool can_split = canSplit(cell, w.in.max_depth);
  if (!can_split) return leaf_bits;
  const double leaf_cost = leaf_bits + bitCost(models_->split[cell.depth], 0);
  // A leaf with nothing to correct and little error left is not worth searching below.
  if (leaf_eval.all_zero && leaf_eval.distortion_bits < kPruneDistortionBits) return leaf_cost;
  const Node leaf = s.plan[mark];
  s.plan[mark].split = true;
  Cell children[8];
  s.partition.split(cell, children);
  const double split_cost = searchChildren(w, s, cell, children, leaf_cost);
  if (split_cost < leaf_cost) return split_cost;
  s.plan.resize(mark + 1);
  s.plan[mark] = leaf;
  return leaf_cost;
}

// The children's subtrees in order, while their cost stays below the leaf's. A large cell's
// are searched on threads, each in a partition and plan of its own and in its own window of
// the cell's gathered points (just gathered by the cell's evaluateLeaf()); then added up and
// appended in order, up to where the serial walk would have stopped: the same plan, cost and
// overflow either way (a search reads only the frame and the models, which it leaves as they
// are; the partition lists each cell's vertices in increasing order however it is walked).
double PredictiveOctreeEncoder::searchChildren(Walk& w, Search& s, const Cell& cell, const Cell children[8],
                                               double leaf_cost) {
  double cost = bitCost(models_->split[cell.depth], 1);
  if (cell.end - cell.begin < kMinThreadedSearch || ThreadBudget::current() == 1) {
    for (int c = 0; c < 8; ++c) {
      cost += search(w, s, children[c]);
      if (cost >= leaf_cost) break;
    }
    return cost;
  }
  struct Subtree {
    double cost = 0;
    bool overflow = false;
    std::vector<Node> plan;
  };
  Subtree subtrees[8];
  parallelFor(8, [&](size_t c) {
    OctreePartition partition(s.partition, children[c]);
    CellPoints points(s.points, children[c].begin - cell.begin);
    Search own{partition, points, subtrees[c].plan};
    Walk walk = w;
    subtrees[c].cost = search(walk, own, OctreePartition::rebased(children[c]));
    subtrees[c].overflow = walk.overflow;
  });
  for (int c = 0; c < 8; ++c) {
    cost += subtrees[c].cost;
    w.overflow = w.overflow || subtrees[c].overflow;
    s.plan.insert(s.plan.end(), subtrees[c].plan.begin(), subtrees[c].plan.end());
    if (cost >= leaf_cost) break;
  }
  return cost;
}

double PredictiveOctreeEncoder::evaluateLeaf(Walk& w, Search& s, const Cell& cell, Node& node, LeafCost& out) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* idx = s.partition.vertices(cell);
  CellPoints& points = s.points;
  points.gather(w.in, idx, n);
  const LeafModel& m = points.model;
  CentredAffine fit;
  double normal[9];
  fitCentred(path_, points.reference(), points.target(), n, m.frame, m.prior.L, fit, normal);
  const CorrectionSteps steps = correctionSteps(m.frame, n, w.step);
  const PredictiveModels& pm = *models_;
  double bits = quantiseCorrections(pm, fit, m.prior, steps, n, normal, w.bits_per_squared_error, node.coded);
  for (int64_t c : node.coded)
    if (c > kMaxCodedMagnitude || c < -kMaxCodedMagnitude) w.overflow = true;
  const CentredAffine a = codedAffine(m, steps, node.coded);
  double residual_bits = 0, distortion = 0;
  bool all_zero = true;
  for (uint32_t i = 0; i < n; ++i) {
    double p[3];
    const double* t = points.targetPoint(i);
    const size_t v = 3 * size_t(idx[i]);
    predictVertex(points, m, a, i, p);
    double vertex_bits = 0;
    bool vertex_zero = true;
    for (int ax = 0; ax < 3; ++ax) {
      const int64_t k = nearestSteps((t[ax] - p[ax]) / w.step);
      if (k > kMaxCodedMagnitude || k < -kMaxCodedMagnitude) w.overflow = true;
      const int64_t r = w.overflow ? 0 : k;
      vertex_zero = vertex_zero && r == 0;
      vertex_bits += intCost(pm.residuals, contexts_.contextAt(v + ax), r);
      const double e = t[ax] - p[ax] - double(r) * w.step;
      distortion += e * e;
    }
    const BitModel& flag = pm.vertex_residual[contexts_.vertexContext(v)];
    residual_bits += vertex_zero ? bitCost(flag, 0) : bitCost(flag, 1) + vertex_bits;
    all_zero = all_zero && vertex_zero;
  }
  const BitModel& zero_flag = pm.residuals_zero[n <= kMinLinearVertices];
  bits += all_zero ? bitCost(zero_flag, 1) : bitCost(zero_flag, 0) + residual_bits;
  out.all_zero = all_zero;
  out.distortion_bits = distortion * w.bits_per_squared_error;
  return bits + out.distortion_bits;
}

void PredictiveOctreeEncoder::codeCell(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  if (n == 0) return;
  const Node& node = plan_[w.cursor++];
  if (canSplit(cell, w.in.max_depth)) {
    w.rc->encode(models_->split[cell.depth], node.split);
    if (node.split) {
      Cell children[8];
      partition_.split(cell, children);
      for (const Cell& child : children) codeCell(w, child);
      return;
    }
  }
  codeLeaf(w, cell, node);
}

void PredictiveOctreeEncoder::codeLeaf(Walk& w, const Cell& cell, const Node& node) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* idx = partition_.vertices(cell);
  RangeEncoder& rc = *w.rc;
  PredictiveModels& pm = *models_;
  ++w.stats->leaves;
  for (int r = 0; r < 3; ++r) encodeClassed(rc, *w.raw, pm.translation[r], node.coded[r]);
  if (n >= kMinLinearVertices)
    for (int k = 0; k < 9; ++k) encodeClassed(rc, *w.raw, pm.linear, node.coded[3 + k]);
  points_.gather(w.in, idx, n);
  const LeafModel& m = points_.model;
  const CentredAffine a = codedAffine(m, correctionSteps(m.frame, n, w.step), node.coded);
  predictPoints(path_, points_.reference(), n, m.frame.centroid, a, idx, w.recon->data());
  residual_.resize(3 * size_t(n));
  bool all_zero = true;
  for (uint32_t i = 0; i < n; ++i) {
    double* out = &(*w.recon)[3 * size_t(idx[i])];
    for (int ax = 0; ax < 3; ++ax) {
      const int64_t r = nearestSteps((points_.targetPoint(i)[ax] - out[ax]) / w.step);
      residual_[3 * size_t(i) + ax] = r;
      out[ax] += double(r) * w.step;
      all_zero = all_zero && r == 0;
    }
  }
  rc.encode(pm.residuals_zero[n <= kMinLinearVertices], all_zero);
  if (all_zero) return;
  for (uint32_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(idx[i]);
    const int64_t* r = &residual_[3 * size_t(i)];
    const bool vertex_zero = r[0] == 0 && r[1] == 0 && r[2] == 0;
    rc.encode(pm.vertex_residual[contexts_.vertexContext(v)], !vertex_zero);
    if (vertex_zero) continue;
    for (int ax = 0; ax < 3; ++ax) {
      encodeInt(rc, pm.residuals, contexts_.contextAt(v + ax), r[ax]);
      contexts_.setAt(v + ax, r[ax]);
    }
  }
}

}  // namespace animc
