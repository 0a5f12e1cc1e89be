// SPDX-License-Identifier: Apache-2.0
// The trajectory codec's entry in the codec table (codecs/codec_registry.h).
#include <cstdio>

#include "codecs/codec_registry.h"
#include "codecs/trajectory/trajectory_codec.h"

namespace animc {
namespace {

const TrajectoryOptions& trajectory(const CodecOptions& o) { return std::get<TrajectoryOptions>(o); }

// The rate flags, one of which may be given (the default is --target-kg 0.3).
struct RateFlag {
  const char* flag;
  TrajectoryRate rate;
};
constexpr RateFlag kRateFlags[] = {{"target-kg", TrajectoryRate::kTargetKg},
                                   {"step", TrajectoryRate::kStep},
                                   {"max-error", TrajectoryRate::kMaxError},
                                   {"bpvf", TrajectoryRate::kBitsPerVertexFrame}};

Result<TrajectoryOptions> trajectoryFlags(const OptionValues& values) {
  TrajectoryOptions o;
  int given = 0;
  for (const RateFlag& f : kRateFlags) {
    if (!values.has(f.flag)) continue;
    if (++given > 1) return invalidArgument("--target-kg, --step, --max-error and --bpvf exclude each other");
    o.rate = f.rate;
    ANIMC_ASSIGN_OR_RETURN(o.rate_value, values.number(f.flag, 0));
  }
  ANIMC_ASSIGN_OR_RETURN(o.group_frames, groupFramesFlag(values, o.group_frames));
  return o;
}

Result<CodecOptions> fromFlags(const OptionValues& values) {
  ANIMC_ASSIGN_OR_RETURN(TrajectoryOptions o, trajectoryFlags(values));
  return CodecOptions(o);
}

Result<CodecOptions> fromFlags2(const OptionValues& values) {
  Trajectory2Options o;
  ANIMC_ASSIGN_OR_RETURN(o.trajectory, trajectoryFlags(values));
  ANIMC_ASSIGN_OR_RETURN(long long parts, values.integer("parts", o.parts));
  if (parts < 1 || parts > kMaxTrajectoryParts)
    return invalidArgument("--parts must be in [1, " + std::to_string(kMaxTrajectoryParts) + "]");
  o.parts = uint32_t(parts);
  return CodecOptions(o);
}

std::string describeTrajectory(const TrajectoryOptions& o) {
  char text[160];
  const char* unit = o.rate == TrajectoryRate::kTargetKg   ? " %"
                     : o.rate == TrajectoryRate::kStep     ? " of the diagonal"
                     : o.rate == TrajectoryRate::kMaxError ? " of the cube's side"
                                                           : "";
  std::snprintf(text, sizeof text, "%s %g%s, groups of up to %u frames", rateName(o.rate), o.rate_value, unit,
                o.group_frames);
  return text;
}

std::vector<SettingValue> trajectorySettings(const TrajectoryOptions& o) {
  return {{"rate_mode", std::string(rateName(o.rate))},
          {"rate_value", o.rate_value},
          {"group_frames", int64_t(o.group_frames)}};
}

std::string describe(const CodecOptions& options) { return describeTrajectory(trajectory(options)); }
std::vector<SettingValue> settings(const CodecOptions& options) { return trajectorySettings(trajectory(options)); }

std::string describe2(const CodecOptions& options) {
  const Trajectory2Options& o = std::get<Trajectory2Options>(options);
  return describeTrajectory(o.trajectory) + " in up to " + std::to_string(o.parts) + " parts";
}
std::vector<SettingValue> settings2(const CodecOptions& options) {
  const Trajectory2Options& o = std::get<Trajectory2Options>(options);
  std::vector<SettingValue> out = trajectorySettings(o.trajectory);
  out.push_back({"parts", int64_t(o.parts)});
  return out;
}

Status checkMesh(const Topology&) { return Status(); }

[[maybe_unused]] std::unique_ptr<GroupEncoder> makeEncoder(const CodecOptions& o, const Topology& topology,
                                                           SimdPath path) {
  return makeTrajectoryEncoder(trajectory(o), topology, path);
}

[[maybe_unused]] std::unique_ptr<GroupEncoder> makeEncoder2(const CodecOptions& o, const Topology& topology,
                                                            SimdPath path) {
  return makeTrajectory2Encoder(std::get<Trajectory2Options>(o), topology, path);
}

Status refuseProgressive(const DecoderOptions& decoding, const std::string& file) {
  if (decoding.progressive.partial())
    return invalidArgument(file +
                           ": progressive decoding (fewer bitplanes or bytes) needs a wavelet-coded "
                           "file; this one is trajectory");
  return Status();
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder(const CodecOptions&, const Topology& topology,
                                                  const DecoderOptions& decoding, const std::string& file,
                                                  SimdPath path) {
  ANIMC_RETURN_IF_ERROR(refuseProgressive(decoding, file));
  return makeTrajectoryDecoder(topology, decoding.limits, path);
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder2(const CodecOptions&, const Topology& topology,
                                                   const DecoderOptions& decoding, const std::string& file,
                                                   SimdPath path) {
  ANIMC_RETURN_IF_ERROR(refuseProgressive(decoding, file));
  return makeTrajectory2Decoder(topology, decoding.limits, path);
}

constexpr const char* kRateUsage =
    "[--target-kg X | --step S | --max-error E | --bpvf B] [--group-frames G]\n"
    "           per group: X the KG error (in %) to reach with the fewest bits (default 0.3);\n"
    "           S a fixed coefficient step (fraction of the first frame's diagonal); E the\n"
    "           largest vertex error (fraction of its frame's cube side); B the bits per vertex\n"
    "           per frame to fill; G the most frames coded together when --iframe-interval\n"
    "           does not set it (default 512)";

}  // namespace

const CodecEntry kTrajectoryEntry = {
    CodecId::kTrajectory,
    "trajectory",
    {"target-kg", "step", "max-error", "bpvf", "group-frames"},
    {},
    kRateUsage,
    fromFlags,
    validateOptions<TrajectoryOptions>,
    writeOptions<TrajectoryOptions>,
    readOptions<TrajectoryOptions>,
    describe,
    settings,
    checkMesh,
    nullptr,
    ANIMC_ENCODER(makeEncoder),
    makeDecoder,
};

const CodecEntry kTrajectory2Entry = {
    CodecId::kTrajectory2,
    "trajectory2",
    {"target-kg", "step", "max-error", "bpvf", "group-frames", "parts"},
    {},
    "[--target-kg X | --step S | --max-error E | --bpvf B] [--group-frames G] [--parts P]\n"
    "           as trajectory's, each group cut into at most P parts of vertices moving\n"
    "           together, each with its own basis (default 8; half as many,\n"
    "           a quarter, ..., 2 and 1 are tried too, and the best kept)",
    fromFlags2,
    validateOptions<Trajectory2Options>,
    writeOptions<Trajectory2Options>,
    readOptions<Trajectory2Options>,
    describe2,
    settings2,
    checkMesh,
    nullptr,
    ANIMC_ENCODER(makeEncoder2),
    makeDecoder2,
};

}  // namespace animc
