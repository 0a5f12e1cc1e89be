#include "codecs/wavelet/frame_model.h"

#include <algorithm>
#include <cmath>


namespace animc {
namespace {

double boxDiagonal(const std::vector<double>& xyz) {
  const std::array<double, 3> e = boxExtent(xyz);
  return std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

// Context of a coefficient: base vertices share one class; details are split by how coarse
// their level is (coarsest six levels apart, the rest together) and normal vs tangential.
uint8_t classOf(int level, int level_count, int component) {
  if (level < 0) return 0;
  const int coarseness = std::min(level_count - 1 - level, 6);
  return uint8_t(1 + 2 * coarseness + (component == 0 ? 0 : 1));
}

}  // namespace

std::array<double, 3> boxExtent(const std::vector<double>& xyz) {
  if (xyz.empty()) return {0, 0, 0};
  double lo[3] = {xyz[0], xyz[1], xyz[2]}, hi[3] = {xyz[0], xyz[1], xyz[2]};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

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
  for (uint32_t v : order_)
    for (int a = 0; a < 3; ++a) {
      classes_.push_back(classOf(transform_->levelOf()[v], pm.level_count, a));
      parents_.push_back(target[v] == kNoVertex ? kNoParent : 3 * position[target[v]] + uint32_t(a));
    }
  const double diagonal = boxDiagonal(parametric_xyz);
  step_ = options_.step * (diagonal > 0 ? diagonal : 1.0);
  transform_->forward(parametric_xyz.data(), previous_);
  intra_reference_.assign(previous_.size(), 0.0);
  for (uint32_t v : pm.base)
    for (int a = 0; a < 3; ++a) intra_reference_[3 * size_t(v) + a] = previous_[3 * size_t(v) + a];
  reconstruction_ = parametric_xyz;
  history_ = 1;
}

bool WaveletFrameModel::hasReference(DetailReference ref) const {
  return ready() && (ref != DetailReference::kLinear || history_ >= 2);
}

const std::vector<double>& WaveletFrameModel::referenceOf(DetailReference ref) const {
  if (ref == DetailReference::kIntra) return intra_reference_;
  return ref == DetailReference::kInter ? previous_ : extrapolated_;
}

void WaveletFrameModel::residual(const std::vector<double>& coefficients, DetailReference ref,
                                 std::vector<double>& out) const {
  const std::vector<double>& reference = referenceOf(ref);
  const std::vector<double>& weights = transform_->weights();
  out.resize(coefficientCount());
  for (size_t i = 0; i < order_.size(); ++i) {
    const size_t v = order_[i];
    for (int a = 0; a < 3; ++a) out[3 * i + a] = weights[v] * (coefficients[3 * v + a] - reference[3 * v + a]);
  }
}

double WaveletFrameModel::residualEnergy(const std::vector<double>& coefficients, DetailReference ref) const {
  std::vector<double> r;
  residual(coefficients, ref, r);
  double sum = 0;
  for (double x : r) sum += x * x;
  return sum;
}

void WaveletFrameModel::accept(const std::vector<double>& decoded_residual, DetailReference ref) {
  std::vector<double> next = referenceOf(ref);
  const std::vector<double>& weights = transform_->weights();
  for (size_t i = 0; i < order_.size(); ++i) {
    const size_t v = order_[i];
    for (int a = 0; a < 3; ++a) next[3 * v + a] += decoded_residual[3 * i + a] / weights[v];
  }
  before_previous_.swap(previous_);
  previous_.swap(next);
  history_ = std::min(history_ + 1, 2);
  extrapolated_.resize(previous_.size());
  for (size_t i = 0; i < previous_.size(); ++i) extrapolated_[i] = 2 * previous_[i] - before_previous_[i];
  transform_->inverse(previous_, reconstruction_);
}

}  // namespace animc
