#include "codecs/wavelet/wavelet_codec.h"

#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/iframe_coder.h"
#include "codecs/wavelet/bitplane_coder.h"
#include "codecs/wavelet/frame_model.h"

namespace animc {
namespace {

uint8_t frameTypeOf(DetailReference ref) {
  switch (ref) {
    case DetailReference::kIntra: return uint8_t(WaveletFrameType::kDetailIntra);
    case DetailReference::kInter: return uint8_t(WaveletFrameType::kDetailInter);
    case DetailReference::kLinear: return uint8_t(WaveletFrameType::kDetailLinear);
  }
  return 0;
}

double largestSide(const std::vector<double>& xyz) {
  const std::array<double, 3> e = boxExtent(xyz);
  return std::max({e[0], e[1], e[2]});
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
    const DetailReference ref = chooseReference();
    out.push_back(frameTypeOf(ref));
    model_.residual(coefficients_, ref, residual_);
    BitplaneEncodeSettings settings;
    settings.step = model_.step();
    settings.checkpoints = options_.truncatable;
    if (options_.bits_per_vertex > 0)
      settings.byte_budget = uint64_t(std::max(2.0, options_.bits_per_vertex * topology_.vertex_count / 8 - 1));
    encodeBitplanes(residual_.data(), model_.layout(), settings, out, decoded_);
    model_.accept(decoded_, ref);
  }

  const std::vector<double>& reconstruction() const override { return model_.reconstruction(); }

 private:
  // The reference leaving the smallest weighted residual (a proxy for its rate).
  DetailReference chooseReference() const {
    DetailReference best = DetailReference::kIntra;
    if (!options_.temporal_prediction) return best;
    double best_energy = model_.residualEnergy(coefficients_, best);
    for (DetailReference ref : {DetailReference::kInter, DetailReference::kLinear}) {
      if (!model_.hasReference(ref)) continue;
      const double energy = model_.residualEnergy(coefficients_, ref);
      if (energy < best_energy) {
        best = ref;
        best_energy = energy;
      }
    }
    return best;
  }

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
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    // Progressive decoding cuts detail frames only: a parametric frame is needed whole.
    if (type != uint8_t(WaveletFrameType::kParametric) && control_.max_payload_bytes > 0 &&
        payload.remaining() + 1 > control_.max_payload_bytes)
      payload = ByteReader(payload.cursor(), size_t(std::max<uint64_t>(control_.max_payload_bytes, 1) - 1), payload.offset());
    if (type == uint8_t(WaveletFrameType::kParametric)) {
      std::vector<double> recon;
      ANIMC_RETURN_IF_ERROR(static_coder_.decode(payload, recon));
      model_.setParametric(recon);
    } else if (type <= uint8_t(WaveletFrameType::kDetailLinear)) {
      const DetailReference ref = DetailReference(type - 1);
      if (!model_.hasReference(ref)) return corrupt("detail frame without the frames it refers to");
      ANIMC_RETURN_IF_ERROR(decodeDetails(payload, ref));
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
    ANIMC_RETURN_IF_ERROR(decodeBitplanes(payload, model_.layout(), settings, decoded_));
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
