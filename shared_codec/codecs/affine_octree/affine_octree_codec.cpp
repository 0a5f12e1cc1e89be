// SPDX-License-Identifier: Apache-2.0
#include "codecs/affine_octree/affine_octree_codec.h"

#include <cmath>

#include "codecs/common/static_position_coder.h"
#include "codecs/affine_octree/octree_shared.h"
#include "codecs/affine_octree/paper_octree.h"
#include "codecs/affine_octree/predictive_octree.h"

namespace animc {
namespace {

constexpr uint8_t kIntraFrame = 0;
constexpr uint8_t kInterFrame = 1;
// A frame whose vertices sit further than this from the reference cube (in cube sides) is
// coded as an intra frame: the inter coders' ranges are not meant for teleporting meshes.
constexpr double kMaxUnitCoordinate = 1e6;

// The root cube of an inter frame is that of the *reconstructed* previous frame (the paper's
// definition, which the paper profile keeps). That box can stick out of the original's by up
// to the error itself on each side, so the default profile tests against ME/(1+2·ME): its
// errors then stay within ME of the original frames' cube too, which is what an independent
// check (shared/tools/seqmetrics.py) measures.
double innerMaxError(const AffineOctreeOptions& options) {
  const double me = options.max_error;
  return options.profile == Profile::kPaper ? me : me / (1.0 + 2.0 * me);
}

// State both sides keep: the last two reconstructed frames.
struct LoopState {
  explicit LoopState(SimdPath simd_path) : path(simd_path) {}
  SimdPath path;
  std::vector<double> current, before;
  bool has_current = false, has_before = false;
  std::vector<double> u, recon_unit;
  // The bounding cube of `current`, found by advance() on the way (so known exactly when
  // has_before is), saving prepare() a pass.
  RootCube current_cube;

  // Normalises `current` into its root cube, and returns the cube.
  RootCube prepare() {
    const RootCube cube = has_before ? current_cube : boundingCube(current);
    normalise(path, cube, current, u);
    return cube;
  }
  void advance(const RootCube& cube) {
    before.swap(current);
    has_before = true;
    current_cube = denormalise(path, cube, recon_unit, current);
  }
  void restart() {
    has_current = true;
    has_before = false;
  }
};

class AffineOctreeEncoder final : public FrameEncoder {
 public:
  AffineOctreeEncoder(const AffineOctreeOptions& options, const Topology& topology, SimdPath path)
      : options_(options), intra_(topology), paper_(options.bits, path), predictive_(topology.vertex_count, path),
        vertex_count_(topology.vertex_count), state_(path) {}

  void encodeFrame(const float* xyz, bool intra, std::vector<uint8_t>& out,
                   FrameCodingStats& stats) override {
    stats = FrameCodingStats();
    const size_t start = out.size();
    if (!intra && state_.has_current && encodeInter(xyz, out, stats)) return;
    out.resize(start);
    encodeIntra(xyz, out, stats);
  }
  const std::vector<double>& reconstruction() const override { return state_.current; }

 private:
  // The frame in double goes to x_, which an inter frame normalises in place: on a large mesh
  // every frame-sized array counts (docs/auto.md).
  void takeFrame(const float* xyz) { x_.assign(xyz, xyz + 3 * size_t(vertex_count_)); }

  bool encodeInter(const float* xyz, std::vector<uint8_t>& out, FrameCodingStats& stats) {
    const RootCube cube = state_.prepare();
    takeFrame(xyz);
    normalise(state_.path, cube, x_, x_);
    for (double c : x_)
      if (std::fabs(c) > kMaxUnitCoordinate) return false;
    PFrameInput in{&state_.u, state_.has_before ? &state_.before : nullptr, cube, &x_, innerMaxError(options_),
                   options_.max_depth};
    out.push_back(kInterFrame);
    if (options_.profile == Profile::kPaper) {
      PaperFrameStats s;
      paper_.encode(in, out, state_.recon_unit, s);
      stats.cells = s.cells;
    } else {
      PredictiveFrameStats s;
      if (!predictive_.encode(in, out, state_.recon_unit, s)) return false;
      stats.cells = s.leaves;
    }
    state_.advance(cube);
    return true;
  }

  void encodeIntra(const float* xyz, std::vector<uint8_t>& out, FrameCodingStats& stats) {
    stats.intra = true;
    takeFrame(xyz);
    out.push_back(kIntraFrame);
    intra_.encode(x_, intraStep(options_, boundingCube(x_).side), out, state_.current);
    state_.restart();
    paper_.reset();
    predictive_.reset();
  }

  AffineOctreeOptions options_;
  StaticPositionCoder intra_;
  PaperOctreeEncoder paper_;
  PredictiveOctreeEncoder predictive_;
  uint32_t vertex_count_;
  LoopState state_;
  std::vector<double> x_;
};

class AffineOctreeDecoder final : public FrameDecoder {
 public:
  AffineOctreeDecoder(const AffineOctreeOptions& options, const Topology& topology, SimdPath path)
      : options_(options), intra_(topology), paper_(options.bits, path), predictive_(topology.vertex_count, path),
        state_(path) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    if (type == kIntraFrame) {
      ANIMC_RETURN_IF_ERROR(intra_.decode(payload, state_.current));
      state_.restart();
      paper_.reset();
      predictive_.reset();
    } else if (type == kInterFrame) {
      if (!state_.has_current) return corrupt("inter frame without a preceding intra frame");
      ANIMC_RETURN_IF_ERROR(decodeInter(payload));
    } else {
      return corrupt("unknown frame type " + std::to_string(type));
    }
    if (intra) *intra = type == kIntraFrame;
    return decodedFrameToFloats(state_.path, state_.current, xyz);
  }

 private:
  Status decodeInter(ByteReader payload) {
    const RootCube cube = state_.prepare();
    PFrameInput in{&state_.u, state_.has_before ? &state_.before : nullptr, cube, nullptr,
                   innerMaxError(options_), options_.max_depth};
    if (options_.profile == Profile::kPaper)
      ANIMC_RETURN_IF_ERROR(paper_.decode(in, payload, state_.recon_unit));
    else
      ANIMC_RETURN_IF_ERROR(predictive_.decode(in, payload, state_.recon_unit));
    state_.advance(cube);
    return Status();
  }

  AffineOctreeOptions options_;
  StaticPositionCoder intra_;
  PaperOctreeDecoder paper_;
  PredictiveOctreeDecoder predictive_;
  LoopState state_;
};

}  // namespace

double intraStep(const AffineOctreeOptions& options, double side) {
  if (options.profile == Profile::kPaper) return side / double((1u << options.bits) - 1);
  return residualStep(options.max_error) * side;
}

std::unique_ptr<FrameEncoder> makeAffineOctreeEncoder(const AffineOctreeOptions& options,
                                                      const Topology& topology, SimdPath path) {
  return std::make_unique<AffineOctreeEncoder>(options, topology, path);
}

std::unique_ptr<FrameDecoder> makeAffineOctreeDecoder(const AffineOctreeOptions& options,
                                                      const Topology& topology, SimdPath path) {
  return std::make_unique<AffineOctreeDecoder>(options, topology, path);
}

}  // namespace animc
