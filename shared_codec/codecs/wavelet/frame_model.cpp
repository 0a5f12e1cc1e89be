#include "codecs/wavelet/frame_model.h"

#include <algorithm>
#include <cmath>

#include "core/simd_math.h"

namespace animc {
namespace {

// Extent (max - min) of x y z triples along each axis; zeros when there are none.
std::array<double, 3> boxExtent(const std::vector<double>& xyz) {
  if (xyz.empty()) return {0, 0, 0};
  double lo[3] = {xyz[0], xyz[1], xyz[2]}, hi[3] = {xyz[0], xyz[1], xyz[2]};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

double boxDiagonal(const std::vector<double>& xyz) {
  const std::array<double, 3> e = boxExtent(xyz);
  return std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

// Context class of a vertex: base vertices share one; details are split by level, the seven
// finest (which hold most vertices) and the eight coarsest apart, the middle ones together.
uint8_t classOf(int level, int level_count) {
  if (level < 0) return 0;
  if (level <= 6) return uint8_t(1 + level);
  return uint8_t(8 + std::min(level_count - 1 - level, 7));
}

}  // namespace

WaveletFrameModel::WaveletFrameModel(const WaveletOptions& options, const Topology& topology)
    : options_(options), topology_(topology) {}

void WaveletFrameModel::setParametric(const std::vector<double>& parametric_xyz) {
  transform_ = std::make_unique<WaveletTransform>(topology_, parametric_xyz, options_.local_frames);
  const ProgressiveMesh& pm = transform_->hierarchy();
  order_ = pm.base;
  for (size_t i = pm.collapses.size(); i-- > 0;) order_.push_back(pm.collapses[i].vertex);
  std::vector<uint32_t> position(pm.vertex_count, kNoParent), target(pm.vertex_count, kNoVertex);
  for (size_t i = 0; i < order_.size(); ++i) position[order_[i]] = uint32_t(i);
  for (const Collapse& c : pm.collapses) target[c.vertex] = c.target;
  classes_.clear();
  parents_.clear();
  group_.clear();
  for (uint32_t v : order_) {
    classes_.push_back(classOf(transform_->levelOf()[v], pm.level_count));
    group_.push_back(classes_.back() == 0 ? 0 : 1);
    parents_.push_back(target[v] == kNoVertex ? kNoParent : position[target[v]]);
  }
  context_.reset(coefficientCount());
  const double diagonal = boxDiagonal(parametric_xyz);
  step_ = options_.step * (diagonal > 0 ? diagonal : 1.0);
  transform_->forward(parametric_xyz.data(), previous_);
  intra_reference_.assign(previous_.size(), 0.0);
  for (uint32_t v : pm.base)
    for (int a = 0; a < 3; ++a) intra_reference_[3 * size_t(v) + a] = previous_[3 * size_t(v) + a];
  reconstruction_ = parametric_xyz;
  history_ = 1;
}

bool WaveletFrameModel::canPredict(const Prediction& prediction) const {
  if (!ready()) return false;
  for (uint8_t s : prediction.selector)
    if (s > kIntraSelector || (s != 0 && s != kIntraSelector && history_ < 2)) return false;
  return true;
}

Prediction WaveletFrameModel::choosePrediction(const std::vector<double>& coefficients, bool temporal) const {
  if (!temporal) return Prediction::intra();
  // Residual energy against previous + a * (previous - before) is quadratic in a:
  // sum (d - a g)^2 with d = c - previous, g = previous - before.
  struct Sums { double dd = 0, dg = 0, gg = 0, intra = 0; };
  std::array<Sums, kPredictionGroups> sums;
  const std::vector<double>& weights = transform_->weights();
  const bool two = history_ >= 2;
  for (size_t i = 0; i < order_.size(); ++i) {
    const size_t v = order_[i];
    const double w2 = weights[v] * weights[v];
    Sums& s = sums[group_[i]];
    for (size_t j = 3 * v; j < 3 * v + 3; ++j) {
      const double d = coefficients[j] - previous_[j], g = two ? previous_[j] - before_previous_[j] : 0.0;
      const double e = coefficients[j] - intra_reference_[j];
      s.dd += w2 * d * d;
      s.dg += w2 * d * g;
      s.gg += w2 * g * g;
      s.intra += w2 * e * e;
    }
  }
  Prediction best;
  for (int group = 0; group < kPredictionGroups; ++group) {
    const Sums& s = sums[group];
    double best_energy = s.intra;
    best.selector[group] = kIntraSelector;
    for (uint8_t k = 0; k <= (two ? kDampingSteps : 0); ++k) {
      const double a = double(k) / kDampingSteps;
      const double energy = s.dd - 2 * a * s.dg + a * a * s.gg;
      if (energy < best_energy) {
        best_energy = energy;
        best.selector[group] = k;
      }
    }
  }
  return best;
}

template <class PerVertex>
void WaveletFrameModel::forEachPrediction(const Prediction& prediction, PerVertex f) const {
  // Groups are runs of coding positions (base vertices first): one selector per run.
  const size_t n = order_.size();
  for (size_t begin = 0, end; begin < n; begin = end) {
    for (end = begin + 1; end < n && group_[end] == group_[begin];) ++end;
    const uint8_t s = prediction.selector[group_[begin]];
    const double damping = double(s) / kDampingSteps;
    const double* const previous = previous_.data();
    const double* const before = before_previous_.data();
    const double* const intra = intra_reference_.data();
    for (size_t i = begin; i < end; ++i) {
      const size_t v = order_[i];
      const double *const now = previous + 3 * v, *const then = before + 3 * v, *const reference = intra + 3 * v;
      // s = 0: the previous frame; s in 1..8: damped extrapolation; 9: the I-frame reference.
      if (s == kIntraSelector)
        f(i, v, loadPair(reference), reference[2]);
      else if (s == 0)
        f(i, v, loadPair(now), now[2]);
      else
        f(i, v, loadPair(now) + splat(damping) * (loadPair(now) - loadPair(then)), now[2] + damping * (now[2] - then[2]));
    }
  }
}

void WaveletFrameModel::residual(const std::vector<double>& coefficients, const Prediction& prediction,
                                 std::vector<double>& out) const {
  const double* const weights = transform_->weights().data();
  out.resize(coefficientCount());
  double* const r = out.data();
  const double* const c = coefficients.data();
  forEachPrediction(prediction, [&](size_t i, size_t v, Pair p_xy, double p_z) {
    storePair(r + 3 * i, splat(weights[v]) * (loadPair(c + 3 * v) - p_xy));
    r[3 * i + 2] = weights[v] * (c[3 * v + 2] - p_z);
  });
}

void WaveletFrameModel::addResidual(const std::vector<double>& decoded_residual, const Prediction& prediction,
                                    std::vector<double>& coefficients) const {
  const double* const weights = transform_->weights().data();
  coefficients.resize(previous_.size());
  double* const c = coefficients.data();
  const double* const r = decoded_residual.data();
  forEachPrediction(prediction, [&](size_t i, size_t v, Pair p_xy, double p_z) {
    storePair(c + 3 * v, p_xy + loadPair(r + 3 * i) / splat(weights[v]));
    c[3 * v + 2] = p_z + r[3 * i + 2] / weights[v];
  });
}

void WaveletFrameModel::previewReconstruction(const std::vector<double>& decoded_residual,
                                              const Prediction& prediction, std::vector<double>& xyz) {
  addResidual(decoded_residual, prediction, preview_);
  transform_->inverse(preview_, xyz);
}

void WaveletFrameModel::accept(const std::vector<double>& decoded_residual, const Prediction& prediction) {
  addResidual(decoded_residual, prediction, next_);
  context_.bits.swap(next_context_.bits);
  context_.negative.swap(next_context_.negative);
  before_previous_.swap(previous_);
  previous_.swap(next_);
  history_ = std::min(history_ + 1, 2);
  transform_->inverse(previous_, reconstruction_);
}

}  // namespace animc
