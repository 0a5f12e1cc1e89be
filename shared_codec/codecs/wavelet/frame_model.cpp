// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/frame_model.h"

#include <algorithm>
#include <cmath>
#include <cstring>

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

// Runs quad(from, to) over [begin, end) except at the coding positions `stops`, where
// point(stop, stop + 1) runs instead: quad reads one double past each point.
template <class QuadRange, class PointRange>
void aroundStops(size_t begin, size_t end, const std::array<uint32_t, 2>& stops, QuadRange quad, PointRange point) {
  size_t next = begin;
  for (size_t stop : stops) {  // ascending
    if (stop < next || stop >= end) continue;
    quad(next, stop);
    point(stop, stop + 1);
    next = stop + 1;
  }
  quad(next, end);
}

}  // namespace

WaveletFrameModel::WaveletFrameModel(const WaveletOptions& options, const Topology& topology, SimdPath path)
    : options_(options), topology_(topology), path_(path) {}

void WaveletFrameModel::setParametric(const std::vector<double>& parametric_xyz) {
  // The hierarchy is a function of the parametric mesh alone. A decoder that goes back into
  // a frame group (random access backwards) meets the same mesh again and keeps it; the
  // comparison is of the bits, since -0 and +0 may lead to different hierarchies.
  const bool same = transform_ && hierarchy_mesh_.size() == parametric_xyz.size() &&
                    (parametric_xyz.empty() || std::memcmp(hierarchy_mesh_.data(), parametric_xyz.data(),
                                                           parametric_xyz.size() * sizeof(double)) == 0);
  if (!same) buildHierarchy(parametric_xyz);
  context_.reset(coefficientCount());
  const double diagonal = boxDiagonal(parametric_xyz);
  step_ = options_.step * (diagonal > 0 ? diagonal : 1.0);
  transform_->forward(parametric_xyz.data(), previous_);
  intra_reference_.assign(previous_.size(), 0.0);
  for (uint32_t v : transform_->hierarchy().base)
    for (int a = 0; a < 3; ++a) intra_reference_[3 * size_t(v) + a] = previous_[3 * size_t(v) + a];
  reconstruction_ = parametric_xyz;
  history_ = 1;
}

void WaveletFrameModel::buildHierarchy(const std::vector<double>& parametric_xyz) {
  hierarchy_mesh_.clear();  // until the hierarchy is whole
  transform_ = std::make_unique<WaveletTransform>(path_, topology_, parametric_xyz, options_.local_frames);
  const ProgressiveMesh& pm = transform_->hierarchy();
  order_ = pm.base;
  for (size_t i = pm.collapses.size(); i-- > 0;) order_.push_back(pm.collapses[i].vertex);
  std::vector<uint32_t> position(pm.vertex_count, kNoParent), target(pm.vertex_count, kNoVertex);
  for (size_t i = 0; i < order_.size(); ++i) position[order_[i]] = uint32_t(i);
  for (const Collapse& c : pm.collapses) target[c.vertex] = c.target;
  classes_.clear();
  parents_.clear();
  for (uint32_t v : order_) {
    classes_.push_back(classOf(transform_->levelOf()[v], pm.level_count));
    parents_.push_back(target[v] == kNoVertex ? kNoParent : position[target[v]]);
  }
  // Prediction groups: base vertices (class 0), then removed ones.
  const auto group = [&](size_t i) { return uint8_t(classes_[i] == 0 ? 0 : 1); };
  runs_.clear();
  for (uint32_t begin = 0, end; begin < order_.size(); begin = end) {
    for (end = begin + 1; end < order_.size() && group(end) == group(begin);) ++end;
    runs_.push_back({begin, end, group(begin)});
  }
  if (!order_.empty()) {
    quad_stops_ = {position[pm.vertex_count - 1], uint32_t(order_.size() - 1)};
    std::sort(quad_stops_.begin(), quad_stops_.end());
  }
  hierarchy_mesh_ = parametric_xyz;
}

bool WaveletFrameModel::canPredict(const Prediction& prediction) const {
  if (!ready()) return false;
  for (uint8_t s : prediction.selector)
    if (s > kIntraSelector || (s != 0 && s != kIntraSelector && history_ < 2)) return false;
  return true;
}

