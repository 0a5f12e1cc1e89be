// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/wavelet_codec.h"

#include <algorithm>
#include <cmath>

#include "codecs/common/static_position_coder.h"
#include "codecs/common/root_cube.h"
#include "codecs/wavelet/bitplane_coder.h"
#include "codecs/wavelet/frame_model.h"
#include "codecs/wavelet/progressive_mesh.h"
#include "codecs/wavelet/rate_control.h"

namespace animc {
namespace {

// Grid step of a parametric frame coded at `bits` bits with the given largest bounding-box side.
double parametricStep(int bits, double largest_side) {
  const double side = largest_side > 0 && std::isfinite(largest_side) ? largest_side : 1.0;
  return side / double(1u << bits);
}

static_assert(kPredictionGroups == 2 && kIntraSelector < 16, "selectors are two nibbles of one byte");

uint8_t packSelectors(const Prediction& p) { return uint8_t(p.selector[0] | (p.selector[1] << 4)); }

Prediction unpackSelectors(uint8_t byte) {
  Prediction p;
  p.selector = {uint8_t(byte & 15), uint8_t(byte >> 4)};
  return p;
}

class WaveletEncoder final : public FrameEncoder {
 public:
  WaveletEncoder(const WaveletOptions& options, const Topology& topology, SimdPath path)
      : options_(options), topology_(topology), static_coder_(topology_), model_(options, topology_, path) {}

  void encodeFrame(const float* xyz, bool intra, std::vector<uint8_t>& out, FrameCodingStats& stats) override {
    original_ = xyz;
    x_.assign(xyz, xyz + 3 * size_t(topology_.vertex_count));
    error_bound_ = options_.target_kg > 0 ? frameErrorBound(xyz, topology_.vertex_count, options_.target_kg) : 0;
    stats = FrameCodingStats();
    if (intra || !model_.ready()) return encodeParametric(out, stats);
    model_.transform().forward(x_.data(), coefficients_);
    const Prediction prediction = model_.choosePrediction(coefficients_, options_.temporal_prediction);
    model_.residual(coefficients_, prediction, residual_);
    // The group's step (a fraction of its parametric frame's diagonal) is too fine for this
    // frame when the frame is far larger than that one, e.g. after a frame collapsed to a
    // point: a new parametric frame starts a new group with a step of its own size.
    if (!fitsBitplanes(residual_, model_.step())) return encodeParametric(out, stats);
    if (prediction.isIntra()) {
      out.push_back(uint8_t(WaveletFrameType::kDetailIntra));
    } else {
      out.push_back(uint8_t(WaveletFrameType::kDetailPredicted));
      out.push_back(packSelectors(prediction));
    }
    BitplaneEncodeSettings settings;
    settings.path = model_.simdPath();
    settings.step = model_.step();
    settings.checkpoints = options_.truncatable;
    settings.context = model_.contextFor(prediction);
    if (options_.bits_per_vertex > 0)
      settings.byte_budget = uint64_t(std::max(2.0, options_.bits_per_vertex * topology_.vertex_count / 8 - 1));
    if (options_.target_kg > 0 && !cutForTarget(prediction, settings)) std::fill(residual_.begin(), residual_.end(), 0.0);
    encodeBitplanes(residual_.data(), model_.layout(), settings, out, decoded_, model_.nextHistory(),
                    model_.workspace());
    model_.accept(decoded_, prediction);
  }

  const std::vector<double>& reconstruction() const override { return model_.reconstruction(); }

 private:
  // Sets the shortest cut whose output meets the frame's error bound; false when nothing at
  // all (a zero residual) meets it.
  bool cutForTarget(const Prediction& prediction, BitplaneEncodeSettings& settings) {
    const BitplaneCutPreview preview(model_.simdPath(), residual_.data(), model_.layout(), settings.step, model_.workspace());
    const int hint = preview.planeCount() - planes_dropped_;
    const BitplaneCut cut = shortestCut(preview.planeCount(), preview.blockCount(), error_bound_, hint,
                                        [&](const BitplaneCut& c) {
                                          preview.decoded(c.planes, c.blocks, decoded_);
                                          model_.previewReconstruction(decoded_, prediction, trial_);
                                          return floatOutputError(original_, trial_);
                                        });
    planes_dropped_ = preview.planeCount() - cut.planes;
    if (cut.planes == 0) return false;
    settings.max_planes = cut.planes;
    settings.last_plane_blocks = cut.blocks;
    return true;
  }

