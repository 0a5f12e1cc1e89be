// SPDX-License-Identifier: Apache-2.0
// The Wavelet codec's entry in the codec table (codecs/codec_registry.h).
#include <cstdio>

#include "codecs/codec_registry.h"
#include "codecs/wavelet/progressive_mesh.h"
#include "codecs/wavelet/wavelet_codec.h"

namespace animc {
namespace {

const WaveletOptions& wavelet(const CodecOptions& o) { return std::get<WaveletOptions>(o); }

Result<CodecOptions> fromFlags(const OptionValues& values) {
  WaveletOptions o;
  ANIMC_ASSIGN_OR_RETURN(o.step, values.number("step", o.step));
  ANIMC_ASSIGN_OR_RETURN(o.bits_per_vertex, values.number("bpv", o.bits_per_vertex));
  ANIMC_ASSIGN_OR_RETURN(o.target_kg, values.number("target-kg", o.target_kg));
  ANIMC_ASSIGN_OR_RETURN(long long bits, values.integer("parametric-bits", o.parametric_bits));
  if (bits < kMinParametricBits || bits > kMaxParametricBits)
    return invalidArgument("--parametric-bits must be in [" + std::to_string(kMinParametricBits) + ", " +
                           std::to_string(kMaxParametricBits) + "]");
  o.parametric_bits = int(bits);
  o.temporal_prediction = !values.has("i-frames-only");
  o.progressive_p_frames = values.has("progressive-p-frames");
  o.local_frames = values.has("local-frames");
  return CodecOptions(o);
}

std::string describe(const CodecOptions& options) {
  const WaveletOptions& w = wavelet(options);
  char rate[96] = "no rate limit";
  if (w.bits_per_vertex > 0 && w.target_kg > 0)
    std::snprintf(rate, sizeof rate, "target KG %g %% within %g bits per vertex", w.target_kg, w.bits_per_vertex);
  else if (w.bits_per_vertex > 0)
    std::snprintf(rate, sizeof rate, "fixed rate %g bits per vertex", w.bits_per_vertex);
  else if (w.target_kg > 0)
    std::snprintf(rate, sizeof rate, "target KG %g %%", w.target_kg);
  char text[256];
  std::snprintf(text, sizeof text, "%s, step %g of the diagonal, parametric bits %d, %s%s", rate, w.step,
                w.parametric_bits,
                !w.temporal_prediction   ? "I-frames only"
                : w.progressive_p_frames ? "progressive P-frames"
                                         : "P-frames",
                w.local_frames ? ", details in local frames" : "");
  return text;
}

std::vector<SettingValue> settings(const CodecOptions& options) {
  const WaveletOptions& w = wavelet(options);
  return {{"bits_per_vertex_setting", w.bits_per_vertex},
          {"step", w.step},
          {"target_kg_setting", w.target_kg},
          {"parametric_bits", int64_t(w.parametric_bits)},
          {"temporal_prediction", w.temporal_prediction},
          {"progressive_p_frames", w.progressive_p_frames},
          {"local_frames", w.local_frames}};
}

Status checkMesh(const Topology& topology) {
  const Status cost = checkHierarchyCost(topology);
  if (!cost.ok()) return invalidArgument(cost.message() + "; --codec affine-octree has no such limit");
  return Status();
}

[[maybe_unused]] std::unique_ptr<FrameEncoder> makeEncoder(const CodecOptions& o, const Topology& topology,
                                                           SimdPath path) {
  return makeWaveletEncoder(wavelet(o), topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder(const CodecOptions& o, const Topology& topology,
                                                  const DecoderOptions& decoding, const std::string& file,
                                                  SimdPath path) {
  // A P-frame decoded from part of its payload leaves the decoder's coding contexts different
  // from the encoder's unless the file was coded without them: every later frame of the group
  // would decode wrongly.
  if (decoding.progressive.partial() && !wavelet(o).cuttable())
    return invalidArgument(file +
                           ": progressive decoding (fewer bitplanes or bytes) needs a file encoded with "
                           "animc encode --codec wavelet --progressive-p-frames or --i-frames-only; this one's "
                           "P-frames use the previous frame's coding contexts");
  return makeWaveletDecoder(wavelet(o), topology, decoding.progressive, path);
}

}  // namespace

const CodecEntry kWaveletEntry = {
    CodecId::kWavelet,
    "wavelet",
    {"step", "bpv", "target-kg", "parametric-bits"},
    {"i-frames-only", "progressive-p-frames", "local-frames"},
    "[--step S] [--bpv B] [--target-kg X] [--parametric-bits P]\n"
    "           [--i-frames-only | --progressive-p-frames] [--local-frames]\n"
    "           S: the finest quantisation step, a fraction of the first frame's bounding-box\n"
    "           diagonal; B caps each frame at B bits per vertex; X is the KG error (in %) to\n"
    "           reach with the fewest bits (down to what S allows)",
    fromFlags,
    validateOptions<WaveletOptions>,
    writeOptions<WaveletOptions>,
    readOptions<WaveletOptions>,
    describe,
    settings,
    checkMesh,
    ANIMC_ENCODER(makeEncoder),
    nullptr,
    makeDecoder,
};

}  // namespace animc