namespace {

// The sums choosePrediction() weighs predictions with, per group: of w^2 d^2, w^2 d g, w^2 g^2
// and w^2 e^2 over the group's coefficients, with d = c - previous, g = previous - before and
// e = c - the I-frame reference.
struct EnergySums {
  double dd = 0, dg = 0, gg = 0, intra = 0;
};

// What they read: vertices in coding order, then vertex-indexed arrays.
struct EnergyInputs {
  const uint32_t* order;
  const double* weights;
  const double* coefficients;
  const double* previous;
  const double* before;  // unread without kTwo references (g = 0)
  const double* intra;
};

// Adds coding positions [begin, end) to s, coefficient after coefficient: s.dd += w2 * d * d
// and so on.
template <bool kTwo>
void addEnergiesPortable(const EnergyInputs& in, size_t begin, size_t end, EnergySums& s) {
  EnergySums sums = s;
  for (size_t i = begin; i < end; ++i) {
    const size_t v = in.order[i];
    const double w2 = in.weights[v] * in.weights[v];
    for (size_t j = 3 * v; j < 3 * v + 3; ++j) {
      const double d = in.coefficients[j] - in.previous[j], g = kTwo ? in.previous[j] - in.before[j] : 0.0;
      const double e = in.coefficients[j] - in.intra[j];
      sums.dd += w2 * d * d;
      sums.dg += w2 * d * g;
      sums.gg += w2 * g * g;
      sums.intra += w2 * e * e;
    }
  }
  s = sums;
}

#if ANIMC_AVX2_PATH
// addEnergiesPortable with the four sums as the lanes of one Quad: per coefficient, lanes
// (w2 * d, w2 * d, w2 * g, w2 * e) times (d, g, g, e) are added, the same operations in the
// same order. A vertex's d, g and e are computed as Quads (x, y, z, and lane 3 from the next
// point, unused), then transposed into one Quad per coefficient. The caller keeps the last
// vertex's coding position out of [begin, end) (its Quads would read past the arrays).
template <bool kTwo>
ANIMC_TARGET_AVX2 void addEnergiesAvx2(const EnergyInputs& in, size_t begin, size_t end, EnergySums& s) {
  Quad sums = {s.dd, s.dg, s.gg, s.intra};
  for (size_t i = begin; i < end; ++i) {
    const size_t v = in.order[i], o = 3 * v;
    const Quad w2 = splatQuad(in.weights[v] * in.weights[v]);
    const Quad c = loadQuad(in.coefficients + o), p = loadQuad(in.previous + o);
    const Quad d = c - p, g = kTwo ? p - loadQuad(in.before + o) : splatQuad(0.0), e = c - loadQuad(in.intra + o);
    Quad weighted[3], plain[3];
    transposeColumns(w2 * d, w2 * d, w2 * g, w2 * e, weighted);
    transposeColumns(d, g, g, e, plain);
    for (int j = 0; j < 3; ++j) sums += weighted[j] * plain[j];
  }
  s = {sums[0], sums[1], sums[2], sums[3]};
}
#endif

template <bool kTwo>
void addEnergies([[maybe_unused]] SimdPath path, const EnergyInputs& in, size_t begin, size_t end,
                 [[maybe_unused]] const std::array<uint32_t, 2>& stops, EnergySums& s) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path))
    return aroundStops(
        begin, end, stops, [&](size_t from, size_t to) { addEnergiesAvx2<kTwo>(in, from, to, s); },
        [&](size_t from, size_t to) { addEnergiesPortable<kTwo>(in, from, to, s); });
#endif
  addEnergiesPortable<kTwo>(in, begin, end, s);
}

}  // namespace