  // The static coder at parametric_bits, or finer when the target error needs it.
  void encodeParametric(std::vector<uint8_t>& out, FrameCodingStats& stats) {
    stats.intra = true;
    const size_t start = out.size();
    std::vector<double> recon;
    const double largest_side = boundingCube(x_).side;
    for (int bits = options_.parametric_bits;; ++bits) {
      out.resize(start);
      out.push_back(uint8_t(WaveletFrameType::kParametric));
      static_coder_.encode(x_, parametricStep(bits, largest_side), out, recon);
      if (options_.target_kg <= 0 || bits >= kMaxParametricBits || floatOutputError(original_, recon) <= error_bound_) break;
    }
    model_.setParametric(recon);
  }

  WaveletOptions options_;
  Topology topology_;
  StaticPositionCoder static_coder_;
  WaveletFrameModel model_;
  const float* original_ = nullptr;
  double error_bound_ = 0;
  int planes_dropped_ = 0;  // below the top plane in the last frame's cut: the next one's guess
  std::vector<double> x_, coefficients_, residual_, decoded_, trial_;
};

class WaveletDecoder final : public FrameDecoder {
 public:
  WaveletDecoder(const WaveletOptions& options, const Topology& topology, const WaveletDecodeControl& control,
                 SimdPath path)
      : control_(control), topology_(topology), hierarchy_cost_(checkHierarchyCost(topology_)),
        static_coder_(topology_), model_(options, topology_, path) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    ANIMC_RETURN_IF_ERROR(hierarchy_cost_);
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    // Progressive decoding cuts detail frames only: a parametric frame is needed whole.
    const bool cut = type != uint8_t(WaveletFrameType::kParametric) && control_.max_payload_bytes > 0 &&
                     payload.remaining() + 1 > control_.max_payload_bytes;
    if (cut)
      payload = ByteReader(payload.cursor(), size_t(std::max<uint64_t>(control_.max_payload_bytes, 1) - 1), payload.offset());
    if (type == uint8_t(WaveletFrameType::kParametric)) {
      std::vector<double> recon;
      ANIMC_RETURN_IF_ERROR(static_coder_.decode(payload, recon));
      model_.setParametric(recon);
    } else if (type == uint8_t(WaveletFrameType::kDetailIntra)) {
      ANIMC_RETURN_IF_ERROR(decodeDetails(payload, Prediction::intra(), cut));
    } else if (type == uint8_t(WaveletFrameType::kDetailPredicted)) {
      ANIMC_ASSIGN_OR_RETURN(uint8_t selectors, payload.u8("Prediction_Selectors"));
      ANIMC_RETURN_IF_ERROR(decodeDetails(payload, unpackSelectors(selectors), cut));
    } else {
      return corrupt("unknown wavelet frame type " + std::to_string(type));
    }
    if (intra) *intra = type == uint8_t(WaveletFrameType::kParametric);
    return decodedFrameToFloats(model_.simdPath(), model_.reconstruction(), xyz);
  }

 private:
  // cut: the payload was shortened by control_.max_payload_bytes.
  Status decodeDetails(ByteReader& payload, const Prediction& prediction, bool cut) {
    if (!model_.canPredict(prediction)) return corrupt("detail frame without the frames it refers to");
    BitplaneDecodeSettings settings;
    settings.path = model_.simdPath();
    settings.step = model_.step();
    settings.max_planes = control_.max_bitplanes;
    settings.context = model_.contextFor(prediction);
    Status s = decodeBitplanes(payload, model_.layout(), settings, decoded_, nullptr, model_.nextHistory(),
                               model_.workspace());
    // A cut inside the block's header leaves no complete plane: the frame is its prediction.
    if (cut && s.code() == StatusCode::kTruncated) {
      decoded_.assign(model_.coefficientCount(), 0.0);
      s = Status();
    }
    ANIMC_RETURN_IF_ERROR(s);
    model_.accept(decoded_, prediction);
    return Status();
  }

  WaveletDecodeControl control_;
  Topology topology_;
  Status hierarchy_cost_;  // a mesh whose hierarchy would take too long is refused, not decoded
  StaticPositionCoder static_coder_;
  WaveletFrameModel model_;
  std::vector<double> decoded_;
};

}  // namespace

std::unique_ptr<FrameEncoder> makeWaveletEncoder(const WaveletOptions& options, const Topology& topology,
                                                 SimdPath path) {
  return std::make_unique<WaveletEncoder>(options, topology, path);
}

std::unique_ptr<FrameDecoder> makeWaveletDecoder(const WaveletOptions& options, const Topology& topology,
                                                 const WaveletDecodeControl& control, SimdPath path) {
  return std::make_unique<WaveletDecoder>(options, topology, control, path);
}

}  // namespace animc
