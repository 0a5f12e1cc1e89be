#include "codecs/wavelet/wavelet_codec.h"

#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/iframe_coder.h"
#include "codecs/wavelet/bitplane_coder.h"
#include "codecs/wavelet/frame_model.h"

namespace animc {
namespace {

double largestSide(const std::vector<double>& xyz) {
  if (xyz.empty()) return 0;
  double lo[3] = {xyz[0], xyz[1], xyz[2]}, hi[3] = {xyz[0], xyz[1], xyz[2]};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

class WaveletEncoder final : public FrameEncoder {
 public:
  WaveletEncoder(const WaveletOptions& options, const Topology& topology)
      : options_(options), topology_(topology), static_coder_(topology_), model_(options, topology_) {}

  void encodeFrame(const float* xyz, bool intra, std::vector<uint8_t>& out, FrameCodingStats& stats) override {
    x_.assign(xyz, xyz + 3 * size_t(topology_.vertex_count));
    stats = FrameCodingStats();
    if (intra || !model_.ready()) return encodeParametric(out, stats);
    model_.transform().forward(x_.data(), coefficients_);
    DetailReference ref = DetailReference::kIntra;
    if (options_.temporal_prediction &&
        model_.residualEnergy(coefficients_, DetailReference::kInter) <=
            model_.residualEnergy(coefficients_, DetailReference::kIntra))
      ref = DetailReference::kInter;
    out.push_back(uint8_t(ref == DetailReference::kIntra ? WaveletFrameType::kDetailIntra
                                                         : WaveletFrameType::kDetailInter));
    model_.residual(coefficients_, ref, residual_);
    BitplaneEncodeSettings settings;
    settings.step = model_.step();
    settings.checkpoints = options_.truncatable;
    if (options_.bits_per_vertex > 0)
      settings.byte_budget = std::max<uint64_t>(2, uint64_t(options_.bits_per_vertex * topology_.vertex_count / 8) - 1);
    encodeBitplanes(residual_.data(), model_.classes().data(), residual_.size(), settings, out, decoded_);
    model_.accept(decoded_, ref);
    stats.cells = residual_.size();
  }

  const std::vector<double>& reconstruction() const override { return model_.reconstruction(); }

 private:
  void encodeParametric(std::vector<uint8_t>& out, FrameCodingStats& stats) {
    stats.intra = true;
    out.push_back(uint8_t(WaveletFrameType::kParametric));
    std::vector<double> recon;
    static_coder_.encode(x_, parametricStep(options_, largestSide(x_)), out, recon);
    model_.setParametric(recon);
  }

  WaveletOptions options_;
  Topology topology_;
  IFrameCoder static_coder_;
  WaveletFrameModel model_;
  std::vector<double> x_, coefficients_, residual_, decoded_;
};

class WaveletDecoder final : public FrameDecoder {
 public:
  WaveletDecoder(const WaveletOptions& options, const Topology& topology, const WaveletDecodeControl& control)
      : control_(control), topology_(topology), static_coder_(topology_), model_(options, topology_) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    if (control_.max_payload_bytes > 0 && payload.remaining() > control_.max_payload_bytes)
      payload = ByteReader(payload.cursor(), size_t(control_.max_payload_bytes), payload.offset());
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    if (type == uint8_t(WaveletFrameType::kParametric)) {
      std::vector<double> recon;
      ANIMC_RETURN_IF_ERROR(static_coder_.decode(payload, recon));
      if (payload.remaining() != 0) return corrupt("parametric frame: bytes after the coded positions");
      model_.setParametric(recon);
    } else if (type == uint8_t(WaveletFrameType::kDetailIntra) || type == uint8_t(WaveletFrameType::kDetailInter)) {
      if (!model_.ready()) return corrupt("detail frame without a preceding parametric frame");
      ANIMC_RETURN_IF_ERROR(decodeDetails(payload, type == uint8_t(WaveletFrameType::kDetailIntra)
                                                       ? DetailReference::kIntra
                                                       : DetailReference::kInter));
    } else {
      return corrupt("unknown wavelet frame type " + std::to_string(type));
    }
    if (intra) *intra = type == uint8_t(WaveletFrameType::kParametric);
    return output(xyz);
  }

 private:
  Status decodeDetails(ByteReader& payload, DetailReference ref) {
    BitplaneDecodeSettings settings;
    settings.step = model_.step();
    settings.max_planes = control_.max_bitplanes;
    ANIMC_RETURN_IF_ERROR(decodeBitplanes(payload, model_.classes().data(), model_.coefficientCount(),
                                          settings, decoded_));
    model_.accept(decoded_, ref);
    return Status();
  }

  Status output(std::vector<float>& xyz) const {
    const std::vector<double>& r = model_.reconstruction();
    xyz.resize(r.size());
    for (size_t i = 0; i < r.size(); ++i) {
      if (!std::isfinite(r[i]) || std::fabs(r[i]) > 1e30)
        return corrupt("decoded vertex " + std::to_string(i / 3) + " is out of range");
      xyz[i] = float(r[i]);
    }
    return Status();
  }

  WaveletDecodeControl control_;
  Topology topology_;
  IFrameCoder static_coder_;
  WaveletFrameModel model_;
  std::vector<double> decoded_;
};

}  // namespace

double parametricStep(const WaveletOptions& options, double largest_side) {
  const double side = largest_side > 0 && std::isfinite(largest_side) ? largest_side : 1.0;
  return side / double(1u << options.parametric_bits);
}

std::unique_ptr<FrameEncoder> makeWaveletEncoder(const WaveletOptions& options, const Topology& topology) {
  return std::make_unique<WaveletEncoder>(options, topology);
}

std::unique_ptr<FrameDecoder> makeWaveletDecoder(const WaveletOptions& options, const Topology& topology,
                                                 const WaveletDecodeControl& control) {
  return std::make_unique<WaveletDecoder>(options, topology, control);
}

}  // namespace animc