Prediction WaveletFrameModel::choosePrediction(const std::vector<double>& coefficients, bool temporal) const {
  if (!temporal) return Prediction::intra();
  // Residual energy against previous + a * (previous - before) is quadratic in a:
  // sum (d - a g)^2 with d = c - previous, g = previous - before.
  std::array<EnergySums, kPredictionGroups> sums;
  const bool two = history_ >= 2;
  const EnergyInputs in{order_.data(), transform_->weights().data(), coefficients.data(),
                        previous_.data(), before_previous_.data(), intra_reference_.data()};
  for (const PredictionRun& r : runs_) {
    if (two)
      addEnergies<true>(path_, in, r.begin, r.end, quad_stops_, sums[r.group]);
    else
      addEnergies<false>(path_, in, r.begin, r.end, quad_stops_, sums[r.group]);
  }
  Prediction best;
  for (int group = 0; group < kPredictionGroups; ++group) {
    const EnergySums& s = sums[group];
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

// What residual() and addResidual() read besides the coefficients and the residual: the
// vertices in coding order, the weights and the references of the prediction.
struct CodingInputs {
  const uint32_t* order;
  const double* weights;  // vertex indexed
  References references;
};

// residual = weight * (coefficients - prediction) at coding positions [begin, end) (residual
// in coding order, coefficients vertex indexed), x and y as a Pair.
template <Predictor kPredictor>
void residualPortable(const CodingInputs& in, const double* coefficients, size_t begin, size_t end,
                      double* residual) {
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const double w = in.weights[o / 3];
    Pair xy;
    double z;
    predictPoint<kPredictor>(in.references, o, xy, z);
    storePair(residual + 3 * i, splat(w) * (loadPair(coefficients + o) - xy));
    residual[3 * i + 2] = w * (coefficients[o + 2] - z);
  }
}

// Its inverse: coefficients = prediction + residual / weight.
template <Predictor kPredictor>
void addResidualPortable(const CodingInputs& in, const double* residual, size_t begin, size_t end,
                         double* coefficients) {
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const double* const r = residual + 3 * i;
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

// residualPortable and addResidualPortable with x, y and z as lanes of one Quad: the same
// operations per component. Each load reads one double past its point: the caller keeps the
// last coding position and the last vertex's out of [begin, end).
template <Predictor kPredictor>
ANIMC_TARGET_AVX2 void residualAvx2(const CodingInputs& in, const double* coefficients, size_t begin, size_t end,
                                    double* residual) {
  const References references = in.references;  // a copy: the stores below cannot change it
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const Quad difference = loadQuad(coefficients + o) - predictPointQuad<kPredictor>(references, o);
    storeXyz(residual + 3 * i, splatQuad(in.weights[o / 3]) * difference);
  }
}

template <Predictor kPredictor>
ANIMC_TARGET_AVX2 void addResidualAvx2(const CodingInputs& in, const double* residual, size_t begin, size_t end,
                                       double* coefficients) {
  const References references = in.references;
  for (size_t i = begin; i < end; ++i) {
    const size_t o = 3 * size_t(in.order[i]);
    const Quad prediction = predictPointQuad<kPredictor>(references, o);
    storeXyz(coefficients + o, prediction + loadQuad(residual + 3 * i) / splatQuad(in.weights[o / 3]));
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
  out.resize(coefficientCount());
  double* const r = out.data();
  const double* const c = coefficients.data();
  forEachRun(prediction, [&](size_t begin, size_t end, const References& references, auto predictor) {
    const CodingInputs in{order_.data(), transform_->weights().data(), references};
#if ANIMC_AVX2_PATH
    if (useAvx2(path_))
      return aroundStops(
          begin, end, quad_stops_, [&](size_t from, size_t to) { residualAvx2<predictor()>(in, c, from, to, r); },
          [&](size_t from, size_t to) { residualPortable<predictor()>(in, c, from, to, r); });
#endif
    residualPortable<predictor()>(in, c, begin, end, r);
  });
}

void WaveletFrameModel::addResidual(const std::vector<double>& decoded_residual, const Prediction& prediction,
                                    std::vector<double>& coefficients) const {
  coefficients.resize(previous_.size());
  double* const c = coefficients.data();
  const double* const r = decoded_residual.data();
  forEachRun(prediction, [&](size_t begin, size_t end, const References& references, auto predictor) {
    const CodingInputs in{order_.data(), transform_->weights().data(), references};
#if ANIMC_AVX2_PATH
    if (useAvx2(path_))
      return aroundStops(
          begin, end, quad_stops_, [&](size_t from, size_t to) { addResidualAvx2<predictor()>(in, r, from, to, c); },
          [&](size_t from, size_t to) { addResidualPortable<predictor()>(in, r, from, to, c); });
#endif
    addResidualPortable<predictor()>(in, r, begin, end, c);
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
