// SPDX-License-Identifier: Apache-2.0
// The Affine-Octree codec's entry in the codec table (codecs/codec_registry.h).
#include <cstdio>

#include "codecs/affine_octree/affine_octree_codec.h"
#include "codecs/codec_registry.h"

namespace animc {
namespace {

const AffineOctreeOptions& octree(const CodecOptions& o) { return std::get<AffineOctreeOptions>(o); }

Result<Profile> profileFromName(const std::string& name) {
  if (name == "paper") return Profile::kPaper;
  // "default" is the name the predictive profile had, and still the default.
  if (name == "predictive" || name == "default") return Profile::kPredictive;
  return invalidArgument("unknown profile '" + name + "' (paper, predictive)");
}

Result<CodecOptions> fromFlags(const OptionValues& values) {
  AffineOctreeOptions o;
  ANIMC_ASSIGN_OR_RETURN(o.profile, profileFromName(values.get("profile", "predictive")));
  ANIMC_ASSIGN_OR_RETURN(o.max_error, values.number("max-error", o.max_error));
  ANIMC_ASSIGN_OR_RETURN(long long bits, values.integer("bits", o.bits));
  ANIMC_ASSIGN_OR_RETURN(long long depth, values.integer("max-depth", o.max_depth));
  if (bits < kMinBits || bits > kMaxBits) return invalidArgument("--bits must be in [8, 24]");
  if (depth < 1 || depth > kMaxDepthLimit) return invalidArgument("--max-depth must be in [1, 16]");
  o.bits = int(bits);
  o.max_depth = int(depth);
  return CodecOptions(o);
}

std::string describe(const CodecOptions& options) {
  const AffineOctreeOptions& o = octree(options);
  char text[160];
  std::snprintf(text, sizeof text, "profile %s, max error %g of the root cube, bits %d", profileName(o.profile),
                o.max_error, o.bits);
  return text;
}

std::vector<SettingValue> settings(const CodecOptions& options) {
  const AffineOctreeOptions& o = octree(options);
  return {{"profile", std::string(profileName(o.profile))},
          {"max_error_setting", o.max_error},
          {"bits", int64_t(o.bits)},
          {"max_depth", int64_t(o.max_depth)}};
}

Status checkMesh(const Topology&) { return Status(); }

[[maybe_unused]] std::unique_ptr<FrameEncoder> makeEncoder(const CodecOptions& o, const Topology& topology,
                                                           SimdPath path) {
  return makeAffineOctreeEncoder(octree(o), topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder(const CodecOptions& o, const Topology& topology,
                                                  const DecoderOptions& decoding, const std::string& file,
                                                  SimdPath path) {
  if (decoding.progressive.partial())
    return invalidArgument(file +
                           ": progressive decoding (fewer bitplanes or bytes) needs a wavelet-coded "
                           "file; this one is affine-octree");
  return makeAffineOctreeDecoder(octree(o), topology, path);
}

}  // namespace

const CodecEntry kAffineOctreeEntry = {
    CodecId::kAffineOctree,
    "affine-octree",
    {"profile", "max-error", "bits", "max-depth"},
    {},
    "[--profile paper|predictive] [--max-error E] [--bits K] [--max-depth D]\n"
    "           E: the largest vertex error, a fraction of the root cube's side (0.01 = 1%)",
    fromFlags,
    validateOptions<AffineOctreeOptions>,
    writeOptions<AffineOctreeOptions>,
    readOptions<AffineOctreeOptions>,
    describe,
    settings,
    checkMesh,
    ANIMC_ENCODER(makeEncoder),
    nullptr,
    makeDecoder,
};

}  // namespace animc
