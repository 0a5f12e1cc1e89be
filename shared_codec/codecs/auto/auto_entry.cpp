// SPDX-License-Identifier: Apache-2.0
// The entry of `--codec auto` in the codec table (codecs/codec_registry.h).
#include <cstdio>

#include "codecs/codec_registry.h"

namespace animc {

std::unique_ptr<GroupEncoder> makeAutoEncoder(const AutoOptions& options, const Topology& topology, SimdPath path);
Result<std::unique_ptr<FrameDecoder>> makeAutoDecoder(const AutoOptions& options, const Topology& topology,
                                                      const DecoderOptions& decoding, const std::string& file,
                                                      SimdPath path);

namespace {

const AutoOptions& automatic(const CodecOptions& o) { return std::get<AutoOptions>(o); }

Result<CodecOptions> fromFlags(const OptionValues& values) {
  AutoOptions o;
  if (values.has("target-kg") && values.has("max-error"))
    return invalidArgument("--target-kg and --max-error exclude each other");
  if (values.has("target-kg")) {
    o.rate = TrajectoryRate::kTargetKg;
    ANIMC_ASSIGN_OR_RETURN(o.rate_value, values.number("target-kg", 0));
  } else {
    ANIMC_ASSIGN_OR_RETURN(o.rate_value, values.number("max-error", o.rate_value));
  }
  ANIMC_ASSIGN_OR_RETURN(o.group_frames, groupFramesFlag(values, o.group_frames));
  return CodecOptions(withCandidates(o));
}

std::string describe(const CodecOptions& options) {
  const AutoOptions& o = automatic(options);
  std::string names;
  for (const AutoCandidate& c : o.candidates) names += (names.empty() ? "" : " or ") + std::string(codecName(c.codec));
  char text[200];
  std::snprintf(text, sizeof text, "%s %g%s, per group %s, groups of up to %u frames", rateName(o.rate), o.rate_value,
                o.rate == TrajectoryRate::kTargetKg ? " %" : " of the cube's side", names.c_str(), o.group_frames);
  return text;
}

std::vector<SettingValue> settings(const CodecOptions& options) {
  const AutoOptions& o = automatic(options);
  std::string names;
  for (const AutoCandidate& c : o.candidates) names += (names.empty() ? "" : ",") + std::string(codecName(c.codec));
  return {{"rate_mode", std::string(rateName(o.rate))},
          {"rate_value", o.rate_value},
          {"group_frames", int64_t(o.group_frames)},
          {"candidates", names}};
}

Status checkMesh(const Topology&) { return Status(); }

[[maybe_unused]] std::unique_ptr<GroupEncoder> makeEncoder(const CodecOptions& o, const Topology& topology,
                                                           SimdPath path) {
  return makeAutoEncoder(automatic(o), topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder(const CodecOptions& o, const Topology& topology,
                                                  const DecoderOptions& decoding, const std::string& file,
                                                  SimdPath path) {
  return makeAutoDecoder(automatic(o), topology, decoding, file, path);
}

}  // namespace

const CodecEntry kAutoEntry = {
    CodecId::kAuto,
    "auto",
    {"target-kg", "max-error", "group-frames"},
    {},
    "[--max-error E | --target-kg X] [--group-frames G]\n"
    "           per group, the smallest of trajectory2 and affine-octree within the max error E\n"
    "           (default 0.01), or of trajectory2 and wavelet at the KG error X (%)",
    fromFlags,
    validateOptions<AutoOptions>,
    writeOptions<AutoOptions>,
    readOptions<AutoOptions>,
    describe,
    settings,
    checkMesh,
    nullptr,
    ANIMC_ENCODER(makeEncoder),
    makeDecoder,
};

}  // namespace animc
