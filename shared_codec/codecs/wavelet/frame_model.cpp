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
  runs_.clear();
  for (uint32_t begin = 0, end; begin < order_.size(); begin = end) {
    for (end = begin + 1; end < order_.size() && group_[end] == group_[begin];) ++end;
    runs_.push_back({begin, end, group_[begin]});
  }
  if (!order_.empty()) {
    quad_stops_ = {position[pm.vertex_count - 1], uint32_t(order_.size() - 1)};
    std::sort(quad_stops_.begin(), quad_stops_.end());
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

namespace {

// The prediction of a run of coding positions (Prediction::selector, one per run): the
// I-frame reference, the previous frame, or previous + damping * (previous - the one before).
enum class Predictor { kReference, kPrevious, kExtrapolation };
template <Predictor kPredictor>
using PredictorTag = std::integral_constant<Predictor, kPredictor>;

// The coefficients predictions read (all vertex indexed, 3 per vertex).
struct References {
  const double* intra;
  const double* previous;
  const double* before;
  double damping;
};

// The prediction of the point at offset o (3 * vertex): x and y as a Pair, then z.
template <Predictor kPredictor>
inline void predictPoint(const References& r, size_t o, Pair& xy, double& z) {
  if constexpr (kPredictor == Predictor::kReference) {
    xy = loadPair(r.intra + o);
    z = r.intra[o + 2];
  } else if constexpr (kPredictor == Predictor::kPrevious) {
    xy = loadPair(r.previous + o);
    z = r.previous[o + 2];
  } else {
    const double *const now = r.previous + o, *const then = r.before + o;
    xy = loadPair(now) + splat(r.damping) * (loadPair(now) - loadPair(then));
    z = now[2] + r.damping * (now[2] - then[2]);
  }
}

// What addResidual reads, in coding order: vertices, their residuals.
struct ResidualInputs {
  const uint32_t* order;
  const double* weights;   // vertex indexed
  const double* residual;  // coding order, 3 per vertex
  References references;
};

// coefficients = prediction + residual / weight at coding positions [begin, end), x and y as
// a Pair.
template <Predictor kPredictor>
void addResidualPortable(const ResidualInputs& in, size_t begin, size_t end, double* coefficients) {
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const double* const r = in.residual + 3 * i;
    const double w = in.weights[o / 3];
    Pair xy;
    double z;
    predictPoint<kPredictor>(in.references, o, xy, z);
    storePair(coefficients + o, xy + loadPair(r) / splat(w));
    coefficients[o + 2] = z + r[2] / w;
  }
}

#if ANIMC_AVX2_PATH
// predictPoint with x, y and z as lanes 0-2 of a Quad (lane 3: whatever follows, unused).
template <Predictor kPredictor>
ANIMC_TARGET_AVX2 inline Quad predictPointQuad(const References& r, size_t o) {
  if constexpr (kPredictor == Predictor::kReference) {
    return loadQuad(r.intra + o);
  } else if constexpr (kPredictor == Predictor::kPrevious) {
    return loadQuad(r.previous + o);
  } else {
    const Quad now = loadQuad(r.previous + o);
    return now + splatQuad(r.damping) * (now - loadQuad(r.before + o));
  }
}

// addResidualPortable with x, y and z as lanes of one Quad: the same operations per
// component. Each load reads one double past its point: the caller keeps the last coding
// position and the last vertex's out of [begin, end).
template <Predictor kPredictor>
ANIMC_TARGET_AVX2 void addResidualAvx2(const ResidualInputs& in, size_t begin, size_t end, double* coefficients) {
  const References references = in.references;  // a copy: the stores below cannot change it
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const Quad c = predictPointQuad<kPredictor>(references, o) +
                   loadQuad(in.residual + 3 * i) / splatQuad(in.weights[o / 3]);
    storePair(coefficients + o, Pair{c[0], c[1]});  // not lane 3: the next vertex's x
    coefficients[o + 2] = c[2];
  }
}
#endif

}  // namespace

template <class Run>
void WaveletFrameModel::forEachRun(const Prediction& prediction, Run run) const {
  for (const PredictionRun& r : runs_) {
    const uint8_t s = prediction.selector[r.group];
    // s = 0: the previous frame; s in 1..8: damped extrapolation; 9: the I-frame reference.
    const References references{intra_reference_.data(), previous_.data(), before_previous_.data(),
                                double(s) / kDampingSteps};
    if (s == kIntraSelector)
      run(r.begin, r.end, references, PredictorTag<Predictor::kReference>());
    else if (s == 0)
      run(r.begin, r.end, references, PredictorTag<Predictor::kPrevious>());
    else
      run(r.begin, r.end, references, PredictorTag<Predictor::kExtrapolation>());
  }
}

void WaveletFrameModel::residual(const std::vector<double>& coefficients, const Prediction& prediction,
                                 std::vector<double>& out) const {
  const double* const weights = transform_->weights().data();
  out.resize(coefficientCount());
  double* const r = out.data();
  const double* const c = coefficients.data();
  forEachRun(prediction, [&](size_t begin, size_t end, const References& references, auto predictor) {
    for (size_t i = begin; i < end; ++i) {
      const size_t v = order_[i];
      Pair p_xy;
      double p_z;
      predictPoint<predictor()>(references, 3 * v, p_xy, p_z);
      storePair(r + 3 * i, splat(weights[v]) * (loadPair(c + 3 * v) - p_xy));
      r[3 * i + 2] = weights[v] * (c[3 * v + 2] - p_z);
    }
  });
}

void WaveletFrameModel::addResidual(const std::vector<double>& decoded_residual, const Prediction& prediction,
                                    std::vector<double>& coefficients) const {
  coefficients.resize(previous_.size());
  double* const c = coefficients.data();
  forEachRun(prediction, [&](size_t begin, size_t end, const References& references, auto predictor) {
    const ResidualInputs in{order_.data(), transform_->weights().data(), decoded_residual.data(), references};
#if ANIMC_AVX2_PATH
    if (cpuHasAvx2()) {
      // Around the two positions whose Quads would read past the end of an array.
      size_t next = begin;
      for (size_t stop : {quad_stops_[0], quad_stops_[1]}) {
        if (stop < next || stop >= end) continue;
        addResidualAvx2<predictor()>(in, next, stop, c);
        addResidualPortable<predictor()>(in, stop, stop + 1, c);
        next = stop + 1;
      }
      return addResidualAvx2<predictor()>(in, next, end, c);
    }
#endif
    addResidualPortable<predictor()>(in, begin, end, c);
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
